// The library as a host application drives it: scale-free stopping, the
// frame-by-frame Simulation (targets, warm starts, cancellation), per-
// component constraints, body forces with load ramping, and the errors a
// construction must raise.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "material/element_reference.h"
#include "snh/configuration.h"
#include "snh/error.h"
#include "snh/fields.h"
#include "snh/loads.h"
#include "snh/simulation.h"
#include "support/plane_selection.h"

namespace snh::test {
namespace {

double max_difference(const Points& a, const Points& b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.xyz().size(); ++i) worst = std::max(worst, std::abs(a.xyz()[i] - b.xyz()[i]));
  return worst;
}

// A tet bar 2 x 0.5 x 0.5, one end held, the other pulled by 50%.
struct StretchedBar {
  Mesh mesh = make_tet_box(8, 2, 2, 0.25);
  ConstraintSet held{"held", on_plane(mesh, 0, 0.0), {}, {}};
  ConstraintSet pulled{"pulled",
                       on_plane(mesh, 0, 2.0),
                       [](double t) {
                         return RigidTransform::translation_by({t, 0.0, 0.0});
                       },
                       {}};
};

// The solver's tuning is a part of the options: set through either name,
// it is the same setting, and a tuning kept apart can be applied whole.
TEST(Simulation, TuningIsThePartOfTheOptionsItNames) {
  SolveOptions options;
  options.tuning().hessian = HessianMode::projected;
  EXPECT_EQ(options.hessian, HessianMode::projected);
  options.line_search_halvings = 12;
  EXPECT_EQ(options.tuning().line_search_halvings, 12);
  SolverTuning expert;
  expert.preconditioner = Preconditioner::block_jacobi;
  expert.multigrid.rebuild_every = 3;
  options.tuning() = expert;
  EXPECT_EQ(options.preconditioner, Preconditioner::block_jacobi);
  EXPECT_EQ(options.multigrid.rebuild_every, 3);
  EXPECT_EQ(options.hessian, HessianMode::adaptive);  // the tuning's default came with it
}

// The factories name the set, its vertices and what moves them.
TEST(Simulation, ConstraintSetFactoriesFillTheirParts) {
  const ConstraintSet held = ConstraintSet::fixed("held", {1, 2}, {true, false, true});
  EXPECT_EQ(held.name, "held");
  EXPECT_EQ(held.vertices, (std::vector<int32_t>{1, 2}));
  EXPECT_FALSE(held.motion);
  EXPECT_FALSE(held.targets);
  EXPECT_EQ(held.components, (std::array<bool, 3>{true, false, true}));
  const ConstraintSet moved = ConstraintSet::moving("moved", {3}, [](double t) {
    return RigidTransform::translation_by({0, 0, t});
  });
  ASSERT_TRUE(moved.motion);
  EXPECT_EQ(moved.motion(0.25).translation[2], 0.25);
  EXPECT_EQ(moved.components, (std::array<bool, 3>{true, true, true}));
  const ConstraintSet placed = ConstraintSet::targets_of("placed", {4}, [](double t, Points& xyz) {
    xyz = {{t, t, t}};
  });
  ASSERT_TRUE(placed.targets);
  EXPECT_FALSE(placed.motion);
}

TEST(Simulation, DefaultStopIsScaleFreeSameShapeForAnyYoungsModulus) {
  // The same physics at E = 1e-2 ... 1e6: with the default (strain) stop
  // every solve must reach the same shape. (An absolute force tolerance
  // stops E = 1e-2 at its first iterate.)
  StretchedBar bar;
  std::vector<Points> shapes;
  double scaled_tolerance = 0.0;
  for (double youngs : {1e-2, 1.0, 1e4, 1e6}) {
    SolveOptions options;
    options.load_steps = 2;
    QuasistaticSolver solver(bar.mesh, StableNeoHookean::from_youngs_modulus(youngs, 0.45), {bar.held, bar.pulled},
                             options);
    const SolveResult r = solver.solve();
    ASSERT_TRUE(r.converged) << youngs;
    EXPECT_GT(r.tolerance, 0.0);
    if (shapes.empty()) scaled_tolerance = r.tolerance / youngs;
    EXPECT_NEAR(r.tolerance / youngs, scaled_tolerance, 1e-12 * scaled_tolerance);
    shapes.push_back(r.positions);
  }
  // A strain error of 1e-6 moves vertices by about 1e-6 of the bar's
  // length; Newton's last quadratic step usually does much better.
  for (size_t k = 1; k < shapes.size(); ++k) EXPECT_LT(max_difference(shapes[0], shapes[k]), 2e-6) << k;
  // And the bar really stretched: the middle of its axis moved.
  double mid_shift = 0.0;
  for (size_t v = 0; v < bar.mesh.vertex_count(); ++v)
    if (std::abs(bar.mesh.positions(v, 0) - 1.0) < 1e-9)
      mid_shift = std::max(mid_shift, shapes[0](v, 0) - bar.mesh.positions(v, 0));
  EXPECT_GT(mid_shift, 0.3);
}

TEST(Simulation, ToleranceFollowsTheStrainFormula) {
  const Mesh mesh = make_box_lattice(4, 4, 4, 0.25);
  const Material material = StableNeoHookean::from_youngs_modulus(2.0, 0.3);
  SolveOptions options;
  // 125 vertices of spacing (1 / 125)^(1/3) = 0.2.
  EXPECT_NEAR(resolve_configuration(options, mesh, uniform_material(mesh, material), DeviceInfo{}).absolute_tolerance,
              1e-6 * 2.0 * 0.04 * std::sqrt(125.0), 1e-18);
  options.precision = Precision::single;
  EXPECT_NEAR(resolve_configuration(options, mesh, uniform_material(mesh, material), DeviceInfo{}).absolute_tolerance,
              1e-4 * 2.0 * 0.04 * std::sqrt(125.0), 1e-15);
  options.absolute_tolerance = 1e-9;  // an explicit criterion stands alone
  EXPECT_EQ(resolve_configuration(options, mesh, uniform_material(mesh, material), DeviceInfo{}).absolute_tolerance,
            1e-9);
  options.strain_tolerance = 1e-3;  // unless the strain one is asked for too
  EXPECT_NEAR(resolve_configuration(options, mesh, uniform_material(mesh, material), DeviceInfo{}).absolute_tolerance,
              1e-3 * 2.0 * 0.04 * std::sqrt(125.0), 1e-15);
}

TEST(Simulation, FramesWithAbsoluteTransformsReachTheOneShotSolution) {
  // A twisted column, 2 x pi/4 frame by frame from a warm start, against one
  // solve with the same final transform in two load steps.
  const Mesh mesh = make_box_lattice(3, 3, 6, 1.0 / 3);
  const Material material = StableNeoHookean::from_youngs_modulus(1.0, 0.4);
  ConstraintSet base{"base", on_plane(mesh, 2, 0.0), {}, {}};
  ConstraintSet top{"top", on_plane(mesh, 2, 2.0), {}, {}};
  auto twist = [](double angle) { return RigidTransform::rotation_about({0, 0, 1}, angle, {0.5, 0.5, 2.0}); };

  Simulation sim(mesh, material, {base, top});
  std::vector<int> newton;
  for (int frame = 1; frame <= 2; ++frame) {
    sim.set_transform("top", twist(frame * M_PI / 4));
    const SolveResult r = sim.solve(1);
    ASSERT_TRUE(r.converged) << frame;
    newton.push_back(r.steps[0].newton_iterations);
    // The top face sits exactly on its target.
    const RigidTransform t = twist(frame * M_PI / 4);
    for (int32_t v : top.vertices) {
      const auto target = t.apply(mesh.vertex(v));
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(sim.positions()(v, d), target[d], 1e-14);
    }
  }
  top.motion = [&](double s) { return twist(s * M_PI / 2); };
  SolveOptions two_steps;
  two_steps.load_steps = 2;
  QuasistaticSolver one_shot(mesh, material, {base, top}, two_steps);
  const SolveResult reference = one_shot.solve();
  ASSERT_TRUE(reference.converged);
  EXPECT_LT(max_difference(sim.positions(), reference.positions), 1e-5);
  // Interpolated as a rotation, the intermediate targets keep the face rigid:
  // no element inverts on the way.
  EXPECT_EQ(reference.inverted_elements, 0);
}

TEST(Simulation, SetPositionsMovesASetLinearlyAndSolveContinuesFromTheState) {
  const Mesh mesh = make_box_lattice(4, 2, 2, 0.25);
  Simulation sim(
      mesh, StableNeoHookean::from_youngs_modulus(1.0, 0.3),
      {ConstraintSet{"wall", on_plane(mesh, 0, 0.0), {}, {}}, ConstraintSet{"end", on_plane(mesh, 0, 1.0), {}, {}}});
  const std::vector<int32_t>& end = sim.constraints()[1].vertices;
  Points xyz;
  for (int32_t v : end) xyz.push_back({1.2, mesh.positions(v, 1), mesh.positions(v, 2) + 0.1});
  sim.set_positions("end", xyz);
  std::vector<double> seen;
  const SolveResult r = sim.solve(2, {}, [&](int, const Points& x) { seen.push_back(x(end[0], 0)); });
  ASSERT_TRUE(r.converged);
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_NEAR(seen[0], 1.1, 1e-14);  // halfway at load step 1 of 2
  EXPECT_NEAR(seen[1], 1.2, 1e-14);
  // A second solve with nothing changed starts at equilibrium: no update.
  const SolveResult again = sim.solve(1);
  EXPECT_TRUE(again.converged);
  EXPECT_EQ(again.steps[0].newton_iterations, 0);
  EXPECT_THROW(sim.set_positions("end", Points(1)), Error);
  try {
    sim.set_transform("lid", RigidTransform::identity());
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'wall', 'end'"), std::string::npos) << e.what();
  }
}

TEST(Simulation, ProgressCallbackCancelsAndTheNextSolveFinishes) {
  StretchedBar bar;
  Simulation sim(bar.mesh, StableNeoHookean::from_youngs_modulus(1.0, 0.45), {bar.held, bar.pulled});
  int calls = 0;
  const SolveResult cut = sim.solve(2, [&](const NewtonIteration&) { return ++calls < 2; });
  EXPECT_TRUE(cut.cancelled);
  EXPECT_FALSE(cut.converged);
  ASSERT_EQ(cut.steps.size(), 1u);  // the second load step never ran
  EXPECT_EQ(cut.steps[0].status, StepStatus::cancelled);
  EXPECT_EQ(cut.steps[0].newton_iterations, 2);
  EXPECT_EQ(sim.positions(), cut.positions);
  // The targets were not reached: the next solve goes on to them.
  const SolveResult rest = sim.solve(2);
  EXPECT_TRUE(rest.converged);
  EXPECT_FALSE(rest.cancelled);
  for (int32_t v : bar.pulled.vertices) EXPECT_NEAR(sim.positions()(v, 0), bar.mesh.positions(v, 0) + 1.0, 1e-14);
}

// Iteration records give wall time since their own solve began, less the
// callbacks' time: a slow callback in one solve must not make a later
// solve's records negative (the driver once kept subtracting it).
TEST(Simulation, CallbackTimeOfOneSolveIsNotSubtractedFromTheNext) {
  StretchedBar bar;
  Simulation sim(bar.mesh, StableNeoHookean::from_youngs_modulus(1.0, 0.45), {bar.held, bar.pulled});
  const SolveResult slow = sim.solve(1, [](const NewtonIteration&) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    return true;
  });
  ASSERT_TRUE(slow.converged);
  ASSERT_GE(slow.history.size(), 3u);  // at least 0.2 s in the callback
  sim.set_transform("pulled", RigidTransform::translation_by({1.0, 0.01, 0.0}));
  const SolveResult next = sim.solve(1, [](const NewtonIteration&) { return true; });
  ASSERT_TRUE(next.converged);
  double previous = 0.0;
  for (const NewtonIteration& rec : next.history) {
    EXPECT_GE(rec.seconds, previous) << "iteration " << rec.iteration;
    previous = rec.seconds;
  }
  EXPECT_GT(next.history.front().seconds, 0.0);
}

