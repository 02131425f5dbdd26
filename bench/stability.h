// `snh-gpu-bench stability`: the solver on stiff and extreme cases, in float
// and double: nu up to 0.4999, scrambled starts, crushes to a plane, a line
// and a point, a 2 pi twist, 3.4x and 5x stretches, and elements inverted
// mid-solve, and a squash to a tenth of the volume between planes (the lid of
// a box closing and opening) and release at nu = 0.46, 0.49, 0.499, also to
// 5% and 3% (squash_h0.05_nu*, squash_h0.03_nu*). Per case and precision: converged or not, Newton
// and CG iterations, time, min/max J, inverted elements, volume ratio, non-finite positions (there must be none) and
// the solver's recovery events, and per step the exact self-intersection count of the boundary surface. Where float
// fails and double succeeds, float is run again with SolveOptions::fallback_to_double to show the switch. Writes
// stability.{json,csv,md}.
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "record_writer.h"
#include "snh/scenes.h"
#include "snh/simulation.h"

namespace CLI {
class App;
}

namespace snh::bench {

void add_stability_command(CLI::App& app, int& exit_code);

// The case names in suite order.
std::vector<std::string> stability_case_names();

// The squash cases' lid closes to this fraction of the body's height (and,
// with the walls holding its sides, of its volume): `stability
// --squash-height` sets it. Below it the cases meet the limits docs/validation.md describes (at 0.05: the saddle
// between frictionless planes at nu = 0.499, the rough body folding through itself at nu = 0.46).
constexpr double kDefaultSquashHeight = 0.1;

// Case `name` as a scene ready to solve in `precision` (float stops at a
// strain-equivalent residual of 1e-4, double 1e-6); resolution 0: the case's
// default; squash_height: the squash cases' lid height (0 < h < 1). Throws
// snh::Error for an unknown name or a height out of range.
Scene make_stability_case(const std::string& name, Precision precision, int resolution = 0,
                          double squash_height = kDefaultSquashHeight);

struct StabilityRun {
  std::string name;
  std::string precision;  // "float", "double", "float+fallback"
  std::string description;
  size_t elements = 0;
  bool converged = false;
  std::string status;  // the first non-converged step's status, else "converged"
  int newton_iterations = 0;
  int cg_iterations = 0;
  double seconds = 0.0;
  double min_j = 0.0, max_j = 0.0, volume_ratio = 0.0;
  double min_volume_ratio = 0.0;  // the smallest deformed / rest volume at the end of a step
  // With obstacles: the deepest penetration into a contact layer at the end
  // of any step (StepResult::max_penetration) and the layer's thickness (0:
  // no obstacles); above the thickness a vertex is inside an obstacle.
  double max_penetration = 0.0, contact_thickness = 0.0;
  int inverted_elements = 0;
  int initially_inverted_elements = 0;       // at the first step's start
  int non_finite_positions = 0;              // must be 0
  int nan_in_history = 0;                    // NaN residuals or energies in the history (must be 0)
  std::map<std::string, int> recoveries;     // NewtonIteration::recovery -> count
  std::vector<std::string> precisions_used;  // per step
  // "step N: status after K Newton, residual R of tolerance T", per step that
  // did not converge.
  std::vector<std::string> unconverged_steps;
  std::vector<std::string> warnings;
  std::string error;  // an snh::Error, if the run threw
  // Per step: the exact number of intersecting triangle pairs of the
  // boundary surface at the step's end (surface_intersections.h); -1 where
  // the positions were not finite. And the most degenerate (zero-area)
  // boundary triangles at any step's end, which that count leaves out.
  std::vector<int64_t> surface_intersections;
  size_t degenerate_surface_triangles = 0;
  int64_t max_surface_intersections() const {
    int64_t most = 0;  // -1 when a step was not counted
    for (int64_t c : surface_intersections) {
      if (c < 0) return -1;
      most = std::max(most, c);
    }
    return most;
  }
};

// Runs one case in one precision (fallback: SolveOptions::fallback_to_double).
StabilityRun run_stability_case(const std::string& name, Precision precision, int resolution = 0,
                                bool fallback_to_double = false, const std::string& device = "",
                                double squash_height = kDefaultSquashHeight);

// "a x2; b x1" from the recovery counts ("-" for none).
std::string recovery_summary(const std::map<std::string, int>& recoveries);

// What `snh-gpu-bench stability` writes for its runs (each with a note):
// stability.csv and stability.md as tables (bench/record_writer.h renders
// them), stability.json as a document, and how many runs saw a NaN or an
// error.
struct StabilityReport {
  Table csv, markdown;
  nlohmann::ordered_json document;
  int problems = 0;
};
StabilityReport stability_report(const std::vector<std::pair<StabilityRun, std::string>>& runs, int resolution,
                                 double squash_height);

}  // namespace snh::bench
