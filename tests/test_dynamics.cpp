// Implicit Euler dynamics (snh::DynamicsOptions): lumped mass, free fall to
// first order in the time step, conservation of linear momentum, the period
// of a vibrating bar, constrained vertices following their targets, the
// product variants agreeing with inertia, and the options' errors.
#include <gtest/gtest.h>

#include <cmath>

#include "snh/error.h"
#include "snh/loads.h"
#include "snh/simulation.h"
#include "support/plane_selection.h"

namespace snh::test {
namespace {

std::array<double, 3> momentum(const std::vector<double>& mass, const Points& velocity) {
  std::array<double, 3> p{0, 0, 0};
  for (size_t v = 0; v < mass.size(); ++v)
    for (int d = 0; d < 3; ++d) p[d] += mass[v] * velocity(v, d);
  return p;
}

TEST(Dynamics, LumpedMassIsTheBodyForceIntegral) {
  for (const Mesh& mesh : {make_box_lattice(3, 2, 2, 0.1), make_tet_box(3, 2, 2, 0.1)}) {
    const std::vector<double> m = lumped_mass(mesh, 1000.0);
    const Points f = lump_body_force(mesh, {0.0, 0.0, -9.81 * 1000.0});
    double total = 0.0;
    for (size_t v = 0; v < m.size(); ++v) {
      total += m[v];
      EXPECT_GT(m[v], 0.0);
      EXPECT_NEAR(f(v, 2), -9.81 * m[v], 1e-12 * m[v]);
    }
    EXPECT_NEAR(total, 1000.0 * 0.3 * 0.2 * 0.2, 1e-12);
  }
  EXPECT_THROW(lumped_mass(make_box_lattice(1, 1, 1, 1.0), 0.0), Error);
}

// Backward Euler from rest under gravity g: v_n = n h g, x_n = x_0 +
// g h^2 n (n + 1) / 2 = x_0 + g t^2 / 2 + g h t / 2, an error g h t / 2 that
// halves with h (the body translates rigidly: no elastic force).
TEST(Dynamics, FreeFallMatchesTheAnalyticMotionToFirstOrder) {
  const double g = -9.81, density = 1000.0, duration = 0.2;
  for (const Mesh& mesh : {make_box_lattice(2, 2, 2, 0.05), make_tet_box(2, 2, 2, 0.05)}) {
    std::vector<double> errors;
    for (int steps : {10, 20}) {
      SolveOptions options;
      options.dynamics = DynamicsOptions{};
      options.dynamics->time_step = duration / steps;
      options.dynamics->density = density;
      options.body_force = {0.0, 0.0, density * g};
      options.load_steps = steps;
      options.absolute_tolerance = 1e-10;  // Newton's error, not the time step's, would show otherwise
      Simulation sim(mesh, StableNeoHookean::from_youngs_modulus(1e5, 0.3), {}, options);
      const SolveResult r = sim.solve();
      ASSERT_TRUE(r.converged);
      EXPECT_NEAR(sim.time(), duration, 1e-12);
      EXPECT_NE(r.kernel_specialization.find("-DSNH_INERTIA=1"), std::string::npos) << r.kernel_specialization;
      double worst = 0.0;
      for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        const double analytic = mesh.positions(v, 2) + 0.5 * g * duration * duration;
        worst = std::max(worst, std::abs(r.positions(v, 2) - analytic));
        EXPECT_NEAR(r.positions(v, 0), mesh.positions(v, 0), 1e-9);
        EXPECT_NEAR(sim.velocities()(v, 2), g * duration, 1e-6);
      }
      const double h = duration / steps;
      EXPECT_NEAR(worst, std::abs(g) * h * duration / 2.0, 1e-6) << steps;
      errors.push_back(worst);
    }
    EXPECT_NEAR(errors[0] / errors[1], 2.0, 1e-3);
  }
}

// Substeps are time steps of time_step / substeps: 10 steps of 0.02 s with 2
// substeps are 20 steps of 0.01 s. In float too (the float kernels with
// inertia), to float's resolution.
TEST(Dynamics, SubstepsAreShorterTimeStepsInBothPrecisions) {
  const Mesh mesh = make_tet_box(2, 1, 1, 0.1);
  const ConstraintSet held{"held", on_plane(mesh, 0, 0.0), {}, {}};
  for (Precision precision : {Precision::double_, Precision::single}) {
    std::vector<Points> results;
    for (int substeps : {1, 2}) {
      SolveOptions options;
      options.precision = precision;
      options.dynamics = DynamicsOptions{};
      options.dynamics->time_step = 0.01 * substeps;
      options.dynamics->substeps = substeps;
      options.dynamics->density = 1000.0;
      options.body_force = {0.0, 0.0, -9810.0};
      if (precision == Precision::double_) options.absolute_tolerance = 1e-10;  // float: its default stop
      Simulation sim(mesh, StableNeoHookean::from_youngs_modulus(1e5, 0.4), {held}, options);
      const SolveResult r = sim.solve(20 / substeps);
      ASSERT_TRUE(r.converged) << to_string(precision);
      EXPECT_NEAR(sim.time(), 0.2, 1e-12);
      results.push_back(r.positions);
    }
    double sag = 0.0, difference = 0.0;
    for (size_t i = 0; i < results[0].size(); ++i)
      for (int k = 0; k < 3; ++k) {
        sag = std::max(sag, mesh.positions(i, k) - results[0](i, k));
        difference = std::max(difference, std::abs(results[1](i, k) - results[0](i, k)));
      }
    EXPECT_GT(sag, 0.005) << to_string(precision);
    EXPECT_LT(difference, precision == Precision::double_ ? 1e-9 : 1e-5) << to_string(precision);
  }
}

// No external force, no constraint: the elastic forces sum to zero
// (translation invariance), so backward Euler keeps sum m v to the solver's
// tolerance, here with Rayleigh stiffness damping (an internal force) too.
TEST(Dynamics, LinearMomentumIsConservedWithoutExternalForce) {
  for (const Mesh& mesh : {make_tet_box(3, 2, 2, 0.1), make_box_lattice(3, 2, 2, 0.1)}) {
    const double density = 100.0;
    Points v0(mesh.vertex_count());
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
      const double* p = mesh.positions.data() + 3 * v;
      v0(v, 0) = 0.3 + 2.0 * p[1] * p[2];
      v0(v, 1) = -1.5 * p[0] * p[0];
      v0(v, 2) = 0.7 * p[0] - 0.2;
    }
    SolveOptions options;
    options.dynamics = DynamicsOptions{};
    options.dynamics->time_step = 0.01;
    options.dynamics->density = density;
    options.dynamics->damping.stiffness = 0.002;
    options.initial_velocities = v0;
    // Tight: the energy (~1e-3 J) is a small sum of elastic terms of ~40 J,
    // which Newton's rounding allowance (energy_magnitude) must see through.
    options.absolute_tolerance = 1e-10;
    options.load_steps = 10;
    Simulation sim(mesh, StableNeoHookean::from_youngs_modulus(1e4, 0.4), {}, options);
    const std::vector<double> m = lumped_mass(mesh, density);
    const auto p0 = momentum(m, v0);
    const SolveResult r = sim.solve();
    for (const StepResult& s : r.steps) EXPECT_TRUE(s.converged) << s.step << " " << s.status << " " << s.residual_norm;
    ASSERT_TRUE(r.converged);
    const auto p1 = momentum(m, sim.velocities());
    // Each step changes sum m v by h times the sum of the residual entries,
    // at most h sqrt(n) |r| per component.
    const double bound = 10 * 0.01 * std::sqrt(double(mesh.vertex_count())) * 1e-10;
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(p1[d], p0[d], bound) << d;
    // The body did deform: the velocity field is not the initial one.
    double change = 0.0;
    for (size_t i = 0; i < v0.size(); ++i)
      for (int k = 0; k < 3; ++k) change = std::max(change, std::abs(sim.velocities()(i, k) - v0(i, k)));
    EXPECT_GT(change, 0.05);
  }
}

