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

// Measured with `snh-gpu-bench throughput --size 8,16` on pocl (2 CPU cores):
// per-element matrices win for hex8 and tet4 in float and double (setup plus
// 50 products per Newton iteration: e.g. hex8 16^3 double 0.71 ms per product
// and 104 ms setup, against 5.5 ms and 26 ms cached, 3.3 ms and 116 ms
// assembled, 21.9 ms recomputed). No GPU was measured: there the cached
// linearization, 7.5x less memory than element matrices, is the default until
// a measurement says otherwise.
ProductVariant default_product_variant(ElementType, Precision, bool gpu) {
  return gpu ? ProductVariant::cached : ProductVariant::element_matrices;
}

}  // namespace snh