TEST(Simulation, PerComponentConstraintsGiveHomogeneousUniaxialStress) {
  // Compression between two frictionless plates (z prescribed only) with
  // symmetry planes x = 0 and y = 0 (x resp. y prescribed): the exact
  // solution is homogeneous uniaxial stress, F = diag(a, a, 0.8), P_xx = 0.
  const Mesh mesh = make_box_lattice(3, 3, 3, 1.0 / 3);
  ConstraintSet floor{"floor", on_plane(mesh, 2, 0.0), {}, {}, {false, false, true}};
  ConstraintSet plate{"plate",
                      on_plane(mesh, 2, 1.0),
                      [](double t) {
                        return RigidTransform::translation_by({0, 0, -0.2 * t});
                      },
                      {},
                      {false, false, true}};
  ConstraintSet sym_x{"symmetry_x", on_plane(mesh, 0, 0.0), {}, {}, {true, false, false}};
  ConstraintSet sym_y{"symmetry_y", on_plane(mesh, 1, 0.0), {}, {}, {false, true, false}};
  const StableNeoHookean material = StableNeoHookean::from_youngs_modulus(1.0, 0.3);
  SolveOptions options;
  options.strain_tolerance = 1e-10;
  QuasistaticSolver solver(mesh, material, {floor, plate, sym_x, sym_y}, options);
  const SolveResult r = solver.solve();
  ASSERT_TRUE(r.converged);
  // Every vertex at (a X, a Y, 0.8 Z) with one lateral stretch a > 1, to the
  // Newton tolerance (a strain of 1e-10).
  const double a = r.positions(mesh.vertex_count() - 1, 0);  // the corner (1, 1, 1)
  EXPECT_GT(a, 1.0);
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    EXPECT_NEAR(r.positions(v, 0), a * mesh.positions(v, 0), 1e-9);
    EXPECT_NEAR(r.positions(v, 1), a * mesh.positions(v, 1), 1e-9);
    EXPECT_NEAR(r.positions(v, 2), 0.8 * mesh.positions(v, 2), 1e-9);  // free interior vertices too
  }
  // Uniaxial stress: the lateral stress vanishes at F = diag(a, a, 0.8).
  const reference::Mat3<double> f{a, 0, 0, 0, a, 0, 0, 0, 0.8};
  const auto p = reference::material_pk1(f, reference::spec_of(Material(material)));
  EXPECT_LT(std::abs(p[0]), 1e-7 * std::abs(p[8]));
  EXPECT_LT(p[8], 0.0);  // compressive
  // The plate pushes on the unit-area top with the force P_zz; the floor
  // pushes back; the symmetry planes carry nothing (no lateral stress).
  const std::vector<Reaction> reactions = solver.simulation().reactions();
  ASSERT_EQ(reactions.size(), 4u);
  EXPECT_NEAR(reactions[1].force[2], p[8], 1e-6 * std::abs(p[8]));
  EXPECT_NEAR(reactions[0].force[2], -p[8], 1e-6 * std::abs(p[8]));
  for (int k : {2, 3})
    for (int d = 0; d < 3; ++d) EXPECT_LT(std::abs(reactions[k].force[d]), 1e-6 * std::abs(p[8])) << k;
}

