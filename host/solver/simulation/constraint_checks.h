// Constraint bookkeeping shared by Simulation and the host baseline: which
// DOFs the sets prescribe, where a set's callbacks put its vertices, and
// whether the constraints leave rigid motions free.
#pragma once

#include <string>
#include <vector>

#include "snh/mesh.h"
#include "snh/simulation.h"

namespace snh::solver {

// Per DOF (xyz per vertex): 1 where a set prescribes it.
std::vector<char> prescribed_dofs(const Mesh& mesh, const std::vector<ConstraintSet>& sets);

// Writes the set's prescribed components at load parameter t (its `targets`,
// else `motion(t)` of the rest positions, else rest) into x; snh::Error
// naming the set for a wrong-sized or non-finite target.
void place_by_callback(const Mesh& mesh, const ConstraintSet& set, double t, std::vector<double>& x);
void place_by_callback(const Mesh& mesh, const ConstraintSet& set, double t, Points& x);

// The rigid motions (3 translations, 3 rotations) the prescribed DOFs leave
// free, for each piece of the mesh (elements joined through shared vertices:
// snh::mesh_pieces) on its own. With a net external force or torque on a
// piece along one of them there is no equilibrium without inertia:
// snh::Error naming the free motion and, where the mesh has several pieces,
// the piece (its number, element count and rest bounding box). Without such
// a load the solution is defined only up to that motion: a warning.
void check_rigid_modes(const Mesh& mesh, const std::vector<char>& prescribed, const std::vector<double>& force,
                       std::vector<std::string>& warnings);

}  // namespace snh::solver
