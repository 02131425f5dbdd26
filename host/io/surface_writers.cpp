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

#include "fem/boundary_faces.h"
#include "snh/error.h"
#include "snh/mesh_io.h"

namespace snh {
namespace {

using Surface = fem::BoundaryFaces;

Surface boundary(const std::string& writer, const std::string& path, const Mesh& mesh, const Points& x) {
  Surface surface = fem::boundary_faces(mesh, writer + " " + path);
  if (x.size() != mesh.vertex_count()) {
    std::ostringstream s;
    s << writer << " " << path << ": the positions have " << x.xyz().size() << " values, but the mesh has "
      << mesh.vertex_count() << " vertices (" << mesh.positions.xyz().size() << " values expected)";
    throw Error(s.str());
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

void write_obj_surface(const std::string& path, const Mesh& mesh, const Points& x) {
  const Points& p = x.empty() ? mesh.positions : x;
  const Surface s = boundary("write_obj_surface", path, mesh, p);
  std::ofstream file;
  open_for_writing(file, path, "write_obj_surface");
  const size_t faces = s.faces.size() / s.corners;
  file << "# snh boundary surface: " << s.vertices.size() << " vertices, " << faces << " faces\n";
  for (int32_t v : s.vertices) file << "v " << p(v, 0) << ' ' << p(v, 1) << ' ' << p(v, 2) << '\n';
  for (size_t f = 0; f < faces; ++f) {
    file << 'f';
    for (int c = 0; c < s.corners; ++c) file << ' ' << s.faces[s.corners * f + c] + 1;
    file << '\n';
  }
  finish(file, path, "write_obj_surface");
}

void write_ply_surface(const std::string& path, const Mesh& mesh, const Points& x) {
  const Points& p = x.empty() ? mesh.positions : x;
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
  for (int32_t v : s.vertices) file << p(v, 0) << ' ' << p(v, 1) << ' ' << p(v, 2) << '\n';
  for (size_t f = 0; f < faces; ++f) {
    file << s.corners;
    for (int c = 0; c < s.corners; ++c) file << ' ' << s.faces[s.corners * f + c];
    file << '\n';
  }
  finish(file, path, "write_ply_surface");
}

}  // namespace snh
