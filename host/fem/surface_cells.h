// The grid cells a triangle surface passes through: those whose open cube a
// triangle meets. The voxelizer keeps them on request
// (VoxelizeOptions::cover_surface); pieces.cpp joins a lattice piece to
// the body through them, along the surface. Internal.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "snh/surface.h"

namespace snh::fem {

// Whether triangle (v0, v1, v2) meets the axis-aligned box of half-size r
// about `centre`: no separating axis among the box's 3 normals, the
// triangle's normal and the 9 cross products of box and triangle edges
// (Akenine-Moeller, "Fast 3D triangle-box overlap testing", 2001).
inline bool triangle_meets_box(const double* v0, const double* v1, const double* v2, const double centre[3], double r) {
  double v[3][3];
  for (int d = 0; d < 3; ++d) {
    v[0][d] = v0[d] - centre[d];
    v[1][d] = v1[d] - centre[d];
    v[2][d] = v2[d] - centre[d];
  }
  double e[3][3];
  for (int d = 0; d < 3; ++d) {
    e[0][d] = v[1][d] - v[0][d];
    e[1][d] = v[2][d] - v[1][d];
    e[2][d] = v[0][d] - v[2][d];
  }
  const auto separated = [&](const double axis[3]) {
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (const auto& p : v) {
      const double x = axis[0] * p[0] + axis[1] * p[1] + axis[2] * p[2];
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
    const double reach = r * (std::abs(axis[0]) + std::abs(axis[1]) + std::abs(axis[2]));
    return lo > reach || hi < -reach;
  };
  for (int d = 0; d < 3; ++d) {
    const double axis[3] = {double(d == 0), double(d == 1), double(d == 2)};
    if (separated(axis)) return false;
  }
  const double normal[3] = {e[0][1] * e[1][2] - e[0][2] * e[1][1], e[0][2] * e[1][0] - e[0][0] * e[1][2],
                            e[0][0] * e[1][1] - e[0][1] * e[1][0]};
  if (separated(normal)) return false;
  for (int d = 0; d < 3; ++d)
    for (const auto& edge : e) {
      const double unit[3] = {double(d == 0), double(d == 1), double(d == 2)};
      const double axis[3] = {unit[1] * edge[2] - unit[2] * edge[1], unit[2] * edge[0] - unit[0] * edge[2],
                              unit[0] * edge[1] - unit[1] * edge[0]};
      if (separated(axis)) return false;
    }
  return true;
}

// Per cell of the grid (origin, cell size h, dims; x fastest): 1 where a
// triangle meets the cell's cube scaled by `scale` about its centre (by
// default the open cube: shrunk by 1e-9 h, so that a face lying on a cell
// boundary crosses neither cell beside it).
inline std::vector<char> surface_crossed_cells(const TriangleSurface& surface, const std::array<double, 3>& origin,
                                               double h, const std::array<int, 3>& dims, double scale = 1.0 - 1e-9) {
  std::vector<char> crossed(static_cast<size_t>(dims[0]) * dims[1] * dims[2], 0);
  const double r = 0.5 * h * scale;
  for (size_t t = 0; t < surface.triangle_count(); ++t) {
    const double* v[3];
    for (int k = 0; k < 3; ++k) v[k] = surface.positions.data() + 3 * static_cast<size_t>(surface.triangles[3 * t + k]);
    int lo[3], hi[3];
    for (int d = 0; d < 3; ++d) {
      const double mn = std::min({v[0][d], v[1][d], v[2][d]}), mx = std::max({v[0][d], v[1][d], v[2][d]});
      lo[d] = std::max(0, static_cast<int>(std::floor((mn - origin[d]) / h)) - 1);
      hi[d] = std::min(dims[d] - 1, static_cast<int>(std::floor((mx - origin[d]) / h)) + 1);
    }
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) {
          char& c = crossed[size_t(i) + size_t(dims[0]) * (size_t(j) + size_t(dims[1]) * k)];
          if (c) continue;
          const double centre[3] = {origin[0] + (i + 0.5) * h, origin[1] + (j + 0.5) * h, origin[2] + (k + 0.5) * h};
          if (triangle_meets_box(v[0], v[1], v[2], centre, r)) c = 1;
        }
  }
  return crossed;
}

}  // namespace snh::fem
