// The Newton-CG engine end to end: the patch test, bitwise determinism, clear
// errors, and each of the paper's scenes at a small size with its physics.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "snh/error.h"
#include "snh/scenes.h"
#include "snh/simulation.h"
#include "support/lattices.h"
#include "support/scenes.h"

namespace snh::test {
namespace {

// Boundary vertices of a box lattice (any coordinate on the box's faces).
std::vector<int32_t> boundary_vertices(const Mesh& mesh, double size) {
  std::vector<int32_t> out;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const auto x = mesh.vertex(v);
    bool boundary = false;
    for (double c : x) boundary = boundary || c < 1e-9 || c > size - 1e-9;
    if (boundary) out.push_back(static_cast<int32_t>(v));
  }
  return out;
}

void patch_test(Mesh mesh, Precision precision, double tolerance) {
  // A large affine deformation, rotation included: x = A X + b.
  const std::array<double, 9> a{1.3, 0.2, -0.1, 0.15, 0.8, 0.25, -0.2, 0.1, 1.1};
  const std::array<double, 3> b{0.1, -0.2, 0.3};
  auto affine = [&](const std::array<double, 3>& x) {
    std::array<double, 3> y;
    for (int i = 0; i < 3; ++i) y[i] = a[i] * x[0] + a[3 + i] * x[1] + a[6 + i] * x[2] + b[i];
    return y;
  };
  ConstraintSet boundary{"boundary", boundary_vertices(mesh, 1.0), {}, {}};
  boundary.targets = [&](double, Points& xyz) {
    for (size_t k = 0; k < boundary.vertices.size(); ++k) {
      const auto y = affine(mesh.vertex(boundary.vertices[k]));
      for (int d = 0; d < 3; ++d) xyz(k, d) = y[d];
    }
  };
  SolveOptions options;
  options.precision = precision;
  options.absolute_tolerance = precision == Precision::double_ ? 1e-11 : 1e-5;  // alone: no strain criterion
  const StableNeoHookean material = StableNeoHookean::from_youngs_modulus(1.0, 0.45);
  QuasistaticSolver solver(mesh, material, {boundary}, options);
  const SolveResult r = solver.solve();
  EXPECT_TRUE(r.converged);
  double worst = 0.0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const auto y = affine(mesh.vertex(v));
    for (int d = 0; d < 3; ++d) worst = std::max(worst, std::abs(r.positions(v, d) - y[d]));
  }
  EXPECT_LT(worst, tolerance);
}

Mesh jittered_lattice(int n) { return jittered_unit_cube(n, 5); }

TEST(Solver, PatchTestHexLatticeDouble) { patch_test(make_box_lattice(3, 3, 3, 1.0 / 3), Precision::double_, 1e-10); }
TEST(Solver, PatchTestJitteredHexDouble) { patch_test(jittered_lattice(3), Precision::double_, 1e-10); }
TEST(Solver, PatchTestTetDouble) { patch_test(make_tet_box(3, 3, 3, 1.0 / 3), Precision::double_, 1e-10); }
TEST(Solver, PatchTestHexFloat) { patch_test(jittered_lattice(3), Precision::single, 2e-4); }

TEST(Solver, BitwiseDeterministic) {
  for (Precision precision : {Precision::double_, Precision::single}) {
    SceneParameters p;
    p.resolution = 3;
    p.strain_tolerance = 1e-4;
    const Scene scene = make_scene("twist", p);
    SolveOptions options = scene.options;
    options.precision = precision;
    QuasistaticSolver a(scene.mesh, scene.material, scene.constraints, options);
    QuasistaticSolver b(scene.mesh, scene.material, scene.constraints, options);
    const SolveResult ra = a.solve(), rb = b.solve();
    EXPECT_EQ(ra.positions, rb.positions) << to_string(precision);
    ASSERT_EQ(ra.history.size(), rb.history.size());
    for (size_t i = 0; i < ra.history.size(); ++i) {
      EXPECT_EQ(ra.history[i].residual_norm, rb.history[i].residual_norm);
      EXPECT_EQ(ra.history[i].cg_iterations, rb.history[i].cg_iterations);
    }
  }
}

TEST(Solver, RejectsBadConstraintsAndOptions) {
  const Mesh mesh = make_box_lattice(2, 2, 2, 0.5);
  const StableNeoHookean material = StableNeoHookean::from_youngs_modulus(1.0, 0.3);
  EXPECT_THROW(QuasistaticSolver(mesh, material, {ConstraintSet{"empty", {}, {}, {}}}), Error);
  try {
    QuasistaticSolver(mesh, material, {ConstraintSet{"far", {0, 999}, {}, {}}});
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'far' refers to vertex 999"), std::string::npos) << e.what();
  }
  SolveOptions bad;
  bad.initial_positions = {{1.0, 2.0, 0.0}};
  EXPECT_THROW(QuasistaticSolver(mesh, material, {}, bad), Error);
  SolveOptions nan_force;
  nan_force.external_force = Points(mesh.vertex_count(), {std::nan(""), std::nan(""), std::nan("")});
  EXPECT_THROW(QuasistaticSolver(mesh, material, {ConstraintSet{"pin", {0}, {}, {}}}, nan_force), Error);
}

