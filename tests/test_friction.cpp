// Coulomb friction against obstacles (ContactOptions::friction,
// kernels/contact/obstacle.h obstacle_friction): the lagged potential's
// gradient and Hessian against finite differences, its Hessian PSD, the
// obstacle's motion carried into the slip, the device against the host
// reference, and the physics: a block on an incline slides with
// g (sin t - mu cos t) or sticks, a moving plane drags a block along.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "fem/rest_state.h"
#include "material/element_reference.h"
#include "snh/error.h"
#include "snh/loads.h"
#include "snh/simulation.h"
#include "solver/contact/obstacles.h"
#include "solver/model/elastic_model.h"
#include "support/contact_options.h"
#include "support/device_test_support.h"
#include "support/finite_differences.h"

namespace snh::test {
namespace {

using Vec3 = std::array<double, 3>;

constexpr double kStiffness = 7.0, kThickness = 0.05, kMu = 0.4, kSlip = 0.01;

// One obstacle moving by a rotation and a translation between t = 0 and 1.
struct Lag {
  std::vector<double> start, friction;
};

Lag lag(Obstacle o) {
  o.friction = kMu;
  o.motion = [](double t) {
    RigidTransform r = RigidTransform::rotation_about({0.3, 1, 0.2}, 0.2 * t, {0.1, 0.0, 0.1});
    r.translation = {0.02 * t, -0.01 * t, 0.03 * t};
    return r;
  };
  return {solver::obstacle_records({o}, 0.0), solver::friction_records({o}, ContactOptions{}, 0.0, 1.0)};
}

reference::ObstacleContact<double> friction_at(const Lag& l, const Eigen::Vector3d& x0, const Eigen::Vector3d& x) {
  return reference::obstacle_friction<double>(l.start, l.friction, kStiffness, kThickness, kSlip, {x0[0], x0[1], x0[2]},
                                              {x0[0], x0[1], x0[2]}, {x[0], x[1], x[2]});
}

struct Case {
  const char* name;
  Obstacle obstacle;
  Eigen::Vector3d start;  // inside the contact layer at t = 0
};

std::vector<Case> cases() {
  return {{"plane", Obstacle::plane({0.1, -0.2, 0.3}, {1, 2, 2}), {0.1, -0.2, 0.31}},
          {"sphere", Obstacle::sphere({0.2, 0.1, -0.1}, 0.5), {0.2, 0.1, 0.42}},
          {"cylinder", Obstacle::cylinder({0.0, 0.0, 0.0}, {1, 1, 0}, 0.3), {0.5, 0.3, 0.28}}};
}

// Positions about the carried anchor: slips below and above eps, and a
// normal offset (which the slip ignores).
std::vector<Eigen::Vector3d> probes(const Lag& l, const Eigen::Vector3d& x0) {
  Eigen::Matrix3d r;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 3; ++i) r(i, c) = l.friction[1 + 3 * c + i];
  const Eigen::Vector3d anchor = r * x0 + Eigen::Vector3d(l.friction[10], l.friction[11], l.friction[12]);
  std::vector<Eigen::Vector3d> out;
  for (double scale : {0.3 * kSlip, 0.9 * kSlip, 3.0 * kSlip, 20.0 * kSlip})
    out.push_back(anchor + scale * Eigen::Vector3d(0.6, -0.7, 0.4).normalized());
  return out;
}

TEST(Friction, ForceIsMinusTheEnergyGradientAndTheHessianItsDerivative) {
  for (const Case& c : cases()) {
    const Lag l = lag(c.obstacle);
    for (const Eigen::Vector3d& x : probes(l, c.start)) {
      const auto at = friction_at(l, c.start, x);
      const Eigen::Vector3d force(at.force[0], at.force[1], at.force[2]);
      ASSERT_GT(force.norm(), 0.0) << c.name;
      EXPECT_LT(
          best_gradient_error([&](const Eigen::Vector3d& y) { return friction_at(l, c.start, y).energy; }, x, force),
          1e-7)
          << c.name;
      const Eigen::Matrix3d hessian = Eigen::Map<const Eigen::Matrix3d>(at.hessian.data());
      const Eigen::Matrix3d fd =
          force_derivative([&](const Eigen::Vector3d& y) { return friction_at(l, c.start, y).force; }, x, 1e-7);
      EXPECT_LT((fd - hessian).norm(), 1e-6 * hessian.norm()) << c.name;
      EXPECT_LT((hessian - hessian.transpose()).norm(), 1e-12 * hessian.norm()) << c.name;
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(hessian);
      EXPECT_GE(eigen.eigenvalues().minCoeff(), -1e-12 * hessian.norm()) << c.name;
    }
  }
}

// Below the slip eps the force is a spring of stiffness 2 mu lambda / eps
// (f1(y)/y -> 2/eps); beyond it the kinetic force mu lambda, lambda = k g at
// the start; none without contact at the start.
TEST(Friction, StaticSpringThenKineticForceAndNoneWithoutStartContact) {
  Obstacle floor = Obstacle::plane({0, 0, 0}, {0, 0, 1});
  floor.friction = kMu;
  const std::vector<double> start = solver::obstacle_records({floor}, 0.0),
                            still = solver::friction_records({floor}, ContactOptions{}, 0.0, 1.0);
  const Lag l{start, still};
  const double depth = 0.02, lambda = kStiffness * depth;
  const Eigen::Vector3d x0(0.3, 0.1, kThickness - depth);
  const auto tiny = friction_at(l, x0, x0 + Eigen::Vector3d(1e-9, 0, 0));
  // (x - x0 of 1e-9 at positions of 0.3 keeps about 8 digits)
  EXPECT_NEAR(tiny.force[0], -2.0 * kMu * lambda / kSlip * 1e-9, 1e-6 * 2.0 * kMu * lambda / kSlip * 1e-9);
  EXPECT_NEAR(tiny.energy, kMu * lambda * kSlip / 3, 1e-15);
  const auto far = friction_at(l, x0, x0 + Eigen::Vector3d(0, -5 * kSlip, 0.01));  // normal motion: no slip
  EXPECT_NEAR(far.force[1], kMu * lambda, 1e-14);
  EXPECT_EQ(far.force[2], 0.0);
  EXPECT_NEAR(far.force[0], 0.0, 1e-18);
  const Eigen::Vector3d outside(0.3, 0.1, kThickness + 1e-6);
  const auto none = friction_at(l, outside, outside + Eigen::Vector3d(0.1, 0, -0.04));
  EXPECT_EQ(none.energy, 0.0);
  EXPECT_EQ(none.force[0], 0.0);
}

// The anchor moves with the obstacle: a vertex carried along by a plane
// sliding in its own plane feels no friction, one left behind is pulled
// along the plane's motion; a plane moving along its normal (a lid) slips
// nothing.
TEST(Friction, SlipIsRelativeToTheMovingObstacle) {
  Obstacle belt = Obstacle::plane({0, 0, 0}, {0, 0, 1});
  belt.motion = [](double t) { return RigidTransform::translation_by({0.3 * t, 0.0, 0.0}); };
  ContactOptions contact;
  contact.friction = kMu;
  const Lag l{solver::obstacle_records({belt}, 0.0), solver::friction_records({belt}, contact, 0.0, 1.0)};
  EXPECT_EQ(l.friction[0], kMu);
  const Eigen::Vector3d x0(0.1, 0.2, 0.01);
  const double lambda = kStiffness * (kThickness - 0.01);
  const auto carried = friction_at(l, x0, x0 + Eigen::Vector3d(0.3, 0, 0));
  EXPECT_NEAR(carried.force[0], 0.0, 1e-15);
  const auto behind = friction_at(l, x0, x0);
  EXPECT_NEAR(behind.force[0], kMu * lambda, 1e-14);
  Obstacle lid = Obstacle::plane({0, 0, 1}, {0, 0, -1});
  lid.motion = [](double t) { return RigidTransform::translation_by({0.0, 0.0, -0.4 * t}); };
  lid.friction = kMu;
  const Lag down{solver::obstacle_records({lid}, 0.0), solver::friction_records({lid}, contact, 0.0, 1.0)};
  const Eigen::Vector3d top(0.1, 0.2, 0.99);
  const auto pressed = friction_at(down, top, top + Eigen::Vector3d(0, 0, -0.3));
  EXPECT_NEAR(pressed.force[0], 0.0, 1e-15);
  EXPECT_NEAR(pressed.force[1], 0.0, 1e-15);
  EXPECT_NEAR(pressed.force[2], 0.0, 1e-15);
}

// The device kernels against the host reference: with friction the model's
// energy, residual and product gain exactly the per-vertex friction terms.
TEST(Friction, DeviceTermsMatchTheHostReference) {
  const Mesh mesh = make_tet_box(3, 2, 2, 0.1);
  const fem::RestState rest = fem::compute_rest_state(mesh);
  const MaterialMap map = uniform_material(mesh, StableNeoHookean::from_youngs_modulus(10.0, 0.3));
  std::vector<Obstacle> obstacles = {Obstacle::plane({0, 0, 0.03}, {0, 0, 1}), Obstacle::sphere({0.3, 0.2, 0.25}, 0.1),
                                     Obstacle::cylinder({0, 0.1, 0.1}, {1, 0, 0}, 0.06)};
  obstacles[0].motion = [](double t) { return RigidTransform::translation_by({0.01 * t, 0.0, 0.002 * t}); };
  obstacles[1].friction = 0.0;  // no friction against the sphere
  ContactOptions contact;
  contact.friction = kMu;
  const std::vector<double> records = solver::obstacle_records(obstacles, 1.0),
                            start = solver::obstacle_records(obstacles, 0.0),
                            friction = solver::friction_records(obstacles, contact, 0.0, 1.0);
  solver::ModelTerms terms;
  terms.obstacles = 3;
  solver::ModelTerms with_friction = terms;
  with_friction.friction = true;
  solver::ElasticModel<double> with(device_for(Precision::double_), mesh, rest, map, ProductVariant::cached,
                                    device::MaterialKernel::specialized, with_friction);
  solver::ElasticModel<double> without(device_for(Precision::double_), mesh, rest, map, ProductVariant::cached,
                                       device::MaterialKernel::specialized, terms);
  EXPECT_NE(with.data().config.defines().find("-DSNH_FRICTION=1"), std::string::npos) << with.data().config.defines();
  EXPECT_EQ(without.data().config.defines().find("SNH_FRICTION"), std::string::npos);
  with.contact().set_obstacles(records, kStiffness, kThickness);
  without.contact().set_obstacles(records, kStiffness, kThickness);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  std::vector<double> x0 = mesh.positions.xyz(), x(x0.size()), p(x0.size());
  for (double& e : x0) e += jitter(rng);
  for (size_t i = 0; i < x.size(); ++i) x[i] = x0[i] + 0.5 * jitter(rng);
  for (double& e : p) e = jitter(rng);
  // Anchors near the start positions (kept from earlier steps), per obstacle.
  std::vector<double> anchors(3 * x0.size());
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    for (int o = 0; o < 3; ++o)
      for (int d = 0; d < 3; ++d) anchors[3 * (3 * v + o) + d] = x0[3 * v + d] + 0.2 * jitter(rng);
  with.contact().set_friction(x0, anchors, start, friction, kSlip);
  viennacl::vector<double> xd(x.size()), pd(x.size());
  viennacl::copy(x.begin(), x.end(), xd.begin());
  viennacl::copy(p.begin(), p.end(), pd.begin());
  double energy = 0.0;
  std::vector<double> force(x.size()), product(x.size());
  int active = 0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const auto c = reference::obstacle_friction<double>(
        start, friction, kStiffness, kThickness, kSlip, {x0[3 * v], x0[3 * v + 1], x0[3 * v + 2]},
        std::vector<double>(anchors.begin() + 9 * v, anchors.begin() + 9 * v + 9),
        {x[3 * v], x[3 * v + 1], x[3 * v + 2]});
    energy += c.energy;
    for (int i = 0; i < 3; ++i) {
      force[3 * v + i] = c.force[i];
      for (int j = 0; j < 3; ++j) product[3 * v + i] += c.hessian[3 * j + i] * p[3 * v + j];
    }
    active += c.energy > 0.0;
  }
  ASSERT_GT(active, 5);
  expect_vertex_term_matches(with, without, xd, pd, energy, force, product);
  // The anchors for the next step, on the device and by the reference.
  const std::vector<double> next = with.contact().next_friction_anchors(xd);
  ASSERT_EQ(next.size(), anchors.size());
  int moved = 0, reset = 0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    for (int o = 0; o < 3; ++o) {
      auto slice = [o](const std::vector<double>& t, int n) {
        return std::vector<double>(t.begin() + n * o, t.begin() + n * o + n);
      };
      const size_t k = 3 * (3 * v + o);
      const auto expected = reference::obstacle_friction_anchor<double>(
          slice(start, 8), slice(friction, 16), slice(records, 8), kThickness, kSlip,
          {x0[3 * v], x0[3 * v + 1], x0[3 * v + 2]}, {anchors[k], anchors[k + 1], anchors[k + 2]},
          {x[3 * v], x[3 * v + 1], x[3 * v + 2]});
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(next[k + d], expected[d], 1e-15) << v << " " << o;
      moved += expected[0] != anchors[k] || expected[1] != anchors[k + 1];
      reset += expected[0] == x[3 * v] && expected[1] == x[3 * v + 1] && expected[2] == x[3 * v + 2];
    }
  EXPECT_GT(moved, 0);
  EXPECT_GT(reset, 0);
}

