// Outward faces of a positively oriented tet4 and of a VTK-ordered hex8
// (counter-clockwise seen from outside), as local nodes: the boundary faces
// (fem/boundary_faces.h) and the mesh writers' face groups (io/writers.h)
// read the same tables.
#pragma once

namespace snh::fem {

inline constexpr int kTetFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
inline constexpr int kHexFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                        {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

}  // namespace snh::fem
