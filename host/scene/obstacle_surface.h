// The kinematic obstacles as a triangle surface for ParaView, so that the
// scene command's .vtu series shows what the body is pressed against.
#pragma once

#include <array>
#include <vector>

#include "snh/simulation.h"
#include "snh/surface.h"

namespace snh::scene_io {

// Every obstacle placed at load parameter t (its motion, as the solver
// places it), as one surface: a plane as a square of side 2 extent and a
// cylinder as an open tube of length 2 extent, both centred at the point
// nearest `center`, a sphere whole. Normals point to the free side.
TriangleSurface obstacle_surface(const std::vector<Obstacle>& obstacles, double t, const std::array<double, 3>& center,
                                 double extent);

}  // namespace snh::scene_io
