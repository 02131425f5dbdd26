#include "rig/winding_number.h"

#include <cmath>

namespace snh::rig {

double winding_number(const TriangleSurface& surface, const std::array<double, 3>& p) {
  double total = 0.0;
  for (size_t t = 0; t < surface.triangle_count(); ++t) {
    double a[3], b[3], c[3];
    for (int d = 0; d < 3; ++d) {
      a[d] = surface.positions[3 * surface.triangles[3 * t] + d] - p[d];
      b[d] = surface.positions[3 * surface.triangles[3 * t + 1] + d] - p[d];
      c[d] = surface.positions[3 * surface.triangles[3 * t + 2] + d] - p[d];
    }
    const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    const double lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    const double lc = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    // tan(Omega / 2) = a . (b x c) / (|a||b||c| + (a.b)|c| + (b.c)|a| + (c.a)|b|)
    const double det =
        a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    const double ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const double bc = b[0] * c[0] + b[1] * c[1] + b[2] * c[2];
    const double ca = c[0] * a[0] + c[1] * a[1] + c[2] * a[2];
    total += 2.0 * std::atan2(det, la * lb * lc + ab * lc + bc * la + ca * lb);
  }
  return total / (4.0 * M_PI);
}

}  // namespace snh::rig
