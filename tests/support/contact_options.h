// What a Simulation says about its obstacles and contact options, for the
// tests of their checks.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "snh/error.h"
#include "snh/material.h"
#include "snh/mesh.h"
#include "snh/simulation.h"

namespace snh::test {

// The snh::Error a Simulation of one unit hex throws with these obstacles
// and contact options; empty when it accepts them.
inline std::string contact_options_error(std::vector<Obstacle> obstacles, const ContactOptions& contact) {
  const Mesh mesh = make_box_lattice(1, 1, 1, 1.0);
  const Material material = StableNeoHookean::from_youngs_modulus(1.0, 0.3);
  SolveOptions options;
  options.obstacles = std::move(obstacles);
  options.contact = contact;
  try {
    Simulation(mesh, material, {}, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace snh::test
