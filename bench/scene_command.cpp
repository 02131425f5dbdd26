// `snh-gpu-bench scene NAME`: one of the paper's scenes through the library,
// with a JSON summary and ParaView output on request; `scene --file F` runs
// a scene file as `snh run F` does (cli/scene_run.h).
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <set>
#include <string>

#include "commands.h"
#include "enum_names.h"
#include "material_options.h"
#include "product_precision_flag.h"
#include "scene_run.h"
#include "snh/error.h"
#include "snh/scene.h"
#include "snh/scenes.h"

namespace snh::bench {
namespace {

struct SceneOptions {
  std::string name;
  int resolution = 0;
  std::string element = "hex8";
  double youngs_modulus = std::numeric_limits<double>::quiet_NaN();  // NaN: the scene's (scene_defaults)
  double poisson_ratio = std::numeric_limits<double>::quiet_NaN();
  std::string barrier = "auto";
  std::string model = "snh";
  double alpha = 1.0;
  std::string lambda_model;
  double alpha_lambda = std::numeric_limits<double>::quiet_NaN();  // NaN: --alpha
  unsigned seed = 1;
  std::string file;
  std::string device;
  double strain_tolerance = 0.0;
  cli::SolverFlags solver;      // with --file, those given override the file's "solver"
  cli::SceneOutputs outputs;    // --json, --vtu, --surface, --frames
  std::set<std::string> given;  // the scene-building flags on the command line
};

// Flags that build a named scene (make_scene); a scene file sets these
// itself, so with --file they are errors rather than silently ignored.
const char* const kSceneBuildingFlags[] = {
    "--res",          "--element",      "--E",       "--nu",   "--model",     "--alpha",
    "--lambda-model", "--alpha-lambda", "--barrier", "--seed", "--strain-tol"};

int run_scene(const SceneOptions& given) {
  SceneOptions o = given;
  if (o.name.empty() == o.file.empty()) throw Error("scene: give either a scene NAME or --file FILE");
  if (!o.file.empty()) {
    // A scene file carries its own material and solver settings; --json,
    // --vtu and --surface on the command line override its outputs.
    const SceneFile f = load_scene(o.file);
    cli::warn_surface_defects(f);
    if (!o.outputs.surface_prefix.empty() && !f.embedded) throw Error("scene: --surface needs a scene with \"embed\"");
    for (const char* flag : kSceneBuildingFlags)
      if (o.given.count(flag))
        throw Error(std::string("scene: ") + flag + " builds a named scene; with --file set it in the file");
    return cli::run_scene_file(f, o.solver.file_options(f, o.device), o.outputs);
  }
  if (!o.outputs.surface_prefix.empty()) throw Error("scene: --surface needs a scene file with \"embed\"");
  // The material the scene is meant to run with unless --E / --nu say otherwise.
  const SceneParameters defaults = scene_defaults(o.name);
  if (std::isnan(o.youngs_modulus)) o.youngs_modulus = defaults.youngs_modulus;
  if (std::isnan(o.poisson_ratio)) o.poisson_ratio = defaults.poisson_ratio;
  const cli::SolverFlags& flags = o.solver;
  SceneParameters p;
  if (o.resolution > 0) p.resolution = o.resolution;  // 0: unset
  p.youngs_modulus = o.youngs_modulus;
  p.poisson_ratio = o.poisson_ratio;
  p.barrier = parse_barrier(o.barrier);
  if (flags.steps > 0) p.steps = flags.steps;  // 0: unset
  p.seed = o.seed;
  p.element_type = cli::element_type_named(o.element);
  p.strain_tolerance =
      o.strain_tolerance > 0.0 ? o.strain_tolerance : strain_tolerance_default(parse_precision(flags.precision));
  SceneFile f;
  f.scene = make_scene(o.name, p);
  SolveOptions options = f.scene.options;
  options.precision = parse_precision(flags.precision);
  options.device.match = o.device;
  options.product = parse_optional(flags.variant, parse_product_variant);
  cli::apply_product_precision(flags.product_precision, options);
  options.preconditioner = parse_optional(flags.preconditioner, parse_preconditioner);
  flags.multigrid.apply(options.multigrid);
  flags.apply_limits(options);
  options.hessian = parse_hessian_mode(flags.hessian);
  snh::MaterialOptions material_options;
  material_options.barrier = p.barrier;
  material_options.alpha = o.alpha;
  if (!o.lambda_model.empty()) material_options.lambda_model = parse_material_model(o.lambda_model);
  if (!std::isnan(o.alpha_lambda)) material_options.alpha_lambda = o.alpha_lambda;
  f.material =
      Material::from_youngs_modulus(parse_material_model(o.model), o.youngs_modulus, o.poisson_ratio, material_options);
  f.materials = uniform_material(f.scene.mesh, f.material);
  return cli::run_scene_file(f, options, o.outputs);
}

}  // namespace

void add_scene_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<SceneOptions>();
  CLI::App* cmd =
      app.add_subcommand("scene", "Run one of the paper's scenes (stretch, twist, scramble, flex, drop, elbow)");
  cmd->add_option("name", o->name, "scene name (or --file)")->check(CLI::IsMember(scene_names()));
  cmd->add_option("--file", o->file,
                  "a scene in JSON: mesh (file or generator) or embed (a surface voxelized), material, constraints "
                  "(ids/box/plane, rigid or keyframed motion), rig (bones and an animation: run frame by frame), "
                  "body_force, initial, dynamics (implicit Euler: solver.steps counts time steps), obstacles "
                  "(plane, sphere, cylinder; keyframes), contact, solver, output (see data/scenes/)");
  cmd->add_option("--res", o->resolution,
                  "cells across the scene's thickness (0: scene default; drop: 1 the coarse mesh, 2 the default)");
  cmd->add_option("--element", o->element, "hex8 (the paper's lattices) or tet4 (each lattice hex split in six)")
      ->check(CLI::IsMember(cli::element_type_names()))
      ->capture_default_str();
  cmd->add_option("--E", o->youngs_modulus, "Young's modulus (default: the scene's; 1, drop 5e4 Pa)");
  cmd->add_option("--nu", o->poisson_ratio, "Poisson's ratio (default: the scene's; 0.49, drop 0.46)");
  cmd->add_option("--model", o->model,
                  "material: snh, fung, arruda-boyce, corotational, fixed-corotational, stvk-kikuuwe, neohookean "
                  "(normalized to the same small-strain E, nu; model settings at their defaults)")
      ->check(CLI::IsMember(cli::kModelNames))
      ->capture_default_str();
  cmd->add_option(
         "--alpha", o->alpha,
         "nonlinearity (Chen and Barbic 2024, Eq. 16): psi(sigma^alpha) / alpha^2 at the same small-strain E, nu")
      ->capture_default_str();
  cmd->add_option("--lambda-model", o->lambda_model,
                  "take the lambda_Lame (volume) part from this model (Chen and Barbic 2024, Eq. 19)")
      ->check(CLI::IsMember(cli::kModelNames));
  cmd->add_option("--alpha-lambda", o->alpha_lambda, "nonlinearity of the lambda_Lame part (Eq. 20; default --alpha)");
  cmd->add_option("--barrier", o->barrier, "origin barrier: on, off, auto")
      ->check(CLI::IsMember({"on", "off", "auto"}))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "random seed (scramble)")->capture_default_str();
  o->solver.add_to(cmd, "load steps (0: scene default; drop: frames over its 2 s, default 60)");
  cli::add_output_options(cmd, o->outputs);
  cmd->add_flag("--quiet,-q", o->outputs.quiet, "no progress lines on stderr");
  cmd->add_option("--device", o->device, "substring of '<platform> / <device>'");
  cmd->add_option(
      "--strain-tol", o->strain_tolerance,
      "stop at the residual of this strain error, |r| <= tol E h^2 sqrt(vertices) (default 1e-6; float 1e-4)");
  cmd->callback([o, cmd, &exit_code] {
    for (const char* flag : kSceneBuildingFlags)
      if (cmd->count(flag) > 0) o->given.insert(flag);
    o->solver.note_given(cmd);
    exit_code = run_scene(*o);
  });
}

}  // namespace snh::bench
