// The smallest useful host application: a soft bar, one end held, the other
// pulled and turned; prints the equilibrium's statistics.
#include <cmath>
#include <iostream>

#include "snh/error.h"
#include "snh/simulation.h"

int main() {
  try {
    snh::Mesh bar = snh::make_box_lattice(6, 2, 2, 0.5);  // 3 x 1 x 1
    std::vector<int32_t> left_end, right_end;
    for (size_t v = 0; v < bar.vertex_count(); ++v) {
      if (bar.positions(v, 0) < 1e-9) left_end.push_back(static_cast<int32_t>(v));
      if (bar.positions(v, 0) > 3.0 - 1e-9) right_end.push_back(static_cast<int32_t>(v));
    }
    const auto held = snh::ConstraintSet::fixed("held", left_end);
    const auto pulled = snh::ConstraintSet::moving("pulled", right_end, [](double t) {
      snh::RigidTransform m = snh::RigidTransform::rotation_about({1, 0, 0}, t * 0.5 * M_PI, {3.0, 0.5, 0.5});
      m.translation = {0.5 * t, 0.0, 0.0};
      return m;
    });
    snh::SolveOptions options;
    options.load_steps = 3;
    options.relative_tolerance = 1e-6;
    const auto flesh = snh::StableNeoHookean::from_youngs_modulus(1.0e4, 0.49);  // Pa, nearly incompressible
    snh::QuasistaticSolver solver(bar, flesh, {held, pulled}, options);
    const snh::SolveResult result = solver.solve();
    std::cout << "device: " << result.device.name << "\nconverged: " << (result.converged ? "yes" : "no")
              << "\nNewton iterations: " << result.history.size() << "\nvolume ratio: " << result.volume_ratio
              << "\nmin J: " << result.min_j << "\ninverted elements: " << result.inverted_elements << '\n';
    return result.converged && result.inverted_elements == 0 ? 0 : 1;
  } catch (const snh::Error& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 2;
  }
}