// A bar of length L = 1 (10 hex8 of 0.1, nu = 0, E = 1, rho = 1, so
// c = sqrt(E / rho) = 1) whose end x = 0 is held axially vibrates in its
// first axial mode with period T = 4 L / c = 4. Started with the velocity
// v_x = v0 sin(pi X / 2L), v0 = 1e-3 (strain ~ 1.6e-3, linear regime), and
// stepped with dt = T / 100. Expected deviations, both lengthening the
// period: backward Euler's phase error (omega dt)^2 / 3 = 0.13% and the
// lumped-mass lattice's (2 c / dx) sin(pi dx / 4 L) = 0.9990 omega, 0.10%:
// 0.23% together. Against 4 L / c the tolerance is 1%; against the
// prediction that combines both, exactly
//   T = 2 pi dt / atan(omega_h dt),  omega_h = (2 c / dx) sin(pi dx / 4 L)
// (backward Euler turns each step's phase omega dt into atan(omega dt)),
// 0.05%. The zero crossings (spaced by half the damped period however
// strongly backward Euler damps the amplitude) are located by linear
// interpolation between steps.
TEST(Dynamics, BarOscillatesAtTheLinearElasticPeriod) {
  const Mesh mesh = make_box_lattice(10, 1, 1, 0.1);
  const ConstraintSet held{"held", on_plane(mesh, 0, 0.0), {}, {}, {true, false, false}};
  const std::vector<int32_t> tip = on_plane(mesh, 0, 1.0);
  const double period = 4.0, dt = period / 100.0, pi = std::acos(-1.0);
  SolveOptions options;
  options.dynamics = DynamicsOptions{};
  options.dynamics->time_step = dt;
  options.dynamics->density = 1.0;
  options.initial_velocities = Points(mesh.vertex_count());
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    options.initial_velocities(v, 0) = 1e-3 * std::sin(pi * mesh.positions(v, 0) / 2.0);
  options.strain_tolerance = 1e-9;
  Simulation sim(mesh, StableNeoHookean::from_youngs_modulus(1.0, 0.0), {held}, options);
  std::vector<double> times{0.0}, tip_u{0.0};
  const SolveResult r = sim.solve(170, {}, [&](int, const Points& x) {
    double u = 0.0;
    for (int32_t v : tip) u += x(v, 0) - mesh.positions(v, 0);
    times.push_back(sim.time());
    tip_u.push_back(u / tip.size());
  });
  ASSERT_TRUE(r.converged);
  std::vector<double> crossings;
  for (size_t k = 2; k < tip_u.size(); ++k)
    if ((tip_u[k - 1] > 0.0) != (tip_u[k] > 0.0))
      crossings.push_back(times[k - 1] + dt * tip_u[k - 1] / (tip_u[k - 1] - tip_u[k]));
  ASSERT_GE(crossings.size(), 3u);
  const double measured = crossings[2] - crossings[0];
  RecordProperty("period", std::to_string(measured));
  EXPECT_NEAR(measured / period, 1.0, 0.01) << measured;
  EXPECT_GT(measured, period);  // both predicted deviations lengthen it
  const double omega_h = 2.0 / 0.1 * std::sin(pi * 0.1 / 4.0);
  const double predicted = 2.0 * pi * dt / std::atan(omega_h * dt);
  EXPECT_NEAR(measured, predicted, 5e-4 * predicted);
  // Backward Euler damps: each half cycle's extreme is smaller.
  double first = 0.0, second = 0.0;
  for (size_t k = 0; k < tip_u.size(); ++k) {
    if (times[k] < crossings[0]) first = std::max(first, std::abs(tip_u[k]));
    if (times[k] > crossings[0] && times[k] < crossings[1]) second = std::max(second, std::abs(tip_u[k]));
  }
  RecordProperty("half_cycle_amplitude_ratio", std::to_string(second / first));
  EXPECT_LT(second, first);
  EXPECT_GT(second, 0.5 * first);
}

