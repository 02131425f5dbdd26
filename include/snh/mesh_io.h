// Reading volumetric meshes from the formats VFX and meshing tools write,
// writing them back in those formats, and writing boundary surfaces. Every reader checks what it reads and
// throws snh::Error naming the file, the line (or byte offset for binary
// data) or the element, and what is wrong.
#pragma once

#include <string>

#include "snh/mesh.h"

namespace snh {

struct MeshReadOptions {
  // Vertices at the same position are refused by default: a mesh whose
  // vertices were not merged falls apart into pieces under load. A lattice
  // kept open across gaps thinner than a cell (voxelize: the two sides of a
  // slit keep their own copies of the vertices on it, the paper's
  // non-manifold lattices) has them on purpose; this accepts them.
  bool allow_coincident_vertices = false;
};

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
// volume cells, in file order. TetGen attributes and markers are not read;
// Medit reference 0 means no group.
Mesh read_mesh(const std::string& path, const MeshReadOptions& options = {});

// Writes `mesh` (at its rest positions) in the format its extension names,
// so that read_mesh gives back the same vertices and elements, in the same
// order and node order, with every coordinate bit for bit (ASCII numbers of
// max_digits10 digits):
//   .msh   Gmsh 2.2 ASCII; groups as physical groups with their names
//          (lower-dimensional groups as the points, element edges or
//          element faces that lie in them)
//   .vtk   VTK legacy ASCII UNSTRUCTURED_GRID; point and cell arrays as
//          FIELD arrays
//   .vtu   VTK XML (write_vtu); point and cell arrays
//   .mesh  Medit; groups as reference numbers (named by their number when
//          read back; point groups and elements in two groups cannot be kept)
//   .node or .ele  the TetGen pair stem.node + stem.ele (tet4 only)
// Groups and arrays a format cannot give back as they are are left out (the
// writers in host/io/ say which); read_mesh lists groups by dimension and
// then tag. Throws snh::Error naming the path for an unknown extension, a
// hex8 mesh to TetGen, a mesh validate_mesh refuses (checked before the
// file is touched), or a file that cannot be written.
void write_mesh(const std::string& path, const Mesh& mesh);

// The boundary surface (faces used by one element), triangles for tet4 and
// quads for hex8, oriented outwards, at positions x (empty:
// the rest positions). OBJ (ASCII) and PLY (ASCII).
void write_obj_surface(const std::string& path, const Mesh& mesh, const Points& x = {});
void write_ply_surface(const std::string& path, const Mesh& mesh, const Points& x = {});

}  // namespace snh
