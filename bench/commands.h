// The subcommands of snh-gpu-bench, each in its own file (probe, voxelize
// and hessian are snh's too: cli/cli_commands.h).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace snh::bench {

// Registers the subcommand on `app`; the callback it installs runs it and
// stores the process exit code in `exit_code`.
void add_scene_command(CLI::App& app, int& exit_code);
void add_errtime_command(CLI::App& app, int& exit_code);  // errtime.h: run_errtime for the suite
void add_scale_command(CLI::App& app, int& exit_code);    // scale.h: run_scale for the suite
void add_voxelize_compare_command(CLI::App& app, int& exit_code);

// The default suite, run when no subcommand is given: the element check,
// throughput, specialization, errtime and a small scale, into out_dir with a combined summary.{json,md}.
// `quick`: tiny sizes, for the tests.
int run_default_suite(const std::string& out_dir, int samples, bool quick);

}  // namespace snh::bench
