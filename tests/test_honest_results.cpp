// A damaged result is never reported as clean: steps and frames that end
// with inverted elements, or short of their tolerance, carry min J, the
// inverted count and warnings; fail_on_inverted turns inverted elements into
// a failure. And an embedded surface in contact with an obstacle
// (Simulation::set_contact_surface) stays out of it.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "snh/error.h"
#include "snh/frames.h"
#include "snh/loads.h"
#include "snh/rig.h"
#include "snh/scene.h"
#include "snh/scenes.h"
#include "snh/simulation.h"
#include "snh/surface.h"
#include "stability.h"
#include "support/cli_run.h"
#include "support/plane_selection.h"
#include "support/scenes.h"
#include "support/surface_shapes.h"

namespace snh::test {
namespace {

TEST(HonestResults, WarningNamesRoundTrip) {
  const std::pair<ResultWarning, const char*> expected[] = {
      {ResultWarning::inverted_elements, "inverted_elements"},
      {ResultWarning::not_converged, "not_converged"},
      {ResultWarning::obstacle_penetration, "obstacle_penetration"},
      {ResultWarning::surface_intersections, "surface_intersections"},
  };
  for (const auto& [kind, name] : expected) {
    EXPECT_STREQ(to_string(kind), name);
    EXPECT_EQ(parse_result_warning(name), kind);
    const std::string text = warning_text(kind, "load step 2 ...");
    EXPECT_EQ(text, std::string(name) + ": load step 2 ...");
    EXPECT_TRUE(has_warning({"something else", text}, kind));
  }
  EXPECT_FALSE(has_warning({"not_converged: x"}, ResultWarning::inverted_elements));
  EXPECT_THROW(parse_result_warning("inverted"), Error);
  EXPECT_STREQ(to_string(StepStatus::inverted_elements), "inverted_elements");
  EXPECT_EQ(parse_step_status("inverted_elements"), StepStatus::inverted_elements);
}

// One hex whose every vertex is prescribed, its top face pulled down
// through its bottom: Newton has nothing to solve (converged at once), and
// the element is inverted at the end of each step.
Simulation flipped_hex(bool fail_on_inverted) {
  Mesh mesh = make_box_lattice(1, 1, 1, 1.0);
  std::vector<int32_t> all(mesh.vertex_count());
  for (size_t v = 0; v < all.size(); ++v) all[v] = static_cast<int32_t>(v);
  const Points rest = mesh.positions;
  ConstraintSet set = ConstraintSet::targets_of("all", all, [rest](double t, Points& xyz) {
    xyz = rest;
    for (size_t v = 0; v < xyz.size(); ++v)
      if (rest(v, 2) > 0.5) xyz(v, 2) = 1.0 - 3.0 * t;  // below the bottom from t = 1/3
  });
  SolveOptions options;
  options.load_steps = 2;
  options.fail_on_inverted = fail_on_inverted;
  return Simulation(std::move(mesh), StableNeoHookean::from_youngs_modulus(1.0, 0.3), {set}, options);
}

TEST(HonestResults, ConvergedStepWithInvertedElementsWarns) {
  Simulation sim = flipped_hex(false);
  const SolveResult r = sim.solve();
  ASSERT_EQ(r.steps.size(), 2u);
  for (const StepResult& s : r.steps) {
    EXPECT_TRUE(s.converged);  // Newton's criterion, unchanged
    EXPECT_EQ(s.status, StepStatus::converged);
    EXPECT_EQ(s.inverted_elements, 1);
    EXPECT_LT(s.min_j, 0.0);
    ASSERT_TRUE(has_warning(s.warnings, ResultWarning::inverted_elements));
  }
  EXPECT_NE(r.steps[1].warnings[0].find("load step 2"), std::string::npos);
  EXPECT_TRUE(has_warning(r.warnings, ResultWarning::inverted_elements));
  EXPECT_EQ(sim.last_step().step, 2);
  EXPECT_EQ(sim.last_step().inverted_elements, 1);
}

TEST(HonestResults, FailOnInvertedStopsAtTheFirstInvertedStep) {
  Simulation sim = flipped_hex(true);
  const SolveResult r = sim.solve();
  ASSERT_EQ(r.steps.size(), 1u);  // step 2 not run
  EXPECT_EQ(r.steps[0].status, StepStatus::inverted_elements);
  EXPECT_TRUE(r.steps[0].converged);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.inverted_elements, 1);
}

TEST(HonestResults, CleanStepHasNoWarnings) {
  const Mesh mesh = make_box_lattice(2, 2, 2, 0.5);
  const ConstraintSet bottom = ConstraintSet::fixed("bottom", on_plane(mesh, 2, 0.0));
  const ConstraintSet top = ConstraintSet::moving("top", on_plane(mesh, 2, 1.0), [](double t) {
    return RigidTransform::translation_by({0, 0, 0.1 * t});
  });
  Simulation sim(mesh, StableNeoHookean::from_youngs_modulus(1.0, 0.3), {bottom, top});
  const SolveResult r = sim.solve();
  ASSERT_TRUE(r.converged);
  EXPECT_TRUE(r.steps[0].warnings.empty());
  EXPECT_EQ(r.steps[0].inverted_elements, 0);
  EXPECT_GT(r.steps[0].min_j, 0.9);
  EXPECT_TRUE(r.warnings.empty());
}

TEST(HonestResults, NewtonLimitWarns) {
  const Scene s = scene_at("twist", 2);
  SolveOptions options = s.options;
  options.load_steps = 1;
  options.max_newton_iterations = 1;
  Simulation sim(s.mesh, s.material, s.constraints, options);
  const SolveResult r = sim.solve();
  ASSERT_EQ(r.steps.size(), 1u);
  EXPECT_EQ(r.steps[0].status, StepStatus::max_newton_iterations);
  ASSERT_TRUE(has_warning(r.steps[0].warnings, ResultWarning::not_converged));
  EXPECT_NE(r.steps[0].warnings[0].find("max_newton_iterations"), std::string::npos);
}

// A bone that mirrors its hex in frame 1: the frame ends inverted.
TEST(HonestResults, FramesCarryWarningsReactionsAndFailOnInverted) {
  for (bool fail : {false, true}) {
    Mesh mesh = make_box_lattice(1, 1, 1, 1.0);
    std::vector<int32_t> all(mesh.vertex_count());
    for (size_t v = 0; v < all.size(); ++v) all[v] = static_cast<int32_t>(v);
    Simulation sim(std::move(mesh), StableNeoHookean::from_youngs_modulus(1.0, 0.3),
                   {ConstraintSet::fixed("bone", all)});
    Animation animation;
    animation.bones = {"bone"};
    Matrix4 mirror = identity_matrix4();
    mirror[10] = -1.0;
    animation.times = {0.0, 1.0, 2.0};
    animation.transforms = {{identity_matrix4()}, {mirror}, {identity_matrix4()}};
    FrameOptions options;
    options.fail_on_inverted = fail;
    const std::vector<FrameRecord> records = run_frames(sim, animation, nullptr, options);
    ASSERT_EQ(records.size(), fail ? 2u : 3u);
    EXPECT_TRUE(records[0].warnings.empty());
    EXPECT_EQ(records[0].status, StepStatus::converged);
    ASSERT_EQ(records[0].reactions.size(), 1u);
    EXPECT_EQ(records[0].reactions[0].name, "bone");
    EXPECT_EQ(records[1].inverted_elements, 1);
    EXPECT_TRUE(has_warning(records[1].warnings, ResultWarning::inverted_elements));
    EXPECT_EQ(records[1].status, fail ? StepStatus::inverted_elements : StepStatus::converged);
    EXPECT_EQ(records[1].converged, !fail);
    ASSERT_EQ(records[1].reactions.size(), 1u);
  }
}

// `snh run` on a hex whose top is pushed through its bottom (every vertex
// prescribed: Newton converges at once, the element inverted): the step
// table and progress line show min J and the inverted count, the warning is
// printed and written to the JSON, and --fail-on-inverted (or the file's
// solver.fail_on_inverted) fails the run naming the step.
TEST(HonestResults, CommandLineShowsAndFailsOnInvertedElements) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("snh_honest_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  nlohmann::json scene = {{"mesh", {{"generator", "box"}, {"cells", {1, 1, 1}}, {"size", 1.0}}},
                          {"constraints",
                           {{{"name", "bottom"}, {"select", {{"plane", {{"axis", "z"}, {"value", 0.0}}}}}},
                            {{"name", "top"},
                             {"select", {{"plane", {{"axis", "z"}, {"value", 1.0}}}}},
                             {"motion", {{"translation", {0.0, 0.0, -1.5}}}}}}},
                          {"solver", {{"steps", 2}}}};
  const fs::path file = dir / "flipped.json";
  std::ofstream(file) << scene.dump();
  const fs::path json = dir / "flipped_out.json";
  const CliRun plain = run_cli("run " + file.string() + " --json " + json.string());
  EXPECT_EQ(plain.status, 0) << plain.output;  // Newton converged: not a failure unless asked
  EXPECT_NE(plain.output.find("min_J       inverted"), std::string::npos) << plain.output;
  EXPECT_NE(plain.output.find("step 2/2: converged"), std::string::npos) << plain.output;
  EXPECT_NE(plain.output.find("warning: inverted_elements: load step 2 ended with 1 inverted elements"),
            std::string::npos)
      << plain.output;
  nlohmann::json written;
  std::ifstream(json) >> written;
  EXPECT_EQ(written["steps"][1]["inverted_elements"], 1);
  ASSERT_EQ(written["steps"][1]["warnings"].size(), 1u);
  EXPECT_EQ(written["steps"][0]["warnings"].size(), 0u);  // step 1: the top at z = 0.25, not inverted
  EXPECT_EQ(written["warnings"].size(), 1u);
  const CliRun failing = run_cli("run " + file.string() + " --quiet --fail-on-inverted");
  EXPECT_EQ(failing.status, 4) << failing.output;
  EXPECT_NE(failing.output.find("error: load step"), std::string::npos) << failing.output;
  scene["solver"]["fail_on_inverted"] = true;
  std::ofstream(file) << scene.dump();
  EXPECT_EQ(run_cli("run " + file.string() + " --quiet").status, 4);
  scene["solver"]["fail_on_inverted"] = "yes";
  std::ofstream(file) << scene.dump();
  const CliRun bad = run_cli("run " + file.string() + " --quiet");
  EXPECT_EQ(bad.status, 1);
  EXPECT_NE(bad.output.find("solver.fail_on_inverted"), std::string::npos) << bad.output;
  fs::remove_all(dir);
}

