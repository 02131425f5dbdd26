// A Simulation's state in a SimulationState (Simulation::checkpoint and
// restore): its constraint targets in the public form and back, and the
// checks that a state belongs to a simulation before anything is restored.
#pragma once

#include <cstdint>
#include <vector>

#include "snh/simulation.h"
#include "solver/simulation/load_stepping.h"

namespace snh::solver {

SimulationState::Target state_target(const ConstraintSet& set, const SetTarget& target);
SetTarget set_target(const SimulationState::Target& target);

// snh::Error naming the first item of `s` that does not fit a simulation of
// this mesh (vertex count and fingerprint), these constraint sets, with or
// without dynamics, and friction anchors for `anchored_obstacles` obstacles.
void check_restorable(const SimulationState& s, size_t vertex_count, uint64_t fingerprint,
                      const std::vector<ConstraintSet>& constraints, bool dynamics, size_t anchored_obstacles);

}  // namespace snh::solver
