// Volume change and the range of J over a deformed mesh's quadrature points,
// and what a step's end state warns of (solver/simulation/step_assessment.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "fem/rest_state.h"
#include "snh/simulation.h"
#include "solver/simulation/step_assessment.h"

namespace snh {

namespace solver {

DeformationStatistics deformation_statistics(const Mesh& mesh, const fem::RestState& rest,
                                             const std::vector<double>& x) {
  DeformationStatistics s;
  s.min_j = std::numeric_limits<double>::infinity();
  s.max_j = -std::numeric_limits<double>::infinity();
  double volume = 0.0;
  for (size_t e = 0; e < mesh.element_count(); ++e) {
    bool inverted = false;
    for (int q = 0; q < rest.quadrature; ++q) {
      double f[9];
      fem::deformation_gradient(mesh, rest, x.data(), e, q, f);
      const double j = fem::determinant(f);
      s.min_j = std::min(s.min_j, j);
      s.max_j = std::max(s.max_j, j);
      inverted = inverted || !(j > 0.0);
      volume += j * rest.weight(e, q);
    }
    s.inverted_elements += inverted ? 1 : 0;
  }
  s.volume_ratio = volume / rest.rest_volume;
  return s;
}

namespace {

std::string number(double v) {
  std::ostringstream out;
  out.precision(3);
  out << v;
  return out.str();
}

}  // namespace

void assess_step(const Mesh& mesh, const fem::RestState& rest, const std::vector<double>& x,
                 const SolveOptions& options, const std::string& label, StepResult& step) {
  const DeformationStatistics stats = deformation_statistics(mesh, rest, x);
  step.min_j = stats.min_j;
  step.inverted_elements = stats.inverted_elements;
  if (step.status != StepStatus::converged && step.status != StepStatus::cancelled && step.status != StepStatus::none)
    step.warnings.push_back(
        warning_text(ResultWarning::not_converged, label + " ended " + to_string(step.status) + " at residual " +
                                                       number(step.residual_norm) + " after " +
                                                       std::to_string(step.newton_iterations) + " Newton iterations"));
  // A NaN min J (a non-finite state) counts its elements as inverted too.
  if (stats.inverted_elements > 0) {
    step.warnings.push_back(warning_text(ResultWarning::inverted_elements,
                                         label + " ended with " + std::to_string(stats.inverted_elements) +
                                             " inverted elements (J <= 0), min J " + number(stats.min_j)));
    if (options.fail_on_inverted && step.status != StepStatus::cancelled) step.status = StepStatus::inverted_elements;
  }
  // (With self-contact max_penetration also covers spring lengths: not a depth.)
  if (!options.obstacles.empty() && !options.contact.self && step.max_penetration > options.contact.thickness)
    step.warnings.push_back(
        warning_text(ResultWarning::obstacle_penetration,
                     label + " ended with a point " + number(step.max_penetration - options.contact.thickness) +
                         " inside an obstacle (contact layer " + number(options.contact.thickness) + ")"));
}

}  // namespace solver

DeformationStatistics deformation_statistics(const Mesh& mesh, const Points& x) {
  return solver::deformation_statistics(mesh, fem::compute_rest_state(mesh), x.xyz());
}

}  // namespace snh
