// The elastic operator on the device: one mesh's element data
// (solver/model/element_data.h) and its materials (one, or one per region), with
// energy, forces, residual, linearization and the dispatch of the Hessian
// products (solver/model/product_variants.h) and the per-vertex terms
// (solver/model/vertex_terms.h, solver/contact/self_contact_terms.h,
// solver/contact/barrier_terms.h), operating on ViennaCL vectors so that
// ViennaCL's CG can drive the matrix-free product. Its users reach the
// element data, the products, the lanes setting (solver/model/point_lanes.h)
// and the contact (solver/model/model_contact.h) through their own faces:
// data(), products(), lanes() and contact(). Internal to the library.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "device/kernel_args.h"
#include "device/material_args.h"
#include "device/opencl_context.h"
#include "device/phase_profile.h"
#include "fem/rest_state.h"
#include "snh/material.h"
#include "snh/mesh.h"
#include "snh/regions.h"
#include "snh/simulation.h"
#include "solver/contact/barrier_terms.h"
#include "solver/contact/self_contact.h"
#include "solver/contact/self_contact_terms.h"
#include "solver/linear/block_jacobi.h"
#include "solver/linear/device_reduction.h"
#include "solver/model/block_stencil.h"
#include "solver/model/element_data.h"
#include "solver/model/model_contact.h"
#include "solver/model/point_lanes.h"
#include "solver/model/product_variants.h"
#include "solver/model/vertex_terms.h"
#include "viennacl/vector.hpp"

namespace snh::solver {

// The OpenCL buffer under a ViennaCL vector (to pass it to our kernels).
template <typename Real>
cl_mem mem(const viennacl::vector_base<Real>& v) {
  return v.handle().opencl_handle().get();
}

// How a mesh's per-point data, its linearization cache
// (kernels/fem/element.h) and, for hex8, its rest gradients
// (kernels/fem/element_data.h), are laid out on the device. tet4 meshes have
// one point per element: value-major and point-major coincide for them.
enum class PointDataLayout {
  automatic,    // value-major on devices where the lanes program is the default (CPUs), else tiled
  value_major,  // per element, value k of point q at 240 e + 8 k + q (gradients 192 e + 8 k + q): one vector
                // load per value for the lanes program
  point_major,  // value k of point P at 30 P + k (gradients 24 P + k), SNH_POINT_MAJOR: a work-item reads its
                // element's points in turn
  tiled,        // the cache in tiles of 32 elements, value k of point q of element e at
                // 30 Q 32 (e / 32) + 32 (30 q + k) + e % 32 (SNH_CACHE_TILE; hex8 gradients point-major), and
                // the block stencils (assembled variant, multigrid levels) in tiles of 32 vertices
                // (SNH_STENCIL_TILE, kernels/fem/block_stencil.h): the scalar kernels' consecutive
                // work-items read consecutive words; not for the lanes program
};

// Terms beyond elasticity that a scene compiles into the kernels (printed in
// the kernel specialization): only what it uses; and the layout of the
// per-point data they read.
struct ModelTerms {
  bool inertia = false;       // implicit Euler's inertia (SNH_INERTIA)
  int obstacles = 0;          // kinematic obstacles' contact penalty (SNH_OBSTACLES)
  bool self_contact = false;  // self-collision springs (SNH_SELF_CONTACT, solver/contact/self_contact.h)
  bool friction = false;      // lagged Coulomb friction against the obstacles (SNH_FRICTION)
  bool self_barrier = false;  // barrier self-contact (SNH_SELF_BARRIER, solver/contact/barrier_terms.h)
  std::optional<SelfBroadPhase> self_broad_phase;                // its candidate pairs' (BarrierTerms)
  PointDataLayout hex8_point_data = PointDataLayout::automatic;  // SNH_POINT_MAJOR, SNH_CACHE_TILE (tet4 too)
};

// The terms a simulation with these options builds its model with.
ModelTerms model_terms(const SolveOptions& options);

template <typename Real>
class ElasticModel {
 public:
  using Vector = viennacl::vector<Real>;
  using VectorBase = viennacl::vector_base<Real>;

