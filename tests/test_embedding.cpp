// The embedding of a surface in a lattice (snh/surface.h: embed,
// embedded_positions) on hand-made voxelizations: exact under affine maps of
// the lattice (trilinear interpolation reproduces them), each vertex in the
// element that contains it, boundary vertices to the first kept cell in grid
// order, vertices outside the lattice extrapolated from the nearest kept
// cell, and errors for vertices far from it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "snh/error.h"
#include "snh/surface.h"
#include "voxel_test_support.h"

namespace snh {
namespace {

using test::box_voxelization;

const std::array<double, 3> kOrigin{-1.0, 0.3, 2.0};
constexpr double kCell = 0.5;

TriangleSurface points(const std::vector<std::array<double, 3>>& p) {
  TriangleSurface s;
  for (const auto& x : p) s.positions.push_back(x);
  return s;
}

std::array<double, 3> grid_point(double i, double j, double k) {
  return {kOrigin[0] + kCell * i, kOrigin[1] + kCell * j, kOrigin[2] + kCell * k};
}

// Random points in the 4 x 3 x 2 box, grid points on faces, edges and
// corners, and points just outside the box's faces.
TriangleSurface sample_points() {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::array<double, 3>> p;
  for (int n = 0; n < 200; ++n) p.push_back(grid_point(4 * u(rng), 3 * u(rng), 2 * u(rng)));
  p.push_back(grid_point(2, 1, 1));         // an interior lattice vertex: 8 cells
  p.push_back(grid_point(1.5, 1, 0.5));     // a face between two cells
  p.push_back(grid_point(0, 0, 0));         // the box's corner
  p.push_back(grid_point(4, 3, 2));         // the opposite corner
  p.push_back(grid_point(-0.3, 1.2, 0.7));  // outside the x- face
  p.push_back(grid_point(2.5, 3.4, 2.2));   // outside the y+ and z+ faces
  return points(p);
}

// x = A X + b on the lattice's rest positions.
Points affine(const Points& rest, const double a[9], const double b[3]) {
  Points x(rest.size());
  for (size_t v = 0; v < rest.size(); ++v)
    for (int r = 0; r < 3; ++r)
      x(v, r) = a[3 * r] * rest(v, 0) + a[3 * r + 1] * rest(v, 1) + a[3 * r + 2] * rest(v, 2) + b[r];
  return x;
}

double max_abs_difference(const Points& a, const Points& b) {
  double m = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k) m = std::max(m, std::abs(a(i, k) - b(i, k)));
  return m;
}

TEST(Embedding, WeightsSumToOneAndReproduceTheRestSurface) {
  const Voxelization v = box_voxelization(4, 3, 2, kCell, kOrigin);
  const TriangleSurface s = sample_points();
  const Embedding e = embed(v, s);
  ASSERT_EQ(e.element.size(), s.vertex_count());
  ASSERT_EQ(e.weights.size(), 8 * s.vertex_count());
  for (size_t i = 0; i < s.vertex_count(); ++i) {
    double sum = 0.0;
    for (int a = 0; a < 8; ++a) sum += e.weights[8 * i + a];
    EXPECT_NEAR(sum, 1.0, 1e-14) << "vertex " << i;
  }
  EXPECT_LT(max_abs_difference(embedded_positions(e, v.lattice, v.lattice.positions), s.positions), 1e-14);
}

TEST(Embedding, AffineDeformationsMoveTheSurfaceByTheSameMap) {
  // With a dropped corner cell, so that extrapolated vertices are covered too.
  const Voxelization v =
      box_voxelization(4, 3, 2, kCell, kOrigin, [](int i, int j, int k) { return !(i == 0 && j == 1 && k == 0); });
  TriangleSurface s = sample_points();
  const auto in_dropped = grid_point(0.4, 1.6, 0.3);
  s.positions.push_back(in_dropped);
  const Embedding e = embed(v, s);
  const double maps[3][9] = {{1.3, 0.2, -0.1, 0.05, 0.8, 0.3, -0.2, 0.1, 1.1},  // general, det > 0
                             {0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0},    // rotation
                             {2.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 1.0}};    // non-uniform scale
  const double b[3] = {0.7, -2.0, 0.25};
  for (const auto& a : maps) {
    const Points moved = embedded_positions(e, v.lattice, affine(v.lattice.positions, a, b));
    const Points expected = affine(s.positions, a, b);
    EXPECT_LT(max_abs_difference(moved, expected), 1e-13);
  }
}

TEST(Embedding, EachVertexLiesInItsElement) {
  const Voxelization v = box_voxelization(4, 3, 2, kCell, kOrigin);
  const TriangleSurface s = sample_points();
  const Embedding e = embed(v, s);
  for (size_t i = 0; i < 200; ++i) {  // the random points inside the box
    const auto& cell = v.element_cell[e.element[i]];
    for (int d = 0; d < 3; ++d) {
      const double u = (s.positions(i, d) - kOrigin[d]) / kCell;
      EXPECT_GE(u, cell[d] - 1e-12) << "vertex " << i;
      EXPECT_LE(u, cell[d] + 1 + 1e-12) << "vertex " << i;
    }
    for (int a = 0; a < 8; ++a) EXPECT_GE(e.weights[8 * i + a], -1e-14) << "vertex " << i;
  }
}

TEST(Embedding, BoundaryVerticesGoToTheFirstKeptCellInGridOrder) {
  const Voxelization all = box_voxelization(4, 3, 2, kCell, kOrigin);
  const TriangleSurface s =
      points({grid_point(2, 1, 1), grid_point(1.5, 1, 0.5), grid_point(4, 3, 2), grid_point(2 + 1e-12, 1 - 1e-12, 1)});
  Embedding e = embed(all, s);
  using Cell = std::array<int, 3>;
  EXPECT_EQ(all.element_cell[e.element[0]], (Cell{1, 0, 0}));  // the lowest of the 8 cells around the vertex
  EXPECT_EQ(all.element_cell[e.element[1]], (Cell{1, 0, 0}));  // of (1, 0, 0) and (1, 1, 0)
  EXPECT_EQ(all.element_cell[e.element[2]], (Cell{3, 2, 1}));  // the only cell there
  EXPECT_EQ(all.element_cell[e.element[3]], (Cell{1, 0, 0}));  // rounding does not change the choice
  // The vertex at the corner of a lattice vertex's cells: the corner's weight is 1.
  EXPECT_NEAR(e.weights[8 * 0 + 6], 1.0, 1e-15);

  // Without cell (1, 0, 0), the next of the 8 in grid order, (2, 0, 0).
  const Voxelization holed =
      box_voxelization(4, 3, 2, kCell, kOrigin, [](int i, int j, int k) { return !(i == 1 && j == 0 && k == 0); });
  e = embed(holed, s);
  EXPECT_EQ(holed.element_cell[e.element[0]], (Cell{2, 0, 0}));
  EXPECT_EQ(holed.element_cell[e.element[1]], (Cell{1, 1, 0}));
}

TEST(Embedding, VerticesOutsideTheLatticeFollowTheNearestCell) {
  // One kept cell of three: vertices in the dropped cells next to it
  // extrapolate its trilinear field.
  const Voxelization v = box_voxelization(3, 1, 1, kCell, kOrigin, [](int i, int, int) { return i == 1; });
  const TriangleSurface s = points({grid_point(0.6, 0.5, 0.5), grid_point(2.7, 0.2, 0.9), grid_point(1.5, 1.4, -0.3)});
  const Embedding e = embed(v, s);
  for (size_t i = 0; i < 3; ++i) EXPECT_EQ(e.element[i], 0);
  // The first vertex is 0.4 cells below the cell in x: weights of u = -0.4.
  EXPECT_NEAR(e.weights[0], 1.4 * 0.5 * 0.5, 1e-14);
  EXPECT_NEAR(e.weights[1], -0.4 * 0.5 * 0.5, 1e-14);
  EXPECT_LT(max_abs_difference(embedded_positions(e, v.lattice, v.lattice.positions), s.positions), 1e-14);
}

TEST(Embedding, ErrorsNameTheVertexAndTheInput) {
  const Voxelization v = box_voxelization(3, 1, 1, kCell, kOrigin, [](int i, int, int) { return i == 1; });
  try {
    embed(v, points({grid_point(1.5, 0.5, 0.5), grid_point(-0.2, 0.5, 0.5)}));  // 1.2 cells from the kept cell
    FAIL() << "no error";
  } catch (const Error& err) {
    EXPECT_NE(std::string(err.what()).find("surface vertex 1"), std::string::npos) << err.what();
  }
  EXPECT_THROW(embed(v, points({grid_point(1.5, 0.5, 5.0)})), Error);  // far outside the grid
  const Embedding e = embed(v, points({grid_point(1.5, 0.5, 0.5)}));
  EXPECT_THROW(embedded_positions(e, v.lattice, Points{Vec3{1.0, 2.0, 0.0}}), Error);  // wrong size
  Voxelization bad = v;
  bad.element_cell.clear();
  EXPECT_THROW(embed(bad, points({grid_point(1.5, 0.5, 0.5)})), Error);
  bad = v;
  bad.cell = 0.0;
  EXPECT_THROW(embed(bad, points({grid_point(1.5, 0.5, 0.5)})), Error);
}

}  // namespace
}  // namespace snh
