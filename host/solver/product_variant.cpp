// Names of the Hessian-product variants and the measured default.
#include "snh/error.h"
#include "snh/simulation.h"

namespace snh {

const char* to_string(ProductVariant v) {
  switch (v) {
    case ProductVariant::automatic:
      return "automatic";
    case ProductVariant::cached:
      return "cached";
    case ProductVariant::recompute:
      return "recompute";
    case ProductVariant::element_matrices:
      return "element-matrices";
    case ProductVariant::assembled:
      return "assembled";
  }
  return "?";
}

ProductVariant parse_product_variant(const std::string& text) {
  for (ProductVariant v : {ProductVariant::automatic, ProductVariant::cached, ProductVariant::recompute,
                           ProductVariant::element_matrices, ProductVariant::assembled})
    if (text == to_string(v)) return v;
  throw Error("product variant: expected automatic, cached, recompute, element-matrices or assembled, got '" + text +
              "'");
}

// Measured with `snh-gpu-bench throughput` (sizes 8^3 and 12^3; README) on
// pocl, 2 CPU cores, scored as setup + 50 products per Newton iteration:
// hex8: per-element matrices win in float and double at both sizes (e.g.
// double 12^3: 0.136 ms per product + 19.9 ms setup, against 0.93 + 5.1
// cached, 0.41 + 21.8 assembled, 5.9 + 5.2 recomputed); tet4: the assembled
// matrix wins in 3 of 4 cases (double 12^3: 0.196 + 10.8 against 0.255 + 9.4
// element matrices). On an NVIDIA H100 (NVIDIA's OpenCL, session 8,
// `throughput --size 48,96`) the cached linearization wins every hex8 and
// tet4 double case so scored (hex8 double 48^3: 0.196 ms + 0.59 ms setup,
// against 0.363 + 4.5 element matrices, 0.186 + 482 assembled; tet4 double
// 48^3: 0.246 + 0.44 against 0.120 + 641 assembled) and ties the recomputed
// product for tet4 float (0.147 against 0.143 ms), so it is the GPU default.
ProductVariant default_product_variant(ElementType type, Precision, bool gpu) {
  if (gpu) return ProductVariant::cached;
  return type == ElementType::hex8 ? ProductVariant::element_matrices : ProductVariant::assembled;
}

// Measured with `snh-gpu-bench scene twist --res 32 --preconditioner
// multigrid --variant V` (pocl, 2 CPU cores, double, nu = 0.49; README):
// element matrices rebuilt at every linearization 24.4 s, cached 24.7 s; with
// the hierarchy reused (rebuild_every 4) element matrices 22.7 s (their
// per-Newton build and product stay), cached 19.2-19.9 s.
ProductVariant default_product_variant(ElementType type, Precision precision, bool gpu, Preconditioner preconditioner) {
  if (!gpu && preconditioner == Preconditioner::multigrid) return ProductVariant::cached;
  return default_product_variant(type, precision, gpu);
}

}  // namespace snh
