// Newton's stopping test from the options (solver/newton/stopping_test.h).
#include "solver/newton/stopping_test.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace snh::solver {

StoppingTest stopping_test(const Mesh& mesh, const MaterialMap& materials, const SolveOptions& options) {
  // The default strain criterion steps aside for an explicit absolute or
  // relative one.
  const bool explicit_other = options.absolute_tolerance > 0.0 || options.relative_tolerance > 0.0;
  const double strain = options.strain_tolerance ? *options.strain_tolerance
                        : explicit_other         ? 0.0
                                                 : defaults::strain_tolerance(options.precision);
  double scale = 0.0;
  if (strain > 0.0 && mesh.element_count() > 0) {
    // The smallest Young's modulus among the materials elements use.
    std::vector<char> used_material(materials.materials.size(), 0);
    for (int32_t k : materials.element_material) used_material[k] = 1;
    double youngs = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < materials.materials.size(); ++k) {
      if (!used_material[k]) continue;
      const LameParameters l = materials.materials[k].lame();
      youngs = std::min(youngs, l.mu * (3.0 * l.lambda + 2.0 * l.mu) / (l.lambda + l.mu));
    }
    std::vector<char> used(mesh.vertex_count(), 0);
    for (int32_t v : mesh.elements) used[v] = 1;
    const double n = static_cast<double>(std::count(used.begin(), used.end(), 1));
    const double h = vertex_spacing(mesh);
    scale = strain * youngs * h * h * std::sqrt(n);
  }
  return {std::max(scale, options.absolute_tolerance), options.relative_tolerance, strain};
}

}  // namespace snh::solver
