// QuasistaticSolver (one solve over a Simulation), rigid transforms and the
// checks of a simulation's inputs.
#include <algorithm>
#include <cmath>
#include <map>

#include "fem/rest_state.h"
#include "snh/error.h"
#include "snh/simulation.h"
#include "solver/constraint_checks.h"
#include "solver/obstacles.h"

namespace snh {

RigidTransform RigidTransform::rotation_about(const std::array<double, 3>& axis, double angle,
                                              const std::array<double, 3>& center) {
  const double len = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  if (!(len > 0.0)) throw Error("RigidTransform: rotation axis must be non-zero");
  const double x = axis[0] / len, y = axis[1] / len, z = axis[2] / len;
  const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  RigidTransform r;
  // Rodrigues, column-major.
  r.rotation = {t * x * x + c,     t * x * y + s * z, t * x * z - s * y, t * x * y - s * z, t * y * y + c,
                t * y * z + s * x, t * x * z + s * y, t * y * z - s * x, t * z * z + c};
  r.center = center;
  return r;
}

RigidTransform RigidTransform::translation_by(const std::array<double, 3>& offset) {
  RigidTransform r;
  r.translation = offset;
  return r;
}

std::array<double, 3> RigidTransform::apply(const std::array<double, 3>& p) const {
  const double d[3] = {p[0] - center[0], p[1] - center[1], p[2] - center[2]};
  std::array<double, 3> out;
  for (int i = 0; i < 3; ++i)
    out[i] = rotation[i] * d[0] + rotation[3 + i] * d[1] + rotation[6 + i] * d[2] + center[i] + translation[i];
  return out;
}

DeformationStatistics deformation_statistics(const Mesh& mesh, const std::vector<double>& x) {
  const fem::RestState rest = fem::compute_rest_state(mesh);
  DeformationStatistics s;
  s.min_j = std::numeric_limits<double>::infinity();
  s.max_j = -std::numeric_limits<double>::infinity();
  double volume = 0.0;
  for (size_t e = 0; e < mesh.element_count(); ++e) {
    bool inverted = false;
    for (int q = 0; q < rest.quadrature; ++q) {
      double f[9];
      fem::deformation_gradient(mesh, rest, x.data(), e, q, f);
      const double j = fem::determinant(f);
      s.min_j = std::min(s.min_j, j);
      s.max_j = std::max(s.max_j, j);
      inverted = inverted || !(j > 0.0);
      volume += j * rest.weight(e, q);
    }
    s.inverted_elements += inverted ? 1 : 0;
  }
  s.volume_ratio = volume / rest.rest_volume;
  return s;
}

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
  auto check_vector = [&](const std::vector<double>& v, const char* what) {
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

double residual_tolerance(const Mesh& mesh, const MaterialMap& materials, const SolveOptions& options) {
  // The default strain criterion steps aside for an explicit absolute or
  // relative one.
  const bool explicit_other = options.absolute_tolerance > 0.0 || options.relative_tolerance > 0.0;
  const double strain = options.strain_tolerance ? *options.strain_tolerance
                        : explicit_other         ? 0.0
                                                 : (options.precision == Precision::double_ ? 1e-6 : 1e-4);
  double scale = 0.0;
  if (strain > 0.0 && mesh.element_count() > 0) {
    // The smallest Young's modulus among the materials elements use.
    std::vector<char> used_material(materials.materials.size(), 0);
    for (int32_t k : materials.element_material) used_material[k] = 1;
    double youngs = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < materials.materials.size(); ++k) {
      if (!used_material[k]) continue;
      const LameParameters l = materials.materials[k].lame();
      youngs = std::min(youngs, l.mu * (3.0 * l.lambda + 2.0 * l.mu) / (l.lambda + l.mu));
    }
    std::vector<char> used(mesh.vertex_count(), 0);
    for (int32_t v : mesh.elements) used[v] = 1;
    const double n = static_cast<double>(std::count(used.begin(), used.end(), 1));
    const double h = vertex_spacing(mesh);
    scale = strain * youngs * h * h * std::sqrt(n);
  }
  return std::max(scale, options.absolute_tolerance);
}

void apply_constraints(const Mesh& mesh, const std::vector<ConstraintSet>& constraints, double t,
                       std::vector<double>& x) {
  for (const ConstraintSet& c : constraints) solver::place_by_callback(mesh, c, t, x);
}

QuasistaticSolver::QuasistaticSolver(Mesh mesh, const Material& material, std::vector<ConstraintSet> constraints,
                                     SolveOptions options)
    : simulation_(std::move(mesh), material, std::move(constraints), std::move(options)) {}
QuasistaticSolver::QuasistaticSolver(Mesh mesh, const MaterialMap& materials, std::vector<ConstraintSet> constraints,
                                     SolveOptions options)
    : simulation_(std::move(mesh), materials, std::move(constraints), std::move(options)) {}
QuasistaticSolver::~QuasistaticSolver() = default;
QuasistaticSolver::QuasistaticSolver(QuasistaticSolver&&) noexcept = default;
QuasistaticSolver& QuasistaticSolver::operator=(QuasistaticSolver&&) noexcept = default;

const Mesh& QuasistaticSolver::mesh() const { return simulation_.mesh(); }
const DeviceInfo& QuasistaticSolver::device() const { return simulation_.device(); }
Simulation& QuasistaticSolver::simulation() { return simulation_; }

SolveResult QuasistaticSolver::solve(const StepCallback& on_step, const ProgressCallback& progress) {
  simulation_.restart();
  return simulation_.solve(0, progress, on_step);
}

}  // namespace snh
