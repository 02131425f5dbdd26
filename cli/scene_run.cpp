#include "scene_run.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>

#include "enum_names.h"
#include "product_precision_flag.h"
#include "snh/error.h"

namespace snh::cli {
namespace {

// The flags whose presence (not value) decides whether they override a file.
const char* const kSolverFlags[] = {"--precision", "--variant", "--preconditioner", "--hessian",    "--steps",
                                    "--rtol",      "--atol",    "--max-newton",     "--forcing-max"};

void print_header(const SceneFile& file, const SolveOptions& options, int frames) {
  const Scene& scene = file.scene;
  std::cerr << "scene " << scene.name << ": " << scene.description << "; " << scene.mesh.element_count() << " "
            << to_string(scene.mesh.type) << " elements, " << 3 * scene.mesh.vertex_count() << " dofs, ";
  if (file.rig) {
    std::cerr << file.rig->bones.size() << " bones, " << frames << " frames of " << options.load_steps
              << " load step(s), " << to_string(options.precision);
    if (file.embedded) std::cerr << "; surface of " << file.embedded->surface.vertex_count() << " vertices";
  } else {
    std::cerr << to_string(options.precision);
  }
  std::cerr << '\n';
  for (const std::string& line : scene_setup_report(file)) std::cerr << line << '\n';
}

void print_progress(const SceneProgress& p) {
  if (p.frame) {
    std::cerr << "  frame " << p.index << "/" << p.count << " (t = " << p.time << "): " << p.status << ", "
              << p.newton_iterations << " Newton, " << p.cg_iterations << " CG, " << std::setprecision(3) << p.seconds
              << " s, min J " << p.min_j << ", inverted " << p.inverted_elements;
  } else {
    std::cerr << "  step " << p.index << "/" << p.count << ": " << p.status << ", " << p.newton_iterations
              << " Newton, " << p.cg_iterations << " CG, " << std::setprecision(3) << p.seconds << " s";
    if (p.time > 0.0) std::cerr << ", t = " << std::setprecision(4) << p.time << " s";
    std::cerr << ", min J " << std::setprecision(3) << p.min_j << ", inverted " << p.inverted_elements;
  }
  if (!p.warnings.empty())
    std::cerr << " (" << p.warnings.size() << (p.warnings.size() == 1 ? " warning)" : " warnings)");
  std::cerr << '\n';
}

// "output.check_intersections": the most intersecting pairs at any step's or
// frame's end, and how many steps or frames had any.
void print_intersections_summary(const SceneRun& run) {
  if (run.surface_intersections.empty()) return;
  size_t most = 0, damaged = 0;
  for (const SelfIntersections& c : run.surface_intersections) {
    most = std::max(most, c.intersecting_pairs);
    damaged += c.clean() ? 0 : 1;
  }
  std::cout << ", surface intersections " << most << " (most in a " << (run.frames.empty() ? "step" : "frame") << "; "
            << damaged << " of " << run.surface_intersections.size() << " not clean)";
}

void print_frames(const SceneRun& run) {
  double seconds = 0.0;
  const bool checked = !run.surface_intersections.empty();
  const bool skinned = !run.skin_deviation.empty();
  std::cout << "frame  seconds  newton  cg      status                 residual   min J       inverted  self_pairs"
            << (skinned ? "  lbs_max     " : "") << "  warnings" << (checked ? "  intersections" : "") << "\n";
  for (size_t k = 0; k < run.frames.size(); ++k) {
    const FrameRecord& r = run.frames[k];
    seconds += r.seconds;
    std::cout << std::left << std::setw(7) << r.frame << std::setw(9) << std::setprecision(3) << r.seconds
              << std::setw(8) << r.newton_iterations << std::setw(8) << r.cg_iterations << std::setw(23) << r.status
              << std::setw(11) << std::setprecision(3) << r.residual_norm << std::setw(12) << std::setprecision(4)
              << r.min_j << std::setw(10) << r.inverted_elements << std::setw(12) << r.self_contact_pairs;
    if (skinned) std::cout << std::setw(14) << std::setprecision(4) << run.skin_deviation[k].max_distance;
    if (checked && k < run.surface_intersections.size())
      std::cout << std::setw(10) << r.warnings.size() << run.surface_intersections[k].intersecting_pairs;
    else
      std::cout << r.warnings.size();
    std::cout << '\n';
  }
  for (const FrameRecord& r : run.frames)
    for (const std::string& w : r.warnings) std::cerr << "warning: frame " << r.frame << ": " << w << '\n';
  std::cout << "all frames converged " << (run.converged ? "yes" : "no") << ", " << std::setprecision(4) << seconds
            << " s solving, " << run.frames.size() << " frames";
  print_intersections_summary(run);
  std::cout << "\n";
}

void print_steps(const SceneRun& run) {
  const SolveOptions& options = run.options;
  const SolveResult& r = run.result;
  const bool contact = !options.obstacles.empty() || options.contact.self, dynamic = options.dynamics.has_value();
  const bool measured = !options.contact.self && options.contact.stiffness > 0.0;
  const bool self_column = options.contact.self || measured;
  std::cout << "step  newton  cg      status                 residual    min_J       inverted"
            << (dynamic ? "    time      volume    min_J     shape_rms" : "")
            << (contact ? "   contacts  max_penetration" : "")
            << (options.contact.self ? "  self_contacts  max_self_penetration"
                : measured           ? "  unresolved_self_contacts  max_self_penetration"
                                     : "")
            << (run.surface_intersections.empty() ? "" : "  intersections") << '\n';
  for (size_t k = 0; k < r.steps.size(); ++k) {
    const StepResult& s = r.steps[k];
    static const SceneStep none;
    const SceneStep& record = k < run.steps.size() ? run.steps[k] : none;
    std::cout << std::left << std::setw(6) << s.step << std::setw(8) << s.newton_iterations << std::setw(8)
              << s.cg_iterations << std::setw(23) << s.status << std::setw(12) << std::setprecision(3)
              << s.residual_norm << std::setw(12) << std::setprecision(4) << s.min_j << std::setw(10)
              << s.inverted_elements;
    if (dynamic) {
      const StepShape& sh = record.shape;
      std::cout << std::setw(10) << std::setprecision(4) << s.time << std::setw(10) << std::setprecision(5)
                << (sh.defined ? sh.volume_ratio : std::nan("")) << std::setw(10) << std::setprecision(3)
                << (sh.defined ? sh.min_j : std::nan("")) << std::setw(12) << std::setprecision(3)
                << (sh.defined ? sh.rigid_fit_rms_relative : std::nan(""));
    }
    if (contact) std::cout << std::setw(10) << s.contacts << std::setw(17) << std::setprecision(3) << s.max_penetration;
    if (self_column) {
      const int n = options.contact.self ? s.self_contacts : record.unresolved_self_contacts;
      const double d = options.contact.self ? s.max_self_penetration : record.max_self_penetration;
      std::cout << "  " << std::setw(13) << n << std::setprecision(3) << d;
    }
    if (k < run.surface_intersections.size()) std::cout << "  " << run.surface_intersections[k].intersecting_pairs;
    std::cout << '\n';
  }
  std::cout << "converged " << (r.converged ? "yes" : "no") << ", " << std::setprecision(4) << r.seconds
            << " s, volume ratio " << std::setprecision(6) << r.volume_ratio << ", min J " << std::setprecision(4)
            << r.min_j << ", inverted elements " << r.inverted_elements;
  print_intersections_summary(run);
  std::cout << '\n';
}

}  // namespace

void SolverFlags::add_to(CLI::App* cmd, const std::string& steps_help) {
  cmd->add_option("--precision", precision, "float or double")
      ->check(CLI::IsMember(precision_names()))
      ->capture_default_str();
  cmd->add_option("--steps", steps, steps_help);
  cmd->add_option("--variant", variant,
                  "Hessian product: automatic (measured default), cached, recompute, element-matrices, assembled")
      ->check(CLI::IsMember(product_variant_names()))
      ->capture_default_str();
  cmd->add_option("--preconditioner", preconditioner,
                  "automatic (measured default), block-jacobi, multigrid (hex8 lattices) or none")
      ->check(CLI::IsMember(preconditioner_names()))
      ->capture_default_str();
  add_product_precision_option(cmd, product_precision);
  multigrid.add_to(cmd);
  cmd->add_option("--rtol", relative_tolerance, "relative residual tolerance per step (default: none)");
  cmd->add_option("--atol", absolute_tolerance,
                  "absolute residual tolerance (overrides a strain tolerance: --strain-tol or the file's)");
  cmd->add_option("--max-newton", max_newton,
                  "Newton iteration limit per step (default: the file's solver.max_newton_iterations, else " +
                      std::to_string(defaults::max_newton_iterations) + ")");
  cmd->add_option("--forcing-max", forcing_max, "cap of the Eisenstat-Walker forcing term (default 0.5)");
  cmd->add_option("--hessian", hessian,
                  "projected (always the PSD projection) or adaptive (true Hessian near convergence)")
      ->check(CLI::IsMember(hessian_mode_names()))
      ->capture_default_str();
}

void SolverFlags::note_given(const CLI::App* cmd) {
  for (const char* flag : kSolverFlags)
    if (cmd->count(flag) > 0) given.insert(flag);
}

void SolverFlags::apply_limits(SolveOptions& options) const {
  if (relative_tolerance >= 0.0) options.relative_tolerance = relative_tolerance;
  if (absolute_tolerance >= 0.0) {  // overrides a scene file's strain tolerance
    options.absolute_tolerance = absolute_tolerance;
    options.strain_tolerance.reset();
  }
  if (max_newton > 0) options.max_newton_iterations = max_newton;
  if (forcing_max > 0.0) options.forcing_max = forcing_max;
}

void SolverFlags::apply_to_file(const SceneFile& file, SolveOptions& options) const {
  if (given.count("--precision")) {
    options.precision = parse_precision(precision);
    if (!file.tolerance_given) options.strain_tolerance = defaults::strain_tolerance(options.precision);
  }
  if (given.count("--variant")) options.product = parse_optional(variant, parse_product_variant);
  if (given.count("--preconditioner")) options.preconditioner = parse_optional(preconditioner, parse_preconditioner);
  if (given.count("--hessian")) options.hessian = parse_hessian_mode(hessian);
  if (steps > 0) options.load_steps = steps;
  apply_limits(options);
  multigrid.apply(options.multigrid);
  apply_product_precision(product_precision, options);  // the file's unless given
}

SolveOptions SolverFlags::file_options(const SceneFile& file, const std::string& device) const {
  SolveOptions options = file.scene.options;
  options.device.match = device;
  apply_to_file(file, options);
  return options;
}

void warn_surface_defects(const SceneFile& file) {
  if (file.embedded)
    for (const std::string& warning : file.embedded->voxels.warnings) std::cerr << "warning: " << warning << "\n";
}

void add_output_options(CLI::App* cmd, SceneOutputs& outputs) {
  cmd->add_option("--json", outputs.json_path,
                  "write a JSON summary with the per-iteration history and each step's constraint reactions here");
  cmd->add_option("--vtu", outputs.vtu_dir,
                  "write ASCII .vtu per step (displacement; F, J, P, Cauchy, von Mises, energy density per element) "
                  "and a .pvd into this folder");
  cmd->add_option("--surface", outputs.surface_prefix,
                  "scene files with \"embed\": write the embedded surface per step or frame as OBJ, to FOLDER/ "
                  "(<scene>_NNNN.obj) or PREFIX_NNNN.obj");
  cmd->add_option("--frames", outputs.frames, "scene files with \"rig\": run only the first N frames (0: all)");
}

void explain_scene_file(const SceneFile& file, const SolveOptions& options, std::ostream& out) {
  const Simulation simulation(file.scene.mesh, file.materials, file.scene.constraints, options);
  const ResolvedConfiguration& config = simulation.configuration();
  size_t name_width = 0, value_width = 0;
  for (const ResolvedSetting& s : config.settings) {
    name_width = std::max(name_width, s.name.size());
    value_width = std::max(value_width, s.value.size());
  }
  out << "resolved configuration of " << file.scene.name << " (" << 3 * file.scene.mesh.vertex_count() << " DOFs, "
      << to_string(file.scene.mesh.type) << "):\n";
  for (const ResolvedSetting& s : config.settings)
    out << "  " << std::left << std::setw(static_cast<int>(name_width)) << s.name << "  "
        << std::setw(static_cast<int>(value_width)) << s.value << "  " << s.reason << '\n';
}

int run_scene_file(const SceneFile& file, const SolveOptions& options, const SceneOutputs& given) {
  SceneOutputs o = given;
  if (o.json_path.empty()) o.json_path = file.json_path;
  if (o.vtu_dir.empty()) o.vtu_dir = file.vtu_dir;
  if (o.surface_prefix.empty()) o.surface_prefix = file.surface_prefix;
  if (!o.surface_prefix.empty() && !file.embedded) throw Error("scene: --surface needs a scene with \"embed\"");
  int frames = 0;
  if (file.rig) {
    frames = static_cast<int>(file.rig->animation.frame_count());
    if (o.frames > 0 && o.frames < frames) frames = o.frames;
  }
  print_header(file, options, frames);

  SceneRunOptions run_options;
  run_options.max_frames = o.frames;
  run_options.reactions = !o.json_path.empty();
  if (!o.quiet) run_options.progress = print_progress;
  std::optional<SceneVtuSeries> vtu;
  if (!o.vtu_dir.empty()) {
    vtu.emplace(o.vtu_dir, file, options);
    run_options.writers.push_back(vtu->writer());
  }
  if (!o.surface_prefix.empty()) run_options.writers.push_back(surface_obj_writer(o.surface_prefix, file));
  std::optional<CharacterCacheSeries> caches;
  if (file.character && !(file.pc2_path.empty() && file.mdd_path.empty() && file.lbs_path.empty())) {
    caches.emplace(file.character->character, file.pc2_path, file.mdd_path, file.lbs_path);
    run_options.writers.push_back(
        [&caches](int frame, double, const Points&, const Points& surface) { caches->add(frame, surface); });
  }
  const SceneRun run = run_scene(file, options, run_options);
  if (caches) caches->finish();
  if (vtu) {
    vtu->finish();
    for (const std::string& w : vtu->warnings()) std::cerr << "warning: " << w << '\n';
  }
  for (const std::string& w : run.result.warnings) std::cerr << "warning: " << w << '\n';
  for (const std::string& w : run.warnings) std::cerr << "warning: " << w << '\n';
  if (file.rig)
    print_frames(run);
  else
    print_steps(run);
  if (!o.json_path.empty()) write_scene_json(o.json_path, file, run);
  // SolveOptions::fail_on_inverted: the step or frame that failed, named.
  for (const StepResult& s : run.result.steps)
    if (s.status == StepStatus::inverted_elements) {
      std::cerr << "error: " << (run.options.dynamics ? "time step " : "load step ") << s.step << " ended with "
                << s.inverted_elements << " inverted elements (min J " << s.min_j
                << ") and inverted elements fail this run\n";
      return 4;
    }
  for (const FrameRecord& r : run.frames)
    if (r.status == StepStatus::inverted_elements) {
      std::cerr << "error: frame " << r.frame << " ended with " << r.inverted_elements << " inverted elements (min J "
                << r.min_j << ") and inverted elements fail this run\n";
      return 4;
    }
  return run.converged ? 0 : 3;
}

}  // namespace snh::cli