// The anchor kept for the next step (return mapping): out of contact at the
// end it is the vertex itself; in contact it stays where the vertex stuck
// (slip <= eps), is dragged to eps behind where it slid, and is carried by
// the obstacle's motion.
TEST(Friction, AnchorStaysWhereItSticksAndFollowsWhereItSlides) {
  Obstacle belt = Obstacle::plane({0, 0, 0}, {0, 0, 1});
  belt.motion = [](double t) { return RigidTransform::translation_by({0.3 * t, 0.0, 0.0}); };
  belt.friction = kMu;
  const std::vector<double> start = solver::obstacle_records({belt}, 0.0), end = solver::obstacle_records({belt}, 1.0),
                            friction = solver::friction_records({belt}, ContactOptions{}, 0.0, 1.0);
  auto next = [&](const Vec3& x0, const Vec3& anchor, const Vec3& x) {
    return reference::obstacle_friction_anchor<double>(start, friction, end, kThickness, kSlip, x0, anchor, x);
  };
  const Vec3 x0{0.1, 0.2, 0.01}, anchor{0.1 + 0.5 * kSlip, 0.2, 0.01};
  // Carried by the belt (anchor + 0.3 in x), the vertex within eps of it: kept.
  const Vec3 stuck = next(x0, anchor, {0.4 + 0.2 * kSlip, 0.2, 0.012});
  EXPECT_NEAR(stuck[0], 0.4 + 0.5 * kSlip, 1e-15);
  EXPECT_NEAR(stuck[1], 0.2, 1e-15);
  // Left 0.1 behind the carried anchor: dragged to eps behind the vertex.
  const Vec3 slid = next(x0, anchor, {0.3, 0.2, 0.01});
  EXPECT_NEAR(slid[0], 0.3 + kSlip, 1e-15);
  EXPECT_NEAR(slid[1], 0.2, 1e-15);
  // Off the belt's layer at the end: the vertex itself.
  const Vec3 free = next(x0, anchor, {0.3, 0.2, kThickness + 0.01});
  EXPECT_EQ(free[0], 0.3);
  EXPECT_EQ(free[2], kThickness + 0.01);
}

