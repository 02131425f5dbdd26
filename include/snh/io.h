// Writing results for ParaView: ASCII VTK XML unstructured grids (.vtu) and a
// .pvd collection indexing them by step.
#pragma once

#include <string>
#include <vector>

#include "snh/mesh.h"

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

// Writes `mesh` with vertex positions `x` (xyz per vertex) to `path`.
// Throws snh::Error naming the path when it cannot be written or a field's
// size does not match the mesh.
void write_vtu(const std::string& path, const Mesh& mesh, const std::vector<double>& x,
               const std::vector<VtuPointField>& point_fields = {}, const std::vector<VtuCellField>& cell_fields = {});

// A ParaView collection: one (time, relative .vtu path) entry per step.
void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& steps);

}  // namespace snh
