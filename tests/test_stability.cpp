// Stability on stiff and extreme cases: the small cases of `snh-gpu-bench
// stability` in both precisions without NaN, the Newton solver's recovery
// paths, and the float-to-double fallback.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "snh/error.h"
#include "snh/scenes.h"
#include "snh/simulation.h"
#include "stability.h"

namespace snh::test {
namespace {

bool all_finite(const Points& x) {
  for (double v : x.xyz())
    if (!std::isfinite(v)) return false;
  return true;
}

void expect_no_nan(const SolveResult& r, const std::string& what) {
  EXPECT_TRUE(all_finite(r.positions)) << what;
  for (const NewtonIteration& h : r.history) {
    EXPECT_FALSE(std::isnan(h.residual_norm)) << what << " iteration " << h.iteration;
    EXPECT_FALSE(std::isnan(h.energy)) << what << " iteration " << h.iteration;
  }
}

// Every case of the suite at a tiny size, float and double: no NaN anywhere.
class StabilitySmallCases : public ::testing::TestWithParam<std::string> {};

TEST_P(StabilitySmallCases, NoNanInEitherPrecision) {
  for (Precision p : {Precision::single, Precision::double_}) {
    const bench::StabilityRun r = bench::run_stability_case(GetParam(), p, 2);
    EXPECT_TRUE(r.error.empty()) << r.error;
    EXPECT_EQ(r.non_finite_positions, 0) << GetParam() << " " << r.precision;
    EXPECT_EQ(r.nan_in_history, 0) << GetParam() << " " << r.precision;
    EXPECT_FALSE(r.status.empty());
  }
}

INSTANTIATE_TEST_SUITE_P(Stability, StabilitySmallCases,
                         ::testing::Values("nu0.4999", "scramble_seed3", "crush_plane", "crush_line", "crush_point",
                                           "twist_2pi", "stretch_5x", "inverted_start", "flip_top", "push_through",
                                           "squash_nu0.499"),
                         [](const auto& info) {
                           std::string n = info.param;
                           for (char& c : n)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

// The squash between planes (a cube of 4^3 hexes in a box whose lid closes
// to a tenth of its height and opens; docs/validation.md), frictionless and
// with a rough floor and lid: squashed to a tenth of its volume, never a
// vertex deeper than the contact layer, and the rest volume and J = 1
// recovered after release, at each nu. At a lid height of 0.05 two of these
// six fail (the frictionless body at nu = 0.499 takes the squashed saddle's
// shear mode, the rough one at nu = 0.46 folds through itself).
TEST(Stability, SquashToATenthOfTheVolumeAndReleaseRecoversAtEachNu) {
  for (const char* name : {"squash_nu0.46", "squash_nu0.49", "squash_nu0.499", "squash_rough_nu0.46",
                           "squash_rough_nu0.49", "squash_rough_nu0.499"}) {
    SCOPED_TRACE(name);
    const bench::StabilityRun r = bench::run_stability_case(name, Precision::double_, 4);
    EXPECT_TRUE(r.error.empty()) << r.error;
    EXPECT_EQ(r.non_finite_positions, 0);
    EXPECT_EQ(r.nan_in_history, 0);
    EXPECT_EQ(r.contact_thickness, 0.01);
    EXPECT_LT(r.min_volume_ratio, 0.105);
    EXPECT_GT(r.max_penetration, 0.0);
    EXPECT_LE(r.max_penetration, r.contact_thickness);
    EXPECT_NEAR(r.volume_ratio, 1.0, 1e-3);
    EXPECT_NEAR(r.min_j, 1.0, 1e-3);
    EXPECT_NEAR(r.max_j, 1.0, 1e-3);
    EXPECT_EQ(r.inverted_elements, 0);
  }
}

// `stability --squash-height H`: the lid's layer edge comes down to H (of
// the unit body's height) and is held there from t = 0.3 to 0.4; heights
// outside (0, 1) are refused.
TEST(Stability, SquashHeightSetsTheLid) {
  for (double height : {0.05, bench::kDefaultSquashHeight}) {
    const Scene s = bench::make_stability_case("squash_rough_nu0.49", Precision::double_, 2, height);
    const Obstacle& lid = s.options.obstacles.back();
    ASSERT_TRUE(static_cast<bool>(lid.motion));
    const double d = s.options.contact.thickness;
    for (double t : {0.3, 0.35, 0.4}) EXPECT_NEAR(lid.motion(t).apply(lid.point)[2] - d, height, 1e-12) << t;
    EXPECT_NEAR(lid.motion(0.0).apply(lid.point)[2] - d, 1.0 + d, 1e-12);
    std::ostringstream text;
    text << "lid closed to " << height << " of its height";
    EXPECT_NE(s.description.find(text.str()), std::string::npos) << s.description;
  }
  for (double bad : {0.0, 1.0, -0.1, std::nan("")})
    EXPECT_THROW(bench::make_stability_case("squash_nu0.49", Precision::double_, 2, bad), snh::Error) << bad;
}

// squash_h<H>_nu<nu>: the frictionless squash at its own lid height H,
// whatever --squash-height says, at 5% and 3% for nu 0.46, 0.49, 0.499.
TEST(Stability, SquashHeightCasesCloseTheLidToTheirOwnHeight) {
  int cases = 0;
  for (const std::string& name : bench::stability_case_names()) {
    if (name.rfind("squash_h", 0) != 0) continue;
    ++cases;
    const double height = std::stod(name.substr(8, name.find("_nu") - 8));
    const Scene s = bench::make_stability_case(name, Precision::double_, 2, bench::kDefaultSquashHeight);
    const Obstacle& lid = s.options.obstacles.back();
    ASSERT_TRUE(static_cast<bool>(lid.motion)) << name;
    EXPECT_NEAR(lid.motion(0.35).apply(lid.point)[2] - s.options.contact.thickness, height, 1e-12) << name;
    EXPECT_FALSE(lid.friction.has_value()) << name;  // frictionless
  }
  EXPECT_EQ(cases, 6);
  EXPECT_THROW(bench::make_stability_case("squash_hx_nu0.49", Precision::double_, 2), snh::Error);
}

TEST(Stability, SmallCasesConvergeInDouble) {
  for (const char* name : {"nu0.4999", "crush_point", "twist_2pi", "inverted_start"}) {
    const bench::StabilityRun r = bench::run_stability_case(name, Precision::double_, 2);
    EXPECT_TRUE(r.converged) << name << ": " << r.status;
  }
}

// A free vertex far away (1e6 cells): in float its elements' energy is huge
// and the first Newton directions are poor. Whatever the solver does, it
// must never accept a non-finite state, and it reports what it did.
TEST(Stability, FarVertexNeverProducesNan) {
  for (Precision p : {Precision::single, Precision::double_}) {
    Scene s = bench::make_stability_case("crush_plane", p, 2);
    s.options.initial_positions = s.mesh.positions;
    const size_t v = s.mesh.vertex_count() - 1;  // the top corner, free
    s.options.initial_positions(v, 0) = 1e6;
    s.options.max_newton_iterations = 60;
    QuasistaticSolver solver(s.mesh, s.material, s.constraints, s.options);
    const SolveResult r = solver.solve();
    expect_no_nan(r, to_string(p));
    ASSERT_EQ(r.steps.size(), 1u);
    EXPECT_NE(r.steps[0].status, StepStatus::none);
  }
}

// Crushed to a point: F = 0 in every free element (zero gradient there).
TEST(Stability, CrushToPointRecoversInBothPrecisions) {
  for (Precision p : {Precision::single, Precision::double_}) {
    const Scene s = bench::make_stability_case("crush_point", p, 2);
    QuasistaticSolver solver(s.mesh, s.material, s.constraints, s.options);
    const SolveResult r = solver.solve();
    expect_no_nan(r, to_string(p));
    EXPECT_TRUE(r.converged) << to_string(p) << " " << r.steps[0].status;
    EXPECT_EQ(r.inverted_elements, 0);
  }
}

// A vertex so far out that float's energy overflows: the first state is not
// finite, the step stops at once with "non_finite_state" and the positions
// are returned as they were (finite), never a NaN.
TEST(Stability, NonFiniteEnergyIsNeverAccepted) {
  Scene s = bench::make_stability_case("crush_plane", Precision::single, 2);
  s.options.initial_positions = s.mesh.positions;
  const size_t v = s.mesh.vertex_count() - 1;
  s.options.initial_positions(v, 0) = 1e30;
  QuasistaticSolver solver(s.mesh, s.material, s.constraints, s.options);
  const SolveResult r = solver.solve();
  ASSERT_EQ(r.steps.size(), 1u);
  EXPECT_EQ(r.steps[0].status, StepStatus::non_finite_state);
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(all_finite(r.positions));
  EXPECT_EQ(r.positions(v, 0), 1e30f);
}

// One CG iteration per Newton step on a hard start: poor directions, finite
// positions after every iteration; any steepest-descent retry after a failed
// line search must have taken a step. (This start does not provoke a failed
// line search on pocl; the retry path is not forced here.)
TEST(Stability, PoorDirectionsKeepPositionsFinite) {
  int retries = 0;
  for (Precision p : {Precision::single, Precision::double_}) {
    Scene s = bench::make_stability_case("flip_top", p, 2);
    s.options.max_cg_iterations = 1;
    s.options.max_newton_iterations = 40;
    s.options.on_iteration = [&](const NewtonIteration&, const Points& x) { EXPECT_TRUE(all_finite(x)); };
    QuasistaticSolver solver(s.mesh, s.material, s.constraints, s.options);
    const SolveResult r = solver.solve();
    expect_no_nan(r, to_string(p));
    for (const NewtonIteration& h : r.history)
      if (contains(h.recovery, RecoveryAction::line_search_steepest_descent)) {
        ++retries;
        EXPECT_GT(h.step_length, 0.0);
      } else if (contains(h.recovery, RecoveryAction::line_search_steepest_descent_failed)) {
        ++retries;
      }
  }
  RecordProperty("steepest_descent_retries", retries);
}

// A tolerance below float's floor: float stagnates (or runs out of
// iterations); with fallback_to_double the step is re-solved in double and
// converges, and the result says so.
TEST(Stability, FallbackToDoubleRescuesAFloatStep) {
  Scene s = bench::make_stability_case("nu0.49", Precision::single, 2);
  s.options.load_steps = 1;
  s.options.absolute_tolerance = 1e-11;
  s.options.max_newton_iterations = 60;
  {
    QuasistaticSolver solver(s.mesh, s.material, s.constraints, s.options);
    const SolveResult r = solver.solve();
    ASSERT_EQ(r.steps.size(), 1u);
    EXPECT_FALSE(r.converged);
    EXPECT_EQ(r.steps[0].precision_used, Precision::single);
    EXPECT_TRUE(r.steps[0].fallback.empty());
    expect_no_nan(r, "float");
  }
  s.options.fallback_to_double = true;
  QuasistaticSolver solver(s.mesh, s.material, s.constraints, s.options);
  if (!solver.device().has_fp64) GTEST_SKIP() << "device without fp64";
  const SolveResult r = solver.solve();
  ASSERT_EQ(r.steps.size(), 1u);
  EXPECT_TRUE(r.converged) << r.steps[0].status;
  EXPECT_EQ(r.steps[0].precision_used, Precision::double_);
  EXPECT_NE(r.steps[0].fallback.find("re-solved in double"), std::string::npos) << r.steps[0].fallback;
  EXPECT_LE(r.final_residual_norm, 1e-11);
  bool warned = false;
  for (const std::string& w : r.warnings) warned = warned || w.find("re-solved in double") != std::string::npos;
  EXPECT_TRUE(warned);
  bool marked = false;
  for (const NewtonIteration& h : r.history) marked = marked || contains(h.recovery, RecoveryAction::double_fallback);
  EXPECT_TRUE(marked);
  expect_no_nan(r, "fallback");
}

// Fallback off, or a double solve: nothing changes (precision_used says which).
TEST(Stability, NoFallbackWhenFloatConverges) {
  Scene s = bench::make_stability_case("nu0.45", Precision::single, 2);
  s.options.fallback_to_double = true;
  QuasistaticSolver solver(s.mesh, s.material, s.constraints, s.options);
  const SolveResult r = solver.solve();
  EXPECT_TRUE(r.converged);
  for (const StepResult& step : r.steps) {
    EXPECT_EQ(step.precision_used, Precision::single);
    EXPECT_TRUE(step.fallback.empty());
  }
}

}  // namespace
}  // namespace snh::test

namespace snh::test {
namespace {

// The stability command's files from its records: the CSV row and the
// Markdown row of a run with obstacles (deeper than the layer, recoveries
// with a comma-free CSV form) and of one that threw; the JSON's runs and
// the count of runs with a NaN or an error.
TEST(Stability, ReportWritesEachRunAsRecordsThroughTheTableWriter) {
  bench::StabilityRun a;
  a.name = "squash_nu0.49";
  a.precision = "double";
  a.converged = true;
  a.status = "converged";
  a.newton_iterations = 12;
  a.cg_iterations = 345;
  a.seconds = 1.5;
  a.min_j = 0.25;
  a.max_j = 1.5;
  a.volume_ratio = 1.0;
  a.min_volume_ratio = 0.1;
  a.max_penetration = 0.02;
  a.contact_thickness = 0.01;
  a.recoveries = {{"x", 2}, {"y", 1}};
  a.surface_intersections = {0, 3, 1};
  bench::StabilityRun b;
  b.name = "nu0.45";
  b.precision = "float";
  b.status = "stagnated";
  b.error = "boom";
  b.min_j = std::nan("");
  const bench::StabilityReport r = bench::stability_report({{a, "a note"}, {b, ""}}, 4, 0.1);
  EXPECT_EQ(bench::csv_text(r.csv),
            "case,precision,converged,status,newton,cg,seconds,min_j,max_j,inverted_at_start,inverted,volume_ratio,"
            "min_volume_ratio,max_penetration,contact_thickness,non_finite_positions,nan_in_history,recovery,"
            "max_surface_intersections,note\n"
            "squash_nu0.49,double,yes,converged,12,345,1.500,0.250000,1.500000,0,0,1.000000,0.100000,0.020000,"
            "0.010000,0,0,x x2; y x1,3,a note\n"
            "nu0.45,float,no,stagnated,0,0,0.000,NaN,0.000000,0,0,0.000000,0.000000,,,0,0,-,0,\n");
  const std::string md = bench::markdown_text(r.markdown);
  EXPECT_NE(md.find("| squash_nu0.49 | double | yes | converged | 12 | 345 | 1.50 | 0.250 | 1.500 | 0 → 0 | 1.0000 | "
                    "0.1000 | 0.02000 / 0.01000 **deeper** | none | x x2; y x1 | **3** | a note |\n"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| nu0.45 | float | **no** | error: boom |"), std::string::npos) << md;
  EXPECT_EQ(r.problems, 1);
  EXPECT_EQ(r.document["runs_with_nan_or_error"], 1);
  EXPECT_EQ(r.document["squash_height"], 0.1);
  ASSERT_EQ(r.document["runs"].size(), 2u);
  EXPECT_EQ(r.document["runs"][0]["max_surface_intersections"], 3);
  EXPECT_EQ(r.document["runs"][0]["note"], "a note");
  EXPECT_EQ(r.document["runs"][1]["min_j"], "NaN");
}

}  // namespace
}  // namespace snh::test
