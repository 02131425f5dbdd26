#include "rig/winding_number.h"

#include "fem/fast_winding_number.h"

namespace snh::rig {

double winding_number(const TriangleSurface& surface, const std::array<double, 3>& p) {
  double total = 0.0;
  for (size_t t = 0; t < surface.triangle_count(); ++t) {
    double a[3], b[3], c[3];
    for (int d = 0; d < 3; ++d) {
      a[d] = surface.positions(surface.triangles[3 * t], d) - p[d];
      b[d] = surface.positions(surface.triangles[3 * t + 1], d) - p[d];
      c[d] = surface.positions(surface.triangles[3 * t + 2], d) - p[d];
    }
    total += fem::triangle_winding(a, b, c);
  }
  return total;
}

}  // namespace snh::rig
