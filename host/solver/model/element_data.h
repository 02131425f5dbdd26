// A mesh's device data that the element kernels read (connectivity, rest
// gradients and weights, the per-point linearization cache, the constraint
// mask and the per-element scratch) and how those kernels are built and
// launched: kernels/fem.cl, or over lanes kernels/fem_lanes.cl. Shared by
// the elastic operator (solver/model/elastic_model.h), its Hessian products
// (solver/model/product_variants.h) and its lanes setting
// (solver/model/point_lanes.h); read by the multigrid preconditioner
// (solver/multigrid/multigrid.h) through ElasticModel::data(). Internal to
// the library.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "device/opencl_context.h"

namespace snh::solver {

template <typename Real>
struct ElementData {
  explicit ElementData(device::OpenClContext& context) : cl(context) {}

  device::OpenClContext& cl;
  size_t vertex_count = 0, element_count = 0;
  int nodes = 0, quadrature = 0;
  // Elements per tile of the cache, and vertices per tile of the block
  // stencils (the multigrid's levels read this model's defines): 1, or 32
  // in the tiled layout (PointDataLayout::tiled).
  size_t cache_tile = 1;
  // The model's build (its per-vertex terms included; its defines() are the
  // model's specialization) and the same without those terms (the lanes
  // program and the stencils need only the element's): the build of a
  // multigrid's coarse levels too, whose cell matrices carry those terms
  // already.
  device::KernelConfig config, elastic_config;
  bool point_lanes = false;  // PointLanes::set_point_lanes
  device::Buffer elements, gradients, weights, offsets, adjacency, mask, element_scratch, element_blocks, cache;
  std::vector<int> elements_host;

  size_t dofs() const { return 3 * vertex_count; }
  // The build (device/kernel_config.h) and the specialization a result
  // reports: config.defines() and the precision (-DSNH_DOUBLE).
  std::string kernel_report() const {
    device::KernelConfig c = config;
    c.precision = cl.precision();
    return c.report();
  }
  // 30 values per quadrature point (kernels/fem/element.h), the elements
  // rounded up to whole tiles in the tiled layout.
  size_t cache_values() const {
    return (element_count + cache_tile - 1) / cache_tile * cache_tile * static_cast<size_t>(quadrature) * 30;
  }
  // The width of the lanes kernels that read the cache (cached product,
  // element matrices, element blocks), whatever the material lanes are.
  static constexpr int kCacheLanes = 8;

  // Kernel `name` of the program point_lanes chooses: fem_lanes.cl at
  // `lanes` lanes (the element's build only), or fem.cl (the model's); with
  // the float data of float products (SNH_MIXED) or matrices stored in
  // float (SNH_MATRIX_FLOAT) where asked.
  device::Kernel point_kernel(const char* name, int lanes = kCacheLanes, bool mixed = false,
                              bool matrix_float = false) const {
    device::KernelConfig c = point_lanes ? elastic_config.with_lanes(lanes) : config;
    c.mixed = mixed;
    c.matrix_float = matrix_float;
    return cl.kernel(point_lanes ? "fem_lanes.cl" : "fem.cl", c, name);
  }
  // A work-item per element.
  void run_element_kernel(cl_kernel k) const { cl.run(k, element_count); }
  // lanes: 0 for fem.cl's kernel (a work-item per element), else
  // fem_lanes.cl's at that width (a work-item per lanes / quadrature points
  // elements: tet4 one per lane, hex8 8).
  void run_point_kernel(cl_kernel k, int lanes) const {
    const size_t per_item = lanes == 0 ? 1 : static_cast<size_t>(lanes / quadrature);
    cl.run(k, (element_count + per_item - 1) / per_item);
  }
};

}  // namespace snh::solver
