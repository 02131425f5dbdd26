// Picking vertices and elements by place or by the file's groups and arrays
// (snh/selection.h); every selector returns sorted int32 indices.
#include "snh/selection.h"

#include "common.h"

namespace snh_python {

namespace {

py::array_t<int32_t> indices(std::vector<int32_t>&& v) {
  const py::ssize_t n = static_cast<py::ssize_t>(v.size());
  return to_array(std::move(v), {n});
}

}  // namespace

void bind_selection(py::module_& m) {
  using snh::Mesh;
  using V3 = std::array<double, 3>;
  m.def(
      "vertices_in_box",
      [](const Mesh& mesh, const V3& lo, const V3& hi) { return indices(snh::vertices_in_box(mesh, lo, hi)); },
      py::arg("mesh"), py::arg("lo"), py::arg("hi"), "Vertices with lo <= x <= hi in every coordinate, int32 (k,).");
  m.def(
      "vertices_on_plane",
      [](const Mesh& mesh, const V3& point, const V3& normal, double tolerance) {
        return indices(snh::vertices_on_plane(mesh, point, normal, tolerance));
      },
      py::arg("mesh"), py::arg("point"), py::arg("normal"), py::arg("tolerance") = 1e-9,
      "Vertices within tolerance of the plane through point with normal.");
  m.def(
      "vertices_in_sphere",
      [](const Mesh& mesh, const V3& center, double radius) {
        return indices(snh::vertices_in_sphere(mesh, center, radius));
      },
      py::arg("mesh"), py::arg("center"), py::arg("radius"), "Vertices with |x - center| <= radius.");
  m.def(
      "vertices_in_group",
      [](const Mesh& mesh, py::handle group, int dimension) {
        if (py::isinstance<py::str>(group))
          return indices(snh::vertices_in_group(mesh, group.cast<std::string>(), dimension));
        return indices(snh::vertices_in_group(mesh, group.cast<int>(), dimension));
      },
      py::arg("mesh"), py::arg("group"), py::arg("dimension") = -1,
      "The vertices of the group with this name (str) or tag (int).");
  m.def(
      "vertices_with_value",
      [](const Mesh& mesh, const std::string& array, double value) {
        return indices(snh::vertices_with_value(mesh, array, value));
      },
      py::arg("mesh"), py::arg("array"), py::arg("value"), "Vertices whose point-array value equals value.");
  m.def(
      "vertices_with_value_in",
      [](const Mesh& mesh, const std::string& array, double lo, double hi) {
        return indices(snh::vertices_with_value_in(mesh, array, lo, hi));
      },
      py::arg("mesh"), py::arg("array"), py::arg("lo"), py::arg("hi"), "Vertices whose value lies in [lo, hi].");
  m.def(
      "elements_in_box",
      [](const Mesh& mesh, const V3& lo, const V3& hi) { return indices(snh::elements_in_box(mesh, lo, hi)); },
      py::arg("mesh"), py::arg("lo"), py::arg("hi"), "Elements whose centroid lies in the box.");
  m.def(
      "elements_in_sphere",
      [](const Mesh& mesh, const V3& center, double radius) {
        return indices(snh::elements_in_sphere(mesh, center, radius));
      },
      py::arg("mesh"), py::arg("center"), py::arg("radius"), "Elements whose centroid lies in the sphere.");
  m.def(
      "elements_in_group",
      [](const Mesh& mesh, py::handle group) {
        if (py::isinstance<py::str>(group)) return indices(snh::elements_in_group(mesh, group.cast<std::string>()));
        return indices(snh::elements_in_group(mesh, group.cast<int>()));
      },
      py::arg("mesh"), py::arg("group"), "The elements of the volume group with this name (str) or tag (int).");
  m.def(
      "elements_with_value",
      [](const Mesh& mesh, const std::string& array, double value) {
        return indices(snh::elements_with_value(mesh, array, value));
      },
      py::arg("mesh"), py::arg("array"), py::arg("value"), "Elements whose cell-array value equals value.");
  m.def(
      "elements_with_value_in",
      [](const Mesh& mesh, const std::string& array, double lo, double hi) {
        return indices(snh::elements_with_value_in(mesh, array, lo, hi));
      },
      py::arg("mesh"), py::arg("array"), py::arg("lo"), py::arg("hi"), "Elements whose value lies in [lo, hi].");
}

}  // namespace snh_python
