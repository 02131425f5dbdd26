// Names of the Hessian-product variants and the measured default.
#include "fem/name_table.h"
#include "snh/error.h"
#include "snh/simulation.h"

namespace snh {

namespace {

constexpr NameTable<ProductVariant, 4> kProductVariantNames{{
    {ProductVariant::cached, "cached"},
    {ProductVariant::recompute, "recompute"},
    {ProductVariant::element_matrices, "element-matrices"},
    {ProductVariant::assembled, "assembled"},
}};

}  // namespace

const char* to_string(ProductVariant v) { return name_of(kProductVariantNames, v); }

ProductVariant parse_product_variant(const std::string& text) {
  return value_named(kProductVariantNames, text, "product variant");
}

// CPU devices: the assembled block stencil (kernels/stencil.cl); GPUs: the
// cached linearization. Each measured fastest there (or tied), hex8 and tet4,
// scored as setup + 50 products per Newton iteration (docs/performance.md,
// "Default product variant").
ProductVariant default_product_variant(ElementType, Precision, bool gpu) {
  return gpu ? ProductVariant::cached : ProductVariant::assembled;
}

// Multigrid on CPU devices: the cached linearization. The hierarchy is reused
// between linearizations, but element matrices and the block stencil would
// still be built at every one; cached, which builds neither, measured faster
// than both despite slower products (docs/performance.md, "Product variant
// with multigrid on CPUs").
ProductVariant default_product_variant(ElementType type, Precision precision, bool gpu, Preconditioner preconditioner) {
  if (!gpu && preconditioner == Preconditioner::multigrid) return ProductVariant::cached;
  return default_product_variant(type, precision, gpu);
}

}  // namespace snh
