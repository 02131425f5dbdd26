// The block stencil (host/solver/model/block_stencil.h, kernels/stencil.cl): its
// tables on an irregular tet mesh (gmsh's blob, vertices with up to 21
// neighbours, 11.6 on average: most rows padded), and the assembled product built from them
// against the element-matrix product, the constraint mask and run-to-run
// bitwise equality.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "fem/rest_state.h"
#include "fem/vertex_slots.h"
#include "snh/material.h"
#include "snh/mesh_io.h"
#include "snh/regions.h"
#include "solver/model/block_stencil.h"
#include "solver/model/elastic_model.h"
#include "support/device_test_support.h"
#include "vector_compare.h"

namespace snh::test {
namespace {

const std::string kData = SNH_DATA_DIR;

template <typename Real>
constexpr Precision precision_of = std::is_same_v<Real, double> ? Precision::double_ : Precision::single;

Mesh blob() { return read_mesh(kData + "/meshes/blob.msh"); }

std::vector<int> element_ints(const Mesh& mesh) { return {mesh.elements.begin(), mesh.elements.end()}; }

TEST(BlockStencil, TablesListEveryElementBlockOnceInElementOrder) {
  const Mesh mesh = blob();
  ASSERT_EQ(mesh.type, ElementType::tet4);
  const std::vector<int> elements = element_ints(mesh);
  const size_t count = mesh.vertex_count();
  const solver::StencilTables t = solver::stencil_tables(elements, count, 4, fem::vertex_slots(elements, count));
  const size_t width = static_cast<size_t>(t.width);
  ASSERT_EQ(t.neighbours.size(), width * count);
  ASSERT_EQ(t.part_offsets.size(), width * count + 1);
  // Every (element, a, b) block once: 16 per element.
  ASSERT_EQ(t.parts.size(), 16 * mesh.element_count());
  std::vector<int> sorted = t.parts;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_TRUE(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());
  size_t padded = 0, shortest = width;
  for (size_t v = 0; v < count; ++v) {
    const int* row = t.neighbours.data() + v * width;
    EXPECT_EQ(row[0], static_cast<int>(v));
    size_t size = 1;
    while (size < width && row[size] != static_cast<int>(v)) ++size;
    shortest = std::min(shortest, size);
    for (size_t s = size; s < width; ++s) {
      EXPECT_EQ(row[s], static_cast<int>(v)) << "padding is the vertex itself";
      EXPECT_EQ(t.part_offsets[v * width + s], t.part_offsets[v * width + s + 1]) << "padding adds nothing";
      ++padded;
    }
    EXPECT_TRUE(std::is_sorted(row + 1, row + size));
    for (size_t s = 0; s < size; ++s) {
      const int first = t.part_offsets[v * width + s], last = t.part_offsets[v * width + s + 1];
      EXPECT_GT(last, first) << "a neighbour shares an element";
      // Offset 144 e + 36 a + 3 b: node a of e at v, node b at the neighbour
      // (block (b, a), read transposed).
      for (int k = first; k < last; ++k) {
        const int part = t.parts[k], e = part / 144, a = (part % 144) / 36, b = (part % 36) / 3;
        EXPECT_EQ(part % 3, 0);
        EXPECT_EQ(elements[4 * e + a], static_cast<int>(v));
        EXPECT_EQ(elements[4 * e + b], row[s]);
        if (k > first) {
          EXPECT_LT(t.parts[k - 1] / 144, e) << "element order";
        }
      }
    }
  }
  EXPECT_GT(padded, width * count / 4) << "an irregular mesh: many rows shorter than the widest";
  EXPECT_LT(shortest, width);
}

// The upper layout (the CPUs' multigrid levels): each vertex pair's block
// stored once, in the row of the first of the two, with the full layout's
// parts for it; the other reads it through its index; padding reads the
// zero block after the stored ones.
TEST(BlockStencil, UpperTablesStoreEachPairOnceAndPointAtItsMirror) {
  const Mesh mesh = blob();
  const std::vector<int> elements = element_ints(mesh);
  const size_t count = mesh.vertex_count();
  const solver::StencilTables full = solver::stencil_tables(elements, count, 4, fem::vertex_slots(elements, count));
  const solver::StencilTables t = solver::upper_stencil_tables(full, count);
  const size_t width = static_cast<size_t>(full.width), upper = static_cast<size_t>(t.width),
               lower = static_cast<size_t>(t.lower), row = upper + 2 * lower;
  ASSERT_GT(lower, 0u);
  EXPECT_LT(upper, width);
  ASSERT_EQ(t.neighbours.size(), row * count);
  ASSERT_EQ(t.part_offsets.size(), upper * count + 1);
  EXPECT_EQ(solver::stencil_entries(t, count, 1), 9 * (upper * count + 1));
  const int zero_block = static_cast<int>(upper * count);
  // The full layout's parts of a block, by its vertex pair.
  auto full_parts = [&](size_t v, int n) {
    const int* r = full.neighbours.data() + width * v;
    const size_t s = n == static_cast<int>(v) ? 0 : static_cast<size_t>(std::find(r + 1, r + width, n) - r);
    return std::vector<int>(full.parts.begin() + full.part_offsets[width * v + s],
                            full.parts.begin() + full.part_offsets[width * v + s + 1]);
  };
  size_t stored = 0, mirrored = 0, pairs = 0;
  for (size_t v = 0; v < count; ++v) {
    const int self = static_cast<int>(v);
    const int* r = t.neighbours.data() + row * v;
    EXPECT_EQ(r[0], self);
    for (size_t u = 0; u < upper; ++u) {
      const std::vector<int> parts(t.parts.begin() + t.part_offsets[upper * v + u],
                                   t.parts.begin() + t.part_offsets[upper * v + u + 1]);
      if (u > 0 && r[u] == self) {
        EXPECT_TRUE(parts.empty()) << "padding adds nothing";
        continue;
      }
      EXPECT_TRUE(u == 0 || r[u] > self);
      EXPECT_EQ(parts, full_parts(v, r[u])) << "vertex " << v << " block " << u;
      ++stored;
    }
    for (size_t s = 0; s < lower; ++s) {
      const int n = r[upper + s], block = r[upper + lower + s];
      if (n == self) {
        EXPECT_EQ(block, zero_block) << "padding reads the zero block";
        continue;
      }
      ASSERT_LT(n, self);
      ASSERT_GE(block, 0);
      ASSERT_LT(block, zero_block);
      EXPECT_EQ(static_cast<size_t>(block) / upper, static_cast<size_t>(n)) << "in the row of the first vertex";
      EXPECT_EQ(t.neighbours[row * static_cast<size_t>(n) + static_cast<size_t>(block) % upper], self);
      ++mirrored;
    }
    for (size_t s = 1; s < width && full.neighbours[width * v + s] != self; ++s) ++pairs;
  }
  EXPECT_EQ(mirrored, pairs / 2);
  EXPECT_EQ(stored, count + pairs / 2) << "each vertex's own block and each pair once";
}

template <typename Real>
void check_assembled_on_blob(double bound) {
  Mesh mesh = blob();
  const fem::RestState rest = fem::compute_rest_state(mesh);
  const MaterialMap materials = uniform_material(mesh, StableNeoHookean::from_youngs_modulus(1.0, 0.45));
  // A twisted, stretched state with some jitter.
  std::vector<double> x = mesh.positions.xyz();
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const double px = x[3 * v], py = x[3 * v + 1], pz = x[3 * v + 2], angle = 0.6 * pz;
    x[3 * v] = std::cos(angle) * px - std::sin(angle) * py + u(rng);
    x[3 * v + 1] = std::sin(angle) * px + std::cos(angle) * py + u(rng);
    x[3 * v + 2] = 1.3 * pz + u(rng);
  }
  x = rounded<Real>(x);
  std::vector<double> p(x.size());
  for (double& value : p) value = u(rng) * 50.0;
  p = rounded<Real>(p);
  std::vector<Real> mask(x.size(), Real(1));
  for (size_t i = 0; i < mask.size(); i += 7) mask[i] = Real(0);

