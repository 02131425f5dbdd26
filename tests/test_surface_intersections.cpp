// The exact self-intersection count: the orientation predicates against
// signs known by construction, the pair test on hand-built cases (crossing,
// touching, a gap of 1e-15, coplanar, folds across a shared edge, shared
// vertices), closed surfaces that do not intersect, and the broad phase
// against a count over all pairs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "geometry/exact_predicates.h"
#include "geometry/triangle_intersection.h"
#include "snh/mesh.h"
#include "snh/surface.h"
#include "snh/surface_intersections.h"
#include "support/errors.h"
#include "support/surface_shapes.h"

namespace snh {
namespace {

using geometry::orient2d;
using geometry::orient3d;

int sign(double x) { return (x > 0) - (x < 0); }

TriangleSurface two_triangles(std::array<std::array<double, 3>, 3> s, std::array<std::array<double, 3>, 3> t) {
  TriangleSurface out;
  for (const auto& p : s) out.positions.push_back(p);
  for (const auto& p : t) out.positions.push_back(p);
  out.triangles = {0, 1, 2, 3, 4, 5};
  return out;
}

size_t pairs_of(const TriangleSurface& s) { return count_self_intersections(s).intersecting_pairs; }

// Points p, q on the line y = x and r beside it: the orientation is
// (q_x - p_x)(r_y - r_x), whose sign comparisons give exactly. r one ulp off
// the line, with the line's points far apart, defeats the floating-point
// filter.
TEST(ExactPredicates, Orient2dIsExactNextToALine) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  const uint64_t before = geometry::exact_predicate_fallbacks();
  for (int i = 0; i < 300; ++i) {
    const double x1 = u(rng), x2 = u(rng) * 1e6, x3 = u(rng) * 1e-3;
    for (double y3 : {std::nextafter(x3, -HUGE_VAL), x3, std::nextafter(x3, HUGE_VAL)}) {
      const double p[2] = {x1, x1}, q[2] = {x2, x2}, r[2] = {x3, y3};
      const int expected = (x2 > x1 ? 1 : x2 < x1 ? -1 : 0) * (y3 > x3 ? 1 : y3 < x3 ? -1 : 0);
      ASSERT_EQ(orient2d(p, q, r), expected) << i;
      ASSERT_EQ(orient2d(q, r, p), expected) << i;
      ASSERT_EQ(orient2d(q, p, r), -expected) << i;
    }
  }
  EXPECT_GT(geometry::exact_predicate_fallbacks(), before);
}

// a, b, c on the plane z = x; the orientation of d is an affine function of
// d vanishing there, k (d_z - d_x), with k's sign from a point far off the plane.
TEST(ExactPredicates, Orient3dIsExactNextToAPlane) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const uint64_t before = geometry::exact_predicate_fallbacks();
  int decided_exactly = 0;
  for (int i = 0; i < 300; ++i) {
    double a[3], b[3], c[3];
    for (double* p : {a, b, c}) {
      p[0] = u(rng) * 0.37;  // not dyadic: the differences round
      p[1] = u(rng) * 3.1;
      p[2] = p[0];
    }
    const double x = u(rng) * 0.1, y = u(rng);
    const double far[3] = {x, y, x + 10.0};
    const int k = orient3d(a, b, c, far);
    ASSERT_NE(k, 0);
    for (double z : {std::nextafter(x, -HUGE_VAL), x, std::nextafter(x, HUGE_VAL)}) {
      const double d[3] = {x, y, z};
      const int expected = k * sign(z - x);
      ASSERT_EQ(orient3d(a, b, c, d), expected) << i;
      ASSERT_EQ(orient3d(b, a, c, d), -expected) << i;
      ASSERT_EQ(orient3d(b, c, a, d), expected) << i;
      decided_exactly += expected == 0;
    }
  }
  EXPECT_EQ(decided_exactly, 300);
  EXPECT_GT(geometry::exact_predicate_fallbacks(), before);
}

