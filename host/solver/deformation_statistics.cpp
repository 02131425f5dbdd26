// Volume change and the range of J over a deformed mesh's quadrature points.
#include <algorithm>
#include <limits>

#include "fem/rest_state.h"
#include "snh/simulation.h"

namespace snh {

DeformationStatistics deformation_statistics(const Mesh& mesh, const std::vector<double>& x) {
  const fem::RestState rest = fem::compute_rest_state(mesh);
  DeformationStatistics s;
  s.min_j = std::numeric_limits<double>::infinity();
  s.max_j = -std::numeric_limits<double>::infinity();
  double volume = 0.0;
  for (size_t e = 0; e < mesh.element_count(); ++e) {
    bool inverted = false;
    for (int q = 0; q < rest.quadrature; ++q) {
      double f[9];
      fem::deformation_gradient(mesh, rest, x.data(), e, q, f);
      const double j = fem::determinant(f);
      s.min_j = std::min(s.min_j, j);
      s.max_j = std::max(s.max_j, j);
      inverted = inverted || !(j > 0.0);
      volume += j * rest.weight(e, q);
    }
    s.inverted_elements += inverted ? 1 : 0;
  }
  s.volume_ratio = volume / rest.rest_volume;
  return s;
}

}  // namespace snh
