// VTK legacy ASCII (version 4.2, the layout ParaView, meshio and our reader
// read): DATASET UNSTRUCTURED_GRID with double POINTS, CELLS in mesh order
// with mesh.h's node order (VTK_TETRA 10, VTK_HEXAHEDRON 12, whose node
// orders mesh.h follows), then point and cell arrays as FIELD arrays of
// doubles (arrays the reader would refuse, carried_arrays, are left out).
// Groups are not written: the format has none.
#include "io/writers.h"

namespace snh::io {
namespace {

// Legacy VTK names are single tokens: spaces and other bytes a reader would
// split on or not print are written %XX, as VTK does (and '%' itself).
std::string encode_name(const std::string& name) {
  static const char kHex[] = "0123456789ABCDEF";
  std::string out;
  for (char c : name) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u <= ' ' || u >= 127 || c == '%') {
      out += '%';
      out += kHex[u >> 4];
      out += kHex[u & 15];
    } else {
      out += c;
    }
  }
  return out;
}

// The reader takes at most 64 components (as VTK's own legacy reader).
void write_arrays(std::ofstream& file, const char* section, const std::vector<MeshArray>& all, size_t tuples) {
  const std::vector<const MeshArray*> arrays = carried_arrays(all, 64);
  if (arrays.empty()) return;
  file << section << " " << tuples << "\nFIELD FieldData " << arrays.size() << "\n";
  for (const MeshArray* array : arrays) {
    const MeshArray& a = *array;
    file << encode_name(a.name) << " " << a.components << " " << tuples << " double\n";
    const size_t c = static_cast<size_t>(a.components);
    for (size_t t = 0; t < tuples; ++t)
      for (size_t k = 0; k < c; ++k) file << a.values[c * t + k] << (k + 1 == c ? "\n" : " ");
  }
}

}  // namespace

void write_vtk_legacy(const std::string& path, const Mesh& mesh) {
  const int n = nodes_per_element(mesh.type);
  const size_t vertices = mesh.vertex_count(), elements = mesh.element_count();
  std::ofstream file;
  open_for_writing(file, path);
  file << "# vtk DataFile Version 4.2\nsnh mesh (" << to_string(mesh.type) << ")\nASCII\nDATASET UNSTRUCTURED_GRID\n"
       << "POINTS " << vertices << " double\n";
  for (size_t v = 0; v < vertices; ++v)
    file << mesh.positions(v, 0) << " " << mesh.positions(v, 1) << " " << mesh.positions(v, 2) << "\n";
  file << "CELLS " << elements << " " << static_cast<size_t>(n + 1) * elements << "\n";
  for (size_t e = 0; e < elements; ++e) {
    file << n;
    for (int a = 0; a < n; ++a) file << " " << mesh.elements[static_cast<size_t>(n) * e + a];
    file << "\n";
  }
  const int cell_type = mesh.type == ElementType::hex8 ? 12 : 10;
  file << "CELL_TYPES " << elements << "\n";
  for (size_t e = 0; e < elements; ++e) file << cell_type << "\n";
  write_arrays(file, "POINT_DATA", mesh.point_arrays, vertices);
  write_arrays(file, "CELL_DATA", mesh.cell_arrays, elements);
  finish_writing(file, path);
}

}  // namespace snh::io
