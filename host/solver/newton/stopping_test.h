// Newton's stopping test, both parts in one place: a load step (or implicit
// Euler substep) ends converged when the L2 norm of the free-DOF force
// residual is at most max(absolute, relative * |r_0|), r_0 the residual at
// the step's start. What each part is, and their defaults, is written once,
// at SolveOptions::strain_tolerance (snh/simulation.h).
#pragma once

#include <algorithm>

#include "snh/material.h"
#include "snh/mesh.h"
#include "snh/regions.h"
#include "snh/simulation.h"

namespace snh::solver {

struct StoppingTest {
  double absolute = 0.0;
  double relative = 0.0;
  double strain = 0.0;  // the strain criterion's strain behind `absolute` (0: off)

  // The residual norm a step that starts at |r_0| = initial stops at.
  double threshold(double initial) const { return std::max(absolute, relative * initial); }
};

// The test SolveOptions asks for on this mesh and these materials.
StoppingTest stopping_test(const Mesh& mesh, const MaterialMap& materials, const SolveOptions& options);

}  // namespace snh::solver
