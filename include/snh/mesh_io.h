// Reading volumetric meshes from the formats VFX and meshing tools write, and
// writing boundary surfaces for them. Every reader checks what it reads and
// throws snh::Error naming the file, the line (or byte offset for binary
// data) or the element, and what is wrong.
#pragma once

#include <string>

#include "snh/mesh.h"

namespace snh {

// By extension: .msh (Gmsh 2.2 and 4.1, ASCII and binary), .vtk (VTK legacy),
// .vtu (VTK XML, ascii or raw appended data), .mesh (Medit), .node or .ele
// (TetGen: the other file of the pair is found beside it). Tetrahedra and
// 8-node hexahedra; a mesh mixing them, or holding other volume elements, is
// rejected (surface and line elements are skipped). Elements are
// re-oriented where the file's convention differs from ours (mesh.h), and a
// mesh is validated (validate_mesh) before it is returned.
//
// Groups and arrays (Mesh::groups, point_arrays, cell_arrays): Gmsh physical
// groups with their $PhysicalNames (volume groups hold elements, lower ones
// the vertices of their points, lines and faces); Medit reference numbers,
// named by their number; VTK legacy POINT_DATA/CELL_DATA attributes and FIELD
// arrays; VTU PointData/CellData arrays. Cell arrays keep the entries of the
// volume cells, in file order. TetGen attributes and markers are not read.
Mesh read_mesh(const std::string& path);

// The boundary surface (faces used by one element), triangles for tet4 and
// quads for hex8, oriented outwards, at positions x (xyz per vertex; empty:
// the rest positions). OBJ (ASCII) and PLY (ASCII).
void write_obj_surface(const std::string& path, const Mesh& mesh, const std::vector<double>& x = {});
void write_ply_surface(const std::string& path, const Mesh& mesh, const std::vector<double>& x = {});

}  // namespace snh
