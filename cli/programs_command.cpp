// `snh programs SCENE.json`: the kernel programs the scene's simulation
// builds, each with its build switches (device/kernel_config.h): its setup
// and its first Newton iteration, which build what the solve reads
// (some programs, such as a multigrid's float fine level, are built at
// the first linearization).
#include <iostream>
#include <memory>
#include <string>

#include "cli_commands.h"
#include "programs.h"
#include "scene_run.h"

namespace snh::cli {
namespace {

struct ProgramsCommand {
  std::string file;
  std::string device;
  SolverFlags solver;
};

}  // namespace

std::vector<device::BuiltProgram> scene_programs(const SceneFile& file, const SolveOptions& options) {
  device::ProgramRecorder recorder;
  Simulation simulation(file.scene.mesh, file.materials, file.scene.constraints, options);
  simulation.solve(0, [](const NewtonIteration&) { return false; });  // one Newton update, then cancelled
  return recorder.programs();
}

void print_programs(std::ostream& out, const std::vector<device::BuiltProgram>& programs) {
  for (const device::BuiltProgram& p : programs) out << p.file << "  " << p.config.report() << '\n';
}

void add_programs_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ProgramsCommand>();
  CLI::App* cmd = app.add_subcommand(
      "programs",
      "List the kernel programs a scene file's simulation builds (kernels/<file> and its -DSNH_* switches), one a "
      "line, in build order: its setup and first Newton iteration are run");
  cmd->add_option("scene", o->file, "the scene file (JSON)")->required();
  cmd->add_option("--device", o->device, "substring of '<platform> / <device>'");
  o->solver.add_to(cmd, "load steps (the programs do not depend on them)");
  cmd->callback([o, cmd, &exit_code] {
    o->solver.note_given(cmd);
    const SceneFile file = load_scene(o->file);
    print_programs(std::cout, scene_programs(file, o->solver.file_options(file, o->device)));
    exit_code = 0;
  });
}

}  // namespace snh::cli
