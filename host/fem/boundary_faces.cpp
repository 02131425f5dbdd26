// The faces used by one element: every face keyed by its sorted corners,
// sorted, and those met once kept.
#include "fem/boundary_faces.h"

#include <algorithm>
#include <array>
#include <sstream>

#include "fem/element_faces.h"
#include "snh/error.h"
#include "snh/surface.h"

namespace snh::fem {

BoundaryFaces boundary_faces(const Mesh& mesh, const std::string& context) {
  const int n = nodes_per_element(mesh.type);
  if (mesh.positions.xyz().size() % 3 != 0 || mesh.elements.size() % n != 0) {
    std::ostringstream s;
    s << context << ": the mesh is malformed (" << mesh.positions.xyz().size() << " position values, "
      << mesh.elements.size() << " element indices for " << to_string(mesh.type) << ")";
    throw Error(s.str());
  }
  for (size_t i = 0; i < mesh.elements.size(); ++i)
    if (mesh.elements[i] < 0 || static_cast<size_t>(mesh.elements[i]) >= mesh.vertex_count()) {
      std::ostringstream s;
      s << context << ": element " << i / n << " refers to vertex " << mesh.elements[i] << ", but the mesh has "
        << mesh.vertex_count() << " vertices";
      throw Error(s.str());
    }

  BoundaryFaces surface;
  const bool hex = mesh.type == ElementType::hex8;
  surface.corners = hex ? 4 : 3;
  const int faces_per = hex ? 6 : 4;
  const size_t elements = mesh.element_count();
  // Every face with its sorted corners as the key; faces met once are the boundary.
  struct Face {
    std::array<int32_t, 4> key;
    uint32_t face;  // local face
    size_t element;
  };
  std::vector<Face> all;
  all.reserve(elements * faces_per);
  for (size_t e = 0; e < elements; ++e)
    for (int f = 0; f < faces_per; ++f) {
      Face face{{-1, -1, -1, -1}, static_cast<uint32_t>(f), e};
      for (int c = 0; c < surface.corners; ++c)
        face.key[c] = mesh.elements[n * e + (hex ? kHexFaces[f][c] : kTetFaces[f][c])];
      // Insertion sort of the 3 or 4 corners (std::sort here trips GCC 12's -Warray-bounds).
      for (int i = 1; i < surface.corners; ++i)
        for (int j = i; j > 0 && face.key[j - 1] > face.key[j]; --j) std::swap(face.key[j - 1], face.key[j]);
      all.push_back(face);
    }
  std::sort(all.begin(), all.end(), [](const Face& a, const Face& b) {
    return a.key != b.key ? a.key < b.key : a.element != b.element ? a.element < b.element : a.face < b.face;
  });
  std::vector<const Face*> once;
  for (size_t i = 0; i < all.size();) {
    size_t j = i + 1;
    while (j < all.size() && all[j].key == all[i].key) ++j;
    if (j == i + 1) once.push_back(&all[i]);
    i = j;
  }
  std::sort(once.begin(), once.end(), [](const Face* a, const Face* b) {
    return a->element != b->element ? a->element < b->element : a->face < b->face;
  });

  std::vector<int32_t> index(mesh.vertex_count(), -1);
  for (const Face* face : once)
    for (int c = 0; c < surface.corners; ++c) index[face->key[c]] = 0;
  for (size_t v = 0; v < index.size(); ++v)
    if (index[v] == 0) {
      index[v] = static_cast<int32_t>(surface.vertices.size());
      surface.vertices.push_back(static_cast<int32_t>(v));
    }
  surface.faces.reserve(once.size() * surface.corners);
  for (const Face* face : once)
    for (int c = 0; c < surface.corners; ++c) {
      const int local = hex ? kHexFaces[face->face][c] : kTetFaces[face->face][c];
      surface.faces.push_back(index[mesh.elements[n * face->element + local]]);
    }
  return surface;
}

}  // namespace snh::fem

namespace snh {

MeshBoundary boundary_surface(const Mesh& mesh, const Points& x) {
  const fem::BoundaryFaces faces = fem::boundary_faces(mesh, "boundary_surface");
  const Points& p = x.empty() ? mesh.positions : x;
  if (p.size() != mesh.vertex_count())
    throw Error("boundary_surface: the positions have " + std::to_string(p.xyz().size()) +
                " values, but the mesh has " + std::to_string(mesh.vertex_count()) + " vertices");
  MeshBoundary b;
  b.vertices = faces.vertices;
  b.surface.positions.reserve(faces.vertices.size());
  for (int32_t v : faces.vertices) {
    const size_t i = static_cast<size_t>(v);
    b.surface.positions.push_back({p(i, 0), p(i, 1), p(i, 2)});
  }
  const size_t count = faces.faces.size() / faces.corners;
  b.surface.triangles.reserve(3 * count * (faces.corners - 2));
  for (size_t f = 0; f < count; ++f) {
    const int32_t* c = &faces.faces[faces.corners * f];
    // A fan from the first corner keeps the face's orientation.
    for (int k = 1; k + 1 < faces.corners; ++k)
      b.surface.triangles.insert(b.surface.triangles.end(), {c[0], c[k], c[k + 1]});
  }
  return b;
}

}  // namespace snh
