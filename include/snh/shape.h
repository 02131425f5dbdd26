// How far a deformed body is from its rest shape once rigid motion is
// factored out: what "it recovers its shape" means in numbers (the drop and
// squash scenes report it per step).
#pragma once

#include <vector>

#include "snh/mesh.h"

namespace snh {

// Over the vertices used by elements, each weighted equally: the root mean
// square of |R (X - X_c) - (x - x_c)| for the best rotation R (the
// least-squares rigid fit of Kabsch 1976 / Horn 1987, with det R = +1) and
// the centroids X_c, x_c; and the rest shape's radius of gyration
// sqrt(mean |X - X_c|^2), the body size it is measured against.
struct ShapeDeviation {
  double rms_distance = 0.0;        // length units of the mesh
  double radius_of_gyration = 0.0;  // of the rest shape, > 0
  double relative() const { return rms_distance / radius_of_gyration; }
};

// Throws snh::Error for positions of the wrong size or not finite, or a mesh
// whose used vertices all coincide.
ShapeDeviation shape_deviation(const Mesh& mesh, const Points& positions);

}  // namespace snh
