// Where a solve's time went and what its result reports besides positions:
// phase seconds over the engines' profilers, seconds per kernel over their
// OpenCL contexts, the caller's callbacks kept out of both, preconditioner
// builds, and the deformation statistics of the positions reached.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "device/phase_profile.h"
#include "snh/mesh.h"
#include "snh/simulation.h"

namespace snh::solver {

// The running counters, sampled at the start of a solve or a step and again
// at its end.
struct Counters {
  PhaseSeconds phases{};
  std::map<std::string, double> kernels;  // seconds per kernel
  PhaseTraffic traffic{};                 // device traffic per phase
  long long cg_iterations_past_convergence = 0;
  int preconditioner_builds = 0;
  double callback_seconds = 0.0;  // in the caller's callbacks
};

// Seconds per kernel from `before` to `now`, kernels not run since dropped.
std::map<std::string, double> kernel_difference(std::map<std::string, double> now,
                                                const std::map<std::string, double>& before);

// The profile between two samples `seconds` of wall time apart: phases and
// kernels run between them, the total less the callbacks' share.
SolveProfile profile_between(const Counters& since, const Counters& now, double seconds);

// The volume ratio, range of J and inverted elements of x into the result.
void record_deformation(const Mesh& mesh, const Points& x, SolveResult& result);

}  // namespace snh::solver