TEST(ExactPredicates, HugeAndTinyCoordinatesAreDecidedExactly) {
  const double a[3] = {1e300, 0, 0}, b[3] = {0, 1e300, 0}, c[3] = {0, 0, 1e300}, d[3] = {1e-300, 0, 0};
  EXPECT_EQ(orient3d(a, b, c, d), 1);  // the origin side: below abc (counterclockwise from outside)
  const double e[3] = {1e300, 1e300, 1e300};
  EXPECT_EQ(orient3d(a, b, c, e), -1);
  const double t0[3] = {0, 0, 0}, t1[3] = {1e-310, 0, 0}, t2[3] = {0, 1e-310, 0}, t3[3] = {0, 0, 4.9e-324};
  EXPECT_EQ(orient3d(t0, t1, t2, t3), -1);
}

TEST(SurfaceIntersections, CrossingTrianglesIntersect) {
  EXPECT_EQ(
      pairs_of(two_triangles({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0.2, 0.2, -1}, {0.3, 0.2, 1}, {0.2, 0.3, 1}}})),
      1u);
  // Piercing the edge region only: one triangle's edge through the other's interior.
  EXPECT_EQ(
      pairs_of(two_triangles({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0.25, 0.25, -1}, {0.25, 0.25, 1}, {5, 5, 0}}})),
      1u);
  // Far apart, and apart with overlapping bounding boxes.
  EXPECT_EQ(pairs_of(two_triangles({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{3, 0, 0}, {4, 0, 0}, {3, 1, 0}}})), 0u);
  EXPECT_EQ(pairs_of(two_triangles({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0.9, 0.9, -1}, {0.9, 0.9, 1}, {2, 2, 0}}})),
            0u);
}

TEST(SurfaceIntersections, TouchingCountsAndAGapOf1e15DoesNot) {
  const std::array<std::array<double, 3>, 3> base = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
  // A corner resting on the interior, on an edge, on a corner.
  EXPECT_EQ(pairs_of(two_triangles(base, {{{0.2, 0.2, 0}, {0.3, 0.2, 1}, {0.2, 0.3, 1}}})), 1u);
  EXPECT_EQ(pairs_of(two_triangles(base, {{{0.5, 0, 0}, {0.5, -0.2, 1}, {0.6, -0.2, 1}}})), 1u);
  EXPECT_EQ(pairs_of(two_triangles(base, {{{1, 0, 0}, {2, 0, 1}, {2, 1, 1}}})), 1u);
  // Edge across edge, not coplanar.
  EXPECT_EQ(pairs_of(two_triangles(base, {{{0.5, -0.5, 0}, {0.5, 0.5, 0}, {0.5, 0, 1}}})), 1u);
  // 1e-15 above the plane: apart; 1e-15 below: through it.
  for (double gap : {1e-15, 1e-300}) {
    EXPECT_EQ(pairs_of(two_triangles(base, {{{0.2, 0.2, gap}, {0.3, 0.2, 1}, {0.2, 0.3, 1}}})), 0u) << gap;
    EXPECT_EQ(pairs_of(two_triangles(base, {{{0.2, 0.2, -gap}, {0.3, 0.2, 1}, {0.2, 0.3, 1}}})), 1u) << gap;
  }
  // A corner 1e-15 beyond an edge, in the plane.
  EXPECT_EQ(pairs_of(two_triangles(base, {{{0.5, -1e-15, 0}, {0.5, -0.2, 1}, {0.6, -0.2, 1}}})), 0u);
  EXPECT_EQ(pairs_of(two_triangles(base, {{{0.5, 1e-15, 0}, {0.5, -0.2, 1}, {0.6, -0.2, 1}}})), 1u);
  // On a tilted plane whose points are not representable: a corner exactly
  // on it (by the construction z = x), or one ulp off it.
  const std::array<std::array<double, 3>, 3> tilted = {{{0.1, 0.3, 0.1}, {0.7, 0.2, 0.7}, {0.3, 0.9, 0.3}}};
  const double x = 0.33, y = 0.41;
  EXPECT_EQ(pairs_of(two_triangles(tilted, {{{x, y, x}, {x, y, 2}, {x + 0.1, y, 2}}})), 1u);
  EXPECT_EQ(pairs_of(two_triangles(tilted, {{{x, y, std::nextafter(x, 2.0)}, {x, y, 2}, {x + 0.1, y, 2}}})), 0u);
}