// A stiff block resting on a plane, gravity tilted by theta (an incline),
// under implicit Euler without damping. The bottom starts at its resting
// depth, so the lagged normal force is the weight's share from step one.
struct Incline {
  double mean_velocity_along = 0.0, mean_velocity_normal = 0.0, displacement_along = 0.0;
  double bottom_displacement_along = 0.0;  // mean over the vertices on the plane
  bool converged = false;
  std::string specialization;
};

Incline slide(double mu, double theta, int steps, double plane_speed = 0.0) {
  const double density = 1000.0, g = 9.81, k = 1e4, thickness = 0.01, h = 0.01;
  const Mesh mesh = make_box_lattice(1, 1, 1, 0.1);
  SolveOptions options;
  options.dynamics = DynamicsOptions{};
  options.dynamics->time_step = h;
  options.dynamics->density = density;
  options.body_force = {density * g * std::sin(theta), 0.0, -density * g * std::cos(theta)};
  const double resting = density * g * std::cos(theta) * 1e-3 / (4 * k);
  Obstacle floor = Obstacle::plane({0, 0, -thickness + resting}, {0, 0, 1});
  if (plane_speed != 0.0)
    floor.motion = [=](double t) { return RigidTransform::translation_by({plane_speed * h * steps * t, 0.0, 0.0}); };
  options.obstacles = {floor};
  options.contact.stiffness = k;
  options.contact.thickness = thickness;
  options.contact.friction = mu;
  options.contact.friction_slip = 1e-5;
  options.absolute_tolerance = 1e-9;
  Simulation sim(mesh, StableNeoHookean::from_youngs_modulus(1e7, 0.3), {}, options);
  const SolveResult r = sim.solve(steps);
  Incline out;
  out.converged = r.converged;
  out.specialization = r.kernel_specialization;
  const Points& v = sim.velocities();
  const size_t n = mesh.vertex_count();
  for (size_t i = 0; i < n; ++i) {
    out.mean_velocity_along += v(i, 0) / n;
    out.mean_velocity_normal += v(i, 2) / n;
    out.displacement_along += (r.positions(i, 0) - mesh.positions(i, 0)) / n;
    if (mesh.positions(i, 2) == 0.0) out.bottom_displacement_along += (r.positions(i, 0) - mesh.positions(i, 0)) / 4;
  }
  return out;
}

