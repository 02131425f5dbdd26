// What a solve means physically, per element and per constrained set: the
// deformation, the stress and the energy density for ParaView, and the force
// and torque each constraint set exerts on the body (e.g. a bone's load).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "snh/io.h"
#include "snh/mesh.h"
#include "snh/regions.h"

namespace snh {

struct ConstraintSet;  // simulation.h

// Per element, averaged over the element's quadrature points with their rest
// volume weights (tet4: the one point), except the Cauchy stress, which is
// the average over the deformed element (see `cauchy`). Matrices are 3x3
// row-major (index 3 * row + column, like every matrix of the API), nine
// values per element. For a
// uniform F (an affine motion, or any tet4) every average is the value at
// the points.
struct ElementFields {
  std::vector<double> deformation_gradient;  // F
  std::vector<double> j;                     // det F (the average: deformed / rest element volume)
  std::vector<double> pk1;                   // first Piola-Kirchhoff stress P = dpsi/dF
  // sigma = P F^T / J, averaged over the deformed volume: sum_q w_q P_q F_q^T
  // / sum_q w_q J_q, i.e. (1/v) int sigma dv, the stress whose traction
  // balances the element's forces on average. Symmetrized (it is symmetric
  // up to rounding for an isotropic energy). NaN where J <= 0 at any point:
  // an inverted or flat element has no current volume to refer the stress
  // to (while P, referred to the rest volume, stays defined there).
  std::vector<double> cauchy;
  // sqrt(3/2 s:s), s the deviatoric part of the element's `cauchy` (so it
  // agrees with what ParaView derives from that field); NaN where J <= 0.
  std::vector<double> von_mises;
  std::vector<double> energy_density;  // psi per rest volume (element energy / rest volume)
  std::vector<double> min_j;           // smallest det F over the element's points
};

// Throws snh::Error naming the input for a mesh/material map/positions size
// mismatch, a material index out of the map's range, non-finite positions or
// an invalid mesh (validate_mesh). Energy, P, F and J are finite wherever
// they are returned: a material undefined for J <= 0 (log Neo-Hookean
// without inversion handling) at an element with J <= 0, or a non-finite
// energy or stress, is an snh::Error naming the element and point.
ElementFields compute_element_fields(const Mesh& mesh, const MaterialMap& materials, const Points& x);

// The fields as .vtu cell data: F (9 components), J, min_J, P (9), cauchy (9),
// von_mises, energy_density, and "region" (the material map index) when the
// map has more than one material. Tensors are written as stored, row-major:
// VTK's component order (XX XY XZ YX ...), so ParaView's component labels name
// F_ij correctly. Where cauchy and von_mises are NaN (J <= 0) they are
// written as 0, since VTK's ASCII reader stops at a "nan" and drops the
// whole array; min_J <= 0 marks those elements (threshold on it in
// ParaView). Throws snh::Error when the fields' sizes disagree with each
// other or with the map.
std::vector<VtuCellField> element_fields_for_vtu(const ElementFields& fields, const MaterialMap& materials);

// Elastic nodal forces -dE_elastic/dx at x, in double (the
// kernels' element math compiled for the host), summed per element then per
// vertex in a fixed order: deterministic. Same input checks as
// compute_element_fields.
Points elastic_forces(const Mesh& mesh, const MaterialMap& materials, const Points& x);

// The force and torque a set of prescribed DOFs exerts on the body:
// reaction_v = -(elastic force + external force) at each prescribed
// component of vertex v; torque = sum (x_v - about) x reaction_v.
// At equilibrium the free DOFs carry no net force, so the reactions of all
// sets balance the external load (and each other) up to the solver's
// residual.
struct Reaction {
  std::string name;
  std::array<double, 3> force{0, 0, 0};
  std::array<double, 3> torque{0, 0, 0};
  std::array<double, 3> about{0, 0, 0};  // the torque's reference point
};

// components: which of x, y, z are prescribed, the same for every vertex of
// `vertices` ({true, true, true}: fully pinned, as ConstraintSet is). A
// vertex listed twice counts once. external_force: lumped,
// or empty. about: the reference point of the torque. Throws snh::Error
// naming the set for a vertex out of range or a wrongly sized x,
// elastic_force or external_force.
Reaction reaction(const std::string& name, const std::vector<int32_t>& vertices, const std::array<bool, 3>& components,
                  const Points& x, const Points& elastic_force, const Points& external_force,
                  const std::array<double, 3>& about);

// The centroid of the distinct `vertices` at positions x.
std::array<double, 3> centroid(const std::vector<int32_t>& vertices, const Points& x);

// The reaction of every constraint set at positions x, over each set's
// prescribed components (ConstraintSet::components), with the torque
// taken about the set's current centroid (for a rigidly moved set: its rest
// centroid moved with it, i.e. the point a bone's load is reported at).
// (Sets never share a vertex component: Simulation rejects that.) external_force as in SolveOptions
// (lumped, or empty).
std::vector<Reaction> constraint_reactions(const Mesh& mesh, const MaterialMap& materials,
                                           const std::vector<ConstraintSet>& constraints, const Points& x,
                                           const Points& external_force);

}  // namespace snh
