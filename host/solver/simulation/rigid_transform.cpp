// RigidTransform: rotations about a centre (Rodrigues) and translations.
#include <cmath>

#include "snh/error.h"
#include "snh/simulation.h"

namespace snh {

RigidTransform RigidTransform::rotation_about(const std::array<double, 3>& axis, double angle,
                                              const std::array<double, 3>& center) {
  const double len = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  if (!(len > 0.0)) throw Error("RigidTransform: rotation axis must be non-zero");
  const double x = axis[0] / len, y = axis[1] / len, z = axis[2] / len;
  const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  RigidTransform r;
  // Rodrigues, row-major.
  r.rotation = {t * x * x + c,     t * x * y - s * z, t * x * z + s * y, t * x * y + s * z, t * y * y + c,
                t * y * z - s * x, t * x * z - s * y, t * y * z + s * x, t * z * z + c};
  r.center = center;
  return r;
}

RigidTransform RigidTransform::translation_by(const std::array<double, 3>& offset) {
  RigidTransform r;
  r.translation = offset;
  return r;
}

std::array<double, 3> RigidTransform::apply(const std::array<double, 3>& p) const {
  const double d[3] = {p[0] - center[0], p[1] - center[1], p[2] - center[2]};
  std::array<double, 3> out;
  for (int i = 0; i < 3; ++i)
    out[i] =
        rotation[3 * i] * d[0] + rotation[3 * i + 1] * d[1] + rotation[3 * i + 2] * d[2] + center[i] + translation[i];
  return out;
}

}  // namespace snh