// The stability suite's crush to a line (4^3 hexes, double): Newton
// reaches a symmetric saddle with 4 inverted elements (the true Hessian's
// smallest eigenvalue there is -0.038); the perturbation leaves it for an
// equilibrium without inversion (docs/validation.md).
TEST(HonestResults, CrushToALineLeavesTheInvertedSaddle) {
  const bench::StabilityRun r = bench::run_stability_case("crush_line", Precision::double_);
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.status, "converged");
  EXPECT_EQ(r.inverted_elements, 0);
  EXPECT_GT(r.min_j, 0.0);
  EXPECT_EQ(r.recoveries.count("inverted_equilibrium -> perturbation"), 1u);
}

// The scramble of seed 1 at the suite's 4^3 hexes ends at a strict local
// minimum with one element inverted (energy 0.217 against 0 at rest, the
// true Hessian positive definite, every perturbation tried returns to it;
// docs/validation.md): the solve converges, keeps that state, and says so.
TEST(HonestResults, ScrambleSeedOneTangledMinimumIsReported) {
  const Scene s = bench::make_stability_case("scramble_seed1", Precision::double_);
  Simulation sim(s.mesh, s.material, s.constraints, s.options);
  const SolveResult r = sim.solve();
  ASSERT_EQ(r.steps.size(), 1u);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.steps[0].status, StepStatus::converged);
  EXPECT_EQ(r.steps[0].inverted_elements, 1);
  EXPECT_LT(r.steps[0].min_j, 0.0);
  EXPECT_TRUE(has_warning(r.steps[0].warnings, ResultWarning::inverted_elements));
  EXPECT_TRUE(has_warning(r.warnings, ResultWarning::inverted_elements));
  bool kept = false;
  for (const NewtonIteration& it : r.history)
    kept = kept || contains(it.recovery, RecoveryAction::inverted_equilibrium_kept);
  EXPECT_TRUE(kept);
}