TEST(SurfaceIntersections, CoplanarOverlapsCount) {
  const std::array<std::array<double, 3>, 3> base = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
  EXPECT_EQ(pairs_of(two_triangles(base, {{{0.2, 0.2, 0}, {1.2, 0.2, 0}, {0.2, 1.2, 0}}})), 1u);  // overlap
  EXPECT_EQ(pairs_of(two_triangles(base, {{{0.1, 0.1, 0}, {0.3, 0.1, 0}, {0.1, 0.3, 0}}})), 1u);  // inside
  EXPECT_EQ(pairs_of(two_triangles(base, {{{-1, -1, 0}, {3, -1, 0}, {-1, 3, 0}}})), 1u);          // around
  EXPECT_EQ(pairs_of(two_triangles(base, {{{0.5, 0.5, 0}, {1, 1, 0}, {1, 0.5, 0}}})), 1u);  // touching the hypotenuse
  EXPECT_EQ(pairs_of(two_triangles(base, {{{0.6, 0.6, 0}, {1, 1, 0}, {1, 0.6, 0}}})), 0u);  // apart
  EXPECT_EQ(pairs_of(two_triangles(base, {{{0, 0, 0}, {-1, 0, 0}, {0, -1, 0}}})), 1u);      // a common corner point
  // Coplanar on a tilted plane (z = x exactly).
  EXPECT_EQ(pairs_of(two_triangles({{{0.1, 0.3, 0.1}, {0.7, 0.2, 0.7}, {0.3, 0.9, 0.3}}},
                                   {{{0.3, 0.4, 0.3}, {0.9, 0.9, 0.9}, {0.2, 1.3, 0.2}}})),
            1u);
}

// Two triangles sharing the edge 0-1 (vertex indices, not only positions).
TriangleSurface hinge(std::array<double, 3> a, std::array<double, 3> b) {
  TriangleSurface s;
  s.positions = {{0, 0, 0}, {1, 0, 0}, a, b};
  s.triangles = {0, 1, 2, 1, 0, 3};
  return s;
}

TEST(SurfaceIntersections, SharedEdgeCountsOnlyAFold) {
  EXPECT_EQ(pairs_of(hinge({0.5, 1, 0}, {0.5, -1, 0})), 0u);      // flat
  EXPECT_EQ(pairs_of(hinge({0.5, 1, 0}, {0.5, 0, 1})), 0u);       // at a right angle
  EXPECT_EQ(pairs_of(hinge({0.5, 1, 0}, {0.5, 1, 1e-15})), 0u);   // nearly folded
  EXPECT_EQ(pairs_of(hinge({0.5, 1, 0}, {0.5, 1, -1e-15})), 0u);  // nearly folded, the other way
  EXPECT_EQ(pairs_of(hinge({0.5, 1, 0}, {0.2, 0.3, 0})), 1u);     // folded flat onto it
  EXPECT_EQ(pairs_of(hinge({0.5, 1, 0}, {3.0, 0.1, 0})), 1u);     // folded, reaching beyond it
  // The same positions without the shared indices: the edge is a touch.
  TriangleSurface apart = hinge({0.5, 1, 0}, {0.5, 0, 1});
  apart.positions.push_back({0, 0, 0});
  apart.positions.push_back({1, 0, 0});
  apart.triangles = {0, 1, 2, 5, 4, 3};
  EXPECT_EQ(pairs_of(apart), 1u);
  // The same triangle twice.
  TriangleSurface twice = hinge({0.5, 1, 0}, {0.5, 0, 1});
  twice.triangles = {0, 1, 2, 2, 0, 1};
  EXPECT_EQ(pairs_of(twice), 1u);
}

