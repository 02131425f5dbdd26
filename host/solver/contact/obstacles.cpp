#include "solver/contact/obstacles.h"

#include <cmath>
#include <string>

#include "fem/name_table.h"
#include "snh/error.h"

namespace snh {

namespace {

constexpr NameTable<ObstacleType, 3> kObstacleTypeNames{{
    {ObstacleType::plane, "plane"},
    {ObstacleType::sphere, "sphere"},
    {ObstacleType::cylinder, "cylinder"},
}};

}  // namespace

const char* to_string(ObstacleType type) { return name_of(kObstacleTypeNames, type); }

}  // namespace snh

namespace snh::solver {

namespace {

// Record layout of kernels/contact/obstacle.h.
constexpr int kRecord = 8;
constexpr int kFrictionRecord = 16;

std::string name(size_t k, const Obstacle& o) {
  return "obstacle " + std::to_string(k) + " (" + to_string(o.type) + ")";
}

double norm(const std::array<double, 3>& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

}  // namespace

void validate_obstacles(const std::vector<Obstacle>& obstacles, const ContactOptions& contact) {
  if (!std::isfinite(contact.thickness) || !(contact.thickness >= 0.0))
    throw Error("contact: thickness must be finite and >= 0 (got " + std::to_string(contact.thickness) + ")");
  if (!std::isfinite(contact.stiffness) || contact.stiffness < 0.0)
    throw Error("contact: stiffness must be finite and > 0 (got " + std::to_string(contact.stiffness) + ")");
  if (contact.self_stiffness && !(std::isfinite(*contact.self_stiffness) && *contact.self_stiffness > 0.0))
    throw Error("contact: self_stiffness must be finite and > 0 when set (got " +
                std::to_string(*contact.self_stiffness) + ")");
  if (contact.self && contact.self_method == SelfContactMethod::penalty && !contact.self_stiffness &&
      !(contact.stiffness > 0.0))
    throw Error("contact: penalty self-contact needs stiffness or self_stiffness > 0");
  if (contact.self_method != SelfContactMethod::barrier && contact.self_method != SelfContactMethod::penalty)
    throw Error("contact: self_method is barrier or penalty");
  if (contact.self_distance && !(std::isfinite(*contact.self_distance) && *contact.self_distance > 0.0))
    throw Error("contact: self_distance must be finite and > 0 when set (got " +
                std::to_string(*contact.self_distance) + ")");
  if (!std::isfinite(contact.friction) || !(contact.friction >= 0.0))
    throw Error("contact: friction must be finite and >= 0 (got " + std::to_string(contact.friction) + ")");
  if (contact.friction_slip && !(std::isfinite(*contact.friction_slip) && *contact.friction_slip > 0.0))
    throw Error("contact: friction_slip must be finite and > 0 when set (got " +
                std::to_string(*contact.friction_slip) + ")");
  if (obstacles.empty()) return;
  if (!(contact.stiffness > 0.0))
    throw Error("contact: stiffness must be > 0 with obstacles (got " + std::to_string(contact.stiffness) + ")");
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const Obstacle& o = obstacles[k];
    for (int d = 0; d < 3; ++d)
      if (!std::isfinite(o.point[d]) || !std::isfinite(o.direction[d]))
        throw Error(name(k, o) + ": non-finite point or direction");
    if (o.type != ObstacleType::sphere && !(norm(o.direction) > 0.0))
      throw Error(name(k, o) + (o.type == ObstacleType::plane ? ": zero normal" : ": zero axis"));
    if (o.type != ObstacleType::plane && (!(o.radius > 0.0) || !std::isfinite(o.radius)))
      throw Error(name(k, o) + ": radius must be finite and > 0 (got " + std::to_string(o.radius) + ")");
    if (o.friction && (!std::isfinite(*o.friction) || !(*o.friction >= 0.0)))
      throw Error(name(k, o) + ": friction must be finite and >= 0 (got " + std::to_string(*o.friction) + ")");
  }
}

double friction_coefficient(const Obstacle& obstacle, const ContactOptions& contact) {
  return obstacle.friction ? *obstacle.friction : contact.friction;
}

bool has_friction(const std::vector<Obstacle>& obstacles, const ContactOptions& contact) {
  for (const Obstacle& o : obstacles)
    if (friction_coefficient(o, contact) > 0.0) return true;
  return false;
}

std::vector<double> friction_records(const std::vector<Obstacle>& obstacles, const ContactOptions& contact, double t0,
                                     double t1) {
  std::vector<double> table(kFrictionRecord * obstacles.size(), 0.0);
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const Obstacle& o = obstacles[k];
    const RigidTransform a = o.motion ? o.motion(t0) : RigidTransform::identity();
    const RigidTransform b = o.motion ? o.motion(t1) : RigidTransform::identity();
    // The world point q of the obstacle at t0 is b(a^-1(q)) at t1, with
    // a(p) = R (p - c) + c + s, so a^-1(q) = R^T (q - c - s) + c.
    auto carry = [&](const std::array<double, 3>& q) {
      std::array<double, 3> w{}, p{};
      for (int d = 0; d < 3; ++d) w[d] = q[d] - a.center[d] - a.translation[d];
      for (int d = 0; d < 3; ++d)
        p[d] = a.rotation[d] * w[0] + a.rotation[3 + d] * w[1] + a.rotation[6 + d] * w[2] + a.center[d];
      return b.apply(p);
    };
    double* record = table.data() + kFrictionRecord * k;
    record[0] = friction_coefficient(o, contact);
    const std::array<double, 3> origin = carry({0, 0, 0});
    for (int c = 0; c < 3; ++c) {
      std::array<double, 3> e{0, 0, 0};
      e[c] = 1.0;
      const std::array<double, 3> image = carry(e);
      for (int r = 0; r < 3; ++r) record[1 + 3 * c + r] = image[r] - origin[r];
    }
    for (int d = 0; d < 3; ++d) record[10 + d] = origin[d];
    for (int i = 0; i < kFrictionRecord; ++i)
      if (!std::isfinite(record[i]))
        throw Error(name(k, o) + ": its motion between load parameters " + std::to_string(t0) + " and " +
                    std::to_string(t1) + " is not finite");
  }
  return table;
}

std::vector<double> obstacle_records(const std::vector<Obstacle>& obstacles, double t) {
  std::vector<double> table(kRecord * obstacles.size(), 0.0);
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const Obstacle& o = obstacles[k];
    const RigidTransform motion = o.motion ? o.motion(t) : RigidTransform::identity();
    const std::array<double, 3> point = motion.apply(o.point);
    std::array<double, 3> direction{0, 0, 0};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) direction[r] += motion.rotation[3 * r + c] * o.direction[c];
    const double length = norm(direction);
    double* record = table.data() + kRecord * k;
    record[0] = static_cast<double>(static_cast<int>(o.type));
    for (int d = 0; d < 3; ++d) {
      record[1 + d] = point[d];
      record[4 + d] = o.type == ObstacleType::sphere ? 0.0 : direction[d] / length;
    }
    record[7] = o.type == ObstacleType::plane ? 0.0 : o.radius;
    for (int i = 0; i < kRecord; ++i)
      if (!std::isfinite(record[i]))
        throw Error(name(k, o) + ": its motion at load parameter " + std::to_string(t) +
                    " gives a non-finite placement");
  }
  return table;
}

}  // namespace snh::solver
