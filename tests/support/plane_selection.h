// Test set-ups: the vertices of a mesh on an axis-aligned plane, through the
// library's own selection (snh/selection.h).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "snh/mesh.h"
#include "snh/selection.h"

namespace snh::test {

// Vertices with coordinate `axis` (0, 1, 2) within 1e-9 of `value`, in
// vertex order.
inline std::vector<int32_t> on_plane(const Mesh& mesh, int axis, double value) {
  std::array<double, 3> point{0.0, 0.0, 0.0}, normal{0.0, 0.0, 0.0};
  point[axis] = value;
  normal[axis] = 1.0;
  return vertices_on_plane(mesh, point, normal);
}

}  // namespace snh::test