// A sphere pressed into a coarsely voxelized ball: the ball's surface sticks
// out of its lattice (cells are kept where their centres are inside), so
// the lattice vertices stay clear of the sphere while the surface points
// meet it. Lattice-only contact lets them in by most of the indentation;
// with the surface in contact each stays outside to within 10% of the
// contact layer (in fact inside the layer, outside the sphere).
struct Pressed {
  double deepest = 0.0;  // max over surface points of -phi (inside the sphere: > 0)
  SolveResult result;
  Points positions;
};

constexpr double kBallRadius = 0.5, kCell = 0.3, kThickness = 0.01, kPress = 0.08;

Pressed press(bool surface_contact) {
  const TriangleSurface ball = icosphere(3, kBallRadius);
  const Voxelization voxels = voxelize(ball, kCell);
  const Embedding embedding = embed(voxels, ball);
  const Mesh& mesh = voxels.lattice;
  double low = 1e9, top = -1e9;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    low = std::min(low, mesh.positions(v, 2));
    top = std::max(top, mesh.positions(v, 2));
  }
  EXPECT_LT(top, kBallRadius - 0.05);  // the lattice's top is well below the surface's
  const ConstraintSet held = ConstraintSet::fixed("held", on_plane(mesh, 2, low));
  const double r = 0.3;
  // The obstacle starts just clear of the surface's top and ends kPress into it.
  Obstacle sphere = Obstacle::sphere({0.0, 0.0, kBallRadius + r + 2 * kThickness}, r);
  sphere.motion = [](double t) { return RigidTransform::translation_by({0, 0, -(kPress + 2 * kThickness) * t}); };
  SolveOptions options;
  options.obstacles = {sphere};
  // A stiffness that keeps the points within the layer (their depth into it
  // stays below 0.7 of its thickness) and that Newton with the surface
  // term's block-diagonal Hessian (contact/obstacle.h) solves in a few
  // hundred iterations per step; that majorant converges linearly where the
  // stiffness far exceeds a cell's (1e4: 400 iterations short of the
  // tolerance).
  options.contact.stiffness = 3e3;
  options.contact.thickness = kThickness;
  options.load_steps = 4;
  options.max_newton_iterations = 600;
  Simulation sim(mesh, StableNeoHookean::from_youngs_modulus(1e3, 0.3), {held}, options);
  if (surface_contact) sim.set_contact_surface(embedding);
  Pressed out;
  out.result = sim.solve();
  out.positions = sim.positions();
  const Points skin = embedded_positions(embedding, mesh, out.positions);
  const std::array<double, 3> c = {0.0, 0.0, kBallRadius + r + 2 * kThickness - kPress - 2 * kThickness};
  for (size_t p = 0; p < skin.size(); ++p) {
    const double d = std::hypot(skin(p, 0) - c[0], skin(p, 1) - c[1], skin(p, 2) - c[2]);
    out.deepest = std::max(out.deepest, r - d);
  }
  return out;
}

