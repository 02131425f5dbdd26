// The generalized winding number of a triangle soup, evaluated
// hierarchically (Barill, Dickson, Schmidt, Levin, Jacobson 2018, "Fast
// winding numbers for soups and clouds", Sec. 3-4): a bounding volume
// hierarchy over the triangles; a node far from the query (farther than
// beta times its radius from its area-weighted centre) contributes the
// second-order Taylor expansion of its dipole field, the others recurse down
// to the exact solid angles of their triangles (Van Oosterom and Strackee
// 1983). The winding number is 1 inside a closed surface with outward
// normals, 0 outside, and about 1/2 across a hole (Jacobson, Kavan and
// Sorkine-Hornung 2013, "Robust inside-outside segmentation using
// generalized winding numbers").
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "snh/surface.h"

namespace snh::fem {

// The signed solid angle of triangle (a, b, c) seen from the origin, over
// 4 pi: tan(Omega / 2) = a . (b x c) / (|a||b||c| + (a.b)|c| + (b.c)|a| +
// (c.a)|b|) (Van Oosterom and Strackee 1983). Positive when the triangle
// turns counter-clockwise seen from the origin.
inline double triangle_winding(const double a[3], const double b[3], const double c[3]) {
  const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  const double lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  const double lc = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  const double det =
      a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  const double ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const double bc = b[0] * c[0] + b[1] * c[1] + b[2] * c[2];
  const double ca = c[0] * a[0] + c[1] * a[1] + c[2] * a[2];
  return std::atan2(det, la * lb * lc + ab * lc + bc * la + ca * lb) / (2.0 * M_PI);
}

class FastWindingNumber {
 public:
  // beta > 0: larger is more accurate and slower (|error| below 0.1 at
  // beta = 2, 5e-3 at beta = 8 on the tests' surfaces; see
  // tests/test_fast_winding_number.cpp; a third-order term would reach
  // 1e-3 at beta = 2).
  // Triangles with two equal corners are skipped (they enclose nothing).
  explicit FastWindingNumber(const TriangleSurface& surface, double beta = 2.0);
  double operator()(const std::array<double, 3>& q) const;
  size_t node_count() const { return nodes_.size(); }

 private:
  struct Node {
    double centre[3];      // area-weighted centroid of the node's triangles
    double radius;         // farthest corner from the centre
    double normal[3];      // sum of the triangles' area vectors (first-order, dipole term)
    double moment[9];      // sum of area vector (x) (centroid - centre), row-major (second-order term)
    int32_t first, count;  // the node's triangles in corners_ (leaves)
    int32_t child[2];      // -1 for a leaf
  };
  int32_t build(std::vector<int32_t>& order, int32_t first, int32_t count, const std::vector<double>& centroids,
                const std::vector<double>& areas, const TriangleSurface& surface);

  double beta_;
  std::vector<Node> nodes_;
  std::vector<double> corners_;  // 9 coordinates per triangle, in hierarchy order
};

// The winding number (FastWindingNumber with `beta`) at the centre of every
// cell of the grid (origin, cell size h, dims; x fastest). With every_cell,
// evaluated at each centre. Otherwise evaluated at the cells whose cubes,
// grown by 1e-6 h, a triangle meets, and elsewhere only where it can change.
// Off the surface the winding number is harmonic. A closed surface (every
// edge traversed as often each way) makes it an integer, constant over each
// face-connected region of cells clear of the surface: one evaluation per
// region, its rounded value given to all (an evaluation farther than 1/4
// from an integer falls back to every cell of the region). An open one
// makes it vary smoothly; over a box of cells clear of the surface it lies
// between its least and greatest values on the box's boundary, so the grid
// is split recursively into boxes, and a clear box whose boundary cells,
// evaluated, all lie within 1/4 of one integer k gets k at its interior
// cells; any other box is split down to 4 cells a side and evaluated. The
// margin of 1/4 covers the expansion's error (below 0.1 at beta = 2) and,
// for boxes, the change from the boundary cells' centres to the box's
// faces, so that rounding the values, and comparing them with 1/2, gives
// what evaluating every centre gives (tests/test_fast_winding_number.cpp
// checks this on closed, opened and nested surfaces; snh-gpu-bench
// voxelize-compare on the shipped surfaces).
std::vector<double> winding_at_cell_centres(const TriangleSurface& surface, const std::array<double, 3>& origin,
                                            double h, const std::array<int, 3>& dims, double beta,
                                            bool every_cell = false);

}  // namespace snh::fem