// Two triangles sharing vertex 0 at the origin.
TriangleSurface fan(std::array<double, 3> a, std::array<double, 3> b, std::array<double, 3> c,
                    std::array<double, 3> d) {
  TriangleSurface s;
  s.positions = {{0, 0, 0}, a, b, c, d};
  s.triangles = {0, 1, 2, 0, 3, 4};
  return s;
}

TEST(SurfaceIntersections, SharedVertexCountsOnlyAnotherCommonPoint) {
  EXPECT_EQ(pairs_of(fan({1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0})), 0u);        // coplanar, opposite
  EXPECT_EQ(pairs_of(fan({1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, -1, 1})), 0u);        // apart in space
  EXPECT_EQ(pairs_of(fan({1, 0, 0}, {0, 1, 0}, {1, 1, -1}, {1, 1, 1})), 1u);         // its far edge pierces the first
  EXPECT_EQ(pairs_of(fan({1, 0, 0}, {0, 1, 0}, {0.1, 0.1, 1}, {0.2, 0.1, 1})), 0u);  // above, from the corner
  EXPECT_EQ(pairs_of(fan({1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 2, 0})), 1u);          // coplanar wedge overlapping
  EXPECT_EQ(pairs_of(fan({1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {-1, 1, 0})), 1u);         // coplanar, across the far edge
  EXPECT_EQ(pairs_of(fan({1, 0, 0}, {0, 1, 0}, {0, 1, 0}, {-1, 1, 0})),
            1u);  // touching along a ray (vertex 2 and 3 coincide)
  EXPECT_EQ(pairs_of(fan({1, 0, 0}, {0, 1, 0}, {-1e-15, 1, 0}, {-1, 1, 0})), 0u);  // 1e-15 apart along that ray
  // Crossing through the shared corner's surroundings: the second triangle
  // passes through the first along a segment starting at the shared vertex.
  EXPECT_EQ(pairs_of(fan({1, 0, 0}, {0, 1, 0}, {0.5, 0.5, 1}, {0.5, 0.5, -1})), 1u);
}

TEST(SurfaceIntersections, DegenerateTrianglesAreCountedApart) {
  TriangleSurface s =
      two_triangles({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0.2, 0.2, -1}, {0.2, 0.2, 0}, {0.2, 0.2, 1}}});
  const SelfIntersections r = count_self_intersections(s);
  EXPECT_EQ(r.intersecting_pairs, 0u);
  EXPECT_EQ(r.degenerate_triangles, 1u);
  ASSERT_EQ(r.first_degenerate.size(), 1u);
  EXPECT_EQ(r.first_degenerate[0], 1);
  EXPECT_FALSE(r.clean());
  s.triangles = {0, 1, 2, 3, 3, 4};  // a repeated index
  EXPECT_EQ(count_self_intersections(s).degenerate_triangles, 1u);
}

TEST(SurfaceIntersections, ClosedSurfacesAreClean) {
  for (int level : {0, 2, 4}) {
    const SelfIntersections r = count_self_intersections(test::icosphere(level, 1.3));
    EXPECT_TRUE(r.clean()) << level << ": " << r.intersecting_pairs;
  }
  const MeshBoundary cube = boundary_surface(make_box_lattice(6, 5, 4, 0.25));
  const SelfIntersections r = count_self_intersections(cube.surface);
  EXPECT_EQ(r.triangles, 2u * 2 * (6 * 5 + 5 * 4 + 6 * 4));
  EXPECT_TRUE(r.clean()) << r.intersecting_pairs;
}

