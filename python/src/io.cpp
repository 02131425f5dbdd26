// Mesh files in and out, and results for ParaView (snh/mesh_io.h, io.h).
#include "snh/io.h"

#include "common.h"
#include "snh/fields.h"
#include "snh/mesh_io.h"

namespace snh_python {

namespace {

// Positions (n, 3) of the mesh's vertices given from Python (not None).
snh::Points mesh_positions(const snh::Mesh& mesh, py::handle x) {
  return to_points(x, "positions", mesh.vertex_count());
}

// A field's values as components per row: (rows,), (rows, c) or (rows, 3, 3)
// (row-major: VTK's XX XY XZ YX ... order).
std::vector<double> field_values(py::handle values, const std::string& what, size_t rows, int& components) {
  const py::array a = py::module_::import("numpy").attr("asarray")(values);
  if (a.ndim() == 0 || a.ndim() > 3 || static_cast<size_t>(a.shape(0)) != rows)
    throw py::value_error(what + ": expected " + std::to_string(rows) + " rows (one per vertex or element)");
  components = 1;
  for (py::ssize_t d = 1; d < a.ndim(); ++d) components *= static_cast<int>(a.shape(d));
  return to_doubles(a.attr("reshape")(static_cast<py::ssize_t>(rows), components), what, components, -1, false);
}

}  // namespace

void bind_io(py::module_& m) {
  m.def(
      "read_mesh",
      [](const std::string& path, bool allow_coincident_vertices) {
        snh::MeshReadOptions options;
        options.allow_coincident_vertices = allow_coincident_vertices;
        return snh::read_mesh(path, options);
      },
      py::arg("path"), py::arg("allow_coincident_vertices") = false,
      "Reads .msh, .vtk, .vtu, .mesh, .node/.ele (tet4 or hex8) with groups and arrays; snh.Error names the file "
      "and line at fault.");
  m.def("write_mesh", &snh::write_mesh, py::arg("path"), py::arg("mesh"),
        "Writes the mesh at rest in the format its extension names (.msh, .vtk, .vtu, .mesh, .node/.ele).");
  m.def(
      "write_obj_surface",
      [](const std::string& path, const snh::Mesh& mesh, py::handle x) {
        snh::write_obj_surface(path, mesh, x.is_none() ? snh::Points{} : mesh_positions(mesh, x));
      },
      py::arg("path"), py::arg("mesh"), py::arg("positions") = py::none(), "The boundary surface as OBJ.");
  m.def(
      "write_ply_surface",
      [](const std::string& path, const snh::Mesh& mesh, py::handle x) {
        snh::write_ply_surface(path, mesh, x.is_none() ? snh::Points{} : mesh_positions(mesh, x));
      },
      py::arg("path"), py::arg("mesh"), py::arg("positions") = py::none(), "The boundary surface as PLY.");
  m.def(
      "write_vtu",
      [](const std::string& path, const snh::Mesh& mesh, py::handle x, py::object point_fields,
         py::object cell_fields) {
        std::vector<snh::VtuPointField> points;
        if (!point_fields.is_none())
          for (const auto& item : point_fields.cast<py::dict>()) {
            snh::VtuPointField f;
            f.name = item.first.cast<std::string>();
            f.values = field_values(item.second, "point field '" + f.name + "'", mesh.vertex_count(), f.components);
            points.push_back(std::move(f));
          }
        std::vector<snh::VtuCellField> cells;
        if (!cell_fields.is_none())
          for (const auto& item : cell_fields.cast<py::dict>()) {
            snh::VtuCellField f;
            f.name = item.first.cast<std::string>();
            f.values = field_values(item.second, "cell field '" + f.name + "'", mesh.element_count(), f.components);
            cells.push_back(std::move(f));
          }
        if (x.is_none())
          snh::write_vtu(path, mesh, mesh.positions, points, cells);
        else
          snh::write_vtu(path, mesh, mesh_positions(mesh, x), points, cells);
      },
      py::arg("path"), py::arg("mesh"), py::arg("positions") = py::none(), py::arg("point_fields") = py::none(),
      py::arg("cell_fields") = py::none(),
      "Writes an ASCII .vtu at positions (n, 3) (default: rest). point_fields: {name: (n,) or (n, 3)}; "
      "cell_fields: {name: (m,), (m, 3) or (m, 3, 3)}.");
  m.def(
      "element_fields_for_vtu",
      [](const snh::ElementFields& fields, const snh::MaterialMap& materials) {
        py::dict out;
        for (snh::VtuCellField& f : snh::element_fields_for_vtu(fields, materials)) {
          const py::ssize_t rows = static_cast<py::ssize_t>(f.values.size()) / f.components;
          py::array_t<double> a = f.components == 1   ? to_array(std::move(f.values), {rows})
                                  : f.components == 9 ? to_array(std::move(f.values), {rows, 3, 3})
                                                      : to_array(std::move(f.values), {rows, f.components});
          out[py::str(f.name)] = a;
        }
        return out;
      },
      py::arg("fields"), py::arg("materials"),
      "The fields as write_vtu cell_fields: {name: array}, tensors (m, 3, 3) [row, column].");
  m.def("write_pvd", &snh::write_pvd, py::arg("path"), py::arg("steps"),
        "A ParaView collection of (time, relative .vtu path) entries.");
}

}  // namespace snh_python
