// The multigrid preconditioner of the CG solves on hex8 lattices: a symmetric
// V-cycle over the levels of solver/multigrid/lattice_hierarchy.h.
//   - Fine level (MultigridOptions::fine_level): built, the element matrices
//     of the build's linearization and their block-Jacobi inverse blocks,
//     frozen with the coarse levels; or current, the engine's own
//     matrix-free product (ElasticModel) of each linearization and its
//     block-Jacobi inverse blocks of the build (automatic with inertia,
//     obstacles or barrier self-contact, whose terms only it carries).
//   - Coarse levels: Galerkin operators P^T D A D P of the fine operator A
//     (projected or true Hessian, as linearized) rebuilt at every Newton
//     linearization, one 24x24 matrix per coarse cell (kernels/multigrid.cl),
//     from the fine element matrices when the product variant keeps them,
//     else from the linearization cache; the first takes in the per-vertex
//     blocks of inertia and obstacle contact and the barrier's diagonal
//     blocks, not its couplings between vertices of distant cells
//     (snh_galerkin_vertex_terms).
//   - Products on the built levels: each level's cell matrices assembled
//     per vertex after each build, 3x3 blocks against the vertices sharing
//     a cell (snh_stencil_assemble: a third of the cell matrices' bytes and
//     no gather pass; docs/performance.md, "Multigrid levels as block stencils").
//   - Smoother: Chebyshev of degree k over block-Jacobi (solver/linear/chebyshev.h:
//     first kind on [0.1, 1.1] * lambda_max(D^-1 A), or Lottes' fourth kind
//     on [0, 1.1] * lambda_max; lambda_max by power iteration per level and
//     linearization: 10 steps the first time, then 2 from the last
//     estimate); the same before and after the coarse correction, so the
//     V-cycle is symmetric. On the assembled levels one kernel per degree
//     does the product, the residual, the block-Jacobi solve and both
//     updates (snh_chebyshev_step; docs/performance.md, "One Chebyshev kernel
//     per degree").
//   - Coarsest level: assembled and factored (sparse LDL^T, Eigen) on the
//     host; where that factor is not positive (a true Hessian that is not
//     positive definite there) the coarsest level is smoothed instead. Or
//     (MultigridOptions::coarse_solve_on_device) solved approximately on the
//     device by a first-kind Chebyshev polynomial of degree 8 on [1.1
//     lambda / 60, 1.1 lambda]: no factor, no read in a V-cycle.
//   - Set-up reads: every estimated level's lambda_max together in one read,
//     and with the host's coarsest solve the coarsest cell matrices: two per
//     build whatever the levels, one with the device's coarsest solve.
//   - Reuse (MultigridRebuild below): the operators built at one Newton
//     linearization serve the next few; in between a current fine level
//     follows the new fine operator, its Chebyshev bound re-estimated.
//   - Float cycle (MultigridOptions::float_cycle; double solves with a
//     built fine level): the V-cycle's vectors, stencils, inverse blocks,
//     masks and transfer weights in float, the builds above in double, the
//     residual narrowed at entry and the correction widened at exit (faster
//     to apply, the same CG count: docs/performance.md, "V-cycle in float").
// Constrained DOFs stay exactly zero on every level (masked transfers).
#pragma once

#include <cmath>
#include <memory>
#include <vector>

#include "solver/model/elastic_model.h"
#include "solver/multigrid/lattice_hierarchy.h"

