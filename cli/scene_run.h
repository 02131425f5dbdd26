// A scene file run from the command line, as `snh run FILE` and
// `snh-gpu-bench scene --file FILE` do: the solver flags that override the
// file's settings, progress per load step or frame on stderr, a table on
// stdout, and the outputs the file or the flags name.
#pragma once

#include <CLI/CLI.hpp>
#include <ostream>
#include <set>
#include <string>

#include "multigrid_flags.h"
#include "snh/scene.h"

namespace snh::cli {

struct SolverFlags {
  std::string precision = "double";
  std::string variant = "automatic";
  std::string product_precision = "automatic";  // SolveOptions::product_precision (automatic: unset)
  std::string preconditioner = "automatic";
  std::string hessian = "adaptive";
  int steps = 0;
  double relative_tolerance = -1.0;
  double absolute_tolerance = -1.0;
  int max_newton = 0;
  double forcing_max = 0.0;
  MultigridFlags multigrid;     // --multigrid-* (multigrid_flags.h)
  std::set<std::string> given;  // the flags on the command line (note_given)

  // Registers --precision, --variant, --preconditioner, --product-precision,
  // the --multigrid-* flags, --rtol, --atol, --max-newton, --forcing-max,
  // --hessian and --steps (with `steps_help`).
  void add_to(CLI::App* cmd, const std::string& steps_help);
  void note_given(const CLI::App* cmd);
  // The flags given override the file's settings in `options`; without a
  // tolerance in the file, --precision sets its default strain tolerance.
  void apply_to_file(const SceneFile& file, SolveOptions& options) const;
  // The file's solve options on the device matching `device`, with the flags
  // given applied (apply_to_file): what `run`, `programs` and `scene --file`
  // solve with.
  SolveOptions file_options(const SceneFile& file, const std::string& device) const;
  // --rtol, --atol, --max-newton, --forcing-max where given.
  void apply_limits(SolveOptions& options) const;
};

struct SceneOutputs {
  std::string json_path;       // --json, else the file's output.json
  std::string vtu_dir;         // --vtu, else the file's output.vtu
  std::string surface_prefix;  // --surface, else the file's output.surface
  int frames = 0;              // a rig: only the first frames (0: all)
  bool quiet = false;          // no progress lines
};

// The embedded surface's defects (seams, holes, flipped triangles, ...) as
// warnings on stderr.
void warn_surface_defects(const SceneFile& file);

// Registers --json, --vtu, --surface and --frames.
void add_output_options(CLI::App* cmd, SceneOutputs& outputs);

// Runs the scene (snh::run_scene) with `options`, writes the outputs and
// prints the table. Returns 0 when every step or frame converged, else 3.
int run_scene_file(const SceneFile& file, const SolveOptions& options, const SceneOutputs& outputs);

// Builds the scene's simulation with `options` as a run would and prints its
// resolved configuration (snh/configuration.h): each setting, its value and
// why, one per line. Solves nothing.
void explain_scene_file(const SceneFile& file, const SolveOptions& options, std::ostream& out);

}  // namespace snh::cli
