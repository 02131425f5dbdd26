// The elastic operator on the device: one mesh's element data
// (solver/model/element_data.h) and its materials (one, or one per region), with
// energy, forces, residual, linearization and the dispatch of the Hessian
// products (solver/model/product_variants.h) and the per-vertex terms
// (solver/model/vertex_terms.h, solver/contact/self_contact_terms.h), operating on
// ViennaCL vectors so that ViennaCL's CG can drive the matrix-free product.
// Internal to the library.
#pragma once

#include <cstdint>
#include <memory>
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
  SelfBroadPhase self_broad_phase = SelfBroadPhase::automatic;   // its candidate pairs' (BarrierTerms)
  PointDataLayout hex8_point_data = PointDataLayout::automatic;  // SNH_POINT_MAJOR, SNH_CACHE_TILE (tet4 too)
};

// Contact with the obstacles, and self-contact, at some x.
struct ContactState {
  int contacts = 0;                   // vertices with g = thickness - phi > 0
  double max_penetration = 0.0;       // the largest g (0: none)
  int self_contacts = 0;              // surface vertices in self-contact (detected at x)
  double max_self_penetration = 0.0;  // their largest spring length (0: none)
};

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
  // The obstacles placed for the coming solve (ModelTerms::obstacles records
  // of solver/contact/obstacles.h) and the penalty's stiffness and thickness: the
  // energy gains sum over vertices of their contact energy, the residual
  // their contact force, the Hessian their Gauss-Newton blocks.
  void set_obstacles(const std::vector<double>& records, double stiffness, double thickness);
  // An embedded surface's points join the obstacle contact (VertexTerms).
  void set_contact_surface(const ContactSurface& surface);
  // Friction (ModelTerms::friction) for the coming solve: the step's start
  // positions (xyz per vertex), the anchors (xyz per vertex and obstacle,
  // vertex-major), the obstacles' records at the step's start, their
  // friction records (solver/contact/obstacles.h) and the slip eps > 0. The energy,
  // residual and Hessian blocks gain the lagged friction potential.
  void set_friction(const std::vector<double>& start_positions, const std::vector<double>& anchors,
                    const std::vector<double>& start_records, const std::vector<double>& friction_records, double slip);
  // After the solve, at its end x: the anchors for the next step
  // (kernels/contact/obstacle.h, obstacle_friction_anchor), same layout.
  std::vector<double> next_friction_anchors(const VectorBase& x);
  ContactState contact_state(const VectorBase& x);
  // The vertices in an obstacle's contact layer at the last linearize(), as
  // a hash of their indices (0: none, or no obstacles): where it changes, so
  // do the per-vertex contact blocks of the Hessian (the multigrid's reuse
  // rule, solver/newton/device_problem.h). One read of two integers where the
  // device has fp64 (VertexTerms::contact_set_signature).
  uint64_t contact_set_signature();
  // Self-contact (ModelTerms::self_contact): the springs' stiffness, and the
  // active set detected at x, frozen until the next refresh (energy,
  // residual, products and preconditioner all use it). Within a step
  // (new_step false) a sample still in contact keeps the spring it had.
  // Returns whether the set changed. contact_state(x) refreshes it at x.
  void set_self_contact_stiffness(double stiffness);
  bool refresh_self_contact(const VectorBase& x, bool new_step = false);
  const std::vector<SelfContactPair>& self_contacts() const;
  const SelfContactDetector* self_contact_detector() const {
    return self_contact_ ? &self_contact_->detector() : nullptr;
  }
  // Barrier self-contact (ModelTerms::self_barrier): its dhat and kappa
  // (snh::Error without the term or for values not finite and > 0). The
  // energy, residual, linearization, products and block-Jacobi then carry
  // kappa sum b over the surface pairs within dhat, detected at each x.
  void set_self_barrier(double dhat, double kappa);
  // Barrier self-contact on a surface carried by the mesh's cells
  // (ContactOptions::self_surface) instead of its boundary.
  void set_self_barrier_surface(const Mesh& mesh, const TriangleSurface& surface, const Embedding& embedding);
  // The largest alpha <= 1 that continuous collision detection clears along
  // x + alpha p; infinity without barrier self-contact.
  double step_bound(const VectorBase& x, const VectorBase& p);
  // Null without barrier self-contact.
  const BarrierTerms<Real>* self_barrier() const { return barrier_.get(); }

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

  std::string specialization() const { return data_.config.defines(); }
  // The build (device/kernel_config.h) and the specialization a result
  // reports: specialization() and the precision (-DSNH_DOUBLE).
  const device::KernelConfig& kernel_config() const { return data_.config; }
  std::string kernel_report() const {
    device::KernelConfig c = data_.config;
    c.precision = data_.cl.precision();
    return c.report();
  }
  // The same switches without the per-vertex terms (inertia, obstacles,
  // friction, self-contact): the builds of a multigrid's coarse levels,
  // whose cell matrices carry those terms already.
  std::string elastic_specialization() const { return data_.elastic_config.defines(); }
  const device::KernelConfig& elastic_kernel_config() const { return data_.elastic_config; }
  // What the multigrid preconditioner reads (solver/multigrid/multigrid.h): the
  // context, the mesh's element and rest-state buffers, the linearization
  // cache and the constraint mask (host copy and buffer).
  device::OpenClContext& context() const { return data_.cl; }
  cl_mem elements_buffer() const { return data_.elements.get(); }
  cl_mem gradients_buffer() const { return data_.gradients.get(); }
  cl_mem weights_buffer() const { return data_.weights.get(); }
  cl_mem cache_buffer() const { return data_.cache.get(); }
  // The cache's size in values: 30 per quadrature point (kernels/fem/element.h),
  // with the elements rounded up to whole tiles in the tiled layout.
  size_t cache_values() const { return data_.cache_values(); }
  // Elements per tile of the cache: 1, or 32 in the tiled layout.
  size_t cache_tile() const { return data_.cache_tile; }
  // Vertices per tile of the block stencils (the multigrid's levels read
  // this model's defines): the same.
  size_t stencil_tile() const { return data_.cache_tile; }
  // The per-element matrices of the last linearize() (element_matrices and
  // assembled variants), else null.
  cl_mem element_matrices_buffer() const { return products_->element_matrices_buffer(); }
  size_t element_count() const { return data_.element_count; }
  // The element matrices of the last linearize() (projected or true, as
  // linearized) and their 3x3 diagonal blocks into caller-owned buffers
  // (element_count() * (3N)^2 and * 9N reals; column-major, as
  // snh_element_matrices writes them), whatever the product variant. With
  // single_precision (double builds), the matrices in float, exactly
  // symmetric (kernels/fem/element.h, SNH_MATRIX_FLOAT); the blocks stay in
  // the working precision. With float products on (the cached variant)
  // those float matrices are computed in float from the cache's float copy
  // (SNH_MIXED; multigrid's built fine level).
  void element_matrices_into(cl_mem matrices, cl_mem diagonal_blocks, bool single_precision = false) const {
    products_->element_matrices_into(matrices, diagonal_blocks, single_precision, projected_ != 0);
  }
  // The per-vertex terms a multigrid's coarse levels take in (solver/multigrid/multigrid.h):
  // the terms built in, the elastic energy's scale (implicit Euler's), the
  // inertia coefficients c_v (null without inertia) and the obstacle
  // contact (and friction) 3x3 blocks of the last linearize() (null without
  // obstacles).
  const ModelTerms& terms() const { return terms_; }
  double elastic_scale() const { return elastic_scale_; }
  // The largest small-strain Poisson's ratio over the materials the mesh's
  // elements use (snh::max_poisson_ratio).
  double max_poisson_ratio() const { return max_poisson_ratio_; }
  cl_mem inertia_buffer() const { return vertex_terms_ ? vertex_terms_->inertia_buffer() : nullptr; }
  cl_mem contact_blocks_buffer() const { return vertex_terms_ ? vertex_terms_->contact_blocks_buffer() : nullptr; }
  ProductVariant variant() const { return products_->variant(); }
  // Takes effect at the next linearize(). `automatic` is not accepted here.
  void set_variant(ProductVariant v);
  // Per-point lanes (kernels/fem_lanes.cl): the linearization, the
  // recompute product, the element matrices, block-Jacobi's element blocks
  // and (float) the cached product over 8-wide vectors, a lane per quadrature point of a
  // hex8 element or per tet4 element, the scalar kernels' results bit for
  // bit on pocl (but for exp's rounding; NVIDIA's compiler rounds the two
  // programs' float differently, by a few ulps). On by default on CPU
  // devices (where pocl leaves the scalar kernels' per-point math
  // unvectorized), off on GPUs. Not available with the tiled cache
  // (PointDataLayout, the GPUs' default) or for tet4 meshes with
  // materials per region (throws snh::Error).
  void set_point_lanes(bool on);
  bool point_lanes() const { return data_.point_lanes; }
  // With point lanes on: the width of the kernels that evaluate the
  // material (the linearization and the recompute product), 8 or 16 lanes
  // (a work-item per 2 hex8 elements or 16 tet4 ones); the kernels that
  // read the cache keep 8. set_point_lanes picks default_material_lanes();
  // 16 on hex8 meshes with materials per region throws snh::Error. 0 with
  // lanes off.
  void set_material_lanes(int lanes);
  int material_lanes() const { return material_lanes_; }
  int default_material_lanes() const;
  // Mixed precision, double models with the cached or the assembled
  // variant: CG's products in float. Cached (kernels/snh_portable.h,
  // SNH_MIXED): each linearize() writes its cache's float copy too (the rest
  // gradients and weights are narrowed once, here); the product reads p and
  // writes its per-element values in double. Assembled: each linearize()
  // narrows the assembled blocks to float, and the stencil product reads
  // them with double p and y (SNH_MATRIX_FLOAT). The gather, the vertex
  // terms, the energy, the residual, the linearization and the
  // preconditioners keep double. A float model, or another variant, keeps
  // its products in the working precision.
  void set_float_products(bool on);
  // Whether the products run in float now (set, a double model, the cached
  // or assembled variant).
  bool float_products() const { return products_->float_products(); }
  bool point_lanes_available() const;
  // The element-matrices product with a work-item per matrix row instead of
  // per element (fem.cl, snh_element_matrix_product_rows): coalesced reads
  // on GPUs, where it is the default; the same values.
  void set_matrix_product_rows(bool on) { products_->set_matrix_product_rows(on); }
  bool matrix_product_rows() const { return products_->matrix_product_rows(); }
  // The lanes program and the value-major hex8 point data (PointDataLayout)
  // are the defaults on CPU devices.
  bool lanes_by_default() const { return !data_.cl.info().is_gpu; }
  // Device memory the current variant holds beyond the mesh and vectors:
  // the linearization cache, element matrices or assembled matrix.
  size_t variant_memory_bytes() const { return products_->variant_memory_bytes(); }
  // Seconds the last linearize() spent assembling the block stencil (its
  // tables too, the first time); 0 for other variants.
  double last_assembly_seconds() const { return products_->last_assembly_seconds(); }
  // The assembled operator's 3x3 blocks stored per vertex (0 before the
  // first assembly): the most vertices any vertex shares an element with,
  // plus one (kernels/fem/block_stencil.h).
  int assembled_width() const { return products_->assembled_width(); }
  // The blocks each vertex reads as the transposes of its neighbours' (the
  // upper layout, per-vertex blocks on CPUs: solver/model/block_stencil.h), else
  // 0; and the blocks stored (padding and the upper layout's zero block
  // included).
  int assembled_lower() const { return products_->assembled_lower(); }
  size_t assembled_blocks() const { return products_->assembled_blocks(); }
  // Device memory of every buffer the model holds: mesh, rest state,
  // material, scratch, preconditioner and variant_memory_bytes(); not the
  // solver's vectors.
  size_t memory_bytes() const;

  // Where this model's solves spend their time (device/phase_profile.h); the
  // model charges its own work, its users (DeviceProblem) theirs.
  PhaseProfiler& profiler() const { return profiler_; }
  // Sums and minima of device vectors (solver/linear/device_reduction.h).
  const DeviceReduction& reduction() const { return reduction_; }

 private:
  // hex8 elements with their own materials: a lanes work-item holds one.
  bool hex8_materials_per_element() const { return data_.nodes == 8 && material_.per_element(); }
  // Per-element elastic forces at x into the element scratch (before the gather).
  void run_forces_kernel(const VectorBase& x) const;
  // vertex_mode: 0 none, 1 residual terms of u = x, 2 product terms of u = p
  // (fem.cl, snh_gather_vectors); scale multiplies the element values.
  void gather(const device::Buffer& element_values, VectorBase& out, bool external, const VectorBase* u = nullptr,
              int vertex_mode = 0, double scale = 1.0) const;
  // Runs snh_contact_vertices at x (energy, force, blocks, depth per vertex).
  void contact(const VectorBase& x, bool linearization = false) const;
  bool vertex_terms() const { return terms_.inertia || terms_.obstacles > 0 || terms_.self_contact; }
  // d_c = a_c^T u for the frozen set (before a gather that uses them).
  void self_differences(const VectorBase& u) const;

  ElementData<Real> data_;
  mutable PhaseProfiler profiler_;
  DeviceReduction reduction_;
  device::MaterialArgs<Real> material_;
  int material_lanes_ = 0;  // set_material_lanes
  device::Buffer external_, energies_, min_j_;
  bool has_external_ = false;
  int projected_ = 1;
  double last_min_j_ = 0.0;
  std::vector<double> external_host_;
  device::Buffer external_work_;  // external_host_ on the device, for the energy's work term
  ModelTerms terms_;
  double elastic_scale_ = 1.0;
  double max_poisson_ratio_ = 0.0;
  double elastic_magnitude_ = 0.0, last_energy_magnitude_ = 0.0;
  Vector linearized_x_;
  device::Kernel energy_k_, forces_k_, linearize_k_, diagonal_k_, gather_k_, mask_k_;
  // The Hessian products and what they store.
  std::unique_ptr<ProductVariants<Real>> products_;
  // Inertia, obstacles and friction (null without inertia and obstacles).
  std::unique_ptr<VertexTerms<Real>> vertex_terms_;
  // Self-contact (ModelTerms::self_contact; null without): detector, frozen
  // set and its device arrays.
  std::unique_ptr<SelfContactTerms<Real>> self_contact_;
  // Barrier self-contact (ModelTerms::self_barrier; null without).
  std::unique_ptr<BarrierTerms<Real>> barrier_;
  std::vector<double> host_positions(const VectorBase& x) const;
  // Block-Jacobi's inverted blocks and kernels (setup_preconditioner).
  std::unique_ptr<BlockJacobi<Real>> block_jacobi_;
};

}  // namespace snh::solver