// All pairs through the same exact test: what the broad phase must find.
size_t brute_force(const TriangleSurface& s) {
  size_t n = 0;
  const auto tri = [&](size_t t) {
    geometry::IndexedTriangle out;
    for (int c = 0; c < 3; ++c) {
      out.vertex[c] = s.triangles[3 * t + c];
      out.corner[c] = s.positions.data() + 3 * size_t(out.vertex[c]);
    }
    return out;
  };
  for (size_t a = 0; a < s.triangle_count(); ++a)
    for (size_t b = a + 1; b < s.triangle_count(); ++b)
      if (!geometry::triangle_degenerate(tri(a)) && !geometry::triangle_degenerate(tri(b)) &&
          geometry::triangles_intersect(tri(a), tri(b)))
        ++n;
  return n;
}

// Two spheres, the second moved into the first and turned, and a large
// triangle through both (tested outside the grid).
TriangleSurface two_spheres() {
  TriangleSurface s = test::icosphere(3, 1.0);
  const TriangleSurface t = test::icosphere(3, 0.8);
  const int32_t offset = int32_t(s.vertex_count());
  const double c = std::cos(0.3), n = std::sin(0.3);
  for (size_t v = 0; v < t.vertex_count(); ++v) {
    const double x = t.positions(v, 0), y = t.positions(v, 1), z = t.positions(v, 2);
    s.positions.push_back({c * x - n * y + 0.9, n * x + c * y + 0.05, z - 0.03});
  }
  for (int32_t i : t.triangles) s.triangles.push_back(i + offset);
  const int32_t big = int32_t(s.vertex_count());
  s.positions.push_back({-3, -3, 0.11});
  s.positions.push_back({4, -2.5, 0.13});
  s.positions.push_back({0.5, 4, 0.12});
  s.triangles.insert(s.triangles.end(), {big, big + 1, big + 2});
  return s;
}

TEST(SurfaceIntersections, InterpenetratingSpheresAgreeWithAllPairs) {
  const TriangleSurface s = two_spheres();
  const SelfIntersections r = count_self_intersections(s);
  const size_t expected = brute_force(s);
  EXPECT_GT(expected, 100u);
  EXPECT_EQ(r.intersecting_pairs, expected);
  ASSERT_EQ(r.first_pairs.size(), 10u);
  EXPECT_TRUE(std::is_sorted(r.first_pairs.begin(), r.first_pairs.end()));
  for (const auto& p : r.first_pairs) EXPECT_LT(p[0], p[1]);
}

TEST(SurfaceIntersections, CountDoesNotDependOnTriangleOrCornerOrder) {
  const TriangleSurface s = two_spheres();
  const size_t expected = count_self_intersections(s).intersecting_pairs;
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<size_t> order(s.triangle_count());
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), rng);
    TriangleSurface shuffled = s;
    shuffled.triangles.clear();
    for (size_t t : order) {
      const int r = int(rng() % 3);  // rotate the corners, keeping the orientation
      for (int c = 0; c < 3; ++c) shuffled.triangles.push_back(s.triangles[3 * t + (c + r) % 3]);
    }
    EXPECT_EQ(count_self_intersections(shuffled).intersecting_pairs, expected) << trial;
  }
}

TEST(SurfaceIntersections, BadInputNamesTheItem) {
  TriangleSurface s = two_triangles({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{3, 0, 0}, {4, 0, 0}, {3, 1, 0}}});
  SelfIntersectionOptions o;
  o.name = "limb.obj";
  TriangleSurface bad = s;
  bad.triangles[4] = 6;
  std::string m = test::error_of([&] { count_self_intersections(bad, o); });
  EXPECT_TRUE(test::contains(m, "limb.obj: triangle 1 names vertex 6 of 6")) << m;
  bad = s;
  bad.positions(2, 1) = std::nan("");
  m = test::error_of([&] { count_self_intersections(bad, o); });
  EXPECT_TRUE(test::contains(m, "limb.obj: vertex 2 has a non-finite coordinate")) << m;
  bad = s;
  bad.triangles.pop_back();
  m = test::error_of([&] { count_self_intersections(bad, o); });
  EXPECT_TRUE(test::contains(m, "limb.obj: 5 triangle indices")) << m;
}

}  // namespace
}  // namespace snh
