// ASCII VTK XML output: readable by ParaView and easy to diff or grep in
// tests. Numbers carry 17 significant digits so results read back bit for bit.
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <limits>
#include <locale>
#include <sstream>

#include "io/writers.h"
#include "snh/error.h"
#include "snh/io.h"

namespace snh {
namespace {

// VTK cell type ids (vtkCellType.h).
constexpr int kVtkTriangle = 5;
constexpr int kVtkTetra = 10;
constexpr int kVtkHexahedron = 12;

// Field names and file names go into XML attributes.
std::string xml_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  return out;
}

// `per_line` values to a line, so large arrays stay readable in an editor.
void write_values(std::ofstream& file, const double* values, size_t count, int per_line) {
  for (size_t i = 0; i < count; ++i) file << ((i % per_line == 0) ? "\n          " : " ") << values[i];
  file << "\n";
}

void check_sizes(const std::string& path, const Mesh& mesh, const std::vector<double>& x,
                 const std::vector<VtuPointField>& point_fields, const std::vector<VtuCellField>& cell_fields) {
  const int n = nodes_per_element(mesh.type);
  const size_t vertices = mesh.vertex_count(), elements = mesh.element_count();
  if (mesh.positions.xyz().size() % 3 != 0 || mesh.elements.size() % n != 0) {
    std::ostringstream s;
    s << "write_vtu " << path << ": the mesh is malformed (" << mesh.positions.xyz().size() << " position values, "
      << mesh.elements.size() << " element indices for " << to_string(mesh.type) << ")";
    throw Error(s.str());
  }
  if (x.size() != 3 * vertices) {
    std::ostringstream s;
    s << "write_vtu " << path << ": the positions have " << x.size() << " values, but the mesh has " << vertices
      << " vertices (" << 3 * vertices << " values expected)";
    throw Error(s.str());
  }
  // Offsets are written as Int32 like the connectivity.
  if (mesh.elements.size() > static_cast<size_t>(std::numeric_limits<int32_t>::max())) {
    std::ostringstream s;
    s << "write_vtu " << path << ": " << elements << " elements are too many for 32-bit offsets";
    throw Error(s.str());
  }
  for (size_t i = 0; i < mesh.elements.size(); ++i)
    if (mesh.elements[i] < 0 || static_cast<size_t>(mesh.elements[i]) >= vertices) {
      std::ostringstream s;
      s << "write_vtu " << path << ": element " << i / n << " refers to vertex " << mesh.elements[i]
        << ", but the mesh has " << vertices << " vertices";
      throw Error(s.str());
    }
  for (const VtuPointField& f : point_fields) {
    if (f.name.empty()) throw Error("write_vtu " + path + ": a point field has no name");
    if (f.components != 1 && f.components != 3) {
      std::ostringstream s;
      s << "write_vtu " << path << ": point field \"" << f.name << "\" has " << f.components
        << " components; 1 or 3 are supported";
      throw Error(s.str());
    }
    if (f.values.size() != vertices * f.components) {
      std::ostringstream s;
      s << "write_vtu " << path << ": point field \"" << f.name << "\" has " << f.values.size() << " values, but "
        << vertices << " vertices x " << f.components << " components need " << vertices * f.components;
      throw Error(s.str());
    }
  }
  for (const VtuCellField& f : cell_fields) {
    if (f.name.empty()) throw Error("write_vtu " + path + ": a cell field has no name");
    if (f.components != 1 && f.components != 3 && f.components != 9) {
      std::ostringstream s;
      s << "write_vtu " << path << ": cell field \"" << f.name << "\" has " << f.components
        << " components; 1, 3 or 9 are supported";
      throw Error(s.str());
    }
    if (f.values.size() != elements * f.components) {
      std::ostringstream s;
      s << "write_vtu " << path << ": cell field \"" << f.name << "\" has " << f.values.size() << " values, but "
        << elements << " elements x " << f.components << " components need " << elements * f.components;
      throw Error(s.str());
    }
  }
}

// The <Piece> of an unstructured grid of one cell type, after the sizes are
// checked: `nodes` vertices per cell in `connectivity`.
void write_grid(const std::string& path, const std::vector<double>& x, const std::vector<int32_t>& connectivity,
                int nodes, int cell_type, const std::vector<VtuPointField>& point_fields,
                const std::vector<VtuCellField>& cell_fields) {
  const size_t vertices = x.size() / 3, cells = connectivity.size() / nodes;
  std::ofstream file;
  io::open_for_writing(file, path);
  file << "<?xml version=\"1.0\"?>\n"
       << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
       << "  <UnstructuredGrid>\n"
       << "    <Piece NumberOfPoints=\"" << vertices << "\" NumberOfCells=\"" << cells << "\">\n";

  if (!point_fields.empty()) {
    file << "      <PointData>\n";
    for (const VtuPointField& f : point_fields) {
      file << "        <DataArray type=\"Float64\" Name=\"" << xml_escape(f.name) << "\" NumberOfComponents=\""
           << f.components << "\" format=\"ascii\">";
      write_values(file, f.values.data(), f.values.size(), f.components == 3 ? 3 : 6);
      file << "        </DataArray>\n";
    }
    file << "      </PointData>\n";
  }
  if (!cell_fields.empty()) {
    file << "      <CellData>\n";
    for (const VtuCellField& f : cell_fields) {
      // Scalars without NumberOfComponents, as before it existed here
      // (meshio then reads them as (cells,) rather than (cells, 1)).
      file << "        <DataArray type=\"Float64\" Name=\"" << xml_escape(f.name) << "\"";
      if (f.components != 1) file << " NumberOfComponents=\"" << f.components << "\"";
      file << " format=\"ascii\">";
      write_values(file, f.values.data(), f.values.size(), f.components == 1 ? 6 : f.components);
      file << "        </DataArray>\n";
    }
    file << "      </CellData>\n";
  }

  file << "      <Points>\n"
       << "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">";
  write_values(file, x.data(), x.size(), 3);
  file << "        </DataArray>\n"
       << "      </Points>\n";

  file << "      <Cells>\n"
       << "        <DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">";
  for (size_t e = 0; e < cells; ++e) {
    file << "\n         ";
    for (int a = 0; a < nodes; ++a) file << ' ' << connectivity[nodes * e + a];
  }
  file << "\n        </DataArray>\n"
       << "        <DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">";
  for (size_t e = 0; e < cells; ++e) file << ((e % 12 == 0) ? "\n          " : " ") << nodes * (e + 1);
  file << "\n        </DataArray>\n"
       << "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">";
  for (size_t e = 0; e < cells; ++e) file << ((e % 24 == 0) ? "\n          " : " ") << cell_type;
  file << "\n        </DataArray>\n"
       << "      </Cells>\n"
       << "    </Piece>\n"
       << "  </UnstructuredGrid>\n"
       << "</VTKFile>\n";
  io::finish_writing(file, path);
}

}  // namespace

