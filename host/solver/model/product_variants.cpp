#include "solver/model/product_variants.h"

#include <algorithm>
#include <chrono>

#include "device/kernel_args.h"
#include "fem/vertex_slots.h"
#include "snh/error.h"
#include "solver/model/block_stencil.h"

namespace snh::solver {

namespace {

using device::KernelArgs;

template <typename Real>
cl_mem mem(const viennacl::vector_base<Real>& v) {
  return v.handle().opencl_handle().get();
}

}  // namespace

template <typename Real>
ProductVariants<Real>::ProductVariants(const ElementData<Real>& data, const device::MaterialArgs<Real>& material,
                                       ProductVariant variant, PhaseProfiler* profiler)
    : data_(data), material_(material), profiler_(profiler), variant_(variant) {
  matrix_product_k_ = data_.cl.kernel("fem.cl", data_.config, "snh_element_matrix_product");
  matrix_rows_k_ = data_.cl.kernel("fem.cl", data_.config, "snh_element_matrix_product_rows");
  matrix_rows_ = data_.cl.info().is_gpu;
}

template <typename Real>
void ProductVariants<Real>::set_variant(ProductVariant v) {
  variant_ = v;
  const size_t m = static_cast<size_t>(3 * data_.nodes) * (3 * data_.nodes);
  if ((v == ProductVariant::element_matrices || v == ProductVariant::assembled) && !element_matrices_)
    element_matrices_ = data_.cl.buffer(CL_MEM_READ_WRITE, data_.element_count * m * sizeof(Real));
  if (v == ProductVariant::assembled) prepare_stencil();
  prepare_float_products();
}

template <typename Real>
void ProductVariants<Real>::set_material_lanes(int lanes) {
  material_lanes_ = lanes;
  product_recompute_k_ = data_.point_kernel("snh_element_product_recompute", material_lanes_);
}

template <typename Real>
void ProductVariants<Real>::set_point_lanes(int material_lanes) {
  set_material_lanes(material_lanes);
  // The cached product over lanes in float, and for hex8 in double too (its
  // cache value-major per element: one vector load per value); tet4 in
  // double keeps the scalar kernel, which pocl vectorizes across
  // work-items: the lanes version, gathering each element's 30 cached
  // values into 8-wide vectors, measured slower (docs/performance.md,
  // "Cached products of tet4 in double").
  cached_lanes_ = data_.point_lanes && (sizeof(Real) == sizeof(float) || data_.nodes == 8);
  product_cached_k_ = cached_lanes_ ? data_.point_kernel("snh_element_product_cached")
                                    : data_.cl.kernel("fem.cl", data_.config, "snh_element_product_cached");
  if (product_float_k_) product_float_k_ = float_product_kernel();
  matrices_k_ = data_.point_kernel("snh_element_matrices");
  matrices_float_k_ = Kernel();
  matrices_mixed_k_ = Kernel();
}

template <typename Real>
void ProductVariants<Real>::set_float_products(bool on) {
  if (sizeof(Real) == sizeof(float) || on == float_products_) return;
  float_products_ = on;
  if (!on) {
    product_float_k_ = Kernel();
    stencil_product_float_k_ = Kernel();
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
void ProductVariants<Real>::prepare_float_products() {
  // Made when the products first run in float (the cached or assembled
  // variant): other variants hold no float copies.
  if (!float_products()) return;
  if (!narrow_k_) narrow_k_ = data_.cl.kernel("fem.cl", data_.config, "snh_narrow");
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
  narrow(data_.gradients.get(), device::OpenClContext::bytes(data_.gradients.get()) / sizeof(Real), gradients_float_);
  narrow(data_.weights.get(), device::OpenClContext::bytes(data_.weights.get()) / sizeof(Real), weights_float_);
  // This linearization's cache, if any (else the next linearize() writes it).
  narrow(data_.cache.get(), data_.cache_values(), cache_float_);
}

// The mixed product reads p and writes its results in double, so it takes
// lanes where the double cached product does: hex8 (value-major cache), not
// tet4, whose lanes gather 8 elements' double p into vectors (measured
// slower than the scalar kernel, as in double: docs/performance.md, "Cached
// products of tet4 in double").
template <typename Real>
bool ProductVariants<Real>::float_product_lanes() const {
  return data_.point_lanes && data_.nodes == 8;
}

template <typename Real>
device::Kernel ProductVariants<Real>::float_product_kernel() const {
  return float_product_lanes() ? data_.point_kernel("snh_element_product_cached", ElementData<Real>::kCacheLanes, true)
                               : data_.cl.kernel("fem.cl", data_.config.with_mixed(), "snh_element_product_cached");
}

template <typename Real>
void ProductVariants<Real>::make_stencil_float() {
  if (!stencil_product_float_k_)
    stencil_product_float_k_ =
        data_.cl.kernel("stencil.cl", stencil_config().with_matrix_float(), "snh_stencil_product");
  if (!stencil_float_) stencil_float_ = data_.cl.buffer(CL_MEM_READ_WRITE, stencil_values() * sizeof(float));
}

template <typename Real>
void ProductVariants<Real>::narrow(cl_mem from, size_t values, Buffer& to) {
  if (!to) to = data_.cl.buffer(CL_MEM_READ_WRITE, values * sizeof(float));
  const int n = static_cast<int>(values);
  data_.cl.run(KernelArgs(narrow_k_.get()).add(from).add(n).add(to.get()).bind(), values);
}

template <typename Real>
void ProductVariants<Real>::linearized(bool projected) {
  projected_ = projected ? 1 : 0;
  last_assembly_seconds_ = 0.0;
  if (variant_ == ProductVariant::element_matrices || variant_ == ProductVariant::assembled)
    element_matrices_into(element_matrices_.get(), data_.element_blocks.get(), false);
  if (variant_ == ProductVariant::assembled) assemble();
}

template <typename Real>
void ProductVariants<Real>::element_matrices_into(cl_mem matrices, cl_mem diagonal_blocks,
                                                  bool single_precision) const {
  single_precision = single_precision && sizeof(Real) > sizeof(float);
  if (!single_precision && matrices != element_matrices_.get() && element_matrices_buffer() && projected_) {
    // This linearization's matrices and their blocks exist already
    // (linearize(); setup_preconditioner() keeps those blocks when projected).
    const size_t nodes = static_cast<size_t>(data_.nodes);
    data_.cl.copy(element_matrices_.get(), matrices, data_.element_count * 9 * nodes * nodes * sizeof(Real));
    data_.cl.copy(data_.element_blocks.get(), diagonal_blocks, data_.element_count * 9 * nodes * sizeof(Real));
    return;
  }
  // Float matrices in a model with float products (the cached variant's
  // float copies): computed in float from those copies (SNH_MIXED), the
  // diagonal blocks still written in double; else in the working precision
  // and stored in float.
  const bool from_copies = single_precision && float_cache();
  Kernel& float_kernel = from_copies ? matrices_mixed_k_ : matrices_float_k_;
  if (single_precision && !float_kernel)
    float_kernel = data_.point_kernel("snh_element_matrices", ElementData<Real>::kCacheLanes, from_copies, true);
  const int count = static_cast<int>(data_.element_count);
  KernelArgs args(single_precision ? float_kernel.get() : matrices_k_.get());
  args.add(data_.elements.get())
      .add(from_copies ? gradients_float_.get() : data_.gradients.get())
      .add(from_copies ? weights_float_.get() : data_.weights.get())
      .add(count)
      .add(from_copies ? cache_float_.get() : data_.cache.get())
      .add(matrices)
      .add(diagonal_blocks);
  data_.run_point_kernel(args.bind(), data_.point_lanes ? ElementData<Real>::kCacheLanes : 0);
}

template <typename Real>
size_t ProductVariants<Real>::stencil_values() const {
  return stencil_entries(stencil_width_, data_.vertex_count, data_.cache_tile, stencil_lower_);
}

template <typename Real>
device::KernelConfig ProductVariants<Real>::stencil_config() const {
  return stencil_build(data_.elastic_config, stencil_width_, data_.cache_tile, stencil_lower_);
}

template <typename Real>
void ProductVariants<Real>::prepare_stencil() {
  if (stencil_neighbours_) return;
  // The pattern and the element blocks that add up to each of its blocks
  // (solver/model/block_stencil.h), in the layout for the device.
  const size_t tile = data_.cache_tile;
  const StencilTables t = device_stencil_tables(data_.elements_host, data_.vertex_count, data_.nodes,
                                                fem::vertex_slots(data_.elements_host, data_.vertex_count), tile);
  stencil_width_ = t.width;
  stencil_lower_ = t.lower;
  PhaseScope transfer(profiler_, Phase::transfers);
  auto upload = [&](const std::vector<int>& values) {
    return data_.cl.buffer(CL_MEM_READ_ONLY, std::max<size_t>(values.size(), 1) * sizeof(int),
                           values.empty() ? nullptr : values.data());
  };
  stencil_neighbours_ = upload(tiled_neighbours(t, data_.vertex_count, tile));
  stencil_part_offsets_ = upload(t.part_offsets);
  stencil_parts_ = upload(t.parts);
  stencil_assemble_k_ = data_.cl.kernel("stencil.cl", stencil_config(), "snh_stencil_assemble");
  stencil_product_k_ = data_.cl.kernel("stencil.cl", stencil_config(), "snh_stencil_product");
}

template <typename Real>
void ProductVariants<Real>::assemble() {
  const auto start = std::chrono::steady_clock::now();
  prepare_stencil();
  // With float products only the blocks' float copy is written, and the
  // double blocks, which no product would read, are given back
  // (set_float_products(false) assembles them again).
  if (float_products()) {
    make_stencil_float();
    stencil_.reset();
  } else if (!stencil_) {
    stencil_ = data_.cl.buffer(CL_MEM_READ_WRITE, std::max<size_t>(stencil_values(), 1) * sizeof(Real));
  }
  const int blocks = static_cast<int>(data_.vertex_count) * stencil_width_;
  KernelArgs args(stencil_assemble_k_.get());
  args.add(element_matrices_.get())
      .add(stencil_part_offsets_.get())
      .add(stencil_parts_.get())
      .add(blocks)
      .add(stencil_width_)
      .add(float_products() ? cl_mem{nullptr} : stencil_.get())
      .add(float_products() ? stencil_float_.get() : cl_mem{nullptr});
  data_.cl.run(args.bind(), static_cast<size_t>(blocks));
  data_.cl.finish();
  last_assembly_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

template <typename Real>
bool ProductVariants<Real>::stencil_product(const VectorBase& p, VectorBase& y) const {
  if (variant_ != ProductVariant::assembled) return false;
  // y = mask * (K p) from the blocks (kernels/stencil.cl). Float products:
  // the float blocks, with p and y in double.
  const bool narrow = float_products();
  const int vertices = static_cast<int>(data_.vertex_count);
  KernelArgs stencil(narrow ? stencil_product_float_k_.get() : stencil_product_k_.get());
  stencil.add(mem(p))
      .add(stencil_neighbours_.get())
      .add(narrow ? stencil_float_.get() : stencil_.get())
      .add(data_.mask.get())
      .add(vertices)
      .add(stencil_width_)
      .add(mem(y));
  data_.cl.run(stencil.bind(), data_.vertex_count);
  return true;
}

template <typename Real>
void ProductVariants<Real>::element_product(const VectorBase& p, const VectorBase& linearized_x) const {
  const int count = static_cast<int>(data_.element_count);
  if (variant_ == ProductVariant::element_matrices) {
    KernelArgs args(matrix_rows_ ? matrix_rows_k_.get() : matrix_product_k_.get());
    args.add(mem(p)).add(data_.elements.get()).add(element_matrices_.get()).add(count).add(data_.element_scratch.get());
    data_.cl.run(args.bind(), matrix_rows_ ? data_.element_count * 3 * data_.nodes : data_.element_count);
  } else if (variant_ == ProductVariant::cached) {
    const bool narrow = float_cache();
    KernelArgs args(narrow ? product_float_k_.get() : product_cached_k_.get());
    args.add(mem(p))
        .add(data_.elements.get())
        .add(narrow ? gradients_float_.get() : data_.gradients.get())
        .add(narrow ? weights_float_.get() : data_.weights.get())
        .add(count)
        .add(narrow ? cache_float_.get() : data_.cache.get())
        .add(data_.element_scratch.get());
    const bool lanes = float_products() ? float_product_lanes() : cached_lanes_;
    data_.run_point_kernel(args.bind(), lanes ? ElementData<Real>::kCacheLanes : 0);
  } else {
    KernelArgs args(product_recompute_k_.get());
    args.add(mem(p))
        .add(data_.elements.get())
        .add(data_.gradients.get())
        .add(data_.weights.get())
        .add(count)
        .add(mem(linearized_x));
    material_.add_to(args).add(projected_).add(data_.element_scratch.get());
    data_.run_point_kernel(args.bind(), material_lanes_);
  }
}

template <typename Real>
size_t ProductVariants<Real>::variant_memory_bytes() const {
  const size_t cache = data_.cache_values() * sizeof(Real);
  const size_t m = static_cast<size_t>(3 * data_.nodes) * (3 * data_.nodes);
  switch (variant_) {
    case ProductVariant::recompute:
      return data_.dofs() * sizeof(Real);  // the linearization point x
    case ProductVariant::element_matrices:
      return cache + data_.element_count * m * sizeof(Real);
    case ProductVariant::assembled:  // the blocks (with float products: their float copy only), the tables
      return cache + data_.element_count * m * sizeof(Real) + stencil_memory_bytes();
    default:  // cached: the cache, and its float copy with float products
      return cache + (float_products() ? data_.cache_values() * sizeof(float) : 0);
  }
}

template <typename Real>
size_t ProductVariants<Real>::stencil_memory_bytes() const {
  size_t bytes = 0;
  for (const Buffer* b : {&stencil_, &stencil_float_, &stencil_neighbours_, &stencil_part_offsets_, &stencil_parts_})
    if (*b) bytes += device::OpenClContext::bytes(b->get());
  return bytes;
}

template <typename Real>
size_t ProductVariants<Real>::memory_bytes() const {
  size_t bytes = stencil_memory_bytes();
  for (const Buffer* b : {&element_matrices_, &cache_float_, &gradients_float_, &weights_float_})
    bytes += device::OpenClContext::bytes(b->get());
  return bytes;
}

template class ProductVariants<float>;
template class ProductVariants<double>;

}  // namespace snh::solver
