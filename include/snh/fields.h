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

// Per element, averaged over the element's quadrature points with their rest
// volume weights (tet4: the one point). Matrices are 3x3 column-major
// (index 3 * column + row), nine values per element.
struct ElementFields {
  std::vector<double> deformation_gradient;  // F
  std::vector<double> j;                     // det F
  std::vector<double> pk1;                   // first Piola-Kirchhoff stress P = dpsi/dF
  std::vector<double> cauchy;                // sigma = P F^T / J (symmetrized); NaN where J <= 0
  std::vector<double> von_mises;             // sqrt(3/2 s:s), s the deviatoric Cauchy stress; NaN where J <= 0
  std::vector<double> energy_density;        // psi per rest volume
  std::vector<double> min_j;                 // smallest det F over the element's points
};

// Throws snh::Error for a mesh/material map/positions size mismatch.
ElementFields compute_element_fields(const Mesh& mesh, const MaterialMap& materials, const std::vector<double>& x);

// The fields as .vtu cell data: F (9 components), J, min_J, P (9), cauchy (9),
// von_mises, energy_density, and "region" (the material map index) when the
// map has more than one material.
std::vector<VtuCellField> element_fields_for_vtu(const ElementFields& fields, const MaterialMap& materials);

// Elastic nodal forces -dE_elastic/dx at x, xyz per vertex, in double (the
// kernels' element math compiled for the host), summed per element then per
// vertex in a fixed order: deterministic.
std::vector<double> elastic_forces(const Mesh& mesh, const MaterialMap& materials, const std::vector<double>& x);

// The force and torque a set of prescribed DOFs exerts on the body:
// reaction_v = -(elastic force + external force) at each prescribed
// component of vertex v; torque = sum (x_v - about) x reaction_v.
struct Reaction {
  std::string name;
  std::array<double, 3> force{0, 0, 0};
  std::array<double, 3> torque{0, 0, 0};
  std::array<double, 3> about{0, 0, 0};  // the torque's reference point
};

// components: per vertex of `vertices`, which of x, y, z are prescribed
// (empty: all three for every vertex). external_force: lumped, xyz per
// vertex, or empty. about: the reference point of the torque.
Reaction reaction(const std::string& name, const std::vector<int32_t>& vertices, const std::array<bool, 3>& components,
                  const std::vector<double>& x, const std::vector<double>& elastic_force,
                  const std::vector<double>& external_force, const std::array<double, 3>& about);

}  // namespace snh