TEST(Simulation, BodyForceEqualsItsLumpedExternalForceAndRampsWithTheLoad) {
  const Mesh mesh = make_tet_box(4, 2, 2, 0.25);
  const ConstraintSet wall{"wall", on_plane(mesh, 0, 0.0), {}, {}};
  const Material material = StableNeoHookean::from_youngs_modulus(1.0, 0.3);
  const std::array<double, 3> gravity{0, 0, -0.05};
  SolveOptions as_body;
  as_body.body_force = gravity;
  as_body.load_steps = 2;
  SolveOptions as_external = as_body;
  as_external.body_force = {0, 0, 0};
  as_external.external_force = lump_body_force(mesh, gravity);
  Simulation a(mesh, material, {wall}, as_body), b(mesh, material, {wall}, as_external);
  Points first_step_force;
  const SolveResult ra = a.solve(0, {}, [&](int step, const Points&) {
    if (step == 1) first_step_force = a.applied_force();
  });
  const SolveResult rb = b.solve();
  ASSERT_TRUE(ra.converged && rb.converged);
  EXPECT_EQ(ra.positions, rb.positions);
  // Ramped: half the force at load step 1 of 2, all of it at the end.
  ASSERT_EQ(first_step_force.xyz().size(), as_external.external_force.xyz().size());
  for (size_t i = 0; i < first_step_force.xyz().size(); ++i) {
    EXPECT_DOUBLE_EQ(first_step_force.xyz()[i], 0.5 * as_external.external_force.xyz()[i]);
    EXPECT_DOUBLE_EQ(a.applied_force().xyz()[i], as_external.external_force.xyz()[i]);
  }
  // Not ramped: the same equilibrium (within the tolerance), a different path.
  SolveOptions unramped = as_body;
  unramped.ramp_loads = false;
  Simulation c(mesh, material, {wall}, unramped);
  const SolveResult rc = c.solve();
  ASSERT_TRUE(rc.converged);
  EXPECT_LT(max_difference(rc.positions, ra.positions), 1e-5);
  EXPECT_NE(rc.history.size(), ra.history.size());
  // Doubling gravity between frames moves the tip further down.
  double tip = 0.0;
  for (int32_t v : on_plane(mesh, 0, 1.0)) tip = std::min(tip, ra.positions(v, 2) - mesh.positions(v, 2));
  a.set_body_force({0, 0, -0.1});
  ASSERT_TRUE(a.solve().converged);
  double tip2 = 0.0;
  for (int32_t v : on_plane(mesh, 0, 1.0)) tip2 = std::min(tip2, a.positions()(v, 2) - mesh.positions(v, 2));
  EXPECT_LT(tip2, 1.5 * tip);
}

