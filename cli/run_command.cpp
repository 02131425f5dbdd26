// `snh run SCENE.json`: a scene file (docs/scene-files.md) with its outputs;
// the solver flags override the file's settings.
#include <iostream>
#include <memory>
#include <string>

#include "cli_commands.h"
#include "scene_run.h"

namespace snh::cli {
namespace {

struct RunCommand {
  std::string file;
  std::string device;
  SolverFlags solver;
  SceneOutputs outputs;
  bool fail_on_inverted = false;
  bool explain = false;
};

}  // namespace

void add_run_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<RunCommand>();
  CLI::App* cmd = app.add_subcommand(
      "run",
      "Run a scene file: mesh (file or generator) or embed (a surface voxelized), materials and regions, constraints, "
      "rig (bones and an animation: run frame by frame), body_force, initial, dynamics, obstacles, contact, solver, "
      "output (docs/scene-files.md; examples in data/scenes/)");
  cmd->add_option("scene", o->file, "the scene file (JSON)")->required();
  add_output_options(cmd, o->outputs);
  cmd->add_option("--device", o->device, "substring of '<platform> / <device>'");
  o->solver.add_to(cmd, "load steps (per frame with a rig; time steps with dynamics; 0: the file's solver.steps)");
  cmd->add_flag("--quiet,-q", o->outputs.quiet, "no progress lines on stderr");
  cmd->add_flag("--explain", o->explain,
                "print the resolved configuration (every automatic choice, its value and why) and exit without "
                "solving");
  cmd->add_flag("--fail-on-inverted", o->fail_on_inverted,
                "fail (exit code 4, naming the step or frame) when a step or frame ends with inverted elements "
                "(the file's solver.fail_on_inverted, default false)");
  cmd->callback([o, cmd, &exit_code] {
    o->solver.note_given(cmd);
    const SceneFile file = load_scene(o->file);
    warn_surface_defects(file);
    SolveOptions options = o->solver.file_options(file, o->device);
    if (o->fail_on_inverted) options.fail_on_inverted = true;
    if (o->explain) {
      explain_scene_file(file, options, std::cout);
      exit_code = 0;
      return;
    }
    exit_code = run_scene_file(file, options, o->outputs);
  });
}

}  // namespace snh::cli
