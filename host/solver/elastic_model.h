// The elastic model on the device: buffers of one mesh and its materials
// (one, or one per region) and the kernels of kernels/fem.cl, operating on
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
#include "fem/rest_state.h"
#include "snh/material.h"
#include "snh/mesh.h"
#include "snh/regions.h"
#include "snh/simulation.h"
#include "solver/block_jacobi.h"
#include "solver/block_stencil.h"
#include "solver/device_reduction.h"
#include "solver/phase_profile.h"
#include "solver/self_contact.h"
#include "solver/self_contact_terms.h"
#include "solver/vertex_terms.h"
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
  bool self_contact = false;  // self-collision springs (SNH_SELF_CONTACT, solver/self_contact.h)
  bool friction = false;      // lagged Coulomb friction against the obstacles (SNH_FRICTION)
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

  size_t dofs() const { return 3 * vertex_count_; }
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
  // of solver/obstacles.h) and the penalty's stiffness and thickness: the
  // energy gains sum over vertices of their contact energy, the residual
  // their contact force, the Hessian their Gauss-Newton blocks.
  void set_obstacles(const std::vector<double>& records, double stiffness, double thickness);
  // An embedded surface's points join the obstacle contact (VertexTerms).
  void set_contact_surface(const ContactSurface& surface);
  // Friction (ModelTerms::friction) for the coming solve: the step's start
  // positions (xyz per vertex), the anchors (xyz per vertex and obstacle,
  // vertex-major), the obstacles' records at the step's start, their
  // friction records (solver/obstacles.h) and the slip eps > 0. The energy,
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
  // rule, solver/device_problem.h). Reads the depths back from the device.
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

  std::string specialization() const { return defines_; }
  // The same switches without the per-vertex terms (inertia, obstacles,
  // friction, self-contact): the builds of a multigrid's coarse levels,
  // whose cell matrices carry those terms already.
  std::string elastic_specialization() const { return elastic_defines_; }
  // What the multigrid preconditioner reads (solver/multigrid.h): the
  // context, the mesh's element and rest-state buffers, the linearization
  // cache and the constraint mask (host copy and buffer).
  device::OpenClContext& context() const { return cl_; }
  cl_mem elements_buffer() const { return elements_.get(); }
  cl_mem gradients_buffer() const { return gradients_.get(); }
  cl_mem weights_buffer() const { return weights_.get(); }
  cl_mem cache_buffer() const { return cache_.get(); }
  // The cache's size in values: 30 per quadrature point (kernels/fem/element.h),
  // with the elements rounded up to whole tiles in the tiled layout.
  size_t cache_values() const {
    return (element_count_ + cache_tile_ - 1) / cache_tile_ * cache_tile_ * quadrature_ * 30;
  }
  // Elements per tile of the cache: 1, or 32 in the tiled layout.
  size_t cache_tile() const { return cache_tile_; }
  // Vertices per tile of the block stencils (the multigrid's levels read
  // this model's defines): the same.
  size_t stencil_tile() const { return cache_tile_; }
  // The per-element matrices of the last linearize() (element_matrices and
  // assembled variants), else null.
  cl_mem element_matrices_buffer() const {
    return variant_ == ProductVariant::element_matrices || variant_ == ProductVariant::assembled
               ? element_matrices_.get()
               : nullptr;
  }
  size_t element_count() const { return element_count_; }
  // The element matrices of the last linearize() (projected or true, as
  // linearized) and their 3x3 diagonal blocks into caller-owned buffers
  // (element_count() * (3N)^2 and * 9N reals; column-major, as
  // snh_element_matrices writes them), whatever the product variant. With
  // single_precision (double builds), the matrices in float, exactly
  // symmetric (kernels/fem/element.h, SNH_MATRIX_FLOAT); the blocks stay in
  // the working precision. With float products on (the cached variant)
  // those float matrices are computed in float from the cache's float copy
  // (SNH_MIXED; multigrid's built fine level).
  void element_matrices_into(cl_mem matrices, cl_mem diagonal_blocks, bool single_precision = false) const;
  // The per-vertex terms a multigrid's coarse levels take in (solver/multigrid.h):
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
  ProductVariant variant() const { return variant_; }
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
  bool point_lanes() const { return point_lanes_; }
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
  bool float_products() const {
    return float_products_ && sizeof(Real) > sizeof(float) &&
           (variant_ == ProductVariant::cached || variant_ == ProductVariant::assembled);
  }
  bool point_lanes_available() const;
  // The element-matrices product with a work-item per matrix row instead of
  // per element (fem.cl, snh_element_matrix_product_rows): coalesced reads
  // on GPUs, where it is the default; the same values.
  void set_matrix_product_rows(bool on) { matrix_rows_ = on; }
  bool matrix_product_rows() const { return matrix_rows_; }
  // The lanes program and the value-major hex8 point data (PointDataLayout)
  // are the defaults on CPU devices.
  bool lanes_by_default() const { return !cl_.info().is_gpu; }
  // Device memory the current variant holds beyond the mesh and vectors:
  // the linearization cache, element matrices or assembled matrix.
  size_t variant_memory_bytes() const;
  // Seconds the last linearize() spent assembling the block stencil (its
  // tables too, the first time); 0 for other variants.
  double last_assembly_seconds() const { return last_assembly_seconds_; }
  // The assembled operator's 3x3 blocks stored per vertex (0 before the
  // first assembly): the most vertices any vertex shares an element with,
  // plus one (kernels/fem/block_stencil.h).
  int assembled_width() const { return stencil_width_; }
  // The blocks each vertex reads as the transposes of its neighbours' (the
  // upper layout, per-vertex blocks on CPUs: solver/block_stencil.h), else
  // 0; and the blocks stored (padding and the upper layout's zero block
  // included).
  int assembled_lower() const { return stencil_lower_; }
  size_t assembled_blocks() const { return stencil_values() / 9; }
  // Device memory of every buffer the model holds: mesh, rest state,
  // material, scratch, preconditioner and variant_memory_bytes(); not the
  // solver's vectors.
  size_t memory_bytes() const;

  // Where this model's solves spend their time (solver/phase_profile.h); the
  // model charges its own work, its users (DeviceProblem) theirs.
  PhaseProfiler& profiler() const { return profiler_; }
  // Sums and minima of device vectors (solver/device_reduction.h).
  const DeviceReduction& reduction() const { return reduction_; }

 private:
  void run_element_kernel(cl_kernel k) const;
  // The same for the kernels fem_lanes.cl also has (linearize, cached and
  // recompute products, element matrices, element blocks).
  // lanes: 0 for fem.cl's kernel, else fem_lanes.cl's at that width (a
  // work-item per lanes / quadrature points elements).
  void run_point_kernel(cl_kernel k, int lanes) const;
  // Kernel `name` of the program set_point_lanes chose (fem_lanes.cl at
  // `lanes` lanes, or fem.cl), its defines followed by `extra`.
  device::Kernel point_kernel(const char* name, const std::string& extra = "", int lanes = kCacheLanes) const;
  // The width of the lanes kernels that read the cache (cached product,
  // element matrices, element blocks), whatever material_lanes() is.
  static constexpr int kCacheLanes = 8;
  // hex8 elements with their own materials: a lanes work-item holds one.
  bool hex8_materials_per_element() const { return nodes_ == 8 && material_.per_element(); }
  // Per-element elastic forces at x into element_scratch_ (before the gather).
  void run_forces_kernel(const VectorBase& x) const;
  void compute_element_matrices();
  void assemble();
  // The assembled variant's stencil tables on the device and its kernels,
  // once: made when the variant is chosen, not in the first solve.
  void prepare_stencil();
  // vertex_mode: 0 none, 1 residual terms of u = x, 2 product terms of u = p
  // (fem.cl, snh_gather_vectors); scale multiplies the element values.
  void gather(const device::Buffer& element_values, VectorBase& out, bool external, const VectorBase* u = nullptr,
              int vertex_mode = 0, double scale = 1.0) const;

  device::OpenClContext& cl_;
  mutable PhaseProfiler profiler_;
  DeviceReduction reduction_;
  size_t vertex_count_, element_count_;
  int nodes_, quadrature_;
  device::MaterialArgs<Real> material_;
  ProductVariant variant_;
  std::string defines_, elastic_defines_;
  bool point_lanes_ = false;
  int material_lanes_ = 0;     // set_material_lanes
  size_t cache_tile_ = 1;      // PointDataLayout::tiled: 32
  bool cached_lanes_ = false;  // the cached product's kernel is fem_lanes.cl's
  bool matrix_rows_ = false;   // set_matrix_product_rows
  device::Kernel matrix_rows_k_;
  mutable device::Kernel matrices_float_k_;  // built at its first use
  mutable device::Kernel matrices_mixed_k_;  // the same from the float copies (float products), likewise
  // set_float_products: the SNH_MIXED product, the narrowing kernel and the
  // float copies of the cache, gradients and weights.
  bool float_products_ = false;
  device::Kernel product_float_k_, narrow_k_, stencil_product_float_k_;
  device::Buffer cache_float_, gradients_float_, weights_float_, stencil_float_;
  void make_stencil_float();                                    // the float blocks' buffer and product kernel, once
  void narrow(cl_mem from, size_t values, device::Buffer& to);  // to (made if empty) <- (float)from
  bool float_product_lanes() const;                             // the mixed product runs fem_lanes.cl's kernel
  device::Kernel float_product_kernel() const;                  // the SNH_MIXED cached product
  void prepare_float_products();                                // the above, once float_products() holds
  // The cached variant's products read the float copies now.
  bool float_cache() const { return float_products() && variant_ == ProductVariant::cached; }
  device::Buffer elements_, gradients_, weights_, offsets_, adjacency_, mask_, external_, element_scratch_,
      element_blocks_, cache_, energies_, min_j_, element_matrices_;
  bool has_external_ = false;
  int projected_ = 1;
  double last_assembly_seconds_ = 0.0;
  // Assembled variant: the block stencil (solver/block_stencil.h), assembled
  // on the device from the element matrices in element order
  // (deterministic), and its width.
  device::Buffer stencil_, stencil_neighbours_, stencil_part_offsets_, stencil_parts_;
  device::Kernel stencil_assemble_k_, stencil_product_k_;
  int stencil_width_ = 0, stencil_lower_ = 0;
  // The stencil's stored values (stencil_entries).
  size_t stencil_values() const {
    return stencil_entries(stencil_width_, vertex_count_, stencil_tile(), stencil_lower_);
  }
  size_t stencil_memory_bytes() const;
  // The stencil kernels' build: the model's, with the width made a constant
  // where the layout allows (stencil_width_define).
  std::string stencil_defines() const {
    return elastic_defines_ + stencil_width_define(stencil_width_, stencil_tile(), stencil_lower_);
  }
  std::vector<int> elements_host_;
  double last_min_j_ = 0.0;
  std::vector<double> external_host_;
  ModelTerms terms_;
  // Inertia, obstacles and friction (null without inertia and obstacles).
  std::unique_ptr<VertexTerms<Real>> vertex_terms_;
  double elastic_scale_ = 1.0;
  double max_poisson_ratio_ = 0.0;
  double elastic_magnitude_ = 0.0, last_energy_magnitude_ = 0.0;
  // Runs snh_contact_vertices at x (energy, force, blocks, depth per vertex).
  void contact(const VectorBase& x, bool linearization = false) const;
  bool vertex_terms() const { return terms_.inertia || terms_.obstacles > 0 || terms_.self_contact; }
  // Self-contact (ModelTerms::self_contact; null without): detector, frozen
  // set and its device arrays.
  std::unique_ptr<SelfContactTerms<Real>> self_contact_;
  // d_c = a_c^T u for the frozen set (before a gather that uses them).
  void self_differences(const VectorBase& u) const;
  Vector linearized_x_;
  device::Kernel energy_k_, forces_k_, linearize_k_, product_cached_k_, product_recompute_k_, diagonal_k_, gather_k_,
      matrices_k_, matrix_product_k_, mask_k_;
  // Block-Jacobi's inverted blocks and kernels (setup_preconditioner).
  std::unique_ptr<BlockJacobi<Real>> block_jacobi_;
};

}  // namespace snh::solver