  // build: how much of the material the kernels fix at build time (see
  // device::MaterialKernel; the engine uses `specialized`). A map with
  // regions builds the SNH_REGIONS kernels (device::material_defines).
  // Throws snh::Error when the map does not fit the mesh.
  ElasticModel(device::OpenClContext& cl, const Mesh& mesh, const fem::RestState& rest, const MaterialMap& materials,
               ProductVariant variant, device::MaterialKernel build = device::MaterialKernel::specialized,
               const ModelTerms& terms = {});

  size_t dofs() const { return data_.dofs(); }
  // 1 for free DOFs, 0 for constrained ones (xyz per vertex).
  void set_mask(const std::vector<Real>& mask);
  // Lumped external force, xyz per vertex; empty for none.
  void set_external_force(const std::vector<double>& force);
  // Implicit Euler's terms (ModelTerms::inertia): the energy becomes
  //   elastic_scale * Psi(x) + 1/2 sum_v c_v |x_v - y_v|^2 - f^T x,
  // c_v = coefficient (per vertex, c m_v), y = target (xyz per vertex); the
  // Hessian elastic_scale * K + diag(c_v). snh::Error without the term.
  void set_inertia(const std::vector<double>& coefficient, const std::vector<double>& target, double elastic_scale);
  // -dPsi/dx at x, masked, without external force, inertia or scale.
  void elastic_forces(const VectorBase& x, VectorBase& out);
  // Total potential energy: elastic energy minus external work, summed on the
  // host in double and in element order. Non-finite when any element's is.
  double energy(const VectorBase& x);
  // The smallest J over all quadrature points at the x of the last energy().
  double last_min_j() const { return last_min_j_; }
  // The size of the terms the last energy() summed, for its rounding: the
  // elastic part's sum over elements of (|mu| + |lambda|) V (a material's
  // energy sums terms of that size, e.g. mu/2 (I_C - 3) with I_C ~ 3, even
  // where the total is small) times the elastic scale, plus sum |f_i x_i|.
  double last_energy_magnitude() const { return last_energy_magnitude_; }
  // r = mask * (elastic forces + external force) = -mask * dE/dx.
  void residual(const VectorBase& x, VectorBase& r);
  // The per-Newton linearization at x (SVD and eigensystem per point),
  // clamped to PSD when `projected`, else the true Hessian.
  void linearize(const VectorBase& x, bool projected = true);
  // y = mask * K p, K the (projected) stiffness at the linearized x.
  void product(const VectorBase& p, VectorBase& y) const;
  // Block-Jacobi preconditioner from the current linearization: the 3x3
  // diagonal blocks of the projected Hessian (of the element matrices when
  // the variant keeps them and the linearization is projected, else
  // recomputed from the cache and projected).
  void setup_preconditioner();
  void apply_preconditioner(VectorBase& z) const;  // z <- M^-1 z
  // The preconditioner's inverted 3x3 blocks, column-major per vertex (tests).
  std::vector<Real> preconditioner_blocks() const;