// Constrained vertices reach their targets at each time step; the quasistatic
// rigid-mode check does not apply (inertia holds every rigid motion).
TEST(Dynamics, ConstrainedVerticesFollowTargetsAndFreeBodiesAreAccepted) {
  const Mesh mesh = make_tet_box(4, 1, 1, 0.1);
  const ConstraintSet moved{"moved",
                            on_plane(mesh, 0, 0.0),
                            [](double t) {
                              return RigidTransform::translation_by({0.0, 0.0, 0.05 * t});
                            },
                            {}};
  SolveOptions options;
  options.dynamics = DynamicsOptions{};
  options.dynamics->time_step = 0.01;
  options.dynamics->density = 1000.0;
  options.dynamics->substeps = 2;
  options.body_force = {0.0, -9810.0, 0.0};
  // Quasistatic with a net force on a body held by nothing: no equilibrium.
  SolveOptions quasistatic = options;
  quasistatic.dynamics.reset();
  EXPECT_THROW(Simulation(mesh, StableNeoHookean::from_youngs_modulus(1e5, 0.3), {}, quasistatic), Error);
  Simulation free_body(mesh, StableNeoHookean::from_youngs_modulus(1e5, 0.3), {}, options);
  const SolveResult free_result = free_body.solve(2);
  EXPECT_TRUE(free_result.converged);
  EXPECT_TRUE(free_result.warnings.empty()) << free_result.warnings.front();

  Simulation sim(mesh, StableNeoHookean::from_youngs_modulus(1e5, 0.3), {moved}, options);
  std::vector<double> zs;
  const SolveResult r = sim.solve(4, {}, [&](int, const Points& x) { zs.push_back(x(moved.vertices[0], 2)); });
  ASSERT_TRUE(r.converged);
  ASSERT_EQ(zs.size(), 4u);
  for (int s = 0; s < 4; ++s) EXPECT_NEAR(zs[s], 0.05 * (s + 1) / 4.0, 1e-12) << s;
  EXPECT_EQ(r.steps.size(), 4u);
  EXPECT_NEAR(r.steps.back().time, 0.04, 1e-12);
}

