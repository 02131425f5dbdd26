#include "solver/simulation/load_stepping.h"

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "snh/error.h"
#include "solver/simulation/constraint_checks.h"

namespace snh {

void apply_constraints(const Mesh& mesh, const std::vector<ConstraintSet>& constraints, double t,
                       std::vector<double>& x) {
  for (const ConstraintSet& c : constraints) solver::place_by_callback(mesh, c, t, x);
}

namespace solver {

namespace {

// x = A X + b of a transform.
struct Affine {
  Eigen::Matrix3d a;
  Eigen::Vector3d b;
};

Affine affine_of(const RigidTransform& t) {
  Affine f;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) f.a(r, c) = t.rotation[3 * r + c];
  const Eigen::Vector3d center(t.center[0], t.center[1], t.center[2]);
  f.b = center + Eigen::Vector3d(t.translation[0], t.translation[1], t.translation[2]) - f.a * center;
  return f;
}

bool is_rotation(const Eigen::Matrix3d& a) {
  return (a.transpose() * a - Eigen::Matrix3d::Identity()).norm() < 1e-9 && a.determinant() > 0.0;
}

// The rigid motion at fraction s from `from` to `to`, both rotations: the
// relative rotation's angle scaled by s (slerp) about `to`'s centre, whose
// image moves on a straight line.
Affine interpolate(const RigidTransform& from, const RigidTransform& to, double s) {
  const Affine f = affine_of(from), g = affine_of(to);
  const Eigen::AngleAxisd relative(Eigen::Matrix3d(g.a * f.a.transpose()));
  const Eigen::Matrix3d a = Eigen::AngleAxisd(s * relative.angle(), relative.axis()).toRotationMatrix() * f.a;
  const Eigen::Vector3d c(to.center[0], to.center[1], to.center[2]);
  const Eigen::Vector3d image = (1.0 - s) * (f.a * c + f.b) + s * (g.a * c + g.b);
  return {a, image - a * c};
}

}  // namespace

void record_start(const ConstraintSet& set, const std::vector<double>& x, SetTarget& target) {
  target.start.resize(3 * set.vertices.size());
  for (size_t i = 0; i < set.vertices.size(); ++i)
    for (int d = 0; d < 3; ++d) target.start[3 * i + d] = x[3 * set.vertices[i] + d];
}

namespace {

// place_target into positions, xyz per vertex (`Positions`: std::vector<double> or Points).
template <typename Positions>
void place_target_into(const Mesh& mesh, const ConstraintSet& c, const SetTarget& t, double s, Positions& all) {
  double* positions = all.data();
  auto put = [&](size_t i, const double p[3]) {
    for (int d = 0; d < 3; ++d)
      if (c.components[d]) positions[3 * c.vertices[i] + d] = p[d];
  };
  switch (t.kind) {
    case SetTarget::Kind::callback:
      place_by_callback(mesh, c, s, all);
      break;
    case SetTarget::Kind::transform: {
      const bool rigid = t.from_known && is_rotation(affine_of(t.from).a) && is_rotation(affine_of(t.to).a);
      const Affine f = rigid ? interpolate(t.from, t.to, s) : affine_of(t.to);
      for (size_t i = 0; i < c.vertices.size(); ++i) {
        const auto rest_position = mesh.vertex(c.vertices[i]);
        const Eigen::Vector3d image = f.a * Eigen::Vector3d(rest_position[0], rest_position[1], rest_position[2]) + f.b;
        double p[3];
        for (int d = 0; d < 3; ++d) p[d] = rigid ? image[d] : (1.0 - s) * t.start[3 * i + d] + s * image[d];
        put(i, p);
      }
      break;
    }
    case SetTarget::Kind::positions:
      for (size_t i = 0; i < c.vertices.size(); ++i) {
        double p[3];
        for (int d = 0; d < 3; ++d) p[d] = (1.0 - s) * t.start[3 * i + d] + s * t.xyz[3 * i + d];
        put(i, p);
      }
      break;
  }
  for (size_t i = 0; i < c.vertices.size(); ++i)
    for (int d = 0; d < 3; ++d)
      if (!std::isfinite(positions[3 * c.vertices[i] + d]))
        throw Error("constraint set '" + c.name + "': non-finite target position for vertex " +
                    std::to_string(c.vertices[i]));
}

}  // namespace

void place_target(const Mesh& mesh, const ConstraintSet& c, const SetTarget& t, double s,
                  std::vector<double>& positions) {
  place_target_into(mesh, c, t, s, positions);
}

void place_target(const Mesh& mesh, const ConstraintSet& c, const SetTarget& t, double s, Points& positions) {
  place_target_into(mesh, c, t, s, positions);
}

void ramp_force(const std::vector<double>& from, const std::vector<double>& to, double s, std::vector<double>& out) {
  out.resize(to.size());
  for (size_t i = 0; i < to.size(); ++i) out[i] = from[i] + s * (to[i] - from[i]);
}

}  // namespace solver
}  // namespace snh
