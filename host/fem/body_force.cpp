// Body-force lumping (snh/loads.h) with the elements' own quadrature.
#include <cmath>

#include "fem/rest_state.h"
#include "snh/error.h"
#include "snh/loads.h"

namespace snh {

Points lump_body_force(const Mesh& mesh, const std::array<double, 3>& force_per_rest_volume) {
  // The rest-state code trusts the indices, so the mesh is checked first.
  validate_mesh(mesh);
  const fem::RestState rest = fem::compute_rest_state(mesh);
  const int n = rest.nodes;
  // N_a at each quadrature point: tet4's single point is the centroid
  // (N_a = 1/4); hex8's Gauss points follow rest_state's order
  // q = 4 k + 2 j + i, xi = +-1/sqrt(3).
  std::vector<double> shape(static_cast<size_t>(rest.quadrature * n), 1.0 / n);
  if (mesh.type == ElementType::hex8) {
    const double g = 1.0 / std::sqrt(3.0);
    for (int q = 0; q < 8; ++q) {
      const double xi[3] = {(q & 1) ? g : -g, (q & 2) ? g : -g, (q & 4) ? g : -g};
      for (int a = 0; a < 8; ++a) {
        const double* s = fem::kHexNodeSigns[a];
        shape[8 * q + a] = 0.125 * (1.0 + s[0] * xi[0]) * (1.0 + s[1] * xi[1]) * (1.0 + s[2] * xi[2]);
      }
    }
  }
  Points f(mesh.vertex_count());
  for (size_t e = 0; e < mesh.element_count(); ++e)
    for (int q = 0; q < rest.quadrature; ++q) {
      const double w = rest.weight(e, q);
      for (int a = 0; a < n; ++a) {
        const int32_t v = mesh.elements[n * e + a];
        for (int d = 0; d < 3; ++d) f(v, d) += w * shape[n * q + a] * force_per_rest_volume[d];
      }
    }
  return f;
}

std::vector<double> lumped_mass(const Mesh& mesh, double density) {
  if (!(density > 0.0) || !std::isfinite(density))
    throw Error("lumped_mass: density must be finite and > 0 (got " + std::to_string(density) + ")");
  const Points f = lump_body_force(mesh, {density, 0.0, 0.0});
  std::vector<double> m(mesh.vertex_count());
  for (size_t v = 0; v < m.size(); ++v) m[v] = f(v, 0);
  return m;
}

}  // namespace snh