// The cached, element-matrix and assembled products (the last through the
// masked assembled path) give the same trajectory with inertia and damping.
TEST(Dynamics, ProductVariantsAgreeWithInertia) {
  const Mesh mesh = make_tet_box(3, 2, 2, 0.1);
  const ConstraintSet held{"held", on_plane(mesh, 0, 0.0), {}, {}};
  std::vector<Points> results;
  for (ProductVariant variant : {ProductVariant::cached, ProductVariant::element_matrices, ProductVariant::assembled}) {
    SolveOptions options;
    options.dynamics = DynamicsOptions{};
    options.dynamics->time_step = 0.005;
    options.dynamics->density = 1000.0;
    options.dynamics->damping.mass = 2.0;
    options.dynamics->damping.stiffness = 0.001;
    options.body_force = {0.0, 0.0, -9810.0};
    options.product = variant;
    options.absolute_tolerance = 1e-10;
    Simulation sim(mesh, StableNeoHookean::from_youngs_modulus(1e5, 0.45), {held}, options);
    const SolveResult r = sim.solve(5);
    ASSERT_TRUE(r.converged) << to_string(variant);
    results.push_back(r.positions);
  }
  double sag = 0.0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) sag = std::max(sag, mesh.positions(v, 2) - results[0](v, 2));
  EXPECT_GT(sag, 1e-3);
  for (size_t k = 1; k < results.size(); ++k)
    for (size_t i = 0; i < results[0].xyz().size(); ++i)
      ASSERT_NEAR(results[k].xyz()[i], results[0].xyz()[i], 1e-9) << k << " " << i;
}

TEST(Dynamics, OptionsAreChecked) {
  const Mesh mesh = make_box_lattice(1, 1, 1, 1.0);
  const Material material = StableNeoHookean::from_youngs_modulus(1.0, 0.3);
  auto with = [](auto change) {
    SolveOptions o;
    o.dynamics = DynamicsOptions{};
    o.dynamics->time_step = 0.1;
    o.dynamics->density = 1.0;
    change(o);
    return o;
  };
  auto message = [&](const SolveOptions& o) {
    try {
      Simulation(mesh, material, {}, o);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message(with([](SolveOptions& o) { o.dynamics->time_step = 0.0; })).find("time_step"), std::string::npos);
  EXPECT_NE(message(with([](SolveOptions& o) { o.dynamics->density = -1.0; })).find("density"), std::string::npos);
  EXPECT_NE(message(with([](SolveOptions& o) { o.dynamics->damping.mass = -1.0; })).find("damping.mass"),
            std::string::npos);
  EXPECT_NE(message(with([](SolveOptions& o) { o.dynamics->damping.stiffness = NAN; })).find("damping.stiffness"),
            std::string::npos);
  EXPECT_NE(message(with([](SolveOptions& o) { o.dynamics->substeps = 0; })).find("substeps"), std::string::npos);
  EXPECT_NE(message(with([](SolveOptions& o) { o.initial_velocities = Points(1); })).find("initial_velocities"),
            std::string::npos);
  // Multigrid carries the inertia and the self-contact barrier on its
  // coarse levels, not the self-contact penalty's springs.
  EXPECT_EQ(message(with([](SolveOptions& o) { o.preconditioner = Preconditioner::multigrid; })), "");
  EXPECT_EQ(message(with([](SolveOptions& o) {
              o.preconditioner = Preconditioner::multigrid;
              o.contact.self = true;
            })),
            "");
  EXPECT_NE(message(with([](SolveOptions& o) {
              o.preconditioner = Preconditioner::multigrid;
              o.contact.self = true;
              o.contact.self_method = SelfContactMethod::penalty;
              o.contact.stiffness = 1.0;
              o.contact.thickness = 0.01;
            })).find("preconditioner multigrid: its coarse levels do not carry the self-contact penalty's springs"),
            std::string::npos);
  SolveOptions quasistatic;
  quasistatic.initial_velocities = Points(8);
  EXPECT_NE(message(quasistatic).find("need dynamics"), std::string::npos);
  Simulation sim(mesh, material, {}, with([](SolveOptions&) {}));
  EXPECT_THROW(sim.set_velocities(Points{Vec3{1.0, 2.0, 0.0}}), Error);
  Simulation static_sim(mesh, material, {}, {});
  EXPECT_THROW(static_sim.set_velocities({}), Error);
}

}  // namespace
}  // namespace snh::test
