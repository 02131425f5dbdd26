// `snh-gpu-bench scene NAME`: one of the paper's scenes through the library,
// with a JSON summary and ParaView output on request.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>

#include "commands.h"
#include "material_options.h"
#include "multigrid_flags.h"
#include "obstacle_surface.h"
#include "product_precision_flag.h"
#include "profile_json.h"
#include "rig_frames.h"
#include "scene_file.h"
#include "scene_output.h"
#include "snh/error.h"
#include "snh/fields.h"
#include "snh/io.h"
#include "snh/scenes.h"
#include "snh/shape.h"
#include "snh/simulation.h"
#include "snh/surface.h"
#include "solver/self_contact.h"
#include "solver_json.h"

namespace snh::bench {
namespace {

using json = nlohmann::ordered_json;

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
  std::string precision = "double";
  int steps = 0;
  unsigned seed = 1;
  std::string json_path;
  std::string file;
  std::string vtu_dir;
  std::string surface_prefix;
  int frames = 0;
  std::string device;
  std::string variant = "automatic";
  std::string product_precision = "automatic";  // SolveOptions::product_precision (automatic: unset)
  std::string preconditioner = "automatic";
  MultigridFlags multigrid;  // --multigrid-* (multigrid_flags.h)
  double strain_tolerance = 0.0;
  double relative_tolerance = -1.0;
  double absolute_tolerance = -1.0;
  int max_newton = 0;
  double forcing_max = 0.0;
  std::string hessian = "adaptive";
  std::set<std::string> given;  // the flags on the command line (with --file: which override the file)
};

// Flags that build a named scene (make_scene); a scene file sets these
// itself, so with --file they are errors rather than silently ignored.
const char* const kSceneBuildingFlags[] = {
    "--res",          "--element",      "--E",       "--nu",   "--model",     "--alpha",
    "--lambda-model", "--alpha-lambda", "--barrier", "--seed", "--strain-tol"};
// Solver flags: with --file, those given override the file's "solver".
const char* const kSolverFlags[] = {"--precision", "--variant", "--preconditioner", "--hessian",    "--steps",
                                    "--rtol",      "--atol",    "--max-newton",     "--forcing-max"};

// Per step, how far the body is from its rest shape (docs/design.md, drop): volume, smallest J, and the RMS vertex
// distance after the best rigid fit (snh/shape.h), absolute and relative to the rest radius of gyration. Undefined for
// a non-finite state.
struct StepShape {
  bool defined = false;
  double volume_ratio = 0.0, min_j = 0.0, rigid_fit_rms = 0.0, rigid_fit_rms_relative = 0.0;
};

StepShape step_shape(const Mesh& mesh, const std::vector<double>& x) {
  StepShape s;
  for (double v : x)
    if (!std::isfinite(v)) return s;
  const DeformationStatistics d = deformation_statistics(mesh, x);
  const ShapeDeviation fit = shape_deviation(mesh, x);
  s.defined = true;
  s.volume_ratio = d.volume_ratio;
  s.min_j = d.min_j;
  s.rigid_fit_rms = fit.rms_distance;
  s.rigid_fit_rms_relative = fit.relative();
  return s;
}

json summary_json(const Scene& scene, const SolveOptions& options, const SolveResult& r,
                  const std::vector<StepShape>& shapes) {
  json j;
  j["scene"] = scene.name;
  j["element_type"] = to_string(scene.mesh.type);
  j["elements"] = scene.mesh.element_count();
  j["dofs"] = 3 * scene.mesh.vertex_count();
  j["device"] = r.device.platform + " / " + r.device.name;
  j["precision"] = to_string(options.precision);
  j["kernel_specialization"] = r.kernel_specialization;
  j["youngs_modulus"] = scene.material.youngs_modulus();
  j["poisson_ratio"] = scene.material.poisson_ratio();
  j["barrier"] = scene.material.barrier;
  add_solver_json(j, options, r);
  if (options.dynamics) {
    const DynamicsOptions& d = *options.dynamics;
    j["dynamics"] = {{"time_step", d.time_step},
                     {"density", d.density},
                     {"damping", {{"mass", d.damping.mass}, {"stiffness", d.damping.stiffness}}},
                     {"substeps", d.substeps}};
  }
  if (!options.obstacles.empty() || options.contact.self) {
    j["obstacles"] = options.obstacles.size();
    j["contact"] = {{"stiffness", options.contact.stiffness},
                    {"thickness", options.contact.thickness},
                    {"self", options.contact.self}};
    if (options.contact.self) j["contact"]["self_stiffness"] = options.contact.self_stiffness;
  }
  j["steps"] = json::array();
  for (const StepResult& s : r.steps) {
    json step = {{"step", s.step},
                 {"newton_iterations", s.newton_iterations},
                 {"cg_iterations", s.cg_iterations},
                 {"converged", s.converged},
                 {"status", to_string(s.status)},
                 {"residual", s.residual_norm},
                 {"seconds", s.seconds},
                 {"contacts", s.contacts},
                 {"max_penetration", s.max_penetration},
                 {"profile", profile_json(s.profile)}};
    if (options.preconditioner == Preconditioner::multigrid || s.preconditioner_builds > 0)
      step["preconditioner_builds"] = s.preconditioner_builds;
    if (options.dynamics) step["time"] = s.time;
    if (options.contact.self) {
      step["self_contacts"] = s.self_contacts;
      step["max_self_penetration"] = s.max_self_penetration;
    }
    const size_t k = j["steps"].size();
    if (k < shapes.size() && shapes[k].defined) {
      step["volume_ratio"] = shapes[k].volume_ratio;
      step["min_j"] = shapes[k].min_j;
      step["rigid_fit_rms"] = shapes[k].rigid_fit_rms;
      step["rigid_fit_rms_relative"] = shapes[k].rigid_fit_rms_relative;
    }
    j["steps"].push_back(step);
  }
  j["wall_seconds"] = r.seconds;
  j["profile"] = profile_json(r.profile);
  j["device_memory_bytes"] = r.device_memory_bytes;
  j["final_residual"] = r.final_residual_norm;
  j["tolerance"] = r.tolerance;  // the absolute residual norm Newton stopped at
  j["converged"] = r.converged;
  j["volume_ratio"] = r.volume_ratio;
  j["min_j"] = r.min_j;
  j["max_j"] = r.max_j;
  j["inverted_elements"] = r.inverted_elements;
  j["history"] = history_json(r.history);
  return j;
}

// Per step, the force and torque every constraint set exerts on the body,
// the torque about the set's current centroid (fields.h).
json reactions_json(const std::vector<Reaction>& reactions) {
  json out = json::array();
  for (const Reaction& r : reactions)
    out.push_back({{"name", r.name}, {"force", r.force}, {"torque", r.torque}, {"about", r.about}});
  return out;
}

// The regions of a scene file: name, material, small-strain E and nu, and
// element count.
json regions_json(const MaterialMap& materials) {
  json out = json::array();
  for (size_t k = 1; k < materials.materials.size(); ++k) {
    const Material& m = materials.materials[k];
    const LameParameters l = m.lame();
    out.push_back({{"name", materials.names[k]},
                   {"material", m.description()},
                   {"youngs_modulus", l.mu * (3 * l.lambda + 2 * l.mu) / (l.lambda + l.mu)},
                   {"poisson_ratio", l.lambda / (2 * (l.lambda + l.mu))},
                   {"elements", std::count(materials.element_material.begin(), materials.element_material.end(),
                                           static_cast<int32_t>(k))}});
  }
  return out;
}

// --rtol, --atol, --max-newton, --forcing-max where given.
void apply_solver_limits(const SceneOptions& o, SolveOptions& options) {
  if (o.relative_tolerance >= 0.0) options.relative_tolerance = o.relative_tolerance;
  if (o.absolute_tolerance >= 0.0) {  // overrides a scene file's strain tolerance
    options.absolute_tolerance = o.absolute_tolerance;
    options.strain_tolerance.reset();
  }
  if (o.max_newton > 0) options.max_newton_iterations = o.max_newton;
  if (o.forcing_max > 0.0) options.forcing_max = o.forcing_max;
}

int run_scene(const SceneOptions& given) {
  SceneOptions o = given;
  if (o.name.empty() == o.file.empty()) throw Error("scene: give either a scene NAME or --file FILE");
  Scene scene;
  Material material;
  MaterialMap materials;  // a scene file's regions; else uniform
  SolveOptions options;
  std::optional<SceneFile> from_file;
  // The material the scene is meant to run with unless --E / --nu say otherwise.
  const SceneParameters defaults = scene_defaults(o.name);
  if (std::isnan(o.youngs_modulus)) o.youngs_modulus = defaults.youngs_modulus;
  if (std::isnan(o.poisson_ratio)) o.poisson_ratio = defaults.poisson_ratio;
  if (!o.file.empty()) {
    // A scene file carries its own material and solver settings; --json,
    // --vtu and --surface on the command line override its outputs.
    from_file = load_scene_file(o.file);
    const SceneFile& f = *from_file;
    scene = f.scene;
    material = f.material;
    materials = f.materials;
    options = scene.options;
    if (o.json_path.empty()) o.json_path = f.json_path;
    if (o.vtu_dir.empty()) o.vtu_dir = f.vtu_dir;
    if (o.surface_prefix.empty()) o.surface_prefix = f.surface_prefix;
    if (!o.surface_prefix.empty() && !f.embedded) throw Error("scene: --surface needs a scene with \"embed\"");
    options.device.match = o.device;
    for (const char* flag : kSceneBuildingFlags)
      if (o.given.count(flag))
        throw Error(std::string("scene: ") + flag + " builds a named scene; with --file set it in the file");
    // Solver flags given on the command line override the file's.
    if (o.given.count("--precision")) {
      options.precision = parse_precision(o.precision);
      if (!f.tolerance_given) options.strain_tolerance = strain_tolerance_default(options.precision);
    }
    if (o.given.count("--variant")) options.product = parse_product_variant(o.variant);
    if (o.given.count("--preconditioner")) options.preconditioner = parse_preconditioner(o.preconditioner);
    if (o.given.count("--hessian")) options.hessian = parse_hessian_mode(o.hessian);
    if (o.steps > 0) options.load_steps = o.steps;
    apply_solver_limits(o, options);
    o.multigrid.apply(options.multigrid);
    apply_product_precision(o.product_precision, options);  // the file's unless given
    if (f.rig) return run_rig_scene(f, options, {o.vtu_dir, o.json_path, o.surface_prefix, o.frames});
  } else {
    if (!o.surface_prefix.empty()) throw Error("scene: --surface needs a scene file with \"embed\"");
    SceneParameters p;
    p.resolution = o.resolution;
    p.youngs_modulus = o.youngs_modulus;
    p.poisson_ratio = o.poisson_ratio;
    p.barrier = parse_barrier(o.barrier);
    p.steps = o.steps;
    p.seed = o.seed;
    p.element_type = o.element == "tet4" ? ElementType::tet4 : ElementType::hex8;
    p.strain_tolerance =
        o.strain_tolerance > 0.0 ? o.strain_tolerance : strain_tolerance_default(parse_precision(o.precision));
    scene = make_scene(o.name, p);
    options = scene.options;
    options.precision = parse_precision(o.precision);
    options.device.match = o.device;
    options.product = parse_product_variant(o.variant);
    apply_product_precision(o.product_precision, options);
    options.preconditioner = parse_preconditioner(o.preconditioner);
    o.multigrid.apply(options.multigrid);
    apply_solver_limits(o, options);
    options.hessian = parse_hessian_mode(o.hessian);
    snh::MaterialOptions material_options;
    material_options.barrier = p.barrier;
    material_options.alpha = o.alpha;
    if (!o.lambda_model.empty()) material_options.lambda_model = parse_material_model(o.lambda_model);
    if (!std::isnan(o.alpha_lambda)) material_options.alpha_lambda = o.alpha_lambda;
    material = Material::from_youngs_modulus(parse_material_model(o.model), o.youngs_modulus, o.poisson_ratio,
                                             material_options);
    materials = uniform_material(scene.mesh, material);
  }

  const bool terminal = isatty(STDERR_FILENO);
  std::cerr << "scene " << scene.name << ": " << scene.description << "; " << scene.mesh.element_count() << " "
            << to_string(scene.mesh.type) << " elements, " << 3 * scene.mesh.vertex_count() << " dofs, "
            << to_string(options.precision) << '\n';
  // The .pvd's entries: part 0 the body, part 1 the obstacles (if any) as
  // <scene>_obstacles_NNNN.vtu surfaces (obstacle_surface.h), drawn to the
  // rest bounding box's diagonal either side of its centre.
  std::vector<PvdDataSet> written;
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0};
  for (size_t v = 0; v < scene.mesh.vertex_count(); ++v)
    for (int k = 0; k < 3; ++k) {
      lo[k] = v == 0 ? scene.mesh.positions[3 * v + k] : std::min(lo[k], scene.mesh.positions[3 * v + k]);
      hi[k] = v == 0 ? scene.mesh.positions[3 * v + k] : std::max(hi[k], scene.mesh.positions[3 * v + k]);
    }
  const std::array<double, 3> middle{0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
  const double extent = std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  auto write_obstacles = [&](int step, double time) {
    if (o.vtu_dir.empty() || options.obstacles.empty()) return;
    char file[256];
    std::snprintf(file, sizeof file, "%s_obstacles_%04d.vtu", scene.name.c_str(), step);
    const double t = static_cast<double>(step) / options.load_steps;
    write_surface_vtu(o.vtu_dir + "/" + file, obstacle_surface(options.obstacles, t, middle, extent));
    written.push_back({time, file, 1});
  };
  if (!o.vtu_dir.empty()) {
    std::filesystem::create_directories(o.vtu_dir);
    const std::vector<double>& x0 =
        options.initial_positions.empty() ? scene.mesh.positions : options.initial_positions;
    const std::string file = scene.name + "_0000.vtu";
    write_step_vtu(o.vtu_dir + "/" + file, scene.mesh, materials, x0);
    written.push_back({0.0, file, 0});
    write_obstacles(0, 0.0);
  }
  // The embedded surface per step as OBJ (scene files with "embed").
  auto write_surface = [&](int step, const std::vector<double>& x) {
    if (o.surface_prefix.empty()) return;
    const SceneFile::Embedded& e = *from_file->embedded;
    const std::string obj = surface_obj_path(o.surface_prefix, scene.name, step);
    const auto parent = std::filesystem::path(obj).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    write_obj(obj, e.surface, embedded_positions(e.embedding, scene.mesh, x));
  };
  write_surface(0, options.initial_positions.empty() ? scene.mesh.positions : options.initial_positions);
  QuasistaticSolver solver(scene.mesh, materials, scene.constraints, options);
  const Mesh& mesh = solver.mesh();
  // Each step's positions, for the reactions computed after the solve (so
  // that they do not count in its time).
  std::vector<std::vector<double>> step_positions, step_forces;
  // A scene with a contact stiffness but self-contact off: the same detector
  // measures, after each step, the self-penetration the penalty would see
  // (reported, not resisted; outside the solve's time).
  std::unique_ptr<solver::SelfContactDetector> unresolved;
  if (!options.contact.self && options.contact.stiffness > 0.0)
    unresolved = std::make_unique<solver::SelfContactDetector>(mesh);
  std::vector<std::pair<int, double>> unresolved_steps;
  std::vector<StepShape> shapes;
  const SolveResult r = solver.solve([&](int step, const std::vector<double>& x) {
    if (terminal) std::cerr << "  step " << step << "/" << options.load_steps << " done\n";
    shapes.push_back(step_shape(mesh, x));
    if (unresolved) {
      double deepest = 0.0;
      const auto pairs = unresolved->detect(x);
      for (const auto& c : pairs) deepest = std::max(deepest, solver::self_contact_length(c, x));
      unresolved_steps.push_back({static_cast<int>(pairs.size()), deepest});
    }
    write_surface(step, x);
    if (!o.json_path.empty()) {
      step_positions.push_back(x);
      step_forces.push_back(solver.simulation().applied_force());  // ramped with the load
    }
    if (o.vtu_dir.empty()) return;
    char file[256];
    std::snprintf(file, sizeof file, "%s_%04d.vtu", scene.name.c_str(), step);
    write_step_vtu(o.vtu_dir + "/" + file, mesh, materials, x);
    const double time = options.dynamics ? solver.simulation().time() : static_cast<double>(step);
    written.push_back({time, file, 0});
    write_obstacles(step, time);
  });
  if (!o.vtu_dir.empty()) write_pvd_parts(o.vtu_dir + "/" + scene.name + ".pvd", written);

  for (const std::string& w : r.warnings) std::cerr << "warning: " << w << '\n';
  const bool contact = !options.obstacles.empty() || options.contact.self, dynamic = options.dynamics.has_value();
  const bool self_column = options.contact.self || unresolved;
  std::cout << "step  newton  cg      status                 residual"
            << (dynamic ? "    time      volume    min_J     shape_rms" : "")
            << (contact ? "   contacts  max_penetration" : "")
            << (options.contact.self ? "  self_contacts  max_self_penetration"
                : unresolved         ? "  unresolved_self_contacts  max_self_penetration"
                                     : "")
            << '\n';
  for (size_t k = 0; k < r.steps.size(); ++k) {
    const StepResult& s = r.steps[k];
    std::cout << std::left << std::setw(6) << s.step << std::setw(8) << s.newton_iterations << std::setw(8)
              << s.cg_iterations << std::setw(23) << s.status << std::setw(12) << std::setprecision(3)
              << s.residual_norm;
    if (dynamic) {
      const StepShape sh = k < shapes.size() ? shapes[k] : StepShape{};
      std::cout << std::setw(10) << std::setprecision(4) << s.time << std::setw(10) << std::setprecision(5)
                << (sh.defined ? sh.volume_ratio : std::nan("")) << std::setw(10) << std::setprecision(3)
                << (sh.defined ? sh.min_j : std::nan("")) << std::setw(12) << std::setprecision(3)
                << (sh.defined ? sh.rigid_fit_rms_relative : std::nan(""));
    }
    if (contact) std::cout << std::setw(10) << s.contacts << std::setw(17) << std::setprecision(3) << s.max_penetration;
    if (self_column) {
      const int n = options.contact.self          ? s.self_contacts
                    : k < unresolved_steps.size() ? unresolved_steps[k].first
                                                  : 0;
      const double d = options.contact.self          ? s.max_self_penetration
                       : k < unresolved_steps.size() ? unresolved_steps[k].second
                                                     : 0.0;
      std::cout << "  " << std::setw(13) << n << std::setprecision(3) << d;
    }
    std::cout << '\n';
  }
  std::cout << "converged " << (r.converged ? "yes" : "no") << ", " << std::setprecision(4) << r.seconds
            << " s, volume ratio " << std::setprecision(6) << r.volume_ratio << ", min J " << std::setprecision(4)
            << r.min_j << ", inverted elements " << r.inverted_elements << '\n';
  if (!o.json_path.empty()) {
    const auto parent = std::filesystem::path(o.json_path).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    std::ofstream out(o.json_path);
    if (!out) throw Error("cannot write " + o.json_path);
    json j = summary_json(scene, options, r, shapes);
    // Self-contact off: what the detector measured after each step.
    for (size_t i = 0; i < unresolved_steps.size() && i < j["steps"].size(); ++i) {
      j["steps"][i]["unresolved_self_contacts"] = unresolved_steps[i].first;
      j["steps"][i]["max_self_penetration"] = unresolved_steps[i].second;
    }
    j["tolerance"] = r.tolerance;
    j["model"] = to_string(material.model);
    j["material"] = material.description();
    j["alpha"] = material.alpha_mu;
    j["alpha_lambda"] = material.alpha_lambda;
    if (material.lambda_model) j["lambda_model"] = to_string(*material.lambda_model);
    if (!materials.uniform()) j["regions"] = regions_json(materials);
    // A step without defined forces (a non-finite state) keeps its record
    // without "reactions".
    for (size_t i = 0; i < step_positions.size() && i < j["steps"].size(); ++i) {
      try {
        j["steps"][i]["reactions"] =
            reactions_json(constraint_reactions(mesh, materials, scene.constraints, step_positions[i], step_forces[i]));
      } catch (const Error& e) {
        std::cerr << "warning: step " << i + 1 << " has no reactions: " << e.what() << '\n';
      }
    }
    out << j.dump(2) << '\n';
  }
  return r.converged ? 0 : 3;
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
      ->check(CLI::IsMember({"hex8", "tet4"}))
      ->capture_default_str();
  cmd->add_option("--E", o->youngs_modulus, "Young's modulus (default: the scene's; 1, drop 5e4 Pa)");
  cmd->add_option("--nu", o->poisson_ratio, "Poisson's ratio (default: the scene's; 0.49, drop 0.46)");
  cmd->add_option("--model", o->model,
                  "material: snh, fung, arruda-boyce, corotational, fixed-corotational, stvk-kikuuwe, neohookean "
                  "(normalized to the same small-strain E, nu; model settings at their defaults)")
      ->check(CLI::IsMember(kModelNames))
      ->capture_default_str();
  cmd->add_option(
         "--alpha", o->alpha,
         "nonlinearity (Chen and Barbic 2024, Eq. 16): psi(sigma^alpha) / alpha^2 at the same small-strain E, nu")
      ->capture_default_str();
  cmd->add_option("--lambda-model", o->lambda_model,
                  "take the lambda_Lame (volume) part from this model (Chen and Barbic 2024, Eq. 19)")
      ->check(CLI::IsMember(kModelNames));
  cmd->add_option("--alpha-lambda", o->alpha_lambda, "nonlinearity of the lambda_Lame part (Eq. 20; default --alpha)");
  cmd->add_option("--barrier", o->barrier, "origin barrier: on, off, auto")
      ->check(CLI::IsMember({"on", "off", "auto"}))
      ->capture_default_str();
  cmd->add_option("--precision", o->precision, "float or double")
      ->check(CLI::IsMember({"float", "double"}))
      ->capture_default_str();
  cmd->add_option("--steps", o->steps, "load steps (0: scene default; drop: frames over its 2 s, default 60)");
  cmd->add_option("--seed", o->seed, "random seed (scramble)")->capture_default_str();
  cmd->add_option("--json", o->json_path,
                  "write a JSON summary with the per-iteration history and each step's constraint reactions here");
  cmd->add_option("--vtu", o->vtu_dir,
                  "write ASCII .vtu per step (displacement; F, J, P, Cauchy, von Mises, energy density per element) "
                  "and a .pvd into this folder");
  cmd->add_option("--surface", o->surface_prefix,
                  "scene files with \"embed\": write the embedded surface per step or frame as OBJ, to FOLDER/ "
                  "(<scene>_NNNN.obj) or PREFIX_NNNN.obj");
  cmd->add_option("--frames", o->frames, "scene files with \"rig\": run only the first N frames (0: all)");
  cmd->add_option("--device", o->device, "substring of '<platform> / <device>'");
  cmd->add_option("--variant", o->variant,
                  "Hessian product: automatic (measured default), cached, recompute, element-matrices, assembled")
      ->check(CLI::IsMember({"automatic", "cached", "recompute", "element-matrices", "assembled"}))
      ->capture_default_str();
  cmd->add_option("--preconditioner", o->preconditioner,
                  "automatic (measured default), block-jacobi, multigrid (hex8 lattices) or none")
      ->check(CLI::IsMember({"automatic", "block-jacobi", "multigrid", "none"}))
      ->capture_default_str();
  add_product_precision_option(cmd, o->product_precision);
  o->multigrid.add_to(cmd);
  cmd->add_option(
      "--strain-tol", o->strain_tolerance,
      "stop at the residual of this strain error, |r| <= tol E h^2 sqrt(vertices) (default 1e-6; float 1e-4)");
  cmd->add_option("--rtol", o->relative_tolerance, "relative residual tolerance per step (default: none)");
  cmd->add_option("--atol", o->absolute_tolerance, "absolute residual tolerance (overrides --strain-tol)");
  cmd->add_option("--max-newton", o->max_newton, "Newton iteration limit per step");
  cmd->add_option("--forcing-max", o->forcing_max, "cap of the Eisenstat-Walker forcing term (default 0.5)");
  cmd->add_option("--hessian", o->hessian,
                  "projected (always the PSD projection) or adaptive (true Hessian near convergence)")
      ->check(CLI::IsMember({"projected", "adaptive"}))
      ->capture_default_str();
  cmd->callback([o, cmd, &exit_code] {
    const auto note = [&](const char* flag) {
      if (cmd->count(flag) > 0) o->given.insert(flag);
    };
    for (const char* flag : kSceneBuildingFlags) note(flag);
    for (const char* flag : kSolverFlags) note(flag);
    exit_code = run_scene(*o);
  });
}

}  // namespace snh::bench
