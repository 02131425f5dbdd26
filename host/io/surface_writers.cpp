// Boundary surfaces for VFX tools: the faces used by exactly one element,
// oriented outwards (counter-clockwise seen from outside), as ASCII OBJ or
// PLY. Only the vertices on the boundary are written, renumbered in their
// mesh order.
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <locale>
#include <sstream>

#include "io/writers.h"
#include "snh/error.h"
#include "snh/mesh_io.h"

namespace snh {
namespace {

using io::kHexFaces;
using io::kTetFaces;

struct Surface {
  int corners = 3;                // per face
  std::vector<int32_t> faces;     // new vertex indices, `corners` per face
  std::vector<int32_t> vertices;  // mesh vertex of each surface vertex
};

Surface boundary(const std::string& writer, const std::string& path, const Mesh& mesh, const std::vector<double>& x) {
  const int n = nodes_per_element(mesh.type);
  if (mesh.positions.size() % 3 != 0 || mesh.elements.size() % n != 0) {
    std::ostringstream s;
    s << writer << " " << path << ": the mesh is malformed (" << mesh.positions.size() << " position values, "
      << mesh.elements.size() << " element indices for " << to_string(mesh.type) << ")";
    throw Error(s.str());
  }
  if (x.size() != mesh.positions.size()) {
    std::ostringstream s;
    s << writer << " " << path << ": the positions have " << x.size() << " values, but the mesh has "
      << mesh.vertex_count() << " vertices (" << mesh.positions.size() << " values expected)";
    throw Error(s.str());
  }
  for (size_t i = 0; i < mesh.elements.size(); ++i)
    if (mesh.elements[i] < 0 || static_cast<size_t>(mesh.elements[i]) >= mesh.vertex_count()) {
      std::ostringstream s;
      s << writer << " " << path << ": element " << i / n << " refers to vertex " << mesh.elements[i]
        << ", but the mesh has " << mesh.vertex_count() << " vertices";
      throw Error(s.str());
    }

  Surface surface;
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

void open_for_writing(std::ofstream& file, const std::string& path, const std::string& writer) {
  file.open(path, std::ios::out | std::ios::trunc);
  if (!file) throw Error(writer + " " + path + ": the file cannot be opened for writing (does its directory exist?)");
  file.imbue(std::locale::classic());
  file << std::setprecision(std::numeric_limits<double>::max_digits10);
}

void finish(std::ofstream& file, const std::string& path, const std::string& writer) {
  file.flush();
  if (!file) throw Error(writer + " " + path + ": writing failed part way");
  file.close();
  if (file.fail()) throw Error(writer + " " + path + ": closing failed");
}

}  // namespace

void write_obj_surface(const std::string& path, const Mesh& mesh, const std::vector<double>& x) {
  const std::vector<double>& p = x.empty() ? mesh.positions : x;
  const Surface s = boundary("write_obj_surface", path, mesh, p);
  std::ofstream file;
  open_for_writing(file, path, "write_obj_surface");
  const size_t faces = s.faces.size() / s.corners;
  file << "# snh boundary surface: " << s.vertices.size() << " vertices, " << faces << " faces\n";
  for (int32_t v : s.vertices) file << "v " << p[3 * v] << ' ' << p[3 * v + 1] << ' ' << p[3 * v + 2] << '\n';
  for (size_t f = 0; f < faces; ++f) {
    file << 'f';
    for (int c = 0; c < s.corners; ++c) file << ' ' << s.faces[s.corners * f + c] + 1;
    file << '\n';
  }
  finish(file, path, "write_obj_surface");
}

void write_ply_surface(const std::string& path, const Mesh& mesh, const std::vector<double>& x) {
  const std::vector<double>& p = x.empty() ? mesh.positions : x;
  const Surface s = boundary("write_ply_surface", path, mesh, p);
  std::ofstream file;
  open_for_writing(file, path, "write_ply_surface");
  const size_t faces = s.faces.size() / s.corners;
  file << "ply\n"
       << "format ascii 1.0\n"
       << "comment snh boundary surface\n"
       << "element vertex " << s.vertices.size() << "\n"
       << "property double x\n"
       << "property double y\n"
       << "property double z\n"
       << "element face " << faces << "\n"
       << "property list uchar int vertex_indices\n"
       << "end_header\n";
  for (int32_t v : s.vertices) file << p[3 * v] << ' ' << p[3 * v + 1] << ' ' << p[3 * v + 2] << '\n';
  for (size_t f = 0; f < faces; ++f) {
    file << s.corners;
    for (int c = 0; c < s.corners; ++c) file << ' ' << s.faces[s.corners * f + c];
    file << '\n';
  }
  finish(file, path, "write_ply_surface");
}

}  // namespace snh