// Sliding (mu < tan theta): backward Euler gives the exact velocity under a
// constant force, v = n h g (sin theta - mu cos theta).
TEST(Friction, BlockSlidesDownAnInclineWithTheCoulombAcceleration) {
  const double theta = std::acos(-1.0) / 6, g = 9.81, t = 30 * 0.01;
  for (double mu : {0.0, 0.2, 0.4}) {
    const Incline r = slide(mu, theta, 30);
    ASSERT_TRUE(r.converged) << mu;
    // Kernels carry friction only when some coefficient is > 0.
    EXPECT_EQ(r.specialization.find("-DSNH_FRICTION=1") != std::string::npos, mu > 0.0)
        << mu << " " << r.specialization;
    const double expected = g * (std::sin(theta) - mu * std::cos(theta)) * t;
    EXPECT_NEAR(r.mean_velocity_along, expected, 0.01 * expected) << mu;
    EXPECT_NEAR(r.mean_velocity_normal, 0.0, 1e-3 * expected) << mu;
  }
}

// Sticking (mu > tan theta): the anchors stay, so the bottom moves by less
// than the slip eps over all 30 steps (the static spring's stretch; anchors
// reset every step let it creep by about 0.36 eps per step), nothing like
// the 0.14 m it slides without friction. The block as a whole leans by
// about 1.3e-4 on the penalty's compliance (its weight's moment against
// k = 1e4 per vertex), and no further: the same after 30 and 60 steps.
TEST(Friction, BlockSticksOnAnInclineSteeperThanItsFrictionAngleAllows) {
  const double theta = std::acos(-1.0) / 6;
  const Incline r = slide(0.8, theta, 30), longer = slide(0.8, theta, 60);
  ASSERT_TRUE(r.converged);
  ASSERT_TRUE(longer.converged);
  EXPECT_LT(std::abs(r.bottom_displacement_along), 1e-5);
  EXPECT_LT(std::abs(longer.bottom_displacement_along), 1e-5);
  EXPECT_LT(std::abs(r.displacement_along), 3e-4);
  EXPECT_LT(std::abs(longer.displacement_along - r.displacement_along), 1e-5);
  EXPECT_LT(std::abs(r.mean_velocity_along), 1e-5 / 0.01);
}

