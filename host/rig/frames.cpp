// The animation driver (snh/frames.h).
#include "snh/frames.h"

#include <algorithm>
#include <map>

#include "snh/error.h"
#include "snh/rig.h"

namespace snh {

std::vector<FrameRecord> run_frames(Simulation& simulation, const Animation& animation, const Embedding* embedding,
                                    const FrameOptions& options, const FrameCallback& on_frame) {
  if (options.load_steps < 1) throw Error("run_frames: load_steps must be >= 1");
  if (animation.transforms.size() != animation.times.size())
    throw Error("run_frames: the animation has " + std::to_string(animation.transforms.size()) +
                " frames of transforms for " + std::to_string(animation.times.size()) + " times");
  // Each animated bone's constraint set and the centroid of its rest positions.
  const Mesh& mesh = simulation.mesh();
  std::vector<std::array<double, 3>> centroids;
  for (const std::string& bone : animation.bones) {
    const auto& sets = simulation.constraints();
    const auto set = std::find_if(sets.begin(), sets.end(), [&](const ConstraintSet& s) { return s.name == bone; });
    if (set == sets.end()) {
      std::string known;
      for (const ConstraintSet& s : sets) known += (known.empty() ? "" : ", ") + s.name;
      throw Error("run_frames: the animation moves bone '" + bone +
                  "', which is no constraint set of the simulation (" + known + ")");
    }
    std::array<double, 3> c{0, 0, 0};
    for (int32_t v : set->vertices)
      for (int d = 0; d < 3; ++d) c[d] += mesh.positions(static_cast<size_t>(v), d);
    for (double& x : c) x /= static_cast<double>(set->vertices.size());
    centroids.push_back(c);
  }

  std::vector<FrameRecord> records;
  for (size_t f = 0; f < animation.frame_count(); ++f) {
    if (animation.transforms[f].size() != animation.bones.size())
      throw Error("run_frames: frame " + std::to_string(f) + " has " + std::to_string(animation.transforms[f].size()) +
                  " transforms for " + std::to_string(animation.bones.size()) + " bones");
    for (size_t b = 0; b < animation.bones.size(); ++b)
      simulation.set_transform(animation.bones[b], to_rigid_transform(animation.transforms[f][b], centroids[b]));
    const SolveResult r = simulation.solve(options.load_steps);
    FrameRecord record;
    record.frame = static_cast<int>(f);
    record.time = animation.times[f];
    record.converged = r.converged;
    record.status = r.steps.empty() ? StepStatus::none : r.steps.back().status;
    for (const StepResult& s : r.steps)
      record.warnings.insert(record.warnings.end(), s.warnings.begin(), s.warnings.end());
    for (const StepResult& s : r.steps) {
      record.newton_iterations += s.newton_iterations;
      record.cg_iterations += s.cg_iterations;
      record.self_contact_pairs = s.self_contact_pairs;
      record.min_self_distance = s.min_self_distance;
      record.self_contact_seconds += s.self_contact_seconds;
    }
    record.residual_norm = r.final_residual_norm;
    record.seconds = r.seconds;
    record.profile = r.profile;
    record.volume_ratio = r.volume_ratio;
    record.min_j = r.min_j;
    record.inverted_elements = r.inverted_elements;
    if (record.inverted_elements > 0 && (options.fail_on_inverted || record.status == StepStatus::inverted_elements)) {
      record.status = StepStatus::inverted_elements;
      record.converged = false;
    }
    try {
      record.reactions = simulation.reactions();
    } catch (const Error& e) {
      record.warnings.push_back("frame " + std::to_string(f) + " has no reactions: " + e.what());
    }
    record.history = r.history;
    record.product = r.product;
    record.preconditioner = r.preconditioner;
    record.product_precision = r.product_precision;
    record.multigrid_smoother_degree = r.multigrid_smoother_degree;
    record.multigrid_chebyshev = r.multigrid_chebyshev;
    record.multigrid_float_cycle = r.multigrid_float_cycle;
    record.kernel_specialization = r.kernel_specialization;
    record.device_memory_bytes = r.device_memory_bytes;
    records.push_back(record);
    const Points& x = simulation.positions();
    const Points surface = embedding ? embedded_positions(*embedding, mesh, x) : Points{};
    const bool go_on = on_frame ? on_frame(record, x, surface) : true;
    if (!go_on || (options.stop_on_failure && !record.converged) || record.status == StepStatus::inverted_elements)
      break;
  }
  return records;
}

}  // namespace snh