void write_vtu(const std::string& path, const Mesh& mesh, const Points& x,
               const std::vector<VtuPointField>& point_fields, const std::vector<VtuCellField>& cell_fields) {
  // Everything is checked before the file is touched, so a bad call leaves no
  // half-written file behind.
  check_sizes(path, mesh, x.xyz(), point_fields, cell_fields);
  write_grid(path, x.xyz(), mesh.elements, nodes_per_element(mesh.type),
             mesh.type == ElementType::hex8 ? kVtkHexahedron : kVtkTetra, point_fields, cell_fields);
}

namespace io {

// write_mesh's .vtu: the mesh at rest with its point and cell arrays (the
// reader takes at most 64 components); groups are not written.
void write_vtu_mesh(const std::string& path, const Mesh& mesh) {
  std::vector<VtuPointField> points;
  for (const MeshArray* a : carried_arrays(mesh.point_arrays, 64))
    points.push_back({a->name, a->components, a->values});
  std::vector<VtuCellField> cells;
  for (const MeshArray* a : carried_arrays(mesh.cell_arrays, 64)) cells.push_back({a->name, a->values, a->components});
  // A mesh's arrays may have any number of components (write_vtu's fields
  // are the 1, 3 and 9 ParaView shows as scalars, vectors and tensors).
  check_sizes(path, mesh, mesh.positions.xyz(), {}, {});
  write_grid(path, mesh.positions.xyz(), mesh.elements, nodes_per_element(mesh.type),
             mesh.type == ElementType::hex8 ? kVtkHexahedron : kVtkTetra, points, cells);
}

}  // namespace io