// A plane moving at 0.5 m/s in its own plane drags a block lying on it (flat,
// mu = 0.5): friction accelerates it at mu g until it moves with the plane.
TEST(Friction, MovingPlaneDragsABlockToItsSpeed) {
  const Incline r = slide(0.5, 0.0, 30, 0.5);
  ASSERT_TRUE(r.converged);
  EXPECT_NEAR(r.mean_velocity_along, 0.5, 0.005);
}

TEST(Friction, OptionsAreChecked) {
  auto message = [](const Obstacle& o, const ContactOptions& contact) { return contact_options_error({o}, contact); };
  ContactOptions contact;
  contact.stiffness = 1.0;
  Obstacle o = Obstacle::plane({0, 0, 0}, {0, 0, 1});
  o.friction = -0.1;
  EXPECT_NE(message(o, contact).find("obstacle 0 (plane): friction must be finite and >= 0"), std::string::npos);
  o.friction = std::nan("");
  EXPECT_NE(message(o, contact).find("obstacle 0 (plane): friction"), std::string::npos);
  o.friction.reset();
  contact.friction = -1.0;
  EXPECT_NE(message(o, contact).find("contact: friction must be finite and >= 0"), std::string::npos);
  contact.friction = 0.5;
  contact.friction_slip = -1.0;
  EXPECT_NE(message(o, contact).find("contact: friction_slip"), std::string::npos);
  contact.friction_slip = 0.0;  // set: > 0
  EXPECT_NE(message(o, contact).find("contact: friction_slip"), std::string::npos);
  contact.friction_slip.reset();  // unset: 1% of the vertex spacing
  EXPECT_EQ(message(o, contact), "");
}

}  // namespace
}  // namespace snh::test
