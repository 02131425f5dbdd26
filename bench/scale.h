// `snh-gpu-bench scale`: the paper's scenes at growing resolution with each
// preconditioner side by side: Newton and CG iterations, seconds per load
// step, device memory, kernel launches and blocking read-backs per CG and
// per Newton iteration (iteration_traffic.h) and the per-phase profile
// against DOF. run_scale returns the records; write_scale turns them into
// scale.{json,csv,md} and the log-log plot scale.png (bench/plot_scale.py).
#pragma once

#include <string>
#include <vector>

#include "multigrid_flags.h"
#include "snh/simulation.h"

namespace snh::bench {

struct ScaleOptions {
  std::vector<std::string> scenes{"twist", "stretch"};
  std::vector<int> resolutions{4, 6, 8};  // cells across each scene's thickness
  std::vector<std::string> preconditioners{"none", "block-jacobi", "multigrid"};
  // > 0: after the resolutions above, keep growing the resolution by 2^(1/3)
  // (about twice the DOF per row) while the scene's DOF stay <= max_dofs,
  // and end with the largest resolution that fits (stretch with 1,000,000:
  // ..., 40, 50, then 58 = 306,704 hexes, 969,111 DOF, the paper's
  // cylinder); resolutions above whose DOF exceed it are left out.
  long long max_dofs = 0;
  double youngs_modulus = 1.0;
  double poisson_ratio = 0.49;
  std::string precision = "double";             // float or double
  std::string product_precision = "automatic";  // SolveOptions::product_precision: float, double or automatic (unset)
  int cg_check_every = -1;                      // >= 0: SolverTuning::cg_check_every (else its default)
  std::string device;                           // substring of "<platform> / <device>"
  cli::MultigridFlags multigrid;                // --multigrid-* (multigrid_flags.h)
  std::string out_dir = "bench-results";        // scale.* written here
  bool plots = true;                            // run bench/plot_scale.py
};

// One scene at one resolution with one preconditioner.
struct ScaleRecord {
  std::string scene;
  int resolution = 0;
  std::string element_type;
  size_t elements = 0;
  size_t dofs = 0;
  std::string preconditioner;  // as asked ("none", "block-jacobi", "multigrid")
  std::string skipped;         // why it did not run (e.g. the preconditioner is not built); empty if it ran
  int load_steps = 0;
  int newton_iterations = 0;  // all load steps
  int cg_iterations = 0;      // all load steps
  double cg_per_newton = 0.0;
  double seconds = 0.0;  // the solve (SolveResult::seconds)
  double seconds_per_step = 0.0;
  size_t device_memory_bytes = 0;
  bool converged = false;
  std::string status;  // per-step statuses, e.g. "converged" or "converged x7, stagnated x1"
  std::string product;
  std::string product_precision;  // the precision CG's products ran in (SolveResult::product_precision)
  std::string smoother;      // multigrid: its smoothing as used, e.g. "optimized-fourth 1" (SolveResult); else empty
  bool float_cycle = false;  // multigrid: whether its V-cycle ran in float (SolveResult::multigrid_float_cycle)
  std::string device;
  SolveProfile profile;
};

// A fitted power law: seconds per step ~ DOF^slope over one scene and
// preconditioner's rows that ran (least squares in log-log; two or more).
struct ScaleSlope {
  std::string scene, preconditioner;
  double slope = 0.0;
  int points = 0;
};

// The resolutions run for `scene` (ScaleOptions::resolutions, grown to
// max_dofs when set), with their DOF.
std::vector<std::pair<int, size_t>> scale_resolutions(const std::string& scene, const ScaleOptions& options);

// Runs every scene, resolution and preconditioner; progress on stderr.
std::vector<ScaleRecord> run_scale(const ScaleOptions& options);

std::vector<ScaleSlope> fit_slopes(const std::vector<ScaleRecord>& records);

// Writes scale.json, scale.csv, scale.md (and scale.png when plots are on)
// into options.out_dir.
void write_scale(const ScaleOptions& options, const std::vector<ScaleRecord>& records);

// run_scale, write_scale and a table on stdout; returns the exit code (0
// unless nothing ran).
int run_scale_command(const ScaleOptions& options);

}  // namespace snh::bench
