#include "solver/simulation/simulation_state.h"

#include <string>

#include "snh/error.h"

namespace snh::solver {

SimulationState::Target state_target(const ConstraintSet& set, const SetTarget& t) {
  SimulationState::Target out;
  out.set = set.name;
  out.kind = t.kind == SetTarget::Kind::callback    ? TargetKind::callbacks
             : t.kind == SetTarget::Kind::transform ? TargetKind::transform
                                                    : TargetKind::positions;
  out.from = t.from;
  out.to = t.to;
  out.from_known = t.from_known;
  out.positions = Points::from_xyz(t.xyz);
  return out;
}

SetTarget set_target(const SimulationState::Target& t) {
  SetTarget to;
  to.kind = t.kind == TargetKind::callbacks   ? SetTarget::Kind::callback
            : t.kind == TargetKind::transform ? SetTarget::Kind::transform
                                              : SetTarget::Kind::positions;
  to.from = t.from;
  to.to = t.to;
  to.from_known = t.from_known;
  to.xyz = t.positions.xyz();
  return to;
}

void check_restorable(const SimulationState& s, size_t vertex_count, uint64_t fingerprint,
                      const std::vector<ConstraintSet>& constraints, bool dynamics, size_t anchored_obstacles) {
  const size_t dofs = 3 * vertex_count;
  if (s.vertex_count != vertex_count || s.mesh_fingerprint != fingerprint)
    throw Error("restore: the checkpoint is of another mesh (" + std::to_string(s.vertex_count) +
                " vertices, fingerprint " + std::to_string(s.mesh_fingerprint) + "; this simulation's mesh: " +
                std::to_string(vertex_count) + " vertices, fingerprint " + std::to_string(fingerprint) + ")");
  auto size_check = [&](const Points& p, size_t expected, const char* item, bool may_be_empty) {
    const std::vector<double>& v = p.xyz();
    if (v.size() != expected && !(may_be_empty && v.empty()))
      throw Error(std::string("restore: the checkpoint's ") + item + " has " + std::to_string(v.size()) +
                  " values, expected " + std::to_string(expected) + (may_be_empty ? " or none" : ""));
  };
  size_check(s.positions, dofs, "positions", false);
  size_check(s.velocities, dynamics ? dofs : 0, "velocities (SolveOptions::dynamics)", false);
  size_check(s.friction_anchors, anchored_obstacles * dofs,
             "friction anchors (one per vertex and obstacle with friction)", false);
  size_check(s.external_force, dofs, "external force", true);
  size_check(s.force_from, dofs, "force ramp start", false);
  size_check(s.force_to, dofs, "force ramp end", false);
  size_check(s.force_applied, dofs, "applied force", true);
  if (s.targets.size() != constraints.size())
    throw Error("restore: the checkpoint has " + std::to_string(s.targets.size()) +
                " constraint sets, this simulation " + std::to_string(constraints.size()));
  for (size_t k = 0; k < s.targets.size(); ++k) {
    const SimulationState::Target& t = s.targets[k];
    const ConstraintSet& c = constraints[k];
    if (t.set != c.name)
      throw Error("restore: the checkpoint's constraint set " + std::to_string(k) + " is '" + t.set +
                  "', this simulation's is '" + c.name + "'");
    if (t.kind == TargetKind::positions && t.positions.xyz().size() != 3 * c.vertices.size())
      throw Error("restore: the checkpoint's target positions of set '" + c.name + "' have " +
                  std::to_string(t.positions.xyz().size()) + " values, expected " +
                  std::to_string(3 * c.vertices.size()));
  }
}

}  // namespace snh::solver
