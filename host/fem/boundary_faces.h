// The boundary of a volume mesh: the element faces used by exactly one
// element, oriented outwards (counter-clockwise seen from outside), shared by
// the surface writers (host/io/surface_writers.cpp) and boundary_surface
// (snh/surface.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "snh/mesh.h"

namespace snh::fem {

struct BoundaryFaces {
  int corners = 3;                // per face: 3 for tet4, 4 for hex8
  std::vector<int32_t> faces;     // surface vertex indices, `corners` per face
  std::vector<int32_t> vertices;  // mesh vertex of each surface vertex, ascending
};

// Faces in element order, then local face order. Throws snh::Error, its
// message starting with `context`, for a malformed mesh (sizes, indices out
// of range).
BoundaryFaces boundary_faces(const Mesh& mesh, const std::string& context);

}  // namespace snh::fem
