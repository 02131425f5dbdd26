// A prescribed motion (a constraint set's target, a bone) is placed as
// given: barrier self-contact cannot stop it from moving the surface through
// itself, and once crossed the barrier does not see the crossing. This
// check runs the barrier's continuous collision detection over each
// placement; where it does not clear the move, the step's end surface is
// counted exactly (snh/surface_intersections.h) and more intersecting
// triangle pairs than at rest give a `surface_intersections` warning
// (snh/outcomes.h). A placement the CCD clears costs one CCD and no count.
// Internal to the library.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "snh/simulation.h"
#include "solver/contact/barrier_contact.h"

namespace snh::solver {

class PrescribedCrossingCheck {
 public:
  // The barrier's surface and the lattice (or mesh) positions at rest.
  PrescribedCrossingCheck(const BarrierContact& contact, const Points& rest);

  // x before and after a placement: notes whether the CCD cleared the move.
  void placed(const Points& before, const Points& after);
  // At a step's end x: the warning when a placement since the last call was
  // not cleared and the surface has more intersecting pairs than at rest.
  void assess(const Points& x, const std::string& label, StepResult& step);

  size_t intersecting_at_rest() const { return at_rest_; }

 private:
  size_t intersecting(const Points& x) const;

  const BarrierContact* contact_;
  std::vector<int32_t> triangles_;
  size_t at_rest_ = 0;
  bool unclear_ = false;
};

}  // namespace snh::solver
