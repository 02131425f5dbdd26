// The Hessian products of the elastic model (ProductVariant): what each
// variant stores after a linearization (the cache alone, element matrices,
// the assembled block stencil), its product kernels, and the float copies
// that CG's float products read in double solves. The elastic operator
// (solver/model/elastic_model.h) linearizes, then asks for products; the
// per-vertex terms and the gather stay with it. Internal to the library.
#pragma once

#include <cstddef>
#include <string>

#include "device/material_args.h"
#include "device/opencl_context.h"
#include "device/phase_profile.h"
#include "snh/simulation.h"
#include "solver/model/element_data.h"
#include "viennacl/vector.hpp"

namespace snh::solver {

template <typename Real>
class ProductVariants {
 public:
  using VectorBase = viennacl::vector_base<Real>;

  // `data` and `material` belong to the elastic model and outlive this.
  ProductVariants(const ElementData<Real>& data, const device::MaterialArgs<Real>& material, ProductVariant variant,
                  PhaseProfiler* profiler);

  ProductVariant variant() const { return variant_; }
  // Takes effect at the next linearization. `automatic` is not accepted.
  void set_variant(ProductVariant v);
  // The kernels for data.point_lanes (PointLanes::set_point_lanes), with
  // the material lanes (0 with lanes off) of the recompute product; and
  // those lanes alone (PointLanes::set_material_lanes).
  void set_point_lanes(int material_lanes);
  void set_material_lanes(int lanes);
  // The element-matrices product with a work-item per matrix row instead of
  // per element (fem.cl, snh_element_matrix_product_rows): coalesced reads
  // on GPUs, where it is the default; the same values.
  void set_matrix_product_rows(bool on) { matrix_rows_ = on; }
  bool matrix_product_rows() const { return matrix_rows_; }
  // Mixed precision, double models with the cached or the assembled
  // variant: CG's products in float. Cached (kernels/snh_portable.h,
  // SNH_MIXED): each linearization writes its cache's float copy too (the
  // rest gradients and weights are narrowed once, here); the product reads
  // p and writes its per-element values in double. Assembled: each
  // linearization narrows the assembled blocks to float, and the stencil
  // product reads them with double p and y (SNH_MATRIX_FLOAT). The gather,
  // the vertex terms, the energy, the residual, the linearization and the
  // preconditioners keep double. A float model, or another variant, keeps
  // its products in the working precision.
  void set_float_products(bool on);
  // Whether the products run in float now (set, a double model, the cached
  // or assembled variant).
  bool float_products() const {
    return float_products_ && sizeof(Real) > sizeof(float) &&
           (variant_ == ProductVariant::cached || variant_ == ProductVariant::assembled);
  }
  // The cached variant's products read the float copies now; the
  // linearization writes the cache's float copy into float_cache_buffer().
  bool float_cache() const { return float_products() && variant_ == ProductVariant::cached; }
  cl_mem float_cache_buffer() const { return float_cache() ? cache_float_.get() : nullptr; }

  // After the linearization (its cache written, `projected` or not): the
  // element matrices and the assembly that the variant keeps.
  void linearized(bool projected);
  // Whether the last linearization was projected (before the first: true).
  bool projected() const { return projected_ != 0; }
  // The stencil's product y = mask * K p (assembled variant): true when it
  // wrote y, the per-vertex terms still to add; else false, and
  // element_product() is the variant's product.
  bool stencil_product(const VectorBase& p, VectorBase& y) const;
  // The per-element products of p into data.element_scratch (before the
  // gather): the element matrices', the cache's or, recomputed at
  // `linearized_x` (projected as linearized), the material's.
  void element_product(const VectorBase& p, const VectorBase& linearized_x) const;

