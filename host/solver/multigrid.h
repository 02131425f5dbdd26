// The multigrid preconditioner of the CG solves on hex8 lattices: a symmetric
// V-cycle over the levels of solver/lattice_hierarchy.h.
//   - Fine level: the engine's own matrix-free product (ElasticModel) and its
//     block-Jacobi inverse blocks.
//   - Coarse levels: Galerkin operators P^T D A D P of the fine operator A
//     (projected or true Hessian, as linearized) rebuilt at every Newton
//     linearization, one 24x24 matrix per coarse cell (kernels/multigrid.cl),
//     from the fine element matrices when the product variant keeps them,
//     else from the linearization cache.
//   - Smoother: Chebyshev of degree k over block-Jacobi on the interval
//     [0.1, 1.1] * lambda_max(D^-1 A) (lambda_max by power iteration per
//     level and linearization: 10 steps the first time, then 4 from the last
//     estimate); the same before and after the coarse correction, so the
//     V-cycle is symmetric.
//   - Coarsest level: assembled and factored (sparse LDL^T, Eigen) on the
//     host; where that factor is not positive (a true Hessian that is not
//     positive definite there) the coarsest level is smoothed instead.
// Constrained DOFs stay exactly zero on every level (masked transfers).
#pragma once

#include <Eigen/SparseCholesky>
#include <memory>
#include <vector>

#include "solver/elastic_model.h"
#include "solver/lattice_hierarchy.h"

namespace snh::solver {

template <typename Real>
class MultigridPreconditioner {
 public:
  using Vector = viennacl::vector<Real>;
  using VectorBase = viennacl::vector_base<Real>;

  // mask: 1 free, 0 constrained, per DOF (the mask the model was given).
  // Throws snh::Error when the mesh is not a hex8 lattice.
  MultigridPreconditioner(ElasticModel<Real>& model, const Mesh& mesh, const std::vector<char>& mask,
                          const MultigridOptions& options);
  ~MultigridPreconditioner();

  // After model.linearize() and model.setup_preconditioner(): coarse
  // operators, smoother bounds, the coarsest factorization.
  void setup();
  // z <- V-cycle applied to z (z holds the residual; constrained entries 0).
  void apply(VectorBase& z) const;

  const LatticeHierarchy& hierarchy() const { return hierarchy_; }
  int levels() const { return static_cast<int>(hierarchy_.levels.size()); }
  // The coarse cells' matrices of level >= 1 (tests), column-major 24x24 each.
  std::vector<Real> level_matrices(int level) const;
  // lambda_max(D^-1 A) estimated for each level at the last setup().
  std::vector<double> eigenvalue_estimates() const;
  size_t memory_bytes() const;

 private:
  struct Level;
  void product(int level, const VectorBase& p, VectorBase& y) const;
  void inverse_diagonal(int level, VectorBase& z) const;  // z <- D^-1 z
  // Chebyshev smoothing of A x = b at `level`; r holds b - A x on entry
  // (x = 0, r = b when from_zero) and, if want_residual, on return.
  void chebyshev(int level, VectorBase& x, VectorBase& r, bool want_residual) const;
  void vcycle(int level) const;
  void coarse_solve() const;
  void factor_coarsest();

  ElasticModel<Real>& model_;
  device::OpenClContext& cl_;
  MultigridOptions options_;
  LatticeHierarchy hierarchy_;
  std::vector<std::unique_ptr<Level>> levels_;
  device::Kernel galerkin_cache_k_, galerkin_matrices_k_, prolong_k_, restrict_k_, matrix_product_k_, gather_k_,
      jacobi_setup_k_, jacobi_apply_k_;
  device::Buffer octant_weights_;  // lattice_hierarchy.h's octant_weights()
  size_t table_bytes_ = 0;         // its device memory
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> coarsest_;
  bool coarsest_ok_ = false;
  mutable std::vector<Real> host_rhs_;
};

}  // namespace snh::solver