namespace snh::solver {

// Inertia, obstacle contact or barrier self-contact: per-vertex terms in the
// fine operator (the barrier's diagonal blocks), which a built fine level
// does not carry (MultigridFineLevel).
inline bool has_vertex_terms(const ModelTerms& terms) {
  return terms.inertia || terms.obstacles > 0 || terms.self_barrier;
}

// MultigridOptions::rebuild_every, unset resolved: 2 when each load step
// rebuilds (quasistatic), else 4 (dynamics, whose time steps carry the
// hierarchy), each measured the faster there with the fine level built or
// current alike (docs/performance.md, "Multigrid rebuilds (rebuild_every)").
inline int resolved_rebuild_every(const MultigridOptions& options) {
  if (options.rebuild_every) return *options.rebuild_every;
  return options.rebuild_each_load_step.value_or(true) ? 2 : 4;
}

// When the multigrid's operators are rebuilt (MultigridOptions::rebuild_every
// and rebuild_growth): at a load step's first linearization, at a projected
// linearization after rebuild_every linearizations in all, and at the next
// one after a CG solve that did not reach its tolerance or converged at less
// than 1 / rebuild_growth of the rate of the first solve after the build. The
// rate is decades of relative residual per CG iteration, which unlike the
// iteration count does not follow the forcing term's tolerance; solves of a
// single iteration (a loose tolerance met by the first step) say little about
// it and are not compared. Builds come from projected linearizations: a true
// Hessian (adaptive mode) reuses the last build, which is positive definite,
// unless there is none. rebuild_every 1 builds at every linearization,
// projected or not. With obstacles the caller also invalidates the build when
// the set of vertices in contact changed since it, and with friction at each
// new step (solver/newton/device_problem.h). Not when barrier self-contact's pairs
// within dhat change: that measured no better than refreshing the fine
// smoother's blocks alone (update_fine_bound, docs/performance.md). Host
// bookkeeping only.
class MultigridRebuild {
 public:
  explicit MultigridRebuild(const MultigridOptions& options)
      : every_(resolved_rebuild_every(options)),
        growth_(options.rebuild_growth),
        each_step_(options.rebuild_each_load_step.value_or(true)) {}
  // Whether a linearization (projected or true Hessian) must rebuild.
  bool due(bool projected) const {
    if (every_ <= 1 || builds_ == 0 || restart_ || (!built_projected_ && projected)) return true;
    return projected && (stale_ || uses_ >= every_);
  }
  // The linearization rebuilt the hierarchy.
  void built(bool projected) {
    built_projected_ = projected;
    stale_ = false;
    restart_ = false;
    uses_ = 1;
    baseline_ = 0.0;
    ++builds_;
  }
  void reused() { ++uses_; }
  // A CG solve with this build ended after `iterations` at relative residual
  // `relative_residual`; `converged`: it reached its tolerance.
  void solved(int iterations, double relative_residual, bool converged) {
    if (builds_ == 0) return;
    if (!converged) {
      stale_ = true;
      return;
    }
    if (iterations < 2 || !(relative_residual > 0.0) || !std::isfinite(relative_residual)) return;
    const double rate = -std::log10(relative_residual) / iterations;
    if (baseline_ == 0.0)
      baseline_ = rate;
    else if (rate * growth_ < baseline_)
      stale_ = true;
  }
  void new_step() {
    if (each_step_) stale_ = true;
  }
  // The operator's per-vertex terms changed under the build (obstacle
  // contacts entering or leaving, friction re-lagged): rebuild at the next
  // projected linearization.
  void invalidate() { stale_ = true; }
  // Rebuild at the next linearization, whatever it is, as the first one does.
  void restart() { restart_ = true; }
  int builds() const { return builds_; }

 private:
  int every_;
  double growth_;
  bool each_step_;
  bool built_projected_ = false, stale_ = false, restart_ = false;
  int uses_ = 0, builds_ = 0;
  double baseline_ = 0.0;  // the rate of the first compared solve after the build (0: none yet)
};

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

  // After model.linearize() and, unless fine_level_built(),
  // model.setup_preconditioner(): coarse operators, smoother bounds, the
  // coarsest factorization.
  void setup();
  // After model.linearize() alone, keeping the hierarchy of the last
  // setup(): a current fine level follows the new fine operator (its
  // Chebyshev bound re-estimated, and with barrier self-contact its
  // block-Jacobi blocks too: model.setup_preconditioner()); a built one
  // keeps the build's.
  void update_fine_bound();
  // The next setup() estimates every smoothing bound from the fixed start
  // vector, as the first one does, instead of from the last estimate.
  void forget_estimates();
  // Whether the fine level is the build's element matrices (then the
  // model's block-Jacobi blocks are not used: setup() needs only
  // model.linearize()).
  bool fine_level_built() const;
  // Whether the V-cycle runs in float inside a double solve
  // (MultigridOptions::float_cycle with a built fine level).
  bool float_cycle() const;
  // z <- V-cycle applied to z (z holds the residual; constrained entries 0).
  void apply(VectorBase& z) const;

  const LatticeHierarchy& hierarchy() const;
  // The options as used: the smoothing resolved (resolved_smoothing) from
  // the mesh's DOFs and the model's largest Poisson ratio.
  const MultigridOptions& options() const;
  int levels() const;
  // The cell matrices of a level (tests), column-major 24x24 each: level >= 1,
  // or the fine level when built (fine_level_float: float's values).
  std::vector<Real> level_matrices(int level) const;
  // y <- the operator of a level times p, as the V-cycle applies it (tests;
  // a float cycle's product of p rounded to float, widened back).
  void level_product(int level, const VectorBase& p, VectorBase& y) const;
  // lambda_max(D^-1 A) estimated for each level at the last setup().
  std::vector<double> eigenvalue_estimates() const;
  size_t memory_bytes() const;

  // The levels and the V-cycle in the cycle's precision (multigrid.cpp).
  class Cycle;

 private:
  std::unique_ptr<Cycle> cycle_;
};

}  // namespace snh::solver
