// Loads in the user's terms.
#pragma once

#include <array>
#include <vector>

#include "snh/mesh.h"

namespace snh {

// A body force per rest volume (e.g. density times gravity) lumped to the
// vertices with each element's own quadrature: f_a = sum_q w_q N_a(xi_q) b
// (hex8: 2x2x2 Gauss; tet4: a quarter of the volume per node). xyz per vertex.
std::vector<double> lump_body_force(const Mesh& mesh, const std::array<double, 3>& force_per_rest_volume);

}  // namespace snh
