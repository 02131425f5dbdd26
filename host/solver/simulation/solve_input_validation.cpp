// The checks of a simulation's inputs: constraint sets, solve options,
// dynamics and obstacles, each failure an snh::Error naming what is wrong.
#include "solver/simulation/solve_input_validation.h"

#include <cmath>
#include <map>
#include <string>

#include "snh/error.h"
#include "snh/simulation.h"
#include "solver/contact/obstacles.h"

namespace snh {

void validate_solve_inputs(const Mesh& mesh, const std::vector<ConstraintSet>& constraints,
                           const SolveOptions& options) {
  const size_t n = mesh.vertex_count();
  std::map<std::string, size_t> names;
  // The set prescribing each DOF, to name both sets of a conflict.
  std::vector<int> owner(constraints.empty() ? 0 : 3 * n, -1);
  for (size_t k = 0; k < constraints.size(); ++k) {
    const ConstraintSet& c = constraints[k];
    if (!names.emplace(c.name, k).second)
      throw Error("two constraint sets are named '" + c.name + "': names select sets (Simulation::set_transform)");
    if (c.vertices.empty()) throw Error("constraint set '" + c.name + "' selects no vertex");
    if (!c.components[0] && !c.components[1] && !c.components[2])
      throw Error("constraint set '" + c.name + "' prescribes no component (components all false)");
    for (int32_t v : c.vertices) {
      if (v < 0 || static_cast<size_t>(v) >= n)
        throw Error("constraint set '" + c.name + "' refers to vertex " + std::to_string(v) + ", but the mesh has " +
                    std::to_string(n) + " vertices");
      for (int d = 0; d < 3; ++d) {
        if (!c.components[d]) continue;
        int& o = owner[3 * static_cast<size_t>(v) + d];
        if (o == static_cast<int>(k)) continue;  // listed twice in one set
        if (o >= 0)
          throw Error("vertex " + std::to_string(v) + " is prescribed by constraint sets '" + constraints[o].name +
                      "' and '" + c.name + "' (component " + "xyz"[d] + "); a vertex component may belong to one set");
        o = static_cast<int>(k);
      }
    }
  }
  auto check_vector = [&](const Points& p, const char* what) {
    const std::vector<double>& v = p.xyz();
    if (!v.empty() && v.size() != 3 * n)
      throw Error(std::string("solve options: ") + what + " has " + std::to_string(v.size()) + " entries, expected " +
                  std::to_string(3 * n) + " (xyz per vertex)");
    for (double e : v)
      if (!std::isfinite(e)) throw Error(std::string("solve options: ") + what + " has a non-finite entry");
  };
  check_vector(options.initial_positions, "initial_positions");
  check_vector(options.external_force, "external_force");
  for (double b : options.body_force)
    if (!std::isfinite(b)) throw Error("solve options: body_force has a non-finite entry");
  if (options.load_steps < 1) throw Error("solve options: load_steps must be >= 1");
  if (options.max_newton_iterations < 0 || options.max_cg_iterations < 1)
    throw Error("solve options: iteration limits must be positive");
  if (options.cg_check_every < 0)
    throw Error("solve options: cg_check_every must be >= 0 (0: ViennaCL's CG), got " +
                std::to_string(options.cg_check_every));
  if (!(options.absolute_tolerance >= 0.0) || !(options.relative_tolerance >= 0.0) ||
      (options.strain_tolerance && !(*options.strain_tolerance >= 0.0)))
    throw Error("solve options: tolerances must be finite and >= 0");
  if (!std::isfinite(options.absolute_tolerance) || !std::isfinite(options.relative_tolerance) ||
      (options.strain_tolerance && !std::isfinite(*options.strain_tolerance)))
    throw Error("solve options: tolerances must be finite and >= 0");
  if (options.line_search_halvings < 0) throw Error("solve options: line_search_halvings must be >= 0");
  check_vector(options.initial_velocities, "initial_velocities");
  if (!options.initial_velocities.empty() && !options.dynamics)
    throw Error("solve options: initial_velocities need dynamics (quasistatic solves have no velocities)");
  if (options.dynamics) {
    const DynamicsOptions& d = *options.dynamics;
    if (!(d.time_step > 0.0) || !std::isfinite(d.time_step))
      throw Error("dynamics: time_step must be finite and > 0 (got " + std::to_string(d.time_step) + ")");
    if (!(d.density > 0.0) || !std::isfinite(d.density))
      throw Error("dynamics: density must be finite and > 0 (got " + std::to_string(d.density) + ")");
    if (!(d.damping.mass >= 0.0) || !std::isfinite(d.damping.mass))
      throw Error("dynamics: damping.mass must be finite and >= 0 (got " + std::to_string(d.damping.mass) + ")");
    if (!(d.damping.stiffness >= 0.0) || !std::isfinite(d.damping.stiffness))
      throw Error("dynamics: damping.stiffness must be finite and >= 0 (got " + std::to_string(d.damping.stiffness) +
                  ")");
    if (d.substeps < 1) throw Error("dynamics: substeps must be >= 1 (got " + std::to_string(d.substeps) + ")");
  }
  solver::validate_obstacles(options.obstacles, options.contact);
}

}  // namespace snh
