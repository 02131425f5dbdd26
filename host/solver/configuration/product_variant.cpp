// Names of the Hessian-product variants and the measured default.
#include "fem/name_table.h"
#include "snh/error.h"
#include "snh/simulation.h"

namespace snh {

namespace {

constexpr NameTable<ProductVariant, 5> kProductVariantNames{{
    {ProductVariant::automatic, "automatic"},
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

// Measured with `snh-gpu-bench throughput --element hex8,tet4 --size
// 8,12,24,48 --variant cached,element-matrices,assembled` on pocl, 2 CPU
// cores (docs/performance.md), scored as setup + 50 products per Newton
// iteration: the assembled block stencil (kernels/stencil.cl) wins every
// case, hex8 and tet4, float and double, e.g. hex8 double 12^3 0.055 ms per
// product + 2.4 ms setup against 0.107 + 2.0 element matrices and 0.123 +
// 0.84 cached; 48^3 4.2 + 215 against 12.6 + 143 and 17.2 + 52; tet4 double
// 48^3 2.9 + 234 against 23.8 + 148 and 13.2 + 69. (Before it, with a ViennaCL
// compressed_matrix assembled on the host, element matrices won for hex8.)
// On an NVIDIA H100 (NVIDIA's OpenCL,
// `throughput --size 48,96`) the cached linearization wins every hex8 and
// tet4 double case so scored (hex8 double 48^3: 0.196 ms + 0.59 ms setup,
// against 0.363 + 4.5 element matrices, 0.186 + 482 assembled; tet4 double
// 48^3: 0.246 + 0.44 against 0.120 + 641 assembled) and ties the recomputed
// product for tet4 float (0.147 against 0.143 ms), so it is the GPU default
// (measured before the block stencil, whose setup is on the device: not
// re-measured there).
ProductVariant default_product_variant(ElementType, Precision, bool gpu) {
  return gpu ? ProductVariant::cached : ProductVariant::assembled;
}

// Measured with `snh-gpu-bench scene twist --res 32 --preconditioner
// multigrid --variant V` (pocl, 2 CPU cores, double, nu = 0.49; docs/performance.md):
// element matrices rebuilt at every linearization 24.4 s, cached 24.7 s; with
// the hierarchy reused (rebuild_every 4) element matrices 22.7 s (their
// per-Newton build and product stay), cached 19.2-19.9 s. The
// block stencil against cached, alternating: 6.77 / 6.49 s against 5.48 /
// 5.35 s (products 0.37 against 0.97 s, but element matrices and their
// assembly at every linearization 2.5 against 0.58 s).
ProductVariant default_product_variant(ElementType type, Precision precision, bool gpu, Preconditioner preconditioner) {
  if (!gpu && preconditioner == Preconditioner::multigrid) return ProductVariant::cached;
  return default_product_variant(type, precision, gpu);
}

}  // namespace snh
