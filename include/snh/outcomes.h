// How solves end and what the Newton solver did on the way, as enums with
// printable names (the names of JSON, CSV and reports). Each enum's names
// come from one table, shared by to_string and its parse function; parsing
// an unknown name throws snh::Error listing the known ones.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace snh {

// How a load step's (or time step's) Newton solve ended.
enum class StepStatus {
  none,                   // "": no solve (a default-constructed result)
  converged,              // "converged": the residual reached the tolerance
  max_newton_iterations,  // "max_newton_iterations": SolveOptions::max_newton_iterations reached
  line_search_failed,     // "line_search_failed": no trial lowered the energy, steepest descent included
  // "stagnated": no 1% residual decrease in 8 iterations: the precision
  // floor, or a vertex resting exactly at a contact layer's edge
  // (docs/validation.md)
  stagnated,
  non_finite_state,  // "non_finite_state": a non-finite residual or energy at an iterate
  cancelled,         // "cancelled": the progress callback returned false
  // "inverted_elements": the step ended with elements with J <= 0 and
  // SolveOptions::fail_on_inverted (or FrameOptions::fail_on_inverted) made
  // that a failure; StepResult::converged still says whether Newton met
  // its tolerance.
  inverted_elements,
};

const char* to_string(StepStatus status);
StepStatus parse_step_status(const std::string& text);  // the names above
std::ostream& operator<<(std::ostream& out, StepStatus status);

// What a result warns of. Each warning in StepResult::warnings,
// SolveResult::warnings and FrameRecord::warnings that reports damage
// begins with its kind's name and ": " (warning_text), so that a program can
// tell them apart (has_warning) and a person can read them.
enum class ResultWarning {
  // "inverted_elements": elements with J <= 0 at some quadrature point at
  // the end of the step (or frame), whether or not Newton converged.
  inverted_elements,
  // "not_converged": the Newton solve stopped short of its tolerance (the
  // iteration limit, a failed line search, stagnation, a non-finite state);
  // the text names the status and the residual.
  not_converged,
  // "obstacle_penetration": a vertex (or embedded surface point) ended
  // deeper in an obstacle's contact layer than the layer is thick, that is
  // inside the obstacle itself.
  obstacle_penetration,
  // "surface_intersections": the surface passes through itself at the end
  // of the step: with self-contact, after a prescribed motion (a target, a
  // bone) moved it through itself, which self-contact cannot stop; in
  // scene files also the output surface's count (output.check_intersections).
  surface_intersections,
};

const char* to_string(ResultWarning kind);
ResultWarning parse_result_warning(const std::string& text);  // the names above
// "<name>: <detail>".
std::string warning_text(ResultWarning kind, const std::string& detail);
// Whether one of `warnings` is of that kind (begins with its name and ": ").
bool has_warning(const std::vector<std::string>& warnings, ResultWarning kind);

// Why a Newton iteration's conjugate gradient solve stopped.
enum class CgStop {
  none,                // "": no linear solve (the iteration that found convergence or stopped)
  converged,           // "converged": the forcing term's relative residual reached
  max_iterations,      // "max_iterations": SolveOptions::max_cg_iterations reached
  negative_curvature,  // "negative_curvature": a direction of non-positive curvature met
  breakdown,           // "breakdown": a non-finite or vanishing scalar in the recurrence
};

const char* to_string(CgStop stop);
CgStop parse_cg_stop(const std::string& text);  // the names above
std::ostream& operator<<(std::ostream& out, CgStop stop);

// What the Newton solver did to get past trouble.
enum class RecoveryAction {
  // CG's direction was no descent direction: the preconditioned steepest
  // descent replaced it, after a CG breakdown, a non-finite direction, or a
  // direction along which the energy rises.
  cg_breakdown_steepest_descent,          // "cg_breakdown -> steepest_descent"
  non_finite_direction_steepest_descent,  // "non_finite_direction -> steepest_descent"
  non_descent_steepest_descent,           // "non_descent -> steepest_descent"
  // CG broke down but its partial direction descends and was kept.
  cg_breakdown_partial_direction,  // "cg_breakdown -> partial_cg_direction"
  // The line search along CG's direction failed; the preconditioned
  // steepest descent was tried, and succeeded or failed too.
  line_search_steepest_descent,         // "line_search_failed -> steepest_descent"
  line_search_steepest_descent_failed,  // "line_search_failed -> steepest_descent failed"
  // A trial with finite energy but a non-finite residual was rejected.
  shorter_step,  // "non_finite_residual -> shorter_step"
  // Negative curvature along the accepted full step: the step was extended
  // by Recovery::factor.
  extended_step,  // "negative_curvature -> step x" followed by the factor
  // The step did not converge in float and was re-solved in double
  // (SolveOptions::fallback_to_double); Recovery::float_status says how
  // float ended. On the first record of the re-solve.
  double_fallback,  // "float -> double", printed as "float <status> -> double"
  // Newton met its tolerance with an element inverted: the free vertices
  // were perturbed (by 1% of the vertex spacing) and Newton went on, to
  // leave a saddle such as a symmetric crush (docs/validation.md).
  inverted_equilibrium_perturbed,  // "inverted_equilibrium -> perturbation"
  // Newton after the perturbation found no lower equilibrium: the
  // inverted one (a strict local minimum) was restored and kept.
  inverted_equilibrium_kept,  // "perturbation -> inverted_equilibrium_kept"
};

const char* to_string(RecoveryAction action);
RecoveryAction parse_recovery_action(const std::string& text);  // the names above

struct Recovery {
  RecoveryAction action = RecoveryAction::shorter_step;
  int factor = 0;                              // extended_step: 2, 4, 8, ...
  StepStatus float_status = StepStatus::none;  // double_fallback: how the float solve ended

  bool operator==(const Recovery& o) const {
    return action == o.action && factor == o.factor && float_status == o.float_status;
  }
  bool operator!=(const Recovery& o) const { return !(*this == o); }
};

// The text of one recovery (the action's name with its factor or status),
// and of a list of them joined by "; "; parse_recoveries reads that text
// back ("" for none).
std::string to_string(const Recovery& recovery);
std::string to_string(const std::vector<Recovery>& recoveries);
Recovery parse_recovery(const std::string& text);
std::vector<Recovery> parse_recoveries(const std::string& text);
// Whether `recoveries` holds `action`.
bool contains(const std::vector<Recovery>& recoveries, RecoveryAction action);

}  // namespace snh
