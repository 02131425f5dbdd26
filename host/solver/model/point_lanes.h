// The elastic model's per-point lanes setting (kernels/fem_lanes.cl): whether
// the kernels that evaluate or read the per-point data run over 8- or
// 16-wide vectors, and the model's kernels it picks (the linearization,
// block-Jacobi's element diagonal), the products' too
// (solver/model/product_variants.h). Reached as ElasticModel::lanes().
// Internal to the library.
#pragma once

#include "device/material_args.h"
#include "device/opencl_context.h"
#include "solver/model/element_data.h"
#include "solver/model/product_variants.h"

namespace snh::solver {

template <typename Real>
class PointLanes {
 public:
  // `data`, `material` and `products` belong to the elastic model and
  // outlive this. Lanes are off until set_point_lanes.
  PointLanes(ElementData<Real>& data, const device::MaterialArgs<Real>& material, ProductVariants<Real>& products);

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
  bool point_lanes_available() const;
  // The lanes program and the value-major hex8 point data (PointDataLayout)
  // are the defaults on CPU devices.
  static bool lanes_by_default(const device::OpenClContext& cl) { return !cl.info().is_gpu; }

  // The linearization's kernel (at material_lanes()) and block-Jacobi's
  // element diagonal (at 8 lanes), of the program the setting picks.
  cl_kernel linearize_kernel() const { return linearize_k_.get(); }
  cl_kernel diagonal_kernel() const { return diagonal_k_.get(); }

 private:
  // hex8 elements with their own materials: a lanes work-item holds one.
  bool hex8_materials_per_element() const { return data_.nodes == 8 && material_.per_element(); }

  ElementData<Real>& data_;
  const device::MaterialArgs<Real>& material_;
  ProductVariants<Real>& products_;
  int material_lanes_ = 0;  // set_material_lanes
  device::Kernel linearize_k_, diagonal_k_;
};

}  // namespace snh::solver
