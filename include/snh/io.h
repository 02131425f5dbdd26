// Writing results for ParaView: ASCII VTK XML unstructured grids (.vtu) of
// volume meshes and of triangle surfaces, and .pvd collections indexing them
// by step (and part, for several files per step).
#pragma once

#include <string>
#include <vector>

#include "snh/mesh.h"
#include "snh/surface.h"

namespace snh {

struct VtuPointField {
  std::string name;
  int components = 1;          // 1 or 3
  std::vector<double> values;  // components per vertex
};

struct VtuCellField {
  std::string name;
  std::vector<double> values;  // components per element
  // 1 (scalar), 3 (vector) or 9 (3x3 tensor, row-major: XX XY XZ YX ...,
  // VTK's order). After `values` so that {name, values} stays a scalar.
  int components = 1;
};

// Writes `mesh` with vertex positions `x` to `path`.
// Throws snh::Error naming the path when it cannot be written or a field's
// size does not match the mesh.
void write_vtu(const std::string& path, const Mesh& mesh, const Points& x,
               const std::vector<VtuPointField>& point_fields = {}, const std::vector<VtuCellField>& cell_fields = {});

// A triangle surface with vertex positions x (empty: its
// own) as a .vtu of VTK_TRIANGLE cells, e.g. an embedded surface per frame
// next to its lattice. Errors as write_vtu's.
void write_surface_vtu(const std::string& path, const TriangleSurface& surface, const Points& x = {},
                       const std::vector<VtuPointField>& point_fields = {});

// A ParaView collection: one (time, relative .vtu path) entry per step.
void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& steps);

// One file of a collection: several files of one time with different parts
// (e.g. 0 the lattice, 1 the surface) show as the blocks of one data set.
struct PvdDataSet {
  double time = 0.0;
  std::string file;  // relative to the .pvd
  int part = 0;
};
void write_pvd_parts(const std::string& path, const std::vector<PvdDataSet>& datasets);

}  // namespace snh
