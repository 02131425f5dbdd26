// Medit ASCII .mesh (MeshVersionFormatted 2, Dimension 3): Vertices, then
// Tetrahedra or Hexahedra in mesh order with 1-based indices in mesh.h's
// node order. Groups are Medit reference numbers, which have no names (the
// reader names a group by its number): a volume group is the reference of
// its elements, 0 for elements in none (the reader's "no group"); a curve or
// surface group is the reference of Edges, Triangles (tet4) or
// Quadrilaterals (hex8) whose vertices lie in it (group_cells). Left out:
// groups of tag 0, point groups (vertex references are not read back), a
// second group with the same dimension and tag, groups group_cells cannot
// give back, and volume groups sharing an element with a group written
// before them (an element has one reference). Arrays are not written: the
// format has none.
#include <set>

#include "io/writers.h"

namespace snh::io {

void write_medit(const std::string& path, const Mesh& mesh) {
  const int n = nodes_per_element(mesh.type);
  const size_t elements = mesh.element_count();
  std::vector<int> reference(elements, 0);
  struct Written {
    const MeshGroup* group;
    GroupCells cells;
  };
  std::vector<Written> lower;
  std::set<std::pair<int, int>> keys;
  for (const MeshGroup& g : mesh.groups) {
    if (g.tag == 0 || g.dimension == 0 || keys.count({g.dimension, g.tag})) continue;
    GroupCells cells = group_cells(mesh, g);
    if (!cells.exact) continue;
    if (g.dimension == 3) {
      bool free = true;
      for (int32_t e : g.elements) free = free && reference[static_cast<size_t>(e)] == 0;
      if (!free) continue;
      for (int32_t e : g.elements) reference[static_cast<size_t>(e)] = g.tag;
    } else {
      lower.push_back({&g, std::move(cells)});
    }
    keys.emplace(g.dimension, g.tag);
  }

  std::ofstream file;
  open_for_writing(file, path);
  file << "MeshVersionFormatted 2\nDimension 3\nVertices\n" << mesh.vertex_count() << "\n";
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    file << mesh.positions(v, 0) << " " << mesh.positions(v, 1) << " " << mesh.positions(v, 2) << " 0\n";
  file << (mesh.type == ElementType::hex8 ? "Hexahedra\n" : "Tetrahedra\n") << elements << "\n";
  for (size_t e = 0; e < elements; ++e) {
    for (int a = 0; a < n; ++a) file << mesh.elements[static_cast<size_t>(n) * e + a] + 1 << " ";
    file << reference[e] << "\n";
  }
  for (const char* keyword : {"Edges", "Triangles", "Quadrilaterals"}) {
    const int corners = keyword[0] == 'E' ? 2 : (keyword[0] == 'T' ? 3 : 4);
    size_t count = 0;
    for (const Written& w : lower)
      if (w.cells.corners == corners) count += w.cells.cells.size() / static_cast<size_t>(corners);
    if (count == 0) continue;
    file << keyword << "\n" << count << "\n";
    for (const Written& w : lower) {
      if (w.cells.corners != corners) continue;
      for (size_t c = 0; c < w.cells.cells.size() / static_cast<size_t>(corners); ++c) {
        for (int k = 0; k < corners; ++k) file << w.cells.cells[static_cast<size_t>(corners) * c + k] + 1 << " ";
        file << w.group->tag << "\n";
      }
    }
  }
  file << "End\n";
  finish_writing(file, path);
}

}  // namespace snh::io
