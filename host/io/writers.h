// Internals shared by the mesh writers (write_mesh in mesh_io.h): files
// opened in the classic locale with enough digits to read doubles back bit
// for bit, and the pieces of a group a format stores as lower-dimensional
// cells.
#pragma once

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "snh/mesh.h"

namespace snh::io {

// Opens `path` for writing, in the classic locale (no decimal commas) with
// max_digits10 significant digits; throws snh::Error naming the path.
void open_for_writing(std::ofstream& file, const std::string& path);
// Flushes and closes, throwing when writing failed part way.
void finish_writing(std::ofstream& file, const std::string& path);

// A group of dimension 0, 1 or 2 holds only vertices (mesh.h). A format that
// stores such a group as cells gets the cells of that dimension whose
// vertices all lie in the group: single vertices (0), element edges (1) or
// element faces (2, triangles for tet4 and quads for hex8), each once, in
// the order the elements first meet them. `corners` is 1, 2, 3 or 4 and
// `cells` holds `corners` vertices per cell. `exact` says whether a reader
// gets the group back as it is: the cells hold every vertex of the group,
// or for a volume group (no cells: its elements carry it) its vertices are
// those of its elements. A writer leaves out a group that is not exact.
struct GroupCells {
  int corners = 1;
  std::vector<int32_t> cells;
  bool exact = false;
};
GroupCells group_cells(const Mesh& mesh, const MeshGroup& group);

// The arrays a reader gets back as they are: named, the first of their
// name, and of at most `max_components` components. A writer leaves out
// the others.
std::vector<const MeshArray*> carried_arrays(const std::vector<MeshArray>& arrays, int max_components);

// The writers, on a mesh validate_mesh accepted.
void write_gmsh(const std::string& path, const Mesh& mesh);
void write_vtk_legacy(const std::string& path, const Mesh& mesh);
void write_vtu_mesh(const std::string& path, const Mesh& mesh);
void write_medit(const std::string& path, const Mesh& mesh);
void write_tetgen(const std::string& node_path, const std::string& ele_path, const Mesh& mesh);

}  // namespace snh::io
