// Closed triangle surfaces made in code for the surface and voxelization
// tests, with what is known about them exactly, and an independent inside
// test (the generalized winding number by solid angles).
#pragma once

#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "snh/surface.h"

namespace snh::test {

// An axis-aligned box, 12 triangles facing outwards.
inline TriangleSurface box_surface(std::array<double, 3> lo, std::array<double, 3> hi) {
  TriangleSurface s;
  for (int c = 0; c < 8; ++c) {
    Vec3 p;
    for (int d = 0; d < 3; ++d) p[d] = (c >> d) & 1 ? hi[d] : lo[d];
    s.positions.push_back(p);
  }
  // Corner c: bit 0 +x, bit 1 +y, bit 2 +z; each face counter-clockwise from outside.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) s.triangles.insert(s.triangles.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
  return s;
}

// The octahedron |x| + |y| + |z| = r.
inline TriangleSurface octahedron(double r) {
  TriangleSurface s;
  s.positions = {{r, 0, 0}, {-r, 0, 0}, {0, r, 0}, {0, -r, 0}, {0, 0, r}, {0, 0, -r}};
  for (int sx = 0; sx < 2; ++sx)
    for (int sy = 0; sy < 2; ++sy)
      for (int sz = 0; sz < 2; ++sz) {
        int x = sx, y = 2 + sy, z = 4 + sz;
        // Outwards when the octant's sign count is even; swap two corners otherwise.
        if ((sx + sy + sz) % 2 == 1) std::swap(y, z);
        s.triangles.insert(s.triangles.end(), {x, y, z});
      }
  return s;
}

// The icosahedron subdivided `level` times, vertices on the sphere of `radius`.
inline TriangleSurface icosphere(int level, double radius) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<std::array<double, 3>> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                                          {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  const auto normalize = [](std::array<double, 3> p) {
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    return std::array<double, 3>{p[0] / n, p[1] / n, p[2] / n};
  };
  for (auto& p : v) p = normalize(p);
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<int, int>, int> middle;
    const auto mid = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto found = middle.find(key);
      if (found != middle.end()) return found->second;
      v.push_back(normalize({v[a][0] + v[b][0], v[a][1] + v[b][1], v[a][2] + v[b][2]}));
      return middle[key] = static_cast<int>(v.size() - 1);
    };
    std::vector<std::array<int, 3>> g;
    for (const auto& tri : f) {
      const int a = mid(tri[0], tri[1]), b = mid(tri[1], tri[2]), c = mid(tri[2], tri[0]);
      g.insert(g.end(), {{tri[0], a, c}, {tri[1], b, a}, {tri[2], c, b}, {a, b, c}});
    }
    f = g;
  }
  TriangleSurface s;
  for (const auto& p : v) s.positions.push_back({radius * p[0], radius * p[1], radius * p[2]});
  for (const auto& tri : f) s.triangles.insert(s.triangles.end(), tri.begin(), tri.end());
  return s;
}

// A box [0, 1] x [0, depth] x [0, 1] with a slot of `width` centred on
// x = 0.5, from the top face down to z = bottom, through its whole depth in
// y: the U-shaped outline in xz extruded along y.
inline TriangleSurface slit_box(double width, double bottom, double depth) {
  const double a = 0.5 - width / 2, b = 0.5 + width / 2;
  // The outline, counter-clockwise seen from -y (x right, z up)...
  const std::vector<std::array<double, 2>> outline = {{0, 0},      {1, 0},      {1, bottom}, {1, 1}, {b, 1},
                                                      {b, bottom}, {a, bottom}, {a, 1},      {0, 1}, {0, bottom}};
  // ... and its triangles, counter-clockwise too: the bottom bar fanned from
  // (0, 0) (its top edge holds the slot's corners), then the two prongs.
  const std::vector<std::array<int, 3>> caps = {{0, 1, 2}, {0, 2, 5}, {0, 5, 6}, {0, 6, 9},
                                                {9, 6, 7}, {9, 7, 8}, {5, 2, 3}, {5, 3, 4}};
  const int n = static_cast<int>(outline.size());
  TriangleSurface s;
  for (double y : {0.0, depth})
    for (const auto& p : outline) s.positions.push_back({p[0], y, p[1]});
  // Seen from -y the xz outline is counter-clockwise with x right and z up, so
  // the y = 0 cap faces -y as listed, and the y = depth cap is reversed.
  for (const auto& c : caps) {
    s.triangles.insert(s.triangles.end(), {c[0], c[1], c[2]});
    s.triangles.insert(s.triangles.end(), {n + c[0], n + c[2], n + c[1]});
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    s.triangles.insert(s.triangles.end(), {i, n + i, n + j, i, n + j, j});
  }
  return s;
}

// The generalized winding number of a closed surface at p (Jacobson et
// al. 2013): the triangles' signed solid angles over 4 pi (van Oosterom and
// Strackee's formula). Independent of voxelize's ray counting.
inline double winding_number(const TriangleSurface& s, const std::array<double, 3>& p) {
  double total = 0.0;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    double r[3][3], len[3];
    for (int k = 0; k < 3; ++k) {
      for (int d = 0; d < 3; ++d) r[k][d] = s.positions(s.triangles[3 * t + k], d) - p[d];
      len[k] = std::sqrt(r[k][0] * r[k][0] + r[k][1] * r[k][1] + r[k][2] * r[k][2]);
    }
    const double det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) -
                       r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
                       r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
    const auto dot = [&](int a, int b) { return r[a][0] * r[b][0] + r[a][1] * r[b][1] + r[a][2] * r[b][2]; };
    const double denominator = len[0] * len[1] * len[2] + dot(0, 1) * len[2] + dot(1, 2) * len[0] + dot(2, 0) * len[1];
    total += 2.0 * std::atan2(det, denominator);
  }
  return total / (4.0 * M_PI);
}

}  // namespace snh::test