TEST(Solver, UnusedVertexIsAWarningNotAnError) {
  Mesh mesh = make_box_lattice(2, 2, 2, 0.5);
  mesh.positions.push_back({5.0, 5.0, 5.0});
  QuasistaticSolver solver(mesh, StableNeoHookean::from_youngs_modulus(1.0, 0.3), {ConstraintSet{"pin", {0}, {}, {}}});
  const SolveResult r = solver.solve();
  EXPECT_TRUE(r.converged);
  bool named = false;
  for (const std::string& w : r.warnings)
    named = named || w.find("1 vertices belong to no element (first: 27)") != std::string::npos;
  EXPECT_TRUE(named);
  EXPECT_EQ(r.positions(27, 0), 5.0);
}

TEST(Solver, FreeBodyUnderGravityIsAnErrorNamingTheFreeMotion) {
  // No constraint and a net force: no static equilibrium exists.
  const Mesh mesh = make_box_lattice(2, 2, 2, 0.5);
  SolveOptions options;
  options.external_force = Points(mesh.vertex_count());
  for (size_t v = 0; v < mesh.vertex_count(); ++v) options.external_force(v, 2) = -1e-2;
  try {
    QuasistaticSolver(mesh, StableNeoHookean::from_youngs_modulus(1.0, 0.3), {}, options);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("translation along z"), std::string::npos) << e.what();
  }
}

TEST(Solver, FreeBodyWithoutLoadRecoversItsShapeWithAWarning) {
  // Unconstrained but unloaded: the equilibrium is the rest shape up to a
  // rigid motion. Starting stretched, the stiffness is singular along the
  // six rigid modes; Newton must still return to a rest shape, finite.
  const Mesh mesh = make_box_lattice(2, 2, 2, 0.5);
  SolveOptions options;
  options.initial_positions = mesh.positions;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) options.initial_positions(v, 0) *= 1.3;
  QuasistaticSolver solver(mesh, StableNeoHookean::from_youngs_modulus(1.0, 0.3), {}, options);
  const SolveResult r = solver.solve();
  for (double x : r.positions.xyz()) EXPECT_TRUE(std::isfinite(x));
  EXPECT_TRUE(r.converged) << r.steps[0].status;
  EXPECT_NEAR(r.volume_ratio, 1.0, 1e-5);
  EXPECT_NEAR(r.min_j, 1.0, 1e-4);
  bool warned = false;
  for (const std::string& w : r.warnings) warned = warned || w.find("6 rigid motion(s) left free") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(Solver, FailedLineSearchRetriesAlongSteepestDescentAndReportsIt) {
  // A line search allowed no halving fails where the twist needs a half
  // step (iteration 3 of the first step at this size); the solver retries
  // along the preconditioned steepest descent.
  const Scene scene = scene_at("twist", 6);
  SolveOptions options = scene.options;
  options.line_search_halvings = 0;
  options.max_newton_iterations = 30;
  QuasistaticSolver solver(scene.mesh, scene.material, scene.constraints, options);
  const SolveResult r = solver.solve();
  bool retried = false;
  for (const NewtonIteration& h : r.history)
    retried = retried || contains(h.recovery, RecoveryAction::line_search_steepest_descent) ||
              contains(h.recovery, RecoveryAction::line_search_steepest_descent_failed);
  EXPECT_TRUE(retried);
  for (double x : r.positions.xyz()) EXPECT_TRUE(std::isfinite(x));
}

TEST(Solver, GravityOnPinnedBlockSagsAndBalances) {
  const Mesh mesh = make_box_lattice(4, 2, 2, 0.25);
  ConstraintSet wall{"wall", {}, {}, {}};
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    if (mesh.positions(v, 0) < 1e-9) wall.vertices.push_back(static_cast<int32_t>(v));
  SolveOptions options;
  options.external_force = Points(mesh.vertex_count());
  for (size_t v = 0; v < mesh.vertex_count(); ++v) options.external_force(v, 2) = -1e-3;
  options.absolute_tolerance = 1e-12;
  QuasistaticSolver solver(mesh, StableNeoHookean::from_youngs_modulus(1.0, 0.3), {wall}, options);
  const SolveResult r = solver.solve();
  ASSERT_TRUE(r.converged);
  // The free end sags; the pinned wall does not move.
  double tip = 0.0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    if (mesh.positions(v, 0) > 1.0 - 1e-9) tip = std::min(tip, r.positions(v, 2) - mesh.positions(v, 2));
  EXPECT_LT(tip, -1e-3);
  for (int32_t v : wall.vertices)
    for (int d = 0; d < 3; ++d) EXPECT_EQ(r.positions(v, d), mesh.positions(v, d));
}

