// Loads on a mesh in the user's terms: a body force (gravity, a uniform
// acceleration times density) turned into the nodal forces the solver takes
// as its external force.
#pragma once

#include <array>
#include <vector>

#include "snh/mesh.h"

namespace snh {

// Nodal forces of a uniform body force given per unit rest
// volume, b: f_a = sum over elements and their quadrature points of
// w_q N_a(xi_q) b, with each element's own rule and the rest volume at each
// point (hex8: 2x2x2 Gauss; tet4: V / 4 per node). The forces sum to b times
// the rest volume; for a lattice of cubes of side h an interior vertex gets
// b h^3. Throws snh::Error for an invalid mesh (validate_mesh).
Points lump_body_force(const Mesh& mesh, const std::array<double, 3>& force_per_rest_volume);

// Lumped (row-sum) mass per vertex of a uniform density: the same integral,
// m_a = sum over elements and points of w_q N_a(xi_q) density, so a body
// force density * g lumps to exactly m_a g. Throws snh::Error for an invalid
// mesh or a density that is not finite and positive.
std::vector<double> lumped_mass(const Mesh& mesh, double density);

}  // namespace snh
