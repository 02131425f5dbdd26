// snh-gpu-bench: material probe and benchmark suite of the snh engine.
#include <iostream>
#include <string>

#include "cli_commands.h"
#include "commands.h"
#include "materials_report.h"
#include "snh/error.h"
#include "specialization.h"
#include "stability.h"
#include "throughput.h"

int main(int argc, char** argv) {
  CLI::App app{
      "snh-gpu-bench: Stable Neo-Hookean engine on OpenCL.\n"
      "With no subcommand, runs the default suite on the default device and writes bench-results/."};
  app.require_subcommand(0, 1);
  int exit_code = 0;
  snh::cli::add_probe_command(app, exit_code);
  snh::bench::add_scene_command(app, exit_code);
  snh::bench::add_errtime_command(app, exit_code);
  snh::bench::add_throughput_command(app, exit_code);
  snh::bench::add_materials_command(app, exit_code);
  snh::bench::add_specialization_command(app, exit_code);
  snh::bench::add_stability_command(app, exit_code);
  snh::cli::add_voxelize_command(app, exit_code);
  snh::cli::add_hessian_command(app, exit_code);
  snh::bench::add_scale_command(app, exit_code);
  snh::bench::add_voxelize_compare_command(app, exit_code);
  std::string out_dir = "bench-results";
  int samples = 20000;
  app.add_option("--out", out_dir, "folder for the default suite's results")->capture_default_str();
  app.add_option("--samples", samples, "deformation gradients per case in the default suite")
      ->check(CLI::Range(1, 10000000))
      ->capture_default_str();
  bool quick = false;
  app.add_flag("--quick", quick, "tiny sizes throughout (checks that the suite runs; not for figures)");
  try {
    app.parse(argc, argv);
    if (app.get_subcommands().empty()) exit_code = snh::bench::run_default_suite(out_dir, samples, quick);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const snh::Error& e) {
    std::cerr << "snh-gpu-bench: error: " << e.what() << '\n';
    return 1;
  }
  return exit_code;
}
