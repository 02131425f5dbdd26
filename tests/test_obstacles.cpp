// Kinematic obstacles (snh::Obstacle, kernels/contact/obstacle.h): the
// penalty's gradient and Gauss-Newton Hessian against finite differences and
// the dropped curvature term, PSD, the device against the host reference, a
// block resting on a plane, a moving sphere pushing into a block, keyframed
// placement, and the options' errors.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <memory>
#include <random>

#include "device/opencl_context.h"
#include "device/viennacl_binding.h"
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
#include "support/plane_selection.h"

namespace snh::test {
namespace {

using Vec3 = std::array<double, 3>;

constexpr double kStiffness = 7.0, kThickness = 0.05;

reference::ObstacleContact<double> contact_at(const std::vector<double>& records, const Eigen::Vector3d& x) {
  return reference::obstacle_contact<double>(records, kStiffness, kThickness, {x[0], x[1], x[2]});
}

// Per obstacle kind, points inside the contact layer or the obstacle, where
// the penalty is active and smooth.
struct Case {
  const char* name;
  Obstacle obstacle;
  std::vector<Eigen::Vector3d> points;
};

std::vector<Case> cases() {
  return {
      {"plane", Obstacle::plane({0.1, -0.2, 0.3}, {1, 2, 2}), {{0.1, -0.2, 0.31}, {0.2, -0.3, 0.2}, {0.0, 0.0, 0.2}}},
      {"sphere", Obstacle::sphere({0.2, 0.1, -0.1}, 0.5), {{0.2, 0.1, 0.42}, {0.5, 0.3, 0.1}, {-0.1, 0.0, -0.3}}},
      {"cylinder",
       Obstacle::cylinder({0.0, 0.0, 0.0}, {1, 1, 0}, 0.3),
       {{0.5, 0.3, 0.28}, {-1.0, -0.8, 0.1}, {0.2, 0.4, -0.25}}},
  };
}

// The gradient against central differences of the energy, the best relative
// error over steps 1e-4 ... 1e-9 (as the material derivative tests do).
// The factories fill what each shape uses and leave motion and friction
// unset until asked.
TEST(Obstacles, FactoriesFillTheirShape) {
  const Obstacle p = Obstacle::plane({1, 2, 3}, {0, 1, 0});
  EXPECT_EQ(p.type, ObstacleType::plane);
  EXPECT_EQ(p.point, (Vec3{1, 2, 3}));
  EXPECT_EQ(p.direction, (Vec3{0, 1, 0}));
  EXPECT_FALSE(p.motion);
  EXPECT_FALSE(p.friction.has_value());
  const Obstacle s = Obstacle::sphere({0, 0, 1}, 0.5);
  EXPECT_EQ(s.type, ObstacleType::sphere);
  EXPECT_EQ(s.radius, 0.5);
  const Obstacle c = Obstacle::cylinder({1, 0, 0}, {0, 0, 1}, 0.25).with_friction(0.3).with_motion([](double t) {
    return RigidTransform::translation_by({t, 0, 0});
  });
  EXPECT_EQ(c.type, ObstacleType::cylinder);
  EXPECT_EQ(c.direction, (Vec3{0, 0, 1}));
  EXPECT_EQ(c.radius, 0.25);
  EXPECT_EQ(c.friction, 0.3);
  ASSERT_TRUE(c.motion);
  EXPECT_EQ(c.motion(0.5).translation[0], 0.5);
}

TEST(Obstacles, ForceIsMinusTheEnergyGradient) {
  for (const Case& c : cases()) {
    const std::vector<double> records = solver::obstacle_records({c.obstacle}, 0.0);
    for (const Eigen::Vector3d& x : c.points) {
      const auto at = contact_at(records, x);
      ASSERT_GT(at.depth, 0.0) << c.name;
      const Eigen::Vector3d force(at.force[0], at.force[1], at.force[2]);
      EXPECT_LT(best_gradient_error([&](const Eigen::Vector3d& y) { return contact_at(records, y).energy; }, x, force),
                1e-7)
          << c.name;
    }
  }
}

// The Gauss-Newton Hessian is k grad phi grad phi^T; the true Hessian (finite
// differences of the force) is that minus k g hess(phi), with hess(phi) =
// (I - n n^T) / |r| for the sphere and (I - a a^T - n n^T) / |r| for the
// cylinder (0 for the plane): the dropped term, negative semidefinite, so the
// kept Hessian is PSD and bounds the true one from above.
TEST(Obstacles, GaussNewtonHessianIsTheTrueHessianWithoutTheCurvatureTerm) {
  for (const Case& c : cases()) {
    const std::vector<double> records = solver::obstacle_records({c.obstacle}, 0.0);
    for (const Eigen::Vector3d& x : c.points) {
      const auto at = contact_at(records, x);
      const Eigen::Matrix3d kept = Eigen::Map<const Eigen::Matrix3d>(at.hessian.data());
      const Eigen::Matrix3d fd =
          force_derivative([&](const Eigen::Vector3d& y) { return contact_at(records, y).force; }, x, 1e-6);
      const Eigen::Vector3d p(records[1], records[2], records[3]), axis(records[4], records[5], records[6]);
      Eigen::Vector3d r = x - p;
      Eigen::Matrix3d curvature = Eigen::Matrix3d::Zero();
      if (c.obstacle.type == ObstacleType::cylinder) r -= r.dot(axis) * axis;
      const Eigen::Vector3d n = c.obstacle.type == ObstacleType::plane ? axis : Eigen::Vector3d(r.normalized());
      if (c.obstacle.type != ObstacleType::plane) {
        curvature = (Eigen::Matrix3d::Identity() - n * n.transpose()) / r.norm();
        if (c.obstacle.type == ObstacleType::cylinder) curvature -= axis * axis.transpose() / r.norm();
      }
      EXPECT_LT((kept - kStiffness * n * n.transpose()).norm(), 1e-12) << c.name;
      EXPECT_LT((fd - (kept - kStiffness * at.depth * curvature)).norm(), 1e-6 * kStiffness) << c.name;
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(kept);
      EXPECT_GE(eigen.eigenvalues().minCoeff(), -1e-12 * kStiffness) << c.name;
      EXPECT_NEAR(eigen.eigenvalues().maxCoeff(), kStiffness, 1e-12) << c.name;
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> dropped(-kStiffness * at.depth * curvature);
      EXPECT_LE(dropped.eigenvalues().maxCoeff(), 1e-12) << c.name;
    }
  }
}

TEST(Obstacles, PenaltyIsC1AtTheLayerAndZeroOutside) {
  const std::vector<double> records = solver::obstacle_records({Obstacle::plane({0, 0, 0}, {0, 0, 1})}, 0.0);
  const auto outside = contact_at(records, {0.3, 0.2, kThickness + 1e-9});
  EXPECT_EQ(outside.energy, 0.0);
  EXPECT_EQ(outside.force[2], 0.0);
  EXPECT_EQ(outside.depth, 0.0);
  const auto inside = contact_at(records, {0.3, 0.2, kThickness - 1e-9});
  EXPECT_NEAR(inside.force[2], kStiffness * 1e-9, 1e-15);  // continuous: force -> 0 at the layer
  EXPECT_NEAR(inside.depth, 1e-9, 1e-15);
}

TEST(Obstacles, RecordsFollowKeyframedRigidMotion) {
  Obstacle c = Obstacle::cylinder({1, 0, 0}, {0, 0, 2}, 0.25);
  c.motion = [](double t) {
    RigidTransform r = RigidTransform::rotation_about({0, 1, 0}, t * std::acos(-1.0) / 2, {0, 0, 0});
    r.translation = {0, t, 0};
    return r;
  };
  const std::vector<double> at0 = solver::obstacle_records({c}, 0.0), at1 = solver::obstacle_records({c}, 1.0);
  EXPECT_NEAR(at0[1], 1.0, 1e-15);
  EXPECT_NEAR(at0[6], 1.0, 1e-15);  // axis normalized
  // A quarter turn about y takes (1, 0, 0) to (0, 0, -1) and the axis z to x.
  EXPECT_NEAR(at1[1], 0.0, 1e-12);
  EXPECT_NEAR(at1[2], 1.0, 1e-12);
  EXPECT_NEAR(at1[3], -1.0, 1e-12);
  EXPECT_NEAR(at1[4], 1.0, 1e-12);
  EXPECT_EQ(at1[7], 0.25);
}

// The device kernels against the host reference: with obstacles the model's
// energy, residual and product gain exactly the per-vertex contact terms.
TEST(Obstacles, DeviceContactTermsMatchTheHostReference) {
  const Mesh mesh = make_tet_box(3, 2, 2, 0.1);
  const fem::RestState rest = fem::compute_rest_state(mesh);
  const MaterialMap map = uniform_material(mesh, StableNeoHookean::from_youngs_modulus(10.0, 0.3));
  const std::vector<Obstacle> obstacles = {Obstacle::plane({0, 0, 0.03}, {0, 0, 1}),
                                           Obstacle::sphere({0.3, 0.2, 0.25}, 0.1),
                                           Obstacle::cylinder({0, 0.1, 0.1}, {1, 0, 0}, 0.06)};
  const std::vector<double> records = solver::obstacle_records(obstacles, 0.0);
  solver::ModelTerms terms;
  terms.obstacles = 3;
  solver::ElasticModel<double> with(device_for(Precision::double_), mesh, rest, map, ProductVariant::cached,
                                    device::MaterialKernel::specialized, terms);
  solver::ElasticModel<double> without(device_for(Precision::double_), mesh, rest, map, ProductVariant::cached);
  EXPECT_NE(with.data().config.defines().find("-DSNH_OBSTACLES=3"), std::string::npos) << with.data().config.defines();
  EXPECT_EQ(without.data().config.defines().find("SNH_OBSTACLES"), std::string::npos);
  with.contact().set_obstacles(records, kStiffness, kThickness);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  std::vector<double> x = mesh.positions.xyz(), p(x.size());
  for (double& e : x) e += jitter(rng);
  for (double& e : p) e = jitter(rng);
  viennacl::vector<double> xd(x.size()), pd(x.size());
  viennacl::copy(x.begin(), x.end(), xd.begin());
  viennacl::copy(p.begin(), p.end(), pd.begin());
  double energy = 0.0;
  std::vector<double> force(x.size()), product(x.size());
  int active = 0;
  double deepest = 0.0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const auto c =
        reference::obstacle_contact<double>(records, kStiffness, kThickness, {x[3 * v], x[3 * v + 1], x[3 * v + 2]});
    energy += c.energy;
    for (int i = 0; i < 3; ++i) {
      force[3 * v + i] = c.force[i];
      for (int j = 0; j < 3; ++j) product[3 * v + i] += c.hessian[3 * j + i] * p[3 * v + j];
    }
    active += c.depth > 0.0;
    deepest = std::max(deepest, c.depth);
  }
  ASSERT_GT(active, 5);
  expect_vertex_term_matches(with, without, xd, pd, energy, force, product);
  const solver::ContactState state = with.contact().contact_state(xd);
  EXPECT_EQ(state.contacts, active);
  EXPECT_NEAR(state.max_penetration, deepest, 1e-15);
}

// A stiff block (E h >> k) resting on a plane under gravity, held laterally:
// in equilibrium the contact forces carry its weight W, so the 9 bottom
// vertices sink on average W / (9 k) into the layer; the block's compliance
// spreads them by far less than the stated 1%.
TEST(Obstacles, BlockRestingOnAPlanePenetratesWeightOverStiffness) {
  const double density = 1000.0, g = 9.81, k = 1e3, thickness = 0.02;
  const Mesh mesh = make_box_lattice(2, 2, 2, 0.1);
  const ConstraintSet lateral{"lateral", on_plane(mesh, 2, 0.2), {}, {}, {true, true, false}};
  SolveOptions options;
  options.body_force = {0.0, 0.0, -density * g};
  // The block starts 1 mm into the layer, so the contact holds it from the
  // first Newton iteration (its vertical motion is otherwise free).
  const double plane_z = -thickness + 0.001;
  options.obstacles = {Obstacle::plane({0, 0, plane_z}, {0, 0, 1})};
  options.contact.stiffness = k;
  options.contact.thickness = thickness;
  options.absolute_tolerance = 1e-9;
  Simulation sim(mesh, StableNeoHookean::from_youngs_modulus(1e7, 0.3), {lateral}, options);
  const SolveResult r = sim.solve();
  ASSERT_TRUE(r.converged);
  EXPECT_NE(r.kernel_specialization.find("-DSNH_OBSTACLES=1"), std::string::npos);
  const double weight = density * g * 0.008, expected = weight / (9 * k);
  EXPECT_EQ(r.steps.back().contacts, 9);
  EXPECT_NEAR(r.steps.back().max_penetration, expected, 0.01 * expected);
  double mean = 0.0;
  for (int32_t v : on_plane(mesh, 2, 0.0)) mean += thickness - (r.positions(v, 2) - plane_z);
  EXPECT_NEAR(mean / 9, expected, 1e-9);
  EXPECT_LT(r.steps.back().max_penetration, thickness);  // no vertex inside the plane itself
}

// A sphere keyframed down into a block held at its bottom: no contact while
// it approaches, then it pushes the top in, the top following its surface
// (no vertex deeper than a small fraction of the indentation).
TEST(Obstacles, MovingSpherePushesIntoABlock) {
  const Mesh mesh = make_box_lattice(4, 4, 2, 0.1);
  const ConstraintSet held{"held", on_plane(mesh, 2, 0.0), {}, {}};
  Obstacle ball = Obstacle::sphere({0.2, 0.2, 0.4}, 0.15);  // 0.05 above the top
  ball.motion = [](double t) { return RigidTransform::translation_by({0.0, 0.0, -0.1 * t}); };
  SolveOptions options;
  options.obstacles = {ball};
  options.contact.stiffness = 1e5;
  options.contact.thickness = 0.005;
  options.load_steps = 4;
  Simulation sim(mesh, StableNeoHookean::from_youngs_modulus(1e4, 0.3), {held}, options);
  const SolveResult r = sim.solve();
  ASSERT_TRUE(r.converged);
  EXPECT_EQ(r.steps[0].contacts, 0);  // 0.025 away
  EXPECT_GT(r.steps[3].contacts, 0);
  EXPECT_GE(r.steps[3].contacts, r.steps[2].contacts);
  int top_center = -1;
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    if (std::abs(mesh.positions(v, 0) - 0.2) < 1e-9 && std::abs(mesh.positions(v, 1) - 0.2) < 1e-9 &&
        std::abs(mesh.positions(v, 2) - 0.2) < 1e-9)
      top_center = static_cast<int>(v);
  ASSERT_GE(top_center, 0);
  // The sphere's bottom ends at z = 0.15, 0.05 into the rest top: the top
  // centre follows to within the layer and the penalty's give.
  const double z = r.positions(top_center, 2);
  EXPECT_LT(z, 0.15 + 0.005 + 0.005);
  EXPECT_GT(z, 0.15 - 0.005);
  EXPECT_LT(r.steps[3].max_penetration, 0.005);  // no vertex inside the sphere itself
}

// Inertia and obstacles together: a block dropped from 1 cm onto a plane
// (implicit Euler, mass damping) bounces, settles and rests at the same
// W / (n k) as the quasistatic solve, its velocity gone.
TEST(Obstacles, BlockDroppedOnAPlaneComesToRest) {
  const double density = 1000.0, g = 9.81, k = 1e3, thickness = 0.01;
  const Mesh mesh = make_box_lattice(1, 1, 1, 0.1, {0.0, 0.0, 0.01});
  SolveOptions options;
  options.dynamics = DynamicsOptions{};
  options.dynamics->time_step = 0.01;
  options.dynamics->density = density;
  options.dynamics->damping.mass = 20.0;
  options.body_force = {0.0, 0.0, -density * g};
  options.obstacles = {Obstacle::plane({0, 0, -thickness}, {0, 0, 1})};
  options.contact.stiffness = k;
  options.contact.thickness = thickness;
  options.absolute_tolerance = 1e-9;
  // E = 1e7 at a tight tolerance: the energy (0.5 J) is a small sum of
  // elastic terms of mu V ~ 4e3 J whose rounding the driver must allow for
  // (DeviceProblem::energy_magnitude), else Newton stagnates.
  Simulation sim(mesh, StableNeoHookean::from_youngs_modulus(1e7, 0.3), {}, options);
  const SolveResult r = sim.solve(80);
  for (const StepResult& s : r.steps) EXPECT_TRUE(s.converged) << s.step << " " << s.status << " " << s.residual_norm;
  ASSERT_TRUE(r.converged);
  const std::string& spec = r.kernel_specialization;
  EXPECT_NE(spec.find("-DSNH_INERTIA=1"), std::string::npos) << spec;
  EXPECT_NE(spec.find("-DSNH_OBSTACLES=1"), std::string::npos) << spec;
  EXPECT_EQ(r.steps.front().contacts, 0);  // still falling
  EXPECT_EQ(r.steps.back().contacts, 4);
  const double expected = density * g * 1e-3 / (4 * k);
  EXPECT_NEAR(r.steps.back().max_penetration, expected, 0.01 * expected);
  double speed = 0.0;
  for (double v : sim.velocities().xyz()) speed = std::max(speed, std::abs(v));
  EXPECT_LT(speed, 1e-3);
}

TEST(Obstacles, OptionsAreChecked) {
  auto message = [](std::vector<Obstacle> obstacles, std::array<double, 2> stiffness_thickness) {
    ContactOptions contact;
    contact.stiffness = stiffness_thickness[0];
    contact.thickness = stiffness_thickness[1];
    return contact_options_error(std::move(obstacles), contact);
  };
  EXPECT_NE(message({Obstacle::plane({0, 0, 0}, {0, 0, 1})}, {0.0, 0.0}).find("stiffness"), std::string::npos);
  EXPECT_NE(message({Obstacle::plane({0, 0, 0}, {0, 0, 1})}, {1.0, -1.0}).find("thickness"), std::string::npos);
  EXPECT_NE(message({Obstacle::plane({0, 0, 0}, {0, 0, 0})}, {1.0, 0.0}).find("obstacle 0 (plane): zero normal"),
            std::string::npos);
  EXPECT_NE(message({Obstacle::plane({0, 0, 0}, {0, 0, 1}), Obstacle::sphere({0, 0, 0}, 0.0)}, {1.0, 0.0})
                .find("obstacle 1 (sphere)"),
            std::string::npos);
  EXPECT_NE(message({Obstacle::cylinder({0, 0, 0}, {0, 0, 0}, 1.0)}, {1.0, 0.0}).find("zero axis"), std::string::npos);
  EXPECT_NE(message({Obstacle::sphere({NAN, 0, 0}, 1.0)}, {1.0, 0.0}).find("non-finite"), std::string::npos);
  EXPECT_EQ(message({Obstacle::sphere({0, 0, 5}, 1.0)}, {1.0, 0.0}), "");
}

}  // namespace
}  // namespace snh::test
