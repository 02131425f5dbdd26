// Meshes, their generators and the measures on them (snh/mesh.h, loads.h,
// shape.h).
#include "snh/mesh.h"

#include "common.h"
#include "snh/loads.h"
#include "snh/shape.h"

namespace snh_python {

namespace {

snh::ElementType type_for_columns(py::ssize_t columns) {
  if (columns == 8) return snh::ElementType::hex8;
  if (columns == 4) return snh::ElementType::tet4;
  throw py::value_error("elements: expected 8 (hex8) or 4 (tet4) vertices per element, got " + std::to_string(columns));
}

py::ssize_t columns_of(py::handle elements) {
  const py::array a = py::module_::import("numpy").attr("asarray")(elements);
  if (a.ndim() != 2) throw py::value_error("elements: expected a 2-D array (m, 8) or (m, 4)");
  return a.shape(1);
}

snh::Mesh make_mesh(py::handle positions, py::handle elements, std::optional<snh::ElementType> type) {
  snh::Mesh mesh;
  mesh.positions = to_points(positions, "positions");
  mesh.type = type ? *type : type_for_columns(columns_of(elements));
  mesh.elements =
      to_indices(elements, "elements", snh::nodes_per_element(mesh.type), static_cast<int64_t>(mesh.vertex_count()));
  return mesh;
}

py::array_t<int32_t> elements_array(const snh::Mesh& mesh) {
  const py::ssize_t k = snh::nodes_per_element(mesh.type);
  return copy_array(mesh.elements, {static_cast<py::ssize_t>(mesh.elements.size()) / k, k});
}

py::array_t<double> array_values(const snh::MeshArray& a) {
  const py::ssize_t c = std::max(a.components, 1);
  const py::ssize_t n = static_cast<py::ssize_t>(a.values.size()) / c;
  return c == 1 ? copy_array(a.values, {n}) : copy_array(a.values, {n, c});
}

}  // namespace

void bind_mesh(py::module_& m) {
  py::enum_<snh::ElementType>(m, "ElementType", "Element kind: 8-node hexahedra or 4-node tetrahedra.")
      .value(snh::element_type_name(snh::ElementType::hex8), snh::ElementType::hex8)
      .value(snh::element_type_name(snh::ElementType::tet4), snh::ElementType::tet4);

  py::class_<snh::MeshGroup>(m, "MeshGroup",
                             "A named set of vertices and elements from a mesh file (Gmsh physical group, Medit "
                             "reference).")
      .def(py::init([](const py::kwargs& kw) { return from_kwargs<snh::MeshGroup>(kw); }))
      .def_readwrite("name", &snh::MeshGroup::name, "Group name (empty for an unnamed Gmsh group).")
      .def_readwrite("tag", &snh::MeshGroup::tag, "The file's number for the group.")
      .def_readwrite("dimension", &snh::MeshGroup::dimension, "3 for a volume group; 0, 1, 2 for lower ones.")
      .def_property(
          "vertices", [](const snh::MeshGroup& g) { return copy_array(g.vertices, {py::ssize_t(g.vertices.size())}); },
          [](snh::MeshGroup& g, py::handle v) { g.vertices = to_indices(v, "vertices", 0, -1); },
          "Vertex indices, int32 (n,).")
      .def_property(
          "elements", [](const snh::MeshGroup& g) { return copy_array(g.elements, {py::ssize_t(g.elements.size())}); },
          [](snh::MeshGroup& g, py::handle v) { g.elements = to_indices(v, "elements", 0, -1); },
          "Element indices, int32 (m,).")
      .def("__repr__", [](const snh::MeshGroup& g) {
        return "MeshGroup(name='" + g.name + "', tag=" + std::to_string(g.tag) +
               ", dimension=" + std::to_string(g.dimension) + ")";
      });

  py::class_<snh::MeshArray>(m, "MeshArray", "Values per vertex (point array) or per element (cell array).")
      .def(py::init([](const py::kwargs& kw) { return from_kwargs<snh::MeshArray>(kw); }))
      .def_readwrite("name", &snh::MeshArray::name, "Array name.")
      .def_readwrite("components", &snh::MeshArray::components, "Values per vertex or element.")
      .def_property(
          "values", &array_values,
          [](snh::MeshArray& a, py::handle v) {
            const py::array arr = py::module_::import("numpy").attr("asarray")(v);
            a.values = to_doubles(arr.attr("reshape")(-1, a.components), "values", a.components, -1, false);
          },
          "float64 (n,) for one component, else (n, components).");

  py::class_<snh::Mesh>(m, "Mesh",
                        "A volumetric mesh: rest positions (n, 3) float64 and elements (m, 8) hex8 or (m, 4) tet4.\n\n"
                        "hex8 nodes follow VTK_HEXAHEDRON order; tet4 nodes are positively oriented.")
      .def(py::init(&make_mesh), py::arg("positions"), py::arg("elements"), py::arg("type") = py::none(),
           "Builds a mesh from positions (n, 3) and elements (m, 8) or (m, 4); the element type follows the "
           "column count unless given. Raises ValueError for wrong shapes or dtypes, NaN/Inf positions and "
           "indices outside [0, n).")
      .def_readwrite("type", &snh::Mesh::type, "ElementType of every element.")
      .def_property(
          "positions", [](const snh::Mesh& mesh) { return xyz_array(mesh.positions); },
          [](snh::Mesh& mesh, py::handle v) { mesh.positions = to_points(v, "positions"); },
          "Rest positions, a float64 (n, 3) copy.")
      .def_property(
          "elements", &elements_array,
          [](snh::Mesh& mesh, py::handle v) {
            mesh.elements =
                to_indices(v, "elements", snh::nodes_per_element(mesh.type), static_cast<int64_t>(mesh.vertex_count()));
          },
          "Element vertex indices, an int32 (m, 8) or (m, 4) copy.")
      .def_readwrite("groups", &snh::Mesh::groups, "The file's groups (a list of MeshGroup; a copy).")
      .def_readwrite("point_arrays", &snh::Mesh::point_arrays, "The file's point arrays (MeshArray list; a copy).")
      .def_readwrite("cell_arrays", &snh::Mesh::cell_arrays, "The file's cell arrays (MeshArray list; a copy).")
      .def_property_readonly("vertex_count", &snh::Mesh::vertex_count, "Number of vertices n.")
      .def_property_readonly("element_count", &snh::Mesh::element_count, "Number of elements m.")
      .def_property_readonly(
          "nodes_per_element", [](const snh::Mesh& mesh) { return snh::nodes_per_element(mesh.type); },
          "8 for hex8, 4 for tet4.")
      .def(
          "validate", [](const snh::Mesh& mesh) { return snh::validate_mesh(mesh).unused_vertices; },
          "Raises snh.Error naming the element or vertex at fault; returns the unused vertices.")
      .def(
          "volume",
          [](const snh::Mesh& mesh, py::object x) {
            if (x.is_none()) return snh::mesh_volume(mesh, mesh.positions);
            return snh::mesh_volume(mesh, to_points(x, "positions", mesh.vertex_count()));
          },
          py::arg("positions") = py::none(), "Volume at positions (n, 3) (default: rest).")
      .def(
          "copy", [](const snh::Mesh& mesh) { return snh::Mesh(mesh); }, "A deep copy.")
      .def("__repr__", [](const snh::Mesh& mesh) {
        return std::string("Mesh(") + snh::to_string(mesh.type) + ", " + std::to_string(mesh.vertex_count()) +
               " vertices, " + std::to_string(mesh.element_count()) + " elements)";
      });

  m.def("make_box_lattice", &snh::make_box_lattice, py::arg("nx"), py::arg("ny"), py::arg("nz"), py::arg("h"),
        py::arg("origin") = std::array<double, 3>{0, 0, 0}, "nx * ny * nz hex8 cubes of side h from origin.");
  m.def("make_tet_box", &snh::make_tet_box, py::arg("nx"), py::arg("ny"), py::arg("nz"), py::arg("h"),
        py::arg("origin") = std::array<double, 3>{0, 0, 0},
        "The box lattice with each cube split into six tet4 around its main diagonal.");
  m.def("make_voxel_cylinder", &snh::make_voxel_cylinder, py::arg("radius"), py::arg("length"), py::arg("h"),
        "The lattice cells within radius of the z axis: a voxelized hex8 cylinder.");
  m.def("split_hexes_into_tets", &snh::split_hexes_into_tets, py::arg("mesh"),
        "Each hex of a lattice-like hex8 mesh split into six tets (hex e becomes tets 6e .. 6e+5).");
  m.def("vertex_spacing", &snh::vertex_spacing, py::arg("mesh"), "(rest volume / vertices in elements)^(1/3).");
  m.def(
      "lump_body_force",
      [](const snh::Mesh& mesh, py::handle force) {
        return to_array(snh::lump_body_force(mesh, to_vec3(force, "force_per_rest_volume")));
      },
      py::arg("mesh"), py::arg("force_per_rest_volume"),
      "Nodal forces (n, 3) of a uniform body force per rest volume.");
  m.def(
      "lumped_mass",
      [](const snh::Mesh& mesh, double density) {
        std::vector<double> mass = snh::lumped_mass(mesh, density);
        const py::ssize_t n = static_cast<py::ssize_t>(mass.size());
        return to_array(std::move(mass), {n});
      },
      py::arg("mesh"), py::arg("density"), "Row-sum lumped mass per vertex (n,) of a uniform density.");

  py::class_<snh::ShapeDeviation>(m, "ShapeDeviation", "Distance from the rest shape once rigid motion is removed.")
      .def_readonly("rms_distance", &snh::ShapeDeviation::rms_distance, "RMS distance after the best rigid fit.")
      .def_readonly("radius_of_gyration", &snh::ShapeDeviation::radius_of_gyration, "Of the rest shape.")
      .def_property_readonly("relative", &snh::ShapeDeviation::relative, "rms_distance / radius_of_gyration.");
  m.def(
      "shape_deviation",
      [](const snh::Mesh& mesh, py::handle x) {
        return snh::shape_deviation(mesh, to_points(x, "positions", mesh.vertex_count()));
      },
      py::arg("mesh"), py::arg("positions"), "How far positions (n, 3) are from the rest shape up to a rigid motion.");
}

}  // namespace snh_python
