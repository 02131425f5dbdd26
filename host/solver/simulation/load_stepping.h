// Load stepping: where each constraint set's vertices go at a fraction of a
// solve (its callbacks, a rigid transform followed by slerp, or positions
// reached linearly) and the external force ramped between two load states.
// Simulation uses it for load steps and implicit Euler substeps alike; a
// host baseline stepping the same loads can use it too (apply_constraints
// below places callback targets only).
#pragma once

#include <vector>

#include "snh/mesh.h"
#include "snh/simulation.h"

namespace snh {

// Writes every constrained vertex's target at load parameter t into x (xyz
// per vertex; the set's prescribed components only): `targets` if set, else
// `motion(t)` applied to the rest position, else the rest position. Throws
// snh::Error naming the set for a wrong-sized targets callback or a
// non-finite target.
void apply_constraints(const Mesh& mesh, const std::vector<ConstraintSet>& constraints, double t,
                       std::vector<double>& x);

}  // namespace snh

namespace snh::solver {

// Where a set's vertices go in the coming solve.
struct SetTarget {
  enum class Kind { callback, transform, positions } kind = Kind::callback;
  RigidTransform from, to;    // transform: the last reached and the new one
  bool from_known = false;    // `from` is a transform the set reached
  std::vector<double> xyz;    // positions: the targets, xyz per vertex of the set
  std::vector<double> start;  // positions of the set's vertices at the solve's start
};

// The load parameter of step s of n: s / n.
inline double load_fraction(int step, int steps) { return static_cast<double>(step) / steps; }

// Keeps the set's vertices' positions in x as target.start, where a
// transform without a known start and positions move from linearly.
void record_start(const ConstraintSet& set, const std::vector<double>& x, SetTarget& target);

// Writes the set's prescribed components at fraction s of the solve into
// positions. A transform between two rotations moves rigidly (the relative
// rotation's angle scaled by s about the new transform's centre, whose image
// moves on a straight line); other transforms and positions blend linearly
// from target.start. snh::Error naming the set for a non-finite target.
void place_target(const Mesh& mesh, const ConstraintSet& set, const SetTarget& target, double s,
                  std::vector<double>& positions);
void place_target(const Mesh& mesh, const ConstraintSet& set, const SetTarget& target, double s, Points& positions);

// The external force at fraction s of a ramp: from + s (to - from).
void ramp_force(const std::vector<double>& from, const std::vector<double>& to, double s, std::vector<double>& out);

}  // namespace snh::solver
