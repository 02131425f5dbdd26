#include "solver/contact/prescribed_crossing.h"

#include "snh/outcomes.h"
#include "snh/surface_intersections.h"

namespace snh::solver {

PrescribedCrossingCheck::PrescribedCrossingCheck(const BarrierContact& contact, const Points& rest)
    : contact_(&contact), triangles_(contact.triangles().begin(), contact.triangles().end()) {
  at_rest_ = intersecting(rest);
}

void PrescribedCrossingCheck::placed(const Points& before, const Points& after) {
  std::vector<double> move(after.xyz().size());
  const double* a = after.data();
  const double* b = before.data();
  bool moved = false;
  for (size_t i = 0; i < move.size(); ++i) {
    move[i] = a[i] - b[i];
    moved = moved || move[i] != 0.0;
  }
  if (moved && !(contact_->step_bound(before.xyz(), move) >= 1.0)) unclear_ = true;
}

void PrescribedCrossingCheck::assess(const Points& x, const std::string& label, StepResult& step) {
  if (!unclear_) return;
  unclear_ = false;
  const size_t now = intersecting(x);
  if (now <= at_rest_) return;
  std::string detail =
      label + " ended with " + std::to_string(now) + " intersecting triangle pairs of the " + "self-contact surface";
  if (at_rest_ > 0) detail += " (" + std::to_string(at_rest_) + " at rest)";
  detail += ": a prescribed motion moved it through itself, which self-contact cannot stop";
  step.warnings.push_back(warning_text(ResultWarning::surface_intersections, detail));
}

size_t PrescribedCrossingCheck::intersecting(const Points& x) const {
  const std::vector<int>& carrier = contact_->carriers();
  if (carrier.empty()) return count_self_intersections(x, triangles_).intersecting_pairs;
  // The embedded surface: each vertex at sum_k w_k x(v_k) over its 8 carriers.
  const std::vector<double>& weight = contact_->weights();
  Points surface(contact_->surface_vertex_count());
  for (size_t s = 0; s < contact_->surface_vertex_count(); ++s)
    for (size_t k = 0; k < 8; ++k)
      for (int d = 0; d < 3; ++d) surface(s, d) += weight[8 * s + k] * x(static_cast<size_t>(carrier[8 * s + k]), d);
  return count_self_intersections(surface, triangles_).intersecting_pairs;
}

}  // namespace snh::solver