TEST(SurfaceContact, EmbeddedSurfaceStaysOutOfAPressingSphere) {
  const Pressed lattice_only = press(false);
  const Pressed with_surface = press(true);
  ASSERT_TRUE(lattice_only.result.converged);
  ASSERT_TRUE(with_surface.result.converged) << with_surface.result.steps.back().status;
  // Lattice-only: the surface top goes in by most of the press.
  EXPECT_GT(lattice_only.deepest, 0.5 * kPress);
  EXPECT_LE(with_surface.deepest, 0.1 * kThickness);
  // The contact now reports the surface's depth into the layer.
  EXPECT_GT(with_surface.result.steps.back().contacts, 0);
  EXPECT_EQ(lattice_only.result.steps.back().contacts, 0);
}

// A scene file with "embed" and "obstacles" puts the surface in contact by
// itself: the same press as above, run from the file.
TEST(SurfaceContact, SceneFileWithEmbedAndObstaclesUsesTheSurface) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("snh_surface_contact_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  write_obj((dir / "ball.obj").string(), icosphere(3, kBallRadius));
  const double r = 0.3, start = kBallRadius + r + 2 * kThickness;
  const nlohmann::json scene = {
      {"embed", {{"surface", "ball.obj"}, {"cell", kCell}}},
      {"material", {{"E", 1e3}, {"nu", 0.3}}},
      {"constraints", {{{"name", "held"}, {"select", {{"box", {{"min", {-1, -1, -1}}, {"max", {1, 1, -0.49}}}}}}}}},
      {"obstacles",
       {{{"type", "sphere"},
         {"center", {0.0, 0.0, start}},
         {"radius", r},
         {"keyframes",
          {{{"t", 0.0}, {"translation", {0.0, 0.0, 0.0}}},
           {{"t", 1.0}, {"translation", {0.0, 0.0, -(kPress + 2 * kThickness)}}}}}}}},
      {"contact", {{"stiffness", 3e3}, {"thickness", kThickness}}},
      {"solver", {{"steps", 4}, {"max_newton_iterations", 600}}}};
  std::ofstream(dir / "press.json") << scene.dump();
  const SceneFile file = load_scene((dir / "press.json").string());
  ASSERT_TRUE(file.embedded);
  const SceneRun run = run_scene(file, file.scene.options);
  ASSERT_TRUE(run.converged);
  const StepResult& last = run.result.steps.back();
  EXPECT_GT(last.contacts, 0);  // the lattice vertices alone never reach the layer
  EXPECT_GT(last.max_penetration, 0.0);
  EXPECT_LT(last.max_penetration, kThickness);  // every surface point outside the sphere
  EXPECT_TRUE(last.warnings.empty());
  fs::remove_all(dir);
}

