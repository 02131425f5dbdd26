// What a step's end state and solve show that a caller must not take for a
// clean result: inverted elements, a solve short of its tolerance, a vertex
// inside an obstacle (StepResult::warnings, snh/outcomes.h ResultWarning).
// Internal to the library.
#pragma once

#include <string>
#include <vector>

#include "fem/rest_state.h"
#include "snh/simulation.h"

namespace snh::solver {

// deformation_statistics with the mesh's rest state already computed.
DeformationStatistics deformation_statistics(const Mesh& mesh, const fem::RestState& rest,
                                             const std::vector<double>& x);

// Fills step.min_j, step.inverted_elements and step.warnings from the end
// state x and the step's status and contact depth (`label` names the step in
// the warnings, e.g. "load step 3"); with fail_on_inverted a step left with
// inverted elements gets StepStatus::inverted_elements.
void assess_step(const Mesh& mesh, const fem::RestState& rest, const std::vector<double>& x,
                 const SolveOptions& options, const std::string& label, StepResult& step);

}  // namespace snh::solver
