// Volumetric meshes in the user's terms: vertex positions and elements
// (8-node hexahedra with 2x2x2 Gauss quadrature, or 4-node tetrahedra), the
// named groups and data arrays a mesh file carries, plus generators for the
// lattices the paper's scenes use.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "snh/points.h"

namespace snh {

enum class ElementType { hex8, tet4 };

// "hex8", "tet4": one table gives the names both ways. parse_element_type
// throws snh::Error naming the bad value and the valid ones; to_string is
// element_type_name.
const char* element_type_name(ElementType type);
ElementType parse_element_type(const std::string& text);
const char* to_string(ElementType type);
int nodes_per_element(ElementType type);
int quadrature_points(ElementType type);  // 8 for hex8 (2x2x2 Gauss), 1 for tet4

// A named set of a mesh's vertices and elements from the file: a Gmsh
// physical group, or a Medit reference number. Both lists are sorted
// ascending without repeats.
struct MeshGroup {
  std::string name;  // empty for an unnamed Gmsh physical group
  int tag = 0;       // the file's number for it (physical tag, Medit reference)
  // 3: a volume group, whose elements are the mesh elements in it and whose
  // vertices are theirs. 0, 1, 2: a point, curve or surface group, which
  // holds no mesh elements, only the vertices of its points, lines or faces.
  // Gmsh numbers groups per dimension, so a surface and a volume group may
  // share a tag.
  int dimension = 3;
  std::vector<int32_t> vertices;
  std::vector<int32_t> elements;
};

// Values attached to every vertex (point array) or every element (cell
// array): `components` values per vertex or element, vertex- or
// element-major (a vector array is x0 y0 z0 x1 y1 z1 ...).
struct MeshArray {
  std::string name;
  int components = 1;
  std::vector<double> values;
};

struct Mesh {
  ElementType type = ElementType::hex8;
  // Rest positions, one per vertex.
  Points positions;
  // Vertex indices, nodes_per_element() per element. hex8 nodes follow VTK's
  // VTK_HEXAHEDRON order: the bottom face (z-) counter-clockwise seen from
  // +z, then the top face; tet4 nodes are positively oriented
  // ((x1 - x0) x (x2 - x0)) . (x3 - x0) > 0.
  std::vector<int32_t> elements;
  // Groups and arrays as the file names them (empty for generated meshes).
  // Cell arrays and groups follow `elements`: readers drop the file's lower-
  // dimensional cells and keep the order of its volume cells.
  std::vector<MeshGroup> groups;
  std::vector<MeshArray> point_arrays;
  std::vector<MeshArray> cell_arrays;

  size_t vertex_count() const { return positions.size(); }
  size_t element_count() const { return elements.size() / nodes_per_element(type); }
  Vec3 vertex(size_t i) const { return {positions(i, 0), positions(i, 1), positions(i, 2)}; }
};

// Problems found by validate_mesh that do not stop a solve.
struct MeshWarnings {
  std::vector<int32_t> unused_vertices;
};

// Throws snh::Error naming the element or vertex for: a wrong element array
// length, indices out of range, repeated vertices within an element,
// non-finite coordinates, and rest elements with zero or negative volume at
// any quadrature point (inverted or degenerate), groups with indices out of
// range or unsorted, and arrays whose length is not components times the
// vertex (element) count. Unused vertices are only reported.
MeshWarnings validate_mesh(const Mesh& mesh);

// nx * ny * nz cubes of side h, from `origin`.
Mesh make_box_lattice(int nx, int ny, int nz, double h, std::array<double, 3> origin = {0.0, 0.0, 0.0});

// The cells of an nx * ny * nz lattice whose centres lie within `radius` of
// the lattice's axis parallel to z: a voxelized cylinder (possibly
// non-manifold at its rim, as the paper's lattices are). Unused lattice
// vertices are dropped.
Mesh make_voxel_cylinder(double radius, double length, double h);

// The box lattice with each cube split into six tetrahedra around its main
// diagonal (conforming across cubes).
Mesh make_tet_box(int nx, int ny, int nz, double h, std::array<double, 3> origin = {0.0, 0.0, 0.0});

// Each hex of a lattice-like hex8 mesh (all elements with the same
// orientation, as every generator here makes) split into six tetrahedra
// around its 0-6 diagonal, conforming across hexes. Tets come out positively
// oriented; throws snh::Error for a mesh that is not hex8. Hex e becomes tets
// 6e .. 6e + 5: groups keep their vertices and hold the tets of their hexes,
// point arrays are kept and each hex's cell-array values go to its six tets.
Mesh split_hexes_into_tets(const Mesh& hexes);

// Volume of the mesh at positions `x`: the sum over
// elements and quadrature points of det F times the rest volume.
double mesh_volume(const Mesh& mesh, const Points& x);

// The mesh's vertex spacing: (rest volume / vertices in elements)^(1/3).
double vertex_spacing(const Mesh& mesh);

}  // namespace snh