// Without obstacles a contact surface changes nothing, bit for bit.
TEST(SurfaceContact, NoObstaclesNoChange) {
  const TriangleSurface ball = icosphere(2, kBallRadius);
  const Voxelization voxels = voxelize(ball, kCell);
  const Embedding embedding = embed(voxels, ball);
  const Mesh& mesh = voxels.lattice;
  double low = 1e9;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) low = std::min(low, mesh.positions(v, 2));
  SolveOptions options;
  options.body_force = {0.0, 0.0, -50.0};
  const ConstraintSet held = ConstraintSet::fixed("held", on_plane(mesh, 2, low));
  Simulation plain(mesh, StableNeoHookean::from_youngs_modulus(1e3, 0.3), {held}, options);
  Simulation surfaced(mesh, StableNeoHookean::from_youngs_modulus(1e3, 0.3), {held}, options);
  surfaced.set_contact_surface(embedding);
  const SolveResult a = plain.solve(), b = surfaced.solve();
  ASSERT_TRUE(a.converged);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.history.size(), b.history.size());
}

TEST(SurfaceContact, BadEmbeddingIsNamed) {
  const Mesh mesh = make_box_lattice(1, 1, 1, 1.0);
  SolveOptions options;
  options.obstacles = {Obstacle::plane({0, 0, -1}, {0, 0, 1})};
  options.contact.stiffness = 1.0;
  options.contact.thickness = 0.01;
  Simulation sim(mesh, StableNeoHookean::from_youngs_modulus(1.0, 0.3), {ConstraintSet::fixed("all", {0, 1, 2, 3})},
                 options);
  Embedding bad;
  bad.element = {0, 3};
  bad.weights.assign(16, 0.125);
  try {
    sim.set_contact_surface(bad);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("surface vertex 1"), std::string::npos) << e.what();
  }
  bad.element = {0, 0};
  bad.weights[3] = 0.5;
  EXPECT_THROW(sim.set_contact_surface(bad), Error);  // weights of vertex 0 do not sum to 1
}

}  // namespace
}  // namespace snh::test
