// Turning inside-out shells of an artist's surface outwards before its
// winding number is taken (fem/voxelize.cpp).
#pragma once

#include <string>
#include <vector>

#include "snh/surface.h"

namespace snh::fem {

// The surface's shells (triangles joined through shared edges) that enclose
// a volume (closed, or with at most a tenth of their edges open, and a
// volume at least 1% of the sphere's of the same area) are oriented
// outwards: when their signed volumes add up to less than zero (a mirrored
// file, or every face wound inwards) each such shell is reversed; then each
// remaining shell of negative volume that the other shells do not enclose
// (winding number of the others below 1/2 at most of its vertices) is
// reversed. A negative shell inside another one is a cavity and is kept.
// Returns one warning per reversed shell (at most 8, then a count), naming
// `name`, the shell's first triangle and its triangle count.
std::vector<std::string> orient_shells(TriangleSurface& surface, const std::string& name);

}  // namespace snh::fem
