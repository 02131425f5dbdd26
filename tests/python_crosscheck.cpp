// The C++ side of the Python tests (tests/python): solves a small twisted bar
// and writes its positions as raw float64 (xyz per vertex), so that the same
// problem solved through the Python package can be compared bit for bit; or
// prints the message of an snh::Error the Python package must carry as is.
//
// Usage: snh-python-crosscheck solve <output.bin> <float|double> <hex8|tet4>
//        snh-python-crosscheck error
#include <cmath>
#include <fstream>
#include <iostream>
#include <string>

#include "snh/error.h"
#include "snh/selection.h"
#include "snh/simulation.h"

namespace {

// tests/python/test_crosscheck.py builds the same problem.
int solve(const std::string& path, const std::string& precision, const std::string& type) {
  const snh::Mesh bar = type == "tet4" ? snh::make_tet_box(4, 2, 2, 0.25) : snh::make_box_lattice(4, 2, 2, 0.25);
  const double e = 1e-9;
  snh::ConstraintSet held{"held", snh::vertices_in_box(bar, {-e, -1, -1}, {e, 2, 2}), {}, {}};
  snh::ConstraintSet end{"end", snh::vertices_in_box(bar, {1 - e, -1, -1}, {1 + e, 2, 2}), {}, {}};
  end.motion = [](double t) { return snh::RigidTransform::rotation_about({1, 0, 0}, t * M_PI / 2, {1, 0.25, 0.25}); };
  snh::SolveOptions options;
  options.precision = snh::parse_precision(precision);
  options.load_steps = 2;
  options.body_force = {0, 0, -100};
  snh::Simulation sim(bar, snh::Material::from_youngs_modulus(snh::MaterialModel::stable_neo_hookean, 1e4, 0.45),
                      {held, end}, options);
  const snh::SolveResult result = sim.solve();
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(sim.positions().data()),
            static_cast<std::streamsize>(sim.positions().xyz().size() * sizeof(double)));
  return out && result.converged ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string command = argc > 1 ? argv[1] : "";
  if (command == "solve" && argc == 5) {
    try {
      return solve(argv[2], argv[3], argv[4]);
    } catch (const snh::Error& error) {
      std::cerr << "error: " << error.what() << '\n';
      return 2;
    }
  }
  if (command == "error") {
    try {
      snh::Material::from_youngs_modulus(snh::MaterialModel::stable_neo_hookean, -1.0, 0.3);
    } catch (const snh::Error& error) {
      std::cout << error.what();
      return 0;
    }
    return 1;
  }
  std::cerr << "usage: snh-python-crosscheck solve <output.bin> <float|double> <hex8|tet4> | error\n";
  return 2;
}
