// The float-to-double fallback (SolveOptions::fallback_to_double): a float
// step that ends in anything but convergence or cancellation is solved again
// in double from the step's start, and the solve's remaining steps run in
// double. The failure is recorded as the first Recovery of the double
// solve's first Newton record and in a warning naming the step.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "snh/simulation.h"

namespace snh::solver {

class PrecisionFallback {
 public:
  // At a solve's start: its steps run in `precision` again.
  void begin(Precision precision) {
    fell_back_ = false;
    in_double_ = precision == Precision::double_;
  }

  // One step in the current precision. in_float() and in_double() run the
  // step's Newton solve from the current state in the float or the double
  // engine; rewind() puts the state back where the step started. may_fall_back:
  // a float solve asked for the fallback; has_fp64: the device can run it.
  template <typename InFloat, typename InDouble, typename Rewind>
  StepResult step(int s, int steps, Precision precision, bool may_fall_back, bool has_fp64, SolveResult& result,
                  InFloat&& in_float, InDouble&& in_double, Rewind&& rewind);

 private:
  bool fell_back_ = false, in_double_ = true;
};

template <typename InFloat, typename InDouble, typename Rewind>
StepResult PrecisionFallback::step(int s, int steps, Precision precision, bool may_fall_back, bool has_fp64,
                                   SolveResult& result, InFloat&& in_float, InDouble&& in_double, Rewind&& rewind) {
  StepResult step;
  if (!in_double_) {
    step = in_float();
    step.precision_used = precision;
  }
  const bool failed = !in_double_ && !step.converged && step.status != StepStatus::cancelled;
  if (may_fall_back && (fell_back_ || failed)) {
    if (!fell_back_ && !has_fp64) {
      result.warnings.push_back("step " + std::to_string(s) + ": float did not converge (" + to_string(step.status) +
                                ") and fallback_to_double was asked, but the device has no fp64");
    } else {
      std::string note;
      if (!fell_back_) {
        std::ostringstream why;
        why << "float " << step.status << " after " << step.newton_iterations << " Newton / " << step.cg_iterations
            << " CG iterations (residual " << step.residual_norm << "); re-solved in double";
        note = why.str();
        rewind();
      }
      const size_t first_record = result.history.size();
      StepResult redo = in_double();
      redo.precision_used = Precision::double_;
      if (!fell_back_) {
        if (first_record < result.history.size()) {
          Recovery fallback;
          fallback.action = RecoveryAction::double_fallback;
          fallback.float_status = step.status;
          std::vector<Recovery>& r = result.history[first_record].recovery;
          r.insert(r.begin(), fallback);
        }
        redo.newton_iterations += step.newton_iterations;
        redo.cg_iterations += step.cg_iterations;
        redo.fallback = note;
        result.warnings.push_back(
            "step " + std::to_string(s) + ": " + note +
            (redo.converged ? " (converged)" : " (did not converge: " + std::string(to_string(redo.status)) + ")") +
            (s < steps ? "; the remaining steps run in double" : ""));
      } else {
        redo.fallback = "double (after a float failure in an earlier step)";
      }
      fell_back_ = true;
      step = redo;
    }
  } else if (in_double_) {
    step = in_double();
    step.precision_used = Precision::double_;
  }
  return step;
}

}  // namespace snh::solver
