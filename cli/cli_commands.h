// The subcommands `snh` and `snh-gpu-bench` share, each in its own file,
// and what both do with a scene file (scene_run.h).
#pragma once

#include <CLI/CLI.hpp>

namespace snh::cli {

// Registers the subcommand on `app`; the callback it installs runs it and
// stores the process exit code in `exit_code`.
void add_probe_command(CLI::App& app, int& exit_code);
void add_voxelize_command(CLI::App& app, int& exit_code);
void add_hessian_command(CLI::App& app, int& exit_code);  // hessian_export.h
// `snh run SCENE.json`: the scene file with the solver flags of scene_run.h.
void add_run_command(CLI::App& app, int& exit_code);
// `snh programs SCENE.json`: the kernel programs the scene builds (programs.h).
void add_programs_command(CLI::App& app, int& exit_code);
// `snh intersections FILE`: the exact self-intersection count of a surface
// or of a mesh's boundary (surface_intersections.h).
void add_intersections_command(CLI::App& app, int& exit_code);

}  // namespace snh::cli
