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

ProductVariant default_product_variant(ElementType, Precision, bool) { return ProductVariant::cached; }

}  // namespace snh
