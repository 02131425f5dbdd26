#include "solver/elastic_model.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "device/material_args.h"
#include "device/readback.h"
#include "fem/vertex_slots.h"
#include "snh/error.h"
#include "viennacl/linalg/prod.hpp"

namespace snh::solver {

namespace {

using device::KernelArgs;

const MaterialMap& validated(const Mesh& mesh, const MaterialMap& map) {
  validate_material_map(mesh, map);
  return map;
}

}  // namespace

template <typename Real>
ElasticModel<Real>::ElasticModel(device::OpenClContext& cl, const Mesh& mesh, const fem::RestState& rest,
                                 const MaterialMap& materials, ProductVariant variant, device::MaterialKernel build,
                                 const ModelTerms& terms)
    : cl_(cl),
      profiler_([&cl] { cl.finish(); }),
      reduction_(cl, sizeof(Real), &profiler_),
      vertex_count_(mesh.vertex_count()),
      element_count_(mesh.element_count()),
      nodes_(rest.nodes),
      quadrature_(rest.quadrature),
      material_(cl, validated(mesh, materials), build),
      variant_(variant),
      max_poisson_ratio_(snh::max_poisson_ratio(materials)),
      linearized_x_(3 * mesh.vertex_count()) {
  // Build-time specialization: only what this scene uses is compiled in.
  defines_ = std::string("-DSNH_HEX8=") + (mesh.type == ElementType::hex8 ? "1" : "0") + " " + material_.defines() +
             " -DSNH_UNIFORM_REST=" + (rest.uniform ? "1" : "0");
  // Every program that reads the cache or the gradients (multigrid.cl and
  // stencil.cl too) builds from these defines, so they all agree on the
  // layout.
  PointDataLayout layout = terms.hex8_point_data;
  if (layout == PointDataLayout::automatic)
    layout = lanes_by_default() ? PointDataLayout::value_major : PointDataLayout::tiled;
  const bool value_major = layout == PointDataLayout::value_major;
  if (mesh.type == ElementType::hex8 && !value_major) defines_ += " -DSNH_POINT_MAJOR=1";
  if (layout == PointDataLayout::tiled) {
    cache_tile_ = 32;
    defines_ +=
        " -DSNH_CACHE_TILE=" + std::to_string(cache_tile_) + " -DSNH_STENCIL_TILE=" + std::to_string(cache_tile_);
  }
  elastic_defines_ = defines_;
  terms_ = terms;
  if (terms.inertia) defines_ += " -DSNH_INERTIA=1";
  if (terms.obstacles > 0) defines_ += " -DSNH_OBSTACLES=" + std::to_string(terms.obstacles);
  if (terms.self_contact) defines_ += " -DSNH_SELF_CONTACT=1";
  if (terms.friction && terms.obstacles == 0) throw Error("solver: friction needs obstacles");
  if (terms.friction) defines_ += " -DSNH_FRICTION=1";

  const fem::VertexSlots slots = fem::vertex_slots(mesh.elements, vertex_count_);

  // The device's gradients value-major per element, [element][3 a + j][q]
  // (kernels/fem/element_data.h): a hex8 element's 8 points of one value
  // are one vector for the lanes kernels; point-major, the host's RestState
  // layout [element][q][a][3], with SNH_POINT_MAJOR.
  const size_t per_point = 3 * static_cast<size_t>(rest.nodes), points = static_cast<size_t>(rest.quadrature);
  std::vector<Real> gradients(rest.gradients.size());
  for (size_t e = 0; e < rest.gradients.size() / (per_point * points); ++e)
    for (size_t q = 0; q < points; ++q)
      for (size_t i = 0; i < per_point; ++i)
        gradients[value_major ? (e * per_point + i) * points + q : (e * points + q) * per_point + i] =
            static_cast<Real>(rest.gradients[(e * points + q) * per_point + i]);
  const std::vector<Real> weights(rest.weights.begin(), rest.weights.end());
  const std::vector<int> elements(mesh.elements.begin(), mesh.elements.end());
  elements_ = cl_.buffer(CL_MEM_READ_ONLY, elements.size() * sizeof(int), elements.data());
  gradients_ = cl_.buffer(CL_MEM_READ_ONLY, gradients.size() * sizeof(Real), gradients.data());
  weights_ = cl_.buffer(CL_MEM_READ_ONLY, weights.size() * sizeof(Real), weights.data());
  offsets_ = cl_.buffer(CL_MEM_READ_ONLY, slots.offsets.size() * sizeof(int), slots.offsets.data());
  adjacency_ = cl_.buffer(CL_MEM_READ_ONLY, slots.adjacency.size() * sizeof(int), slots.adjacency.data());
  const std::vector<Real> ones(dofs(), Real(1));
  mask_ = cl_.buffer(CL_MEM_READ_ONLY, dofs() * sizeof(Real), ones.data());
  external_ = cl_.buffer(CL_MEM_READ_ONLY, dofs() * sizeof(Real));
  element_scratch_ = cl_.buffer(CL_MEM_READ_WRITE, element_count_ * nodes_ * 3 * sizeof(Real));
  element_blocks_ = cl_.buffer(CL_MEM_READ_WRITE, element_count_ * nodes_ * 9 * sizeof(Real));
  cache_ = cl_.buffer(CL_MEM_READ_WRITE, cache_values() * sizeof(Real));
  energies_ = cl_.buffer(CL_MEM_READ_WRITE, element_count_ * sizeof(Real));
  min_j_ = cl_.buffer(CL_MEM_READ_WRITE, element_count_ * sizeof(Real));
  if (terms.inertia || terms.obstacles > 0)
    vertex_terms_ = std::make_unique<VertexTerms<Real>>(cl_, vertex_count_, terms.inertia, terms.obstacles,
                                                        terms.friction, defines_, &profiler_);

  energy_k_ = cl_.kernel("fem.cl", defines_, "snh_element_energy");
  forces_k_ = cl_.kernel("fem.cl", defines_, "snh_element_forces");
  set_point_lanes(point_lanes_available() && lanes_by_default());
  gather_k_ = cl_.kernel("fem.cl", defines_, "snh_gather_vectors");
  block_jacobi_ = std::make_unique<BlockJacobi<Real>>(cl_, vertex_count_, defines_);
  matrix_product_k_ = cl_.kernel("fem.cl", defines_, "snh_element_matrix_product");
  matrix_rows_k_ = cl_.kernel("fem.cl", defines_, "snh_element_matrix_product_rows");
  matrix_rows_ = cl_.info().is_gpu;
  mask_k_ = cl_.kernel("fem.cl", defines_, "snh_apply_mask");
  if (terms.self_contact) self_contact_ = std::make_unique<SelfContactTerms<Real>>(cl_, mesh, defines_, &profiler_);
  elements_host_ = elements;
  for (size_t e = 0; e < element_count_; ++e) {
    const Material& m = materials.of_element(e);
    double volume = 0.0;
    for (int q = 0; q < quadrature_; ++q) volume += rest.weight(e, q);
    elastic_magnitude_ += (std::abs(m.mu) + std::abs(m.lambda)) * volume;
  }
  set_variant(variant);
}

template <typename Real>
void ElasticModel<Real>::set_variant(ProductVariant v) {
  if (v == ProductVariant::automatic) throw Error("solver: resolve ProductVariant::automatic before use");
  variant_ = v;
  const size_t m = static_cast<size_t>(3 * nodes_) * (3 * nodes_);
  if ((v == ProductVariant::element_matrices || v == ProductVariant::assembled) && !element_matrices_)
    element_matrices_ = cl_.buffer(CL_MEM_READ_WRITE, element_count_ * m * sizeof(Real));
  if (v == ProductVariant::assembled) prepare_stencil();
  prepare_float_products();
}

template <typename Real>
bool ElasticModel<Real>::point_lanes_available() const {
  // tet4 lanes hold 8 elements, so they share one material; the lanes read
  // the value-major or point-major cache.
  return cache_tile_ == 1 && (nodes_ == 8 || !material_.per_element());
}

template <typename Real>
void ElasticModel<Real>::set_point_lanes(bool on) {
  if (on && cache_tile_ > 1)
    throw Error(
        "solver: the per-point lanes program reads the value-major or point-major cache, not the tiled one "
        "(PointDataLayout)");
  if (on && !point_lanes_available())
    throw Error("solver: per-point lanes of tet4 meshes need one material for the mesh (this map has regions)");
  point_lanes_ = on;
  set_material_lanes(on ? default_material_lanes() : kCacheLanes);
  // The cached product over lanes in float, and for hex8 in double too (its
  // cache value-major per element: one vector load per value); tet4 in
  // double keeps the scalar kernel, which pocl vectorizes across
  // work-items: the lanes version, gathering each element's 30 cached
  // values into 8-wide vectors, measured 1.8x slower (docs/performance.md).
  cached_lanes_ = on && (sizeof(Real) == sizeof(float) || nodes_ == 8);
  product_cached_k_ = cached_lanes_ ? point_kernel("snh_element_product_cached")
                                    : cl_.kernel("fem.cl", defines_, "snh_element_product_cached");
  if (product_float_k_) product_float_k_ = float_product_kernel();
  matrices_k_ = point_kernel("snh_element_matrices");
  matrices_float_k_ = device::Kernel();
  matrices_mixed_k_ = device::Kernel();
  diagonal_k_ = point_kernel("snh_element_diagonal");
}

template <typename Real>
int ElasticModel<Real>::default_material_lanes() const {
  // Two of the device's native vectors per lane vector where it has 8-wide
  // ones for Real (AVX-512 in double, AVX and up in float): the SVD's chains
  // of dependent square roots and divisions bound one vector's throughput,
  // and a second, independent one fills their latency (twice the elements
  // per work-item). 8 where hex8 elements carry their own material (a
  // work-item's material is one element's).
  const unsigned native =
      sizeof(Real) == sizeof(double) ? cl_.info().native_vector_width_double : cl_.info().native_vector_width_float;
  return native >= 8 && !hex8_materials_per_element() ? 16 : kCacheLanes;
}

template <typename Real>
void ElasticModel<Real>::set_material_lanes(int lanes) {
  if (lanes != 8 && lanes != 16) throw Error("solver: material lanes are 8 or 16, not " + std::to_string(lanes));
  if (lanes == 16 && hex8_materials_per_element())
    throw Error(
        "solver: 16 material lanes hold two hex8 elements, so they need one material for the mesh (this map has "
        "regions)");
  material_lanes_ = point_lanes_ ? lanes : 0;
  linearize_k_ = point_kernel("snh_element_linearize", "", material_lanes_);
  product_recompute_k_ = point_kernel("snh_element_product_recompute", "", material_lanes_);
}

template <typename Real>
void ElasticModel<Real>::set_float_products(bool on) {
  if (sizeof(Real) == sizeof(float) || on == float_products_) return;
  float_products_ = on;
  if (!on) {
    product_float_k_ = device::Kernel();
    stencil_product_float_k_ = device::Kernel();
    cache_float_.reset();
    gradients_float_.reset();
    weights_float_.reset();
    stencil_float_.reset();
    // Blocks assembled in float only: the double ones from the same element
    // matrices.
    if (variant_ == ProductVariant::assembled && stencil_neighbours_ && !stencil_) assemble();
    return;
  }
  prepare_float_products();
}

template <typename Real>
void ElasticModel<Real>::prepare_float_products() {
  // Made when the products first run in float (the cached or assembled
  // variant): other variants hold no float copies.
  if (!float_products()) return;
  if (!narrow_k_) narrow_k_ = cl_.kernel("fem.cl", defines_, "snh_narrow");
  if (variant_ == ProductVariant::assembled) {
    // The float blocks' buffer (the stencil's tables are made with the
    // variant), holding the blocks assembled so far, if any (else the next
    // assembly writes their float copy as it goes).
    if (!stencil_float_) {
      make_stencil_float();
      if (stencil_) narrow(stencil_.get(), stencil_values(), stencil_float_);
    }
    return;
  }
  if (!float_cache() || cache_float_) return;
  product_float_k_ = float_product_kernel();
  narrow(gradients_.get(), device::OpenClContext::bytes(gradients_.get()) / sizeof(Real), gradients_float_);
  narrow(weights_.get(), device::OpenClContext::bytes(weights_.get()) / sizeof(Real), weights_float_);
  // This linearization's cache, if any (else the next linearize() writes it).
  narrow(cache_.get(), cache_values(), cache_float_);
}

// The mixed product reads p and writes its results in double, so it takes
// lanes where the double cached product does: hex8 (value-major cache), not
// tet4, whose lanes gather 8 elements' double p into vectors (measured
// slower than the scalar kernel, as in double: `throughput --element tet4
// --size 48 --variant cached-float-products`, docs/performance.md).
template <typename Real>
bool ElasticModel<Real>::float_product_lanes() const {
  return point_lanes_ && nodes_ == 8;
}

template <typename Real>
device::Kernel ElasticModel<Real>::float_product_kernel() const {
  return float_product_lanes() ? point_kernel("snh_element_product_cached", " -DSNH_MIXED=1")
                               : cl_.kernel("fem.cl", defines_ + " -DSNH_MIXED=1", "snh_element_product_cached");
}

template <typename Real>
void ElasticModel<Real>::make_stencil_float() {
  if (!stencil_product_float_k_)
    stencil_product_float_k_ =
        cl_.kernel("stencil.cl", stencil_defines() + " -DSNH_MATRIX_FLOAT=1", "snh_stencil_product");
  if (!stencil_float_) stencil_float_ = cl_.buffer(CL_MEM_READ_WRITE, stencil_values() * sizeof(float));
}

template <typename Real>
void ElasticModel<Real>::narrow(cl_mem from, size_t values, device::Buffer& to) {
  if (!to) to = cl_.buffer(CL_MEM_READ_WRITE, values * sizeof(float));
  const int n = static_cast<int>(values);
  cl_.run(KernelArgs(narrow_k_.get()).add(from).add(n).add(to.get()).bind(), values);
}

template <typename Real>
device::Kernel ElasticModel<Real>::point_kernel(const char* name, const std::string& extra, int lanes) const {
  // The lanes program needs only the element's own specialization.
  if (point_lanes_)
    return cl_.kernel("fem_lanes.cl", elastic_defines_ + " -DSNH_LANES=" + std::to_string(lanes) + extra, name);
  return cl_.kernel("fem.cl", defines_ + extra, name);
}

template <typename Real>
size_t ElasticModel<Real>::variant_memory_bytes() const {
  const size_t cache = cache_values() * sizeof(Real);
  const size_t m = static_cast<size_t>(3 * nodes_) * (3 * nodes_);
  switch (variant_) {
    case ProductVariant::recompute:
      return dofs() * sizeof(Real);  // the linearization point x
    case ProductVariant::element_matrices:
      return cache + element_count_ * m * sizeof(Real);
    case ProductVariant::assembled:  // the blocks (with float products: their float copy only), the tables
      return cache + element_count_ * m * sizeof(Real) + stencil_memory_bytes();
    default:  // cached: the cache, and its float copy with float products
      return cache + (float_products() ? cache_values() * sizeof(float) : 0);
  }
}

template <typename Real>
size_t ElasticModel<Real>::stencil_memory_bytes() const {
  size_t bytes = 0;
  for (const device::Buffer* b :
       {&stencil_, &stencil_float_, &stencil_neighbours_, &stencil_part_offsets_, &stencil_parts_})
    if (*b) bytes += device::OpenClContext::bytes(b->get());
  return bytes;
}

template <typename Real>
size_t ElasticModel<Real>::memory_bytes() const {
  size_t bytes = material_.memory_bytes() + linearized_x_.size() * sizeof(Real);
  for (const device::Buffer* b : {&elements_, &gradients_, &weights_, &offsets_, &adjacency_, &mask_, &external_,
                                  &element_scratch_, &element_blocks_, &cache_, &energies_, &min_j_, &element_matrices_,
                                  &cache_float_, &gradients_float_, &weights_float_})
    bytes += device::OpenClContext::bytes(b->get());
  if (vertex_terms_) bytes += vertex_terms_->memory_bytes();
  bytes += block_jacobi_->memory_bytes();
  return bytes + stencil_memory_bytes();
}

template <typename Real>
void ElasticModel<Real>::compute_element_matrices() {
  element_matrices_into(element_matrices_.get(), element_blocks_.get());
}

template <typename Real>
void ElasticModel<Real>::element_matrices_into(cl_mem matrices, cl_mem diagonal_blocks, bool single_precision) const {
  single_precision = single_precision && sizeof(Real) > sizeof(float);
  if (!single_precision && matrices != element_matrices_.get() && element_matrices_buffer() && projected_) {
    // This linearization's matrices and their blocks exist already
    // (linearize(); setup_preconditioner() keeps those blocks when projected).
    const size_t nodes = static_cast<size_t>(nodes_);
    cl_.copy(element_matrices_.get(), matrices, element_count_ * 9 * nodes * nodes * sizeof(Real));
    cl_.copy(element_blocks_.get(), diagonal_blocks, element_count_ * 9 * nodes * sizeof(Real));
    return;
  }
  // Float matrices in a model with float products (the cached variant's
  // float copies): computed in float from those copies (SNH_MIXED), the
  // diagonal blocks still written in double; else in the working precision
  // and stored in float.
  const bool from_copies = single_precision && float_cache();
  device::Kernel& float_kernel = from_copies ? matrices_mixed_k_ : matrices_float_k_;
  if (single_precision && !float_kernel)
    float_kernel = point_kernel("snh_element_matrices",
                                from_copies ? " -DSNH_MIXED=1 -DSNH_MATRIX_FLOAT=1" : " -DSNH_MATRIX_FLOAT=1");
  const int count = static_cast<int>(element_count_);
  KernelArgs args(single_precision ? float_kernel.get() : matrices_k_.get());
  args.add(elements_.get())
      .add(from_copies ? gradients_float_.get() : gradients_.get())
      .add(from_copies ? weights_float_.get() : weights_.get())
      .add(count)
      .add(from_copies ? cache_float_.get() : cache_.get())
      .add(matrices)
      .add(diagonal_blocks);
  run_point_kernel(args.bind(), point_lanes_ ? kCacheLanes : 0);
}

template <typename Real>
void ElasticModel<Real>::prepare_stencil() {
  if (stencil_neighbours_) return;
  // The pattern and the element blocks that add up to each of its blocks
  // (solver/block_stencil.h), in the layout for the device.
  const StencilTables t = device_stencil_tables(elements_host_, vertex_count_, nodes_,
                                                fem::vertex_slots(elements_host_, vertex_count_), stencil_tile());
  stencil_width_ = t.width;
  stencil_lower_ = t.lower;
  PhaseScope transfer(&profiler_, Phase::transfers);
  auto upload = [&](const std::vector<int>& values) {
    return cl_.buffer(CL_MEM_READ_ONLY, std::max<size_t>(values.size(), 1) * sizeof(int),
                      values.empty() ? nullptr : values.data());
  };
  stencil_neighbours_ = upload(tiled_neighbours(t, vertex_count_, stencil_tile()));
  stencil_part_offsets_ = upload(t.part_offsets);
  stencil_parts_ = upload(t.parts);
  stencil_assemble_k_ = cl_.kernel("stencil.cl", stencil_defines(), "snh_stencil_assemble");
  stencil_product_k_ = cl_.kernel("stencil.cl", stencil_defines(), "snh_stencil_product");
}

template <typename Real>
void ElasticModel<Real>::assemble() {
  const auto start = std::chrono::steady_clock::now();
  prepare_stencil();
  // With float products only the blocks' float copy is written, and the
  // double blocks, which no product would read, are given back
  // (set_float_products(false) assembles them again).
  if (float_products()) {
    make_stencil_float();
    stencil_.reset();
  } else if (!stencil_) {
    stencil_ = cl_.buffer(CL_MEM_READ_WRITE, std::max<size_t>(stencil_values(), 1) * sizeof(Real));
  }
  const int blocks = static_cast<int>(vertex_count_) * stencil_width_;
  KernelArgs args(stencil_assemble_k_.get());
  args.add(element_matrices_.get())
      .add(stencil_part_offsets_.get())
      .add(stencil_parts_.get())
      .add(blocks)
      .add(stencil_width_)
      .add(float_products() ? cl_mem{nullptr} : stencil_.get())
      .add(float_products() ? stencil_float_.get() : cl_mem{nullptr});
  cl_.run(args.bind(), static_cast<size_t>(blocks));
  cl_.finish();
  last_assembly_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

template <typename Real>
void ElasticModel<Real>::set_mask(const std::vector<Real>& mask) {
  if (mask.size() != dofs()) throw Error("solver: constraint mask has the wrong size");
  PhaseScope transfer(&profiler_, Phase::transfers);
  cl_.write(mask_.get(), mask.size() * sizeof(Real), mask.data());
}

template <typename Real>
void ElasticModel<Real>::set_external_force(const std::vector<double>& force) {
  has_external_ = !force.empty();
  if (!has_external_) return;
  if (force.size() != dofs())
    throw Error("solver: external force has " + std::to_string(force.size()) + " entries, expected " +
                std::to_string(dofs()) + " (xyz per vertex)");
  for (double f : force)
    if (!std::isfinite(f)) throw Error("solver: external force has a non-finite entry");
  external_host_ = force;
  const std::vector<Real> f(force.begin(), force.end());
  PhaseScope transfer(&profiler_, Phase::transfers);
  cl_.write(external_.get(), f.size() * sizeof(Real), f.data());
}

template <typename Real>
void ElasticModel<Real>::set_inertia(const std::vector<double>& coefficient, const std::vector<double>& target,
                                     double elastic_scale) {
  if (!terms_.inertia) throw Error("solver: set_inertia on a model built without the inertia term");
  if (coefficient.size() != vertex_count_ || target.size() != dofs())
    throw Error("solver: inertia has " + std::to_string(coefficient.size()) + " coefficients and " +
                std::to_string(target.size()) + " target entries, expected " + std::to_string(vertex_count_) + " and " +
                std::to_string(dofs()));
  for (double c : coefficient)
    if (!(c >= 0.0) || !std::isfinite(c)) throw Error("solver: inertia coefficient not finite and >= 0");
  for (double y : target)
    if (!std::isfinite(y)) throw Error("solver: inertia target has a non-finite entry");
  if (!(elastic_scale > 0.0) || !std::isfinite(elastic_scale)) throw Error("solver: elastic scale not finite and > 0");
  elastic_scale_ = elastic_scale;
  vertex_terms_->set_inertia(coefficient, target);
}

template <typename Real>
void ElasticModel<Real>::run_forces_kernel(const VectorBase& x) const {
  const int count = static_cast<int>(element_count_);
  KernelArgs args(forces_k_.get());
  args.add(mem(x)).add(elements_.get()).add(gradients_.get()).add(weights_.get()).add(count);
  material_.add_to(args).add(element_scratch_.get());
  run_element_kernel(args.bind());
}

template <typename Real>
void ElasticModel<Real>::elastic_forces(const VectorBase& x, VectorBase& out) {
  run_forces_kernel(x);
  gather(element_scratch_, out, false);
}

template <typename Real>
void ElasticModel<Real>::set_obstacles(const std::vector<double>& records, double stiffness, double thickness) {
  if (terms_.obstacles == 0) throw Error("solver: set_obstacles on a model built without obstacles");
  if (records.size() != static_cast<size_t>(8 * terms_.obstacles))
    throw Error("solver: " + std::to_string(records.size()) + " obstacle record entries, expected " +
                std::to_string(8 * terms_.obstacles));
  vertex_terms_->set_obstacles(records, stiffness, thickness);
}

template <typename Real>
void ElasticModel<Real>::set_friction(const std::vector<double>& start_positions, const std::vector<double>& anchors,
                                      const std::vector<double>& start_records,
                                      const std::vector<double>& friction_records, double slip) {
  if (!terms_.friction) throw Error("solver: set_friction on a model built without friction");
  if (start_positions.size() != dofs() || anchors.size() != terms_.obstacles * dofs() ||
      start_records.size() != static_cast<size_t>(8 * terms_.obstacles) ||
      friction_records.size() != static_cast<size_t>(16 * terms_.obstacles))
    throw Error("solver: set_friction with arrays of the wrong size");
  if (!(slip > 0.0) || !std::isfinite(slip)) throw Error("solver: friction slip must be finite and > 0");
  vertex_terms_->set_friction(start_positions, anchors, start_records, friction_records, slip);
}

template <typename Real>
std::vector<double> ElasticModel<Real>::next_friction_anchors(const VectorBase& x) {
  if (!terms_.friction) throw Error("solver: next_friction_anchors on a model built without friction");
  return vertex_terms_->next_friction_anchors(mem(x));
}

template <typename Real>
void ElasticModel<Real>::contact(const VectorBase& x, bool linearization) const {
  vertex_terms_->contact(mem(x), linearization);
}

template <typename Real>
ContactState ElasticModel<Real>::contact_state(const VectorBase& x) {
  ContactState state;
  if (terms_.self_contact) {
    // The springs the penalty has at x: the set refreshed there (samples
    // already in contact keep theirs).
    refresh_self_contact(x);
    std::vector<Real> xh(dofs());
    device::read_back(cl_, x, xh);
    const std::vector<double> xd(xh.begin(), xh.end());
    for (const SelfContactPair& c : self_contact_->pairs()) {
      ++state.self_contacts;
      state.max_self_penetration = std::max(state.max_self_penetration, self_contact_length(c, xd));
    }
  }
  if (terms_.obstacles == 0) return state;
  contact(x);
  for (Real g : vertex_terms_->contact_depths())
    if (g > Real(0)) {
      ++state.contacts;
      state.max_penetration = std::max(state.max_penetration, static_cast<double>(g));
    }
  return state;
}

template <typename Real>
uint64_t ElasticModel<Real>::contact_set_signature() {
  if (terms_.obstacles == 0) return 0;
  std::vector<Real> depth;
  {
    PhaseScope transfer(&profiler_, Phase::transfers);
    depth = vertex_terms_->contact_depths();
  }
  // FNV-1a over the indices of the vertices in a layer, in vertex order.
  uint64_t hash = 0;
  for (size_t v = 0; v < depth.size(); ++v)
    if (depth[v] > Real(0)) {
      if (hash == 0) hash = 14695981039346656037ull;
      for (int byte = 0; byte < 8; ++byte) {
        hash ^= (static_cast<uint64_t>(v) >> (8 * byte)) & 0xffu;
        hash *= 1099511628211ull;
      }
    }
  return hash;
}

template <typename Real>
void ElasticModel<Real>::set_self_contact_stiffness(double stiffness) {
  if (!terms_.self_contact) throw Error("solver: self-contact stiffness on a model built without self-contact");
  if (!(stiffness > 0.0) || !std::isfinite(stiffness)) throw Error("solver: self-contact stiffness not finite and > 0");
  self_contact_->set_stiffness(stiffness);
}

template <typename Real>
bool ElasticModel<Real>::refresh_self_contact(const VectorBase& x, bool new_step) {
  if (!terms_.self_contact) return false;
  std::vector<Real> xh(dofs());
  {
    PhaseScope transfer(&profiler_, Phase::transfers);
    device::read_back(cl_, x, xh);
  }
  return self_contact_->refresh(std::vector<double>(xh.begin(), xh.end()), new_step);
}

template <typename Real>
const std::vector<SelfContactPair>& ElasticModel<Real>::self_contacts() const {
  static const std::vector<SelfContactPair> none;
  return self_contact_ ? self_contact_->pairs() : none;
}

template <typename Real>
void ElasticModel<Real>::self_differences(const VectorBase& u) const {
  if (self_contact_) self_contact_->differences(mem(u));
}

template <typename Real>
void ElasticModel<Real>::run_element_kernel(cl_kernel k) const {
  cl_.run(k, element_count_);
}

template <typename Real>
void ElasticModel<Real>::run_point_kernel(cl_kernel k, int lanes) const {
  // A work-item per lanes / points elements: tet4 one per lane, hex8 8.
  const size_t per_item = lanes == 0 ? 1 : static_cast<size_t>(lanes / quadrature_);
  cl_.run(k, (element_count_ + per_item - 1) / per_item);
}

template <typename Real>
double ElasticModel<Real>::energy(const VectorBase& x) {
  PhaseScope timed(&profiler_, Phase::line_search_energies);
  const int count = static_cast<int>(element_count_);
  KernelArgs args(energy_k_.get());
  args.add(mem(x)).add(elements_.get()).add(gradients_.get()).add(weights_.get()).add(count);
  material_.add_to(args).add(energies_.get()).add(min_j_.get());
  run_element_kernel(args.bind());
  double sum = reduction_.sum(energies_.get(), element_count_) * elastic_scale_;
  last_min_j_ = reduction_.min(min_j_.get(), element_count_);
  last_energy_magnitude_ = elastic_magnitude_ * elastic_scale_;
  if (terms_.obstacles > 0) {
    contact(x);
    sum += reduction_.sum(vertex_terms_->contact_energy(), vertex_count_);
  }
  if (has_external_ || terms_.inertia || terms_.self_contact) {
    std::vector<Real> xh(dofs());
    {
      PhaseScope transfer(&profiler_, Phase::transfers);
      device::read_back(cl_, x, xh);
    }
    if (has_external_)
      for (size_t i = 0; i < xh.size(); ++i) {
        sum -= external_host_[i] * static_cast<double>(xh[i]);
        last_energy_magnitude_ += std::abs(external_host_[i] * static_cast<double>(xh[i]));
      }
    if (terms_.inertia) vertex_terms_->add_inertia_energy(xh, sum);
    if (terms_.self_contact && !self_contact_->pairs().empty()) {
      // The frozen springs, in contact order, in double.
      const double springs = self_contact_energy(self_contact_->pairs(), self_contact_->stiffness(),
                                                 std::vector<double>(xh.begin(), xh.end()));
      sum += springs;
      last_energy_magnitude_ += springs;
    }
  }
  return sum;
}

template <typename Real>
void ElasticModel<Real>::gather(const device::Buffer& element_values, VectorBase& out, bool external,
                                const VectorBase* u, int vertex_mode, double scale) const {
  const int use_external = external && has_external_ ? 1 : 0;
  const Real sign = static_cast<Real>(scale);
  const int count = static_cast<int>(vertex_count_);
  KernelArgs args(gather_k_.get());
  args.add(element_values.get())
      .add(offsets_.get())
      .add(adjacency_.get())
      .add(mask_.get())
      .add(external_.get())
      .add(use_external)
      .add(sign)
      .add(count)
      .add(mem(out));
  if (vertex_terms()) args.add(u ? mem(*u) : mem(out)).add(u ? vertex_mode : 0);  // u read only when vertex_mode > 0
  if (vertex_terms_) vertex_terms_->add_gather_args(args);
  if (terms_.self_contact) self_contact_->add_args(args);
  cl_.run(args.bind(), vertex_count_);
}

template <typename Real>
void ElasticModel<Real>::residual(const VectorBase& x, VectorBase& r) {
  PhaseScope timed(&profiler_, Phase::line_search_energies);
  run_forces_kernel(x);
  if (terms_.obstacles > 0) contact(x);
  self_differences(x);
  gather(element_scratch_, r, true, &x, 1, elastic_scale_);
}

template <typename Real>
void ElasticModel<Real>::linearize(const VectorBase& x, bool projected) {
  PhaseScope timed(&profiler_, Phase::linearization);
  cl_.copy(mem(x), mem(linearized_x_), dofs() * sizeof(Real));  // in queue order, no ViennaCL kernel
  projected_ = projected ? 1 : 0;
  const int count = static_cast<int>(element_count_);
  KernelArgs args(linearize_k_.get());
  args.add(mem(x)).add(elements_.get()).add(gradients_.get()).add(count);
  material_.add_to(args).add(projected_).add(cache_.get());
  // Double: the cache's float copy for float products (null: none).
  if (sizeof(Real) > sizeof(float)) args.add(float_cache() ? cache_float_.get() : cl_mem{nullptr});
  run_point_kernel(args.bind(), material_lanes_);
  if (terms_.obstacles > 0) contact(x, true);  // the Gauss-Newton blocks at x
  last_assembly_seconds_ = 0.0;
  if (variant_ == ProductVariant::element_matrices || variant_ == ProductVariant::assembled) compute_element_matrices();
  if (variant_ == ProductVariant::assembled) assemble();
}

template <typename Real>
void ElasticModel<Real>::product(const VectorBase& p, VectorBase& y) const {
  PhaseScope timed(&profiler_, Phase::products);
  const int count = static_cast<int>(element_count_);
  if (variant_ == ProductVariant::assembled) {
    // y = mask * (K p) from the blocks (kernels/stencil.cl); the per-vertex
    // terms then as after the element products (mask * mask = mask).
    // Float products: the float blocks, with p and y in double.
    const bool narrow = float_products();
    const int vertices = static_cast<int>(vertex_count_);
    KernelArgs stencil(narrow ? stencil_product_float_k_.get() : stencil_product_k_.get());
    stencil.add(mem(p))
        .add(stencil_neighbours_.get())
        .add(narrow ? stencil_float_.get() : stencil_.get())
        .add(mask_.get())
        .add(vertices)
        .add(stencil_width_)
        .add(mem(y));
    cl_.run(stencil.bind(), vertex_count_);
    if (!vertex_terms()) return;
    const int size = static_cast<int>(dofs());
    KernelArgs terms(mask_k_.get());
    terms.add(mask_.get()).add(size).add(mem(y)).add(static_cast<Real>(elastic_scale_)).add(mem(p));
    if (vertex_terms_) vertex_terms_->add_block_args(terms);
    self_differences(p);
    if (terms_.self_contact) self_contact_->add_args(terms);
    cl_.run(terms.bind(), dofs());
    return;
  }
  if (variant_ == ProductVariant::element_matrices) {
    KernelArgs args(matrix_rows_ ? matrix_rows_k_.get() : matrix_product_k_.get());
    args.add(mem(p)).add(elements_.get()).add(element_matrices_.get()).add(count).add(element_scratch_.get());
    cl_.run(args.bind(), matrix_rows_ ? element_count_ * 3 * nodes_ : element_count_);
  } else if (variant_ == ProductVariant::cached) {
    const bool narrow = float_cache();
    KernelArgs args(narrow ? product_float_k_.get() : product_cached_k_.get());
    args.add(mem(p))
        .add(elements_.get())
        .add(narrow ? gradients_float_.get() : gradients_.get())
        .add(narrow ? weights_float_.get() : weights_.get())
        .add(count)
        .add(narrow ? cache_float_.get() : cache_.get())
        .add(element_scratch_.get());
    run_point_kernel(args.bind(), (float_products() ? float_product_lanes() : cached_lanes_) ? kCacheLanes : 0);
  } else {
    KernelArgs args(product_recompute_k_.get());
    args.add(mem(p)).add(elements_.get()).add(gradients_.get()).add(weights_.get()).add(count).add(mem(linearized_x_));
    material_.add_to(args).add(projected_).add(element_scratch_.get());
    run_point_kernel(args.bind(), material_lanes_);
  }
  self_differences(p);
  gather(element_scratch_, y, false, &p, 2, elastic_scale_);
}

template <typename Real>
void ElasticModel<Real>::setup_preconditioner() {
  PhaseScope timed(&profiler_, Phase::preconditioner_setup);
  const int count = static_cast<int>(element_count_);
  if (!(projected_ && element_matrices_buffer())) {
    // Else the projected element matrices' kernel wrote their diagonal
    // blocks already.
    KernelArgs args(diagonal_k_.get());
    args.add(elements_.get())
        .add(gradients_.get())
        .add(weights_.get())
        .add(count)
        .add(cache_.get())
        .add(element_blocks_.get());
    run_point_kernel(args.bind(), point_lanes_ ? kCacheLanes : 0);
  }
  block_jacobi_->setup(element_blocks_.get(), offsets_.get(), adjacency_.get(), mask_.get(), [this](KernelArgs& args) {
    if (vertex_terms()) args.add(static_cast<Real>(elastic_scale_));
    if (vertex_terms_) vertex_terms_->add_block_args(args);
    if (terms_.self_contact) args.add(self_contact_->diagonal());
  });
}

template <typename Real>
void ElasticModel<Real>::apply_preconditioner(VectorBase& z) const {
  PhaseScope timed(&profiler_, Phase::preconditioner_apply);
  block_jacobi_->apply(mem(z));
}

template <typename Real>
std::vector<Real> ElasticModel<Real>::preconditioner_blocks() const {
  PhaseScope transfer(&profiler_, Phase::transfers);
  return block_jacobi_->blocks();
}

template class ElasticModel<float>;
template class ElasticModel<double>;

}  // namespace snh::solver