  // The per-element matrices of the last linearization (element_matrices
  // and assembled variants), else null.
  cl_mem element_matrices_buffer() const {
    return variant_ == ProductVariant::element_matrices || variant_ == ProductVariant::assembled
               ? element_matrices_.get()
               : nullptr;
  }
  // The element matrices of the last linearization (projected or true, as
  // linearized) and their 3x3 diagonal blocks into caller-owned buffers
  // (data.element_count * (3N)^2 and * 9N reals; column-major, as
  // snh_element_matrices writes them), whatever the variant. With
  // single_precision (double builds), the matrices in float, exactly
  // symmetric (kernels/fem/element.h, SNH_MATRIX_FLOAT); the blocks stay in
  // the working precision. With float products on (the cached variant)
  // those float matrices are computed in float from the cache's float copy
  // (SNH_MIXED; multigrid's built fine level).
  void element_matrices_into(cl_mem matrices, cl_mem diagonal_blocks, bool single_precision = false) const;

  // Seconds the last linearization spent assembling the block stencil (its
  // tables too, the first time); 0 for other variants.
  double last_assembly_seconds() const { return last_assembly_seconds_; }
  // The assembled operator's 3x3 blocks stored per vertex (0 before the
  // first assembly): the most vertices any vertex shares an element with,
  // plus one (kernels/fem/block_stencil.h).
  int assembled_width() const { return stencil_width_; }
  // The blocks each vertex reads as the transposes of its neighbours' (the
  // upper layout, per-vertex blocks on CPUs: solver/model/block_stencil.h), else
  // 0; and the blocks stored (padding and the upper layout's zero block
  // included).
  int assembled_lower() const { return stencil_lower_; }
  size_t assembled_blocks() const { return stencil_values() / 9; }
  // Device memory the current variant holds beyond the mesh and vectors:
  // the linearization cache, element matrices or assembled matrix (the
  // recompute variant: the linearization point x); and all this holds
  // (element matrices, float copies, stencil and its tables).
  size_t variant_memory_bytes() const;
  size_t memory_bytes() const;

 private:
  using Kernel = device::Kernel;
  using Buffer = device::Buffer;

  const ElementData<Real>& data_;
  const device::MaterialArgs<Real>& material_;
  PhaseProfiler* profiler_;
  ProductVariant variant_;
  int material_lanes_ = 0;
  bool cached_lanes_ = false;  // the cached product's kernel is fem_lanes.cl's
  bool matrix_rows_ = false;
  int projected_ = 1;  // the last linearization's: projected (1) or the true Hessian (0)
  double last_assembly_seconds_ = 0.0;
  Kernel product_cached_k_, product_recompute_k_, matrix_product_k_, matrix_rows_k_, matrices_k_;
  mutable Kernel matrices_float_k_;  // built at its first use
  mutable Kernel matrices_mixed_k_;  // the same from the float copies (float products), likewise
  Buffer element_matrices_;

  // set_float_products: the SNH_MIXED product, the narrowing kernel and the
  // float copies of the cache, gradients and weights.
  bool float_products_ = false;
  Kernel product_float_k_, narrow_k_, stencil_product_float_k_;
  Buffer cache_float_, gradients_float_, weights_float_, stencil_float_;
  void make_stencil_float();                            // the float blocks' buffer and product kernel, once
  void narrow(cl_mem from, size_t values, Buffer& to);  // to (made if empty) <- (float)from
  bool float_product_lanes() const;                     // the mixed product runs fem_lanes.cl's kernel
  Kernel float_product_kernel() const;                  // the SNH_MIXED cached product
  void prepare_float_products();                        // the above, once float_products() holds

  // Assembled variant: the block stencil (solver/model/block_stencil.h), assembled
  // on the device from the element matrices in element order
  // (deterministic), and its width.
  Buffer stencil_, stencil_neighbours_, stencil_part_offsets_, stencil_parts_;
  Kernel stencil_assemble_k_, stencil_product_k_;
  int stencil_width_ = 0, stencil_lower_ = 0;
  size_t stencil_values() const;
  size_t stencil_memory_bytes() const;
  // The stencil kernels' build: the model's, with the width made a constant
  // where the layout allows (stencil_build).
  device::KernelConfig stencil_config() const;
  // The stencil's tables on the device and its kernels, once: made when the
  // variant is chosen, not in the first solve.
  void prepare_stencil();
  void assemble();
};

}  // namespace snh::solver
