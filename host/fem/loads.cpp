#include "snh/loads.h"

#include <cmath>

#include "fem/rest_state.h"

namespace snh {

std::vector<double> lump_body_force(const Mesh& mesh, const std::array<double, 3>& b) {
  const fem::RestState rest = fem::compute_rest_state(mesh);
  const int nodes = nodes_per_element(mesh.type);
  std::vector<double> f(3 * mesh.vertex_count(), 0.0);
  // Shape function values at the points: hex8 trilinear at the 2x2x2 Gauss
  // points (rest_state.h's order), tet4 1/4 at the centroid.
  const double g = 1.0 / std::sqrt(3.0);
  for (size_t e = 0; e < mesh.element_count(); ++e)
    for (int q = 0; q < rest.quadrature; ++q) {
      const double xi[3] = {(q & 1) ? g : -g, (q & 2) ? g : -g, (q & 4) ? g : -g};
      for (int a = 0; a < nodes; ++a) {
        double n = 0.25;
        if (mesh.type == ElementType::hex8) {
          n = 0.125;
          for (int d = 0; d < 3; ++d) n *= 1.0 + fem::kHexNodeSigns[a][d] * xi[d];
        }
        const int32_t v = mesh.elements[static_cast<size_t>(nodes) * e + a];
        for (int d = 0; d < 3; ++d) f[3 * v + d] += rest.weight(e, q) * n * b[d];
      }
    }
  return f;
}

}  // namespace snh
