// The generalized winding number of a triangle surface about a point
// (Jacobson et al. 2013, "Robust inside-outside segmentation using
// generalized winding numbers", Eq. 4 with the solid angle of Van Oosterom
// and Strackee 1983): 1 inside a closed surface with outward normals, 0
// outside, and about 1/2 near holes, so that w >= 1/2 is a robust inside
// test.
#pragma once

#include <array>

#include "snh/surface.h"

namespace snh::rig {

double winding_number(const TriangleSurface& surface, const std::array<double, 3>& p);

}  // namespace snh::rig
