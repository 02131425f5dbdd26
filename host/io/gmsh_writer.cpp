// Gmsh .msh 2.2 ASCII (gmsh's "msh22"), which gmsh, meshio and our reader
// read. Nodes are numbered from 1 in mesh order, volume elements from 1 in
// mesh order: gmsh numbers tet4 and hex8 nodes as mesh.h does, so no node is
// reordered.
//
// Groups become physical groups, named in $PhysicalNames when they have a
// name: a volume group is the physical tag of its elements (an element in
// several groups is written once in mesh order under its first group, then
// once more per further group after all elements, as gmsh itself does, and
// the reader joins the copies); a point, curve or surface group is written
// as points (element type 15), element edges (type 1) or element faces
// (types 2 and 3) whose vertices lie in it (group_cells). A group the
// format cannot give back as it is (not exact in group_cells; tag 0, which
// gmsh reads as "no group"; a (dimension, tag) pair already used; a name
// holding a line break) is left out. Point and
// cell arrays are not written (gmsh's $NodeData and $ElementData hold time
// steps of fields, and read_mesh skips them).
#include <set>
#include <sstream>

#include "io/writers.h"

namespace snh::io {
namespace {

int gmsh_cell_type(int dimension, int corners) {
  if (dimension == 0) return 15;  // point
  if (dimension == 1) return 1;   // 2-node line
  return corners == 3 ? 2 : 3;    // 3-node triangle, 4-node quadrangle
}

// A name is read back between the first and the last double quote of its
// line, so only a line break cannot be carried.
bool name_fits(const std::string& name) { return name.find_first_of("\n\r") == std::string::npos; }

}  // namespace

void write_gmsh(const std::string& path, const Mesh& mesh) {
  const bool hex = mesh.type == ElementType::hex8;
  const int n = nodes_per_element(mesh.type);
  const size_t elements = mesh.element_count();

  // The groups written, with the cells of the lower-dimensional ones.
  struct Written {
    const MeshGroup* group;
    GroupCells cells;
  };
  std::vector<Written> written;
  std::set<std::pair<int, int>> keys;
  for (const MeshGroup& g : mesh.groups) {
    if (g.tag == 0 || !name_fits(g.name) || !keys.emplace(g.dimension, g.tag).second) continue;
    GroupCells cells = group_cells(mesh, g);
    if (cells.exact) written.push_back({&g, std::move(cells)});
  }

  // Each element's volume groups, in the order the mesh lists them.
  std::vector<std::vector<int>> tags(elements);
  for (const Written& w : written)
    if (w.group->dimension == 3)
      for (int32_t e : w.group->elements) tags[static_cast<size_t>(e)].push_back(w.group->tag);

  std::ofstream file;
  open_for_writing(file, path);
  file << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
  size_t named = 0;
  for (const Written& w : written) named += w.group->name.empty() ? 0 : 1;
  if (named > 0) {
    file << "$PhysicalNames\n" << named << "\n";
    for (const Written& w : written)
      if (!w.group->name.empty()) file << w.group->dimension << " " << w.group->tag << " \"" << w.group->name << "\"\n";
    file << "$EndPhysicalNames\n";
  }
  file << "$Nodes\n" << mesh.vertex_count() << "\n";
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    file << v + 1 << " " << mesh.positions(v, 0) << " " << mesh.positions(v, 1) << " " << mesh.positions(v, 2) << "\n";
  file << "$EndNodes\n";

  size_t total = elements;
  for (const std::vector<int>& t : tags) total += t.empty() ? 0 : t.size() - 1;
  for (const Written& w : written)
    if (w.group->dimension < 3) total += w.cells.cells.size() / static_cast<size_t>(w.cells.corners);
  file << "$Elements\n" << total << "\n";
  // Two tags per element: the physical group (0: none) and the elementary
  // entity, here the same number (1 for elements in no group).
  const int type = hex ? 5 : 4;
  size_t id = 1;
  const auto element = [&](size_t e, int tag) {
    file << id++ << " " << type << " 2 " << tag << " " << (tag == 0 ? 1 : tag);
    for (int a = 0; a < n; ++a) file << " " << mesh.elements[static_cast<size_t>(n) * e + a] + 1;
    file << "\n";
  };
  for (size_t e = 0; e < elements; ++e) element(e, tags[e].empty() ? 0 : tags[e].front());
  for (size_t e = 0; e < elements; ++e)
    for (size_t k = 1; k < tags[e].size(); ++k) element(e, tags[e][k]);
  for (const Written& w : written) {
    if (w.group->dimension == 3) continue;
    const int corners = w.cells.corners;
    const int cell_type = gmsh_cell_type(w.group->dimension, corners);
    for (size_t c = 0; c < w.cells.cells.size() / static_cast<size_t>(corners); ++c) {
      file << id++ << " " << cell_type << " 2 " << w.group->tag << " " << w.group->tag;
      for (int k = 0; k < corners; ++k) file << " " << w.cells.cells[static_cast<size_t>(corners) * c + k] + 1;
      file << "\n";
    }
  }
  file << "$EndElements\n";
  finish_writing(file, path);
}

}  // namespace snh::io
