// What the scene command writes per step or frame, shared by the load-step
// run and the rig's frames.
#pragma once

#include <string>
#include <vector>

#include "snh/mesh.h"
#include "snh/regions.h"

namespace snh::bench {

// Displacement per vertex and the element fields (F, J, P, Cauchy, von
// Mises, energy density) of positions x, for ParaView. Where the fields are
// undefined (a non-finite state, or an inverted element of a material
// undefined for J <= 0) the file still shows the positions, without them.
void write_step_vtu(const std::string& path, const Mesh& mesh, const MaterialMap& materials,
                    const std::vector<double>& x);

}  // namespace snh::bench