  solver::ElasticModel<Real> model(device_for(precision_of<Real>), mesh, rest, materials,
                                   ProductVariant::element_matrices);
  model.set_mask(mask);
  const viennacl::vector<Real> xd = upload<Real>(x), pd = upload<Real>(p);
  model.linearize(xd);
  viennacl::vector<Real> expected(model.dofs()), y(model.dofs()), again(model.dofs());
  model.product(pd, expected);
  model.products().set_variant(ProductVariant::assembled);
  model.linearize(xd);
  EXPECT_GT(model.products().assembled_width(), 13);
  model.product(pd, y);
  const std::vector<double> ye = download(expected), ya = download(y);
  const double difference = relative_difference(ya, ye);
  std::printf("blob (%zu tets), width %d: |assembled - element matrices| / |element matrices| = %.3g\n",
              mesh.element_count(), model.products().assembled_width(), difference);
  EXPECT_LE(difference, bound);
  for (size_t i = 0; i < mask.size(); ++i)
    if (mask[i] == Real(0)) {
      EXPECT_EQ(ya[i], 0.0) << "constrained DOF " << i;
    }
  model.linearize(xd);
  model.product(pd, again);
  EXPECT_EQ(download_raw(again), download_raw(y)) << "bitwise the same on the same device";
}

// Both sum the same element entries, in another order: rounding only.
TEST(BlockStencil, AssembledProductOnAnIrregularTetMeshMatchesElementMatricesDouble) {
  check_assembled_on_blob<double>(1e-13);
}
TEST(BlockStencil, AssembledProductOnAnIrregularTetMeshMatchesElementMatricesFloat) {
  check_assembled_on_blob<float>(2e-5);
}

}  // namespace
}  // namespace snh::test
