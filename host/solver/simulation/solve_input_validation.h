// The checks of a simulation's inputs before anything is built.
#pragma once

#include <vector>

#include "snh/mesh.h"
#include "snh/simulation.h"

namespace snh {

// Checks constraint sets (non-empty, vertices in range, a vertex component
// prescribed by two sets, duplicate names) and solve options (initial
// positions, external and body force, steps, limits, tolerances); throws
// snh::Error naming the set or option at fault. Simulation calls it on
// construction.
void validate_solve_inputs(const Mesh& mesh, const std::vector<ConstraintSet>& constraints,
                           const SolveOptions& options);

}  // namespace snh
