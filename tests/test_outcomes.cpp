// The solve outcomes' names: every value prints as the text the reports
// have always carried and parses back to itself.
#include <gtest/gtest.h>

#include <sstream>

#include "snh/error.h"
#include "snh/simulation.h"

namespace snh::test {
namespace {

TEST(Outcomes, StepStatusNamesRoundTrip) {
  const std::pair<StepStatus, const char*> expected[] = {
      {StepStatus::none, ""},
      {StepStatus::converged, "converged"},
      {StepStatus::max_newton_iterations, "max_newton_iterations"},
      {StepStatus::line_search_failed, "line_search_failed"},
      {StepStatus::stagnated, "stagnated"},
      {StepStatus::non_finite_state, "non_finite_state"},
      {StepStatus::cancelled, "cancelled"},
  };
  for (const auto& [status, name] : expected) {
    EXPECT_STREQ(to_string(status), name);
    EXPECT_EQ(parse_step_status(name), status);
    std::ostringstream out;
    out << status;
    EXPECT_EQ(out.str(), name);
  }
  EXPECT_THROW(parse_step_status("converge"), Error);
}

TEST(Outcomes, CgStopNamesRoundTrip) {
  const std::pair<CgStop, const char*> expected[] = {
      {CgStop::none, ""},
      {CgStop::converged, "converged"},
      {CgStop::max_iterations, "max_iterations"},
      {CgStop::negative_curvature, "negative_curvature"},
      {CgStop::breakdown, "breakdown"},
  };
  for (const auto& [stop, name] : expected) {
    EXPECT_STREQ(to_string(stop), name);
    EXPECT_EQ(parse_cg_stop(name), stop);
  }
  NewtonIteration record;
  record.cg_stop = CgStop::breakdown;
  record.steepest_descent = true;
  EXPECT_EQ(cg_stop_text(record), "breakdown+steepest_descent");
  EXPECT_THROW(parse_cg_stop("diverged"), Error);
}

TEST(Outcomes, RecoveryTextsRoundTrip) {
  for (const char* text :
       {"cg_breakdown -> steepest_descent", "non_finite_direction -> steepest_descent",
        "non_descent -> steepest_descent", "cg_breakdown -> partial_cg_direction",
        "line_search_failed -> steepest_descent", "line_search_failed -> steepest_descent failed",
        "non_finite_residual -> shorter_step", "negative_curvature -> step x8", "float stagnated -> double"}) {
    EXPECT_EQ(to_string(parse_recovery(text)), text);
  }
  const std::string joined = "float max_newton_iterations -> double; negative_curvature -> step x4";
  const std::vector<Recovery> list = parse_recoveries(joined);
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[0].action, RecoveryAction::double_fallback);
  EXPECT_EQ(list[0].float_status, StepStatus::max_newton_iterations);
  EXPECT_EQ(list[1].action, RecoveryAction::extended_step);
  EXPECT_EQ(list[1].factor, 4);
  EXPECT_EQ(to_string(list), joined);
  EXPECT_TRUE(contains(list, RecoveryAction::extended_step));
  EXPECT_FALSE(contains(list, RecoveryAction::shorter_step));
  EXPECT_TRUE(parse_recoveries("").empty());
  EXPECT_THROW(parse_recovery("negative_curvature -> step xx"), Error);
  EXPECT_THROW(parse_recovery("float sideways -> double"), Error);
}

}  // namespace
}  // namespace snh::test
