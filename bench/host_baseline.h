// The host CPU baseline: the same quasistatic Newton solve with the stiffness
// assembled by Eigen on the host (reference::assembled_projected_stiffness)
// and Eigen's ConjugateGradient, so reports can show a ratio, not a lone figure.
#pragma once

#include <functional>
#include <vector>

#include "snh/scenes.h"
#include "snh/simulation.h"

namespace snh::bench {

struct HostBaselineResult {
  std::vector<NewtonIteration> history;  // same fields and meaning as the device solver's
  std::vector<StepResult> steps;
  std::vector<double> positions;
  bool converged = false;
  double seconds = 0.0;           // whole solve
  double assembly_seconds = 0.0;  // summed over Newton iterations
  double cg_seconds = 0.0;        // summed over Newton iterations
  // Per phase as the device solver's (SolveProfile): assembly as
  // linearization, Eigen's diagonal setup as preconditioner_setup, energies,
  // residuals and trial updates as line_search_energies. Eigen's CG solve is
  // one call whose products, diagonal scaling and vector work cannot be told
  // apart without changing it: its time is in `other` (cg_seconds above).
  // total: `seconds`.
  SolveProfile profile;
};

// Runs the scene's load steps with the scene's (or the given) tolerances, in
// double, projected Hessian (the host has no adaptive mode), Armijo
// backtracking on the energy and Eisenstat-Walker forcing like the device
// solver. on_iteration (optional) as SolveOptions::on_iteration; its time is
// excluded from the history's seconds.
HostBaselineResult solve_on_host(
    const Scene& scene, const SolveOptions& options,
    const std::function<void(const NewtonIteration&, const std::vector<double>&)>& on_iteration = {});

// Seconds per sparse matrix-vector product with the Eigen-assembled projected
// stiffness at positions x (mean over `repetitions`), and the assembly time.
struct HostProductTiming {
  double assembly_seconds = 0.0;
  double product_seconds = 0.0;
  size_t nonzeros = 0;
};
HostProductTiming time_host_product(const Mesh& mesh, const StableNeoHookean& material, const std::vector<double>& x,
                                    int repetitions);

}  // namespace snh::bench
