// snh: run scene files, voxelize surfaces, probe materials and export a
// scene's linear system, on OpenCL.
#include <iostream>

#include "cli_commands.h"
#include "snh/error.h"

#ifndef SNH_VERSION
#define SNH_VERSION "unknown"
#endif

int main(int argc, char** argv) {
  CLI::App app{"snh: Stable Neo-Hookean flesh simulation on OpenCL."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "snh " SNH_VERSION);
  int exit_code = 0;
  snh::cli::add_run_command(app, exit_code);
  snh::cli::add_voxelize_command(app, exit_code);
  snh::cli::add_probe_command(app, exit_code);
  snh::cli::add_hessian_command(app, exit_code);
  snh::cli::add_programs_command(app, exit_code);
  snh::cli::add_intersections_command(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const snh::Error& e) {
    std::cerr << "snh: error: " << e.what() << '\n';
    return 1;
  }
  return exit_code;
}
