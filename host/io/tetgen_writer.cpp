// TetGen .node/.ele pair: points numbered from 1 (TetGen's default; the
// reader takes the first number as the base) with no attributes or
// markers, then 4-node tetrahedra in mesh order and node order (positive
// volume, mesh.h; the reader turns mirrored tetrahedra over, so either
// orientation reads back). Groups and arrays are not written. write_mesh
// refuses hex8 meshes before calling this.
#include "io/writers.h"

namespace snh::io {

void write_tetgen(const std::string& node_path, const std::string& ele_path, const Mesh& mesh) {
  std::ofstream node;
  open_for_writing(node, node_path);
  node << "# snh mesh: points, dimension, attributes, boundary markers\n" << mesh.vertex_count() << " 3 0 0\n";
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    node << v + 1 << " " << mesh.positions(v, 0) << " " << mesh.positions(v, 1) << " " << mesh.positions(v, 2) << "\n";
  finish_writing(node, node_path);
  std::ofstream ele;
  open_for_writing(ele, ele_path);
  ele << "# snh mesh: tetrahedra, nodes per tetrahedron, region attribute\n" << mesh.element_count() << " 4 0\n";
  for (size_t e = 0; e < mesh.element_count(); ++e) {
    ele << e + 1;
    for (int a = 0; a < 4; ++a) ele << " " << mesh.elements[4 * e + a] + 1;
    ele << "\n";
  }
  finish_writing(ele, ele_path);
}

}  // namespace snh::io
