// Running a loaded scene: its load steps (or time steps) on one solve, or a
// rig's animation frame by frame (snh/frames.h), each step or frame handed
// to the writers. A rig's targets are absolute per frame, solved from the
// previous frame, so frames do not fit one solve's load parameter.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

#include "scene/character_scene.h"
#include "scene/output_surface_check.h"
#include "scene/scene_progress.h"
#include "snh/error.h"
#include "snh/scene.h"
#include "snh/shape.h"
#include "solver/contact/self_contact.h"

namespace snh {
namespace {

using Clock = std::chrono::steady_clock;

StepShape step_shape(const Mesh& mesh, const Points& x) {
  StepShape s;
  for (double v : x.xyz())
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

void write_all(const SceneRunOptions& run, int index, double time, const Points& x, const Points& surface) {
  for (const SceneStepWriter& w : run.writers)
    if (w) w(index, time, x, surface);
}

SceneRun run_frames_of(const SceneFile& file, const SolveOptions& options, const SceneRunOptions& run) {
  Animation animation = file.rig->animation;
  if (run.max_frames > 0 && static_cast<size_t>(run.max_frames) < animation.frame_count()) {
    animation.times.resize(run.max_frames);
    animation.transforms.resize(run.max_frames);
  }
  const Embedding* embedding = file.embedded ? &file.embedded->embedding : nullptr;
  Simulation simulation(file.scene.mesh, file.materials, file.scene.constraints, options);
  if (file.embedded && !options.obstacles.empty()) simulation.set_contact_surface(file.embedded->embedding);
  SceneRun out;
  out.options = options;
  out.resolved = simulation.configuration();
  out.device = simulation.device();
  FrameOptions frame_options;
  frame_options.load_steps = options.load_steps;
  frame_options.fail_on_inverted = options.fail_on_inverted;
  const int frames = static_cast<int>(animation.frame_count());
  std::optional<scene_io::OutputSurfaceCheck> check;
  if (file.check_intersections) check.emplace(file, file.scene.mesh);
  out.frames = run_frames(simulation, animation, embedding, frame_options,
                          [&](const FrameRecord& r, const Points& x, const Points& surface) {
                            if (check) out.surface_intersections.push_back(check->count(x, surface));
                            if (run.progress) {
                              SceneProgress p = scene_io::frame_progress(r, r.frame + 1, frames);
                              const std::string w =
                                  check ? scene_io::OutputSurfaceCheck::warning(out.surface_intersections.back()) : "";
                              if (!w.empty()) p.warnings.push_back(w);
                              run.progress(p);
                            }
                            write_all(run, r.frame, r.time, x, surface);
                            return true;
                          });
  for (size_t k = 0; k < out.frames.size() && k < out.surface_intersections.size(); ++k) {
    const std::string w = scene_io::OutputSurfaceCheck::warning(out.surface_intersections[k]);
    if (!w.empty()) out.frames[k].warnings.push_back(w);
  }
  out.converged = std::all_of(out.frames.begin(), out.frames.end(), [](const FrameRecord& r) { return r.converged; });
  return out;
}

SceneRun run_load_steps(const SceneFile& file, const SolveOptions& options, const SceneRunOptions& run) {
  const Scene& scene = file.scene;
  // The embedded surface, only for writers to write.
  const auto surface_of = [&](const Mesh& mesh, const Points& x) {
    return file.embedded && (!run.writers.empty() || file.check_intersections)
               ? embedded_positions(file.embedded->embedding, mesh, x)
               : Points{};
  };
  const Points& x0 = options.initial_positions.empty() ? scene.mesh.positions : options.initial_positions;
  write_all(run, 0, 0.0, x0, surface_of(scene.mesh, x0));

  QuasistaticSolver solver(scene.mesh, file.materials, scene.constraints, options);
  if (file.embedded && !options.obstacles.empty()) solver.simulation().set_contact_surface(file.embedded->embedding);
  const Mesh& mesh = solver.mesh();
  std::optional<scene_io::OutputSurfaceCheck> check;
  if (file.check_intersections) check.emplace(file, mesh);
  SceneRun out;
  out.options = options;
  // Each step's positions and applied force (ramped with the load), for the
  // reactions computed after the solve (so that they do not count in its
  // time).
  std::vector<Points> step_positions, step_forces;
  // A scene with a contact stiffness but self-contact off: the same detector
  // measures, after each step, the self-penetration the penalty would see
  // (reported, not resisted; outside the solve's time).
  std::unique_ptr<solver::SelfContactDetector> unresolved;
  if (!options.contact.self && options.contact.stiffness > 0.0)
    unresolved = std::make_unique<solver::SelfContactDetector>(mesh);
  // The progress of the step under way, from its Newton iterations.
  SceneProgress progress;
  progress.count = options.load_steps;
  auto step_start = Clock::now();
  const auto on_newton = [&](const NewtonIteration& it) {
    ++progress.newton_iterations;
    progress.cg_iterations += it.cg_iterations;
    progress.residual_norm = it.residual_norm;
    return true;
  };
  const StepCallback on_step = [&](int step, const Points& x) {
    SceneStep record;
    record.shape = step_shape(mesh, x);
    if (unresolved) {
      record.self_contact_measured = true;
      const auto pairs = unresolved->detect(x.xyz());
      record.unresolved_self_contacts = static_cast<int>(pairs.size());
      for (const auto& c : pairs)
        record.max_self_penetration = std::max(record.max_self_penetration, solver::self_contact_length(c, x.xyz()));
    }
    out.steps.push_back(std::move(record));
    const Points surface = surface_of(mesh, x);
    std::string intersections;
    if (check) {
      out.surface_intersections.push_back(check->count(x, surface));
      intersections = scene_io::OutputSurfaceCheck::warning(out.surface_intersections.back());
      if (!intersections.empty()) out.warnings.push_back("step " + std::to_string(step) + ": " + intersections);
    }
    if (run.reactions) {
      step_positions.push_back(x);
      step_forces.push_back(solver.simulation().applied_force());
    }
    const double time = options.dynamics ? solver.simulation().time() : static_cast<double>(step);
    if (run.progress) {
      const StepResult& done = solver.simulation().last_step();
      progress.index = step;
      progress.status = done.status;
      progress.min_j = done.min_j;
      progress.inverted_elements = done.inverted_elements;
      progress.warnings = done.warnings;
      if (!intersections.empty()) progress.warnings.push_back(intersections);
      progress.seconds = std::chrono::duration<double>(Clock::now() - step_start).count();
      progress.time = options.dynamics ? time : 0.0;
      run.progress(progress);
    }
    write_all(run, step, time, x, surface);
    progress.newton_iterations = progress.cg_iterations = 0;
    step_start = Clock::now();
  };
  out.result = solver.solve(on_newton, on_step);
  out.resolved = solver.simulation().configuration();
  // A step without defined forces (a non-finite state) keeps its record
  // without reactions.
  for (size_t i = 0; i < step_positions.size() && i < out.steps.size(); ++i) {
    try {
      out.steps[i].reactions =
          constraint_reactions(mesh, file.materials, scene.constraints, step_positions[i], step_forces[i]);
    } catch (const Error& e) {
      out.warnings.push_back("step " + std::to_string(i + 1) + " has no reactions: " + e.what());
    }
  }
  out.converged = out.result.converged;
  return out;
}

}  // namespace

SceneRun run_scene(const SceneFile& file, const SolveOptions& options, const SceneRunOptions& run) {
  if (file.character) return scene_io::run_character_scene(file, options, run);
  return file.rig ? run_frames_of(file, options, run) : run_load_steps(file, options, run);
}

}  // namespace snh
