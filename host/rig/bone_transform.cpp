// 4x4 bone matrices as Simulation's transforms (snh/rig.h).
#include <cmath>
#include <sstream>

#include "snh/error.h"
#include "snh/rig.h"

namespace snh {

Matrix4 identity_matrix4() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }

RigidTransform to_rigid_transform(const Matrix4& m, const std::array<double, 3>& center) {
  for (int i = 0; i < 16; ++i)
    if (!std::isfinite(m[i])) throw Error("to_rigid_transform: entry " + std::to_string(i) + " is not finite");
  if (m[12] != 0.0 || m[13] != 0.0 || m[14] != 0.0 || m[15] != 1.0) {
    std::ostringstream s;
    s << "to_rigid_transform: the last row is " << m[12] << " " << m[13] << " " << m[14] << " " << m[15]
      << ", not 0 0 0 1 (a projective matrix)";
    throw Error(s.str());
  }
  RigidTransform t;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) t.rotation[3 * r + c] = m[4 * r + c];
  t.center = center;
  // x' = A (x - c) + c + t' = A x + (c + t' - A c): t' = A c + b - c.
  for (int r = 0; r < 3; ++r) {
    double ac = 0.0;
    for (int c = 0; c < 3; ++c) ac += m[4 * r + c] * center[c];
    t.translation[r] = ac + m[4 * r + 3] - center[r];
  }
  return t;
}

}  // namespace snh