  // The mesh's device data and builds (solver/model/element_data.h), and
  // their context: the model's specialization (data().config.defines()),
  // what a result reports (data().kernel_report()), and what the multigrid
  // preconditioner reads (solver/multigrid/multigrid.h): the context, the
  // element and rest-state buffers, the linearization cache and its tiles,
  // the builds with and without the per-vertex terms.
  const ElementData<Real>& data() const { return data_; }
  device::OpenClContext& context() const { return data_.cl; }
  // The Hessian products and what they store (solver/model/product_variants.h):
  // the variant, float products, the element matrices and the assembly.
  ProductVariants<Real>& products() { return *products_; }
  // Per-point lanes and the material lanes (solver/model/point_lanes.h).
  PointLanes<Real>& lanes() { return *lanes_; }
  // Obstacles, friction, the contact surface, penalty and barrier
  // self-contact: their settings for the coming solve and what they find
  // (solver/model/model_contact.h).
  ModelContact<Real>& contact() { return *contact_; }
  // The per-vertex terms a multigrid's coarse levels take in (solver/multigrid/multigrid.h):
  // the terms built in, the elastic energy's scale (implicit Euler's) and
  // the inertia coefficients c_v (null without inertia); the obstacle
  // contact blocks are contact()'s.
  const ModelTerms& terms() const { return terms_; }
  double elastic_scale() const { return elastic_scale_; }
  // The largest small-strain Poisson's ratio over the materials the mesh's
  // elements use (snh::max_poisson_ratio).
  double max_poisson_ratio() const { return max_poisson_ratio_; }
  cl_mem inertia_buffer() const { return vertex_terms_ ? vertex_terms_->inertia_buffer() : nullptr; }
  // Device memory of every buffer the model holds: mesh, rest state,
  // material, scratch, preconditioner and the products'
  // (ProductVariants::memory_bytes); not the solver's vectors.
  size_t memory_bytes() const;

  // Where this model's solves spend their time (device/phase_profile.h); the
  // model charges its own work, its users (DeviceProblem) theirs.
  PhaseProfiler& profiler() const { return profiler_; }
  // Sums and minima of device vectors (solver/linear/device_reduction.h).
  const DeviceReduction& reduction() const { return reduction_; }

 private:
  // Per-element elastic forces at x into the element scratch (before the gather).
  void run_forces_kernel(const VectorBase& x) const;
  // vertex_mode: 0 none, 1 residual terms of u = x, 2 product terms of u = p
  // (fem.cl, snh_gather_vectors); scale multiplies the element values.
  void gather(const device::Buffer& element_values, VectorBase& out, bool external, const VectorBase* u = nullptr,
              int vertex_mode = 0, double scale = 1.0) const;
  bool vertex_terms() const { return terms_.inertia || terms_.obstacles > 0 || terms_.self_contact; }

  ElementData<Real> data_;
  mutable PhaseProfiler profiler_;
  DeviceReduction reduction_;
  device::MaterialArgs<Real> material_;
  device::Buffer external_, energies_, min_j_;
  bool has_external_ = false;
  double last_min_j_ = 0.0;
  std::vector<double> external_host_;
  device::Buffer external_work_;  // external_host_ on the device, for the energy's work term
  ModelTerms terms_;
  double elastic_scale_ = 1.0;
  double max_poisson_ratio_ = 0.0;
  double elastic_magnitude_ = 0.0, last_energy_magnitude_ = 0.0;
  Vector linearized_x_;
  device::Kernel energy_k_, forces_k_, gather_k_, mask_k_;
  // The Hessian products and what they store.
  std::unique_ptr<ProductVariants<Real>> products_;
  // The lanes setting, and the linearization's and element diagonal's
  // kernels it picks.
  std::unique_ptr<PointLanes<Real>> lanes_;
  // Inertia, obstacles and friction (null without inertia and obstacles).
  std::unique_ptr<VertexTerms<Real>> vertex_terms_;
  // Self-contact (ModelTerms::self_contact; null without): detector, frozen
  // set and its device arrays.
  std::unique_ptr<SelfContactTerms<Real>> self_contact_;
  // Barrier self-contact (ModelTerms::self_barrier; null without).
  std::unique_ptr<BarrierTerms<Real>> barrier_;
  // The contact's face over vertex_terms_, self_contact_ and barrier_.
  std::unique_ptr<ModelContact<Real>> contact_;
  // Block-Jacobi's inverted blocks and kernels (setup_preconditioner).
  std::unique_ptr<BlockJacobi<Real>> block_jacobi_;
};

}  // namespace snh::solver