SolveResult run_scene(const std::string& name, int resolution, Precision precision, unsigned seed = 1) {
  SceneParameters p;
  p.resolution = resolution;
  p.seed = seed;
  if (precision == Precision::single) p.strain_tolerance = 1e-4;
  const Scene scene = make_scene(name, p);
  SolveOptions options = scene.options;
  options.precision = precision;
  QuasistaticSolver solver(scene.mesh, scene.material, scene.constraints, options);
  return solver.solve();
}

TEST(Scenes, StretchGainsVolumeLikeThePaper) {
  const SolveResult r = run_scene("stretch", 4, Precision::double_);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.inverted_elements, 0);
  // Paper (306,406 hexes): +4.3%. At this size: a gain of a few percent.
  EXPECT_GT(r.volume_ratio, 1.0);
  EXPECT_LT(r.volume_ratio, 1.08);
}

TEST(Scenes, TwistHasNoInvertedElements) {
  for (Precision precision : {Precision::double_, Precision::single}) {
    const SolveResult r = run_scene("twist", 4, precision);
    EXPECT_TRUE(r.converged) << to_string(precision);
    EXPECT_EQ(r.inverted_elements, 0) << to_string(precision);
    EXPECT_EQ(r.steps.size(), 2u);
  }
}

TEST(Scenes, ScrambleRecoversRestShape) {
  const SolveResult r = run_scene("scramble", 4, Precision::double_, 2);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.inverted_elements, 0);
  EXPECT_NEAR(r.volume_ratio, 1.0, 1e-3);
  EXPECT_GT(r.min_j, 0.99);
}

TEST(Scenes, FlexBendsWithoutInversion) {
  const SolveResult r = run_scene("flex", 2, Precision::double_);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.inverted_elements, 0);
}

TEST(Solver, AdaptiveHessianUsesTrueHessianNearSolutionAndNeedsFewerIterations) {
  const Scene scene = scene_at("twist", 4);
  int iterations[2] = {0, 0};
  for (HessianMode mode : {HessianMode::projected, HessianMode::adaptive}) {
    SolveOptions options = scene.options;
    options.hessian = mode;
    QuasistaticSolver solver(scene.mesh, scene.material, scene.constraints, options);
    const SolveResult r = solver.solve();
    ASSERT_TRUE(r.converged);
    int unprojected = 0;
    for (const NewtonIteration& h : r.history) unprojected += h.projected ? 0 : 1;
    if (mode == HessianMode::projected) {
      EXPECT_EQ(unprojected, 0);
    }
    if (mode == HessianMode::adaptive) {
      EXPECT_GT(unprojected, 0);
    }
    iterations[mode == HessianMode::adaptive] = static_cast<int>(r.history.size());
  }
  EXPECT_LT(iterations[1], iterations[0]);
}

TEST(Scenes, TetVersionsSplitTheLatticeAndSolve) {
  SceneParameters p;
  p.resolution = 3;
  const Scene hex_stretch = make_scene("stretch", p);
  p.element_type = ElementType::tet4;
  const Scene tet_stretch = make_scene("stretch", p);
  EXPECT_EQ(tet_stretch.mesh.type, ElementType::tet4);
  EXPECT_EQ(tet_stretch.mesh.element_count(), 6 * hex_stretch.mesh.element_count());
  EXPECT_EQ(tet_stretch.mesh.positions, hex_stretch.mesh.positions);
  EXPECT_NEAR(mesh_volume(tet_stretch.mesh, tet_stretch.mesh.positions),
              mesh_volume(hex_stretch.mesh, hex_stretch.mesh.positions), 1e-12);
  EXPECT_TRUE(validate_mesh(tet_stretch.mesh).unused_vertices.empty());
  const Scene twist = make_scene("twist", p);
  QuasistaticSolver solver(twist.mesh, twist.material, twist.constraints, twist.options);
  const SolveResult r = solver.solve();
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.inverted_elements, 0);
  // The measured default for tet4: the assembled matrix on CPUs, the cached
  // linearization on GPUs.
  EXPECT_EQ(r.product, r.device.is_gpu ? ProductVariant::cached : ProductVariant::assembled);
}

TEST(Scenes, UnknownSceneIsAnError) { EXPECT_THROW(make_scene("wobble", {}), Error); }

}  // namespace
}  // namespace snh::test