TEST(Simulation, ConstructionNamesConflictsAndBadInputs) {
  const Mesh mesh = make_box_lattice(2, 2, 2, 0.5);
  const Material material = StableNeoHookean::from_youngs_modulus(1.0, 0.3);
  auto message = [&](std::vector<ConstraintSet> sets, SolveOptions options) -> std::string {
    try {
      Simulation s(mesh, material, std::move(sets), std::move(options));
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  const std::vector<int32_t> bottom = on_plane(mesh, 2, 0.0);
  // A vertex in two sets with different motions: named, not "last wins".
  EXPECT_NE(message({ConstraintSet{"a", bottom, {}, {}}, ConstraintSet{"b", {bottom[0]}, {}, {}}}, {})
                .find("vertex 0 is prescribed by constraint sets 'a' and 'b'"),
            std::string::npos);
  // Disjoint components of one vertex are no conflict.
  EXPECT_EQ(message({ConstraintSet{"a", bottom, {}, {}, {true, true, false}},
                     ConstraintSet{"b", bottom, {}, {}, {false, false, true}}},
                    {}),
            "");
  EXPECT_NE(message({ConstraintSet{"a", bottom, {}, {}}, ConstraintSet{"a", {26}, {}, {}}}, {}).find("named 'a'"),
            std::string::npos);
  EXPECT_NE(message({ConstraintSet{"none", bottom, {}, {}, {false, false, false}}}, {}).find("prescribes no component"),
            std::string::npos);
  SolveOptions short_force;
  short_force.external_force = {{0.0, 0.0, 1.0}};
  EXPECT_NE(
      message({ConstraintSet{"a", bottom, {}, {}}}, short_force).find("external_force has 3 entries, expected 81"),
      std::string::npos);
  SolveOptions nan_body;
  nan_body.body_force = {0, std::nan(""), 0};
  EXPECT_NE(message({ConstraintSet{"a", bottom, {}, {}}}, nan_body).find("body_force"), std::string::npos);
  // Only z held on the floor, gravity along x: free to slide, no equilibrium.
  SolveOptions sideways;
  sideways.body_force = {1.0, 0, 0};
  EXPECT_NE(
      message({ConstraintSet{"floor", bottom, {}, {}, {false, false, true}}}, sideways).find("translation along x"),
      std::string::npos);
  // A non-finite target names its set, at the step that produces it.
  ConstraintSet broken{"broken",
                       bottom,
                       [](double) {
                         RigidTransform t;
                         t.translation = {std::nan(""), 0, 0};
                         return t;
                       },
                       {}};
  Simulation s(mesh, material, {broken});
  try {
    s.solve();
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("constraint set 'broken': non-finite target"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace snh::test
