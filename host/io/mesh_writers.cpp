// write_mesh: dispatch by extension, and what the writers share: opening a
// file for exact numbers, and the cells that carry a lower-dimensional group.
#include <algorithm>
#include <array>
#include <iomanip>
#include <limits>
#include <locale>
#include <map>

#include "fem/element_faces.h"
#include "io/readers.h"
#include "io/writers.h"
#include "snh/error.h"
#include "snh/mesh_io.h"

namespace snh {
namespace io {

void open_for_writing(std::ofstream& file, const std::string& path) {
  file.open(path, std::ios::out | std::ios::trunc | std::ios::binary);
  if (!file) throw Error("cannot write " + path + " (the file cannot be opened; does its directory exist?)");
  file.imbue(std::locale::classic());
  file << std::setprecision(std::numeric_limits<double>::max_digits10);
}

void finish_writing(std::ofstream& file, const std::string& path) {
  file.flush();
  if (!file) throw Error("cannot write " + path + " (writing failed part way)");
  file.close();
  if (file.fail()) throw Error("cannot write " + path + " (closing failed)");
}

namespace {

// The edges of a tet4 and of a hex8, as local nodes.
constexpr int kTetEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
constexpr int kHexEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                  {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

}  // namespace

GroupCells group_cells(const Mesh& mesh, const MeshGroup& group) {
  GroupCells out;
  const int n = nodes_per_element(mesh.type);
  if (group.dimension == 3) {
    // Readers give a volume group the vertices of its elements.
    std::vector<int32_t> vertices;
    for (int32_t e : group.elements)
      vertices.insert(vertices.end(), mesh.elements.begin() + static_cast<std::ptrdiff_t>(n) * e,
                      mesh.elements.begin() + static_cast<std::ptrdiff_t>(n) * (e + 1));
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    out.exact = !group.elements.empty() && vertices == group.vertices;
    return out;
  }
  if (group.dimension == 0) {
    out.cells = group.vertices;
    out.exact = !group.vertices.empty();
    return out;
  }
  const bool hex = mesh.type == ElementType::hex8;
  std::vector<char> in(mesh.vertex_count(), 0), covered(mesh.vertex_count(), 0);
  for (int32_t v : group.vertices) in[static_cast<size_t>(v)] = 1;
  const int count = group.dimension == 1 ? (hex ? 12 : 6) : (hex ? 6 : 4);
  out.corners = group.dimension == 1 ? 2 : (hex ? 4 : 3);
  std::map<std::array<int32_t, 4>, char> seen;
  for (size_t e = 0; e < mesh.element_count(); ++e) {
    const int32_t* nodes = mesh.elements.data() + static_cast<size_t>(n) * e;
    for (int c = 0; c < count; ++c) {
      std::array<int32_t, 4> cell{-1, -1, -1, -1};
      bool inside = true;
      for (int k = 0; k < out.corners; ++k) {
        const int local = group.dimension == 1 ? (hex ? kHexEdges[c][k] : kTetEdges[c][k])
                                               : (hex ? fem::kHexFaces[c][k] : fem::kTetFaces[c][k]);
        cell[k] = nodes[local];
        inside = inside && in[static_cast<size_t>(cell[k])];
      }
      if (!inside) continue;
      std::array<int32_t, 4> key = cell;  // unused corners are -1 and sort first
      std::sort(key.begin(), key.end());
      if (!seen.emplace(key, 0).second) continue;
      out.cells.insert(out.cells.end(), cell.begin(), cell.begin() + out.corners);
      for (int k = 0; k < out.corners; ++k) covered[static_cast<size_t>(cell[k])] = 1;
    }
  }
  out.exact = !group.vertices.empty() && std::all_of(group.vertices.begin(), group.vertices.end(),
                                                     [&](int32_t v) { return covered[static_cast<size_t>(v)] != 0; });
  return out;
}

std::vector<const MeshArray*> carried_arrays(const std::vector<MeshArray>& arrays, int max_components) {
  std::vector<const MeshArray*> out;
  for (const MeshArray& a : arrays) {
    if (a.name.empty() || a.components > max_components) continue;
    if (std::any_of(out.begin(), out.end(), [&](const MeshArray* b) { return b->name == a.name; })) continue;
    out.push_back(&a);
  }
  return out;
}

}  // namespace io

void write_mesh(const std::string& path, const Mesh& mesh) {
  const std::string ext = io::lowercase_extension(path);
  const bool tetgen = ext == ".node" || ext == ".ele";
  if (ext != ".msh" && ext != ".vtk" && ext != ".vtu" && ext != ".mesh" && !tetgen)
    throw Error("write_mesh " + path + ": unknown mesh format " + (ext.empty() ? "(no extension)" : "'" + ext + "'") +
                " (write_mesh writes .msh, .vtk, .vtu, .mesh, and TetGen .node/.ele pairs)");
  if (tetgen && mesh.type != ElementType::tet4)
    throw Error("write_mesh " + path + ": TetGen .node/.ele files hold only tetrahedra, and this mesh is " +
                to_string(mesh.type) + " (write .msh, .vtk, .vtu or .mesh instead)");
  // Checked before the file is touched: a mesh the readers would refuse is
  // not written, and a bad call leaves no half-written file behind.
  try {
    validate_mesh(mesh);
  } catch (const Error& e) {
    throw Error("write_mesh " + path + ": " + e.what());
  }
  if (ext == ".msh") return io::write_gmsh(path, mesh);
  if (ext == ".vtk") return io::write_vtk_legacy(path, mesh);
  if (ext == ".vtu") return io::write_vtu_mesh(path, mesh);
  if (ext == ".mesh") return io::write_medit(path, mesh);
  const std::string stem = path.substr(0, path.size() - ext.size());
  io::write_tetgen(stem + ".node", stem + ".ele", mesh);
}

}  // namespace snh
