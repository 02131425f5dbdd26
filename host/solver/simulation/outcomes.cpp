// Names of the solve outcomes (snh/outcomes.h): one table per enum, read by
// both directions (fem/name_table.h).
#include "snh/outcomes.h"

#include <ostream>

#include "fem/name_table.h"
#include "snh/error.h"
#include "snh/simulation.h"

namespace snh {

namespace {

constexpr NameTable<StepStatus, 8> kStepStatusNames{{
    {StepStatus::none, ""},
    {StepStatus::converged, "converged"},
    {StepStatus::max_newton_iterations, "max_newton_iterations"},
    {StepStatus::line_search_failed, "line_search_failed"},
    {StepStatus::stagnated, "stagnated"},
    {StepStatus::non_finite_state, "non_finite_state"},
    {StepStatus::cancelled, "cancelled"},
    {StepStatus::inverted_elements, "inverted_elements"},
}};

constexpr NameTable<ResultWarning, 4> kResultWarningNames{{
    {ResultWarning::inverted_elements, "inverted_elements"},
    {ResultWarning::not_converged, "not_converged"},
    {ResultWarning::obstacle_penetration, "obstacle_penetration"},
    {ResultWarning::surface_intersections, "surface_intersections"},
}};

constexpr const char* kWarningSeparator = ": ";

constexpr NameTable<CgStop, 5> kCgStopNames{{
    {CgStop::none, ""},
    {CgStop::converged, "converged"},
    {CgStop::max_iterations, "max_iterations"},
    {CgStop::negative_curvature, "negative_curvature"},
    {CgStop::breakdown, "breakdown"},
}};

constexpr NameTable<RecoveryAction, 11> kRecoveryNames{{
    {RecoveryAction::cg_breakdown_steepest_descent, "cg_breakdown -> steepest_descent"},
    {RecoveryAction::non_finite_direction_steepest_descent, "non_finite_direction -> steepest_descent"},
    {RecoveryAction::non_descent_steepest_descent, "non_descent -> steepest_descent"},
    {RecoveryAction::cg_breakdown_partial_direction, "cg_breakdown -> partial_cg_direction"},
    {RecoveryAction::line_search_steepest_descent, "line_search_failed -> steepest_descent"},
    {RecoveryAction::line_search_steepest_descent_failed, "line_search_failed -> steepest_descent failed"},
    {RecoveryAction::shorter_step, "non_finite_residual -> shorter_step"},
    {RecoveryAction::extended_step, "negative_curvature -> step x"},
    {RecoveryAction::double_fallback, "float -> double"},
    {RecoveryAction::inverted_equilibrium_perturbed, "inverted_equilibrium -> perturbation"},
    {RecoveryAction::inverted_equilibrium_kept, "perturbation -> inverted_equilibrium_kept"},
}};

constexpr const char* kFloatPrefix = "float ";
constexpr const char* kDoubleSuffix = " -> double";

bool starts_with(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

const char* to_string(StepStatus status) { return name_of(kStepStatusNames, status); }
StepStatus parse_step_status(const std::string& text) { return value_named(kStepStatusNames, text, "step status"); }
std::ostream& operator<<(std::ostream& out, StepStatus status) { return out << to_string(status); }

const char* to_string(ResultWarning kind) { return name_of(kResultWarningNames, kind); }
ResultWarning parse_result_warning(const std::string& text) {
  return value_named(kResultWarningNames, text, "result warning");
}

std::string warning_text(ResultWarning kind, const std::string& detail) {
  return to_string(kind) + std::string(kWarningSeparator) + detail;
}

bool has_warning(const std::vector<std::string>& warnings, ResultWarning kind) {
  const std::string prefix = to_string(kind) + std::string(kWarningSeparator);
  for (const std::string& w : warnings)
    if (starts_with(w, prefix)) return true;
  return false;
}

const char* to_string(CgStop stop) { return name_of(kCgStopNames, stop); }
CgStop parse_cg_stop(const std::string& text) { return value_named(kCgStopNames, text, "CG stop"); }
std::ostream& operator<<(std::ostream& out, CgStop stop) { return out << to_string(stop); }

const char* to_string(RecoveryAction action) { return name_of(kRecoveryNames, action); }
RecoveryAction parse_recovery_action(const std::string& text) {
  return value_named(kRecoveryNames, text, "recovery action");
}

std::string to_string(const Recovery& recovery) {
  switch (recovery.action) {
    case RecoveryAction::extended_step:
      return to_string(recovery.action) + std::to_string(recovery.factor);
    case RecoveryAction::double_fallback:
      return kFloatPrefix + std::string(to_string(recovery.float_status)) + kDoubleSuffix;
    default:
      return to_string(recovery.action);
  }
}

std::string to_string(const std::vector<Recovery>& recoveries) {
  std::string text;
  for (const Recovery& r : recoveries) text += (text.empty() ? "" : "; ") + to_string(r);
  return text;
}

Recovery parse_recovery(const std::string& text) {
  Recovery r;
  const std::string extended = to_string(RecoveryAction::extended_step);
  if (starts_with(text, extended) && text.size() > extended.size()) {
    r.action = RecoveryAction::extended_step;
    try {
      size_t used = 0;
      r.factor = std::stoi(text.substr(extended.size()), &used);
      if (used == text.size() - extended.size()) return r;
    } catch (const std::exception&) {
    }
    throw Error("recovery: expected a factor after '" + extended + "', got '" + text + "'");
  }
  if (starts_with(text, kFloatPrefix) && ends_with(text, kDoubleSuffix) &&
      text.size() > std::string(kFloatPrefix).size() + std::string(kDoubleSuffix).size()) {
    r.action = RecoveryAction::double_fallback;
    const size_t begin = std::string(kFloatPrefix).size();
    r.float_status = parse_step_status(text.substr(begin, text.size() - begin - std::string(kDoubleSuffix).size()));
    return r;
  }
  r.action = parse_recovery_action(text);
  return r;
}

std::vector<Recovery> parse_recoveries(const std::string& text) {
  std::vector<Recovery> out;
  size_t begin = 0;
  while (begin < text.size()) {
    const size_t end = text.find("; ", begin);
    out.push_back(parse_recovery(text.substr(begin, end == std::string::npos ? std::string::npos : end - begin)));
    if (end == std::string::npos) break;
    begin = end + 2;
  }
  return out;
}

bool contains(const std::vector<Recovery>& recoveries, RecoveryAction action) {
  for (const Recovery& r : recoveries)
    if (r.action == action) return true;
  return false;
}

std::string cg_stop_text(const NewtonIteration& record) {
  return std::string(to_string(record.cg_stop)) + (record.steepest_descent ? "+steepest_descent" : "");
}

}  // namespace snh
