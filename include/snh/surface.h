// From a character's surface to simulated flesh: closed triangle surfaces
// (read from OBJ, PLY or STL), their voxelization into a hex8 lattice, the
// embedding of the surface in that lattice (each surface vertex follows the
// trilinear interpolation of its cell), and the deformed surface written per
// frame.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "snh/mesh.h"

namespace snh {

struct TriangleSurface {
  std::vector<double> positions;   // xyz per vertex
  std::vector<int32_t> triangles;  // three vertex indices per triangle, outward normals by the right-hand rule
  size_t vertex_count() const { return positions.size() / 3; }
  size_t triangle_count() const { return triangles.size() / 3; }
};

// Reads .obj, .ply (ASCII and binary) and .stl (ASCII and binary); polygons
// are fanned into triangles. snh::Error naming the file and line (or byte
// offset) for malformed input.
TriangleSurface read_surface(const std::string& path);

// Writes the surface with vertex positions x (xyz per vertex; empty: its own)
// as OBJ.
void write_obj(const std::string& path, const TriangleSurface& surface, const std::vector<double>& x = {});

// A hex8 lattice covering a closed surface's interior.
struct Voxelization {
  Mesh lattice;                   // hex8, VTK node order, elements of one rest shape (cubes of side `cell`)
  double cell = 0.0;              // the cube side
  std::array<double, 3> origin{}; // the corner of grid cell (0, 0, 0)
  std::array<int, 3> dims{};      // grid cells per axis
  // Per element: its grid cell (i, j, k); the cube spans origin + cell * [i, i+1] x ...
  std::vector<std::array<int, 3>> element_cell;
};

// The rule for which grid cells become elements and how they connect is
// documented in the implementation's header comment and the README. Throws
// snh::Error for a surface that is not closed (naming open edges), cell <= 0,
// or a lattice that would be empty or too large.
Voxelization voxelize(const TriangleSurface& surface, double cell);

// Each surface vertex's element and its 8 trilinear weights (hex8 node
// order), so that the surface follows the lattice.
struct Embedding {
  std::vector<int32_t> element;  // per surface vertex
  std::vector<double> weights;   // 8 per surface vertex, summing to 1
};

// Throws snh::Error naming a surface vertex that lies in no element.
Embedding embed(const Voxelization& voxels, const TriangleSurface& surface);

// The surface's vertex positions (xyz per vertex) for lattice positions x.
std::vector<double> embedded_positions(const Embedding& embedding, const Mesh& lattice, const std::vector<double>& x);

}  // namespace snh