void write_surface_vtu(const std::string& path, const TriangleSurface& surface, const Points& x,
                       const std::vector<VtuPointField>& point_fields) {
  const std::vector<double>& points = x.empty() ? surface.positions.xyz() : x.xyz();
  // The checks of write_vtu on the triangles as a mesh of 3-node cells.
  if (points.size() != surface.positions.xyz().size() || surface.positions.xyz().size() % 3 != 0 ||
      surface.triangles.size() % 3 != 0) {
    std::ostringstream s;
    s << "write_surface_vtu " << path << ": the positions have " << points.size() << " values for a surface of "
      << surface.vertex_count() << " vertices (" << surface.positions.xyz().size() << " values) and "
      << surface.triangles.size() << " triangle indices";
    throw Error(s.str());
  }
  for (size_t i = 0; i < surface.triangles.size(); ++i)
    if (surface.triangles[i] < 0 || static_cast<size_t>(surface.triangles[i]) >= surface.vertex_count()) {
      std::ostringstream s;
      s << "write_surface_vtu " << path << ": triangle " << i / 3 << " refers to vertex " << surface.triangles[i]
        << ", but the surface has " << surface.vertex_count() << " vertices";
      throw Error(s.str());
    }
  for (const VtuPointField& f : point_fields)
    if (f.name.empty() || (f.components != 1 && f.components != 3) ||
        f.values.size() != surface.vertex_count() * f.components) {
      std::ostringstream s;
      s << "write_surface_vtu " << path << ": point field \"" << f.name << "\" has " << f.values.size() << " values in "
        << f.components << " components for " << surface.vertex_count()
        << " vertices (a name and 1 or 3 components needed)";
      throw Error(s.str());
    }
  write_grid(path, points, surface.triangles, 3, kVtkTriangle, point_fields, {});
}

void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& steps) {
  std::vector<PvdDataSet> datasets;
  datasets.reserve(steps.size());
  for (const auto& [time, file] : steps) datasets.push_back({time, file, 0});
  write_pvd_parts(path, datasets);
}

void write_pvd_parts(const std::string& path, const std::vector<PvdDataSet>& datasets) {
  for (size_t i = 0; i < datasets.size(); ++i) {
    if (!std::isfinite(datasets[i].time)) {
      std::ostringstream s;
      s << "write_pvd " << path << ": step " << i << " (" << datasets[i].file << ") has a non-finite time "
        << datasets[i].time;
      throw Error(s.str());
    }
    if (datasets[i].file.empty()) {
      std::ostringstream s;
      s << "write_pvd " << path << ": step " << i << " has no file name";
      throw Error(s.str());
    }
    if (datasets[i].part < 0) {
      std::ostringstream s;
      s << "write_pvd " << path << ": step " << i << " (" << datasets[i].file << ") has part " << datasets[i].part
        << " (parts are numbered from 0)";
      throw Error(s.str());
    }
  }
  std::ofstream file;
  io::open_for_writing(file, path);
  // Times in full: at 6 digits two steps of a long run (1000.001 s and
  // 1000.002 s) would share a timestep.
  file << std::setprecision(std::numeric_limits<double>::max_digits10);
  file << "<?xml version=\"1.0\"?>\n"
       << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
       << "  <Collection>\n";
  for (const PvdDataSet& d : datasets)
    file << "    <DataSet timestep=\"" << d.time << "\" group=\"\" part=\"" << d.part << "\" file=\""
         << xml_escape(d.file) << "\"/>\n";
  file << "  </Collection>\n"
       << "</VTKFile>\n";
  io::finish_writing(file, path);
}

}  // namespace snh
