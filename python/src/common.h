// Shared by the binding files: NumPy arrays in and out of the engine's
// snh::Points (n, 3) and flat std::vector layouts (nodes per element),
// checked before anything reaches the engine, and each copied once.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "snh/points.h"

namespace snh_python {

namespace py = pybind11;

// A (rows, cols) array of float64 from any array-like whose dtype NumPy can
// cast to float64 safely; rows -1 accepts any count. ValueError names `what`
// for a wrong shape or dtype, and the first row holding NaN or Inf when
// `finite`.
std::vector<double> to_doubles(py::handle array, const std::string& what, py::ssize_t cols, py::ssize_t rows = -1,
                               bool finite = true);

// The same for an integer array of any shape whose last axis has `cols`
// entries (0: a flat list), every entry in [0, bound) (bound < 0: no upper
// bound); float, bool and object arrays are refused.
std::vector<int32_t> to_indices(py::handle array, const std::string& what, py::ssize_t cols, int64_t bound);

std::array<double, 3> to_vec3(py::handle value, const std::string& what);

// The vector's buffer handed to NumPy without another copy.
py::array_t<double> to_array(std::vector<double>&& values, std::vector<py::ssize_t> shape);
py::array_t<int32_t> to_array(std::vector<int32_t>&& values, std::vector<py::ssize_t> shape);
// A copy of a vector the engine keeps.
py::array_t<double> copy_array(const std::vector<double>& values, std::vector<py::ssize_t> shape);
py::array_t<int32_t> copy_array(const std::vector<int32_t>& values, std::vector<py::ssize_t> shape);

// An (n, 3) array (rows -1: any n) as Points, checked as to_doubles checks
// it: the one conversion of NumPy points into the engine, one copy.
inline snh::Points to_points(py::handle array, const std::string& what, py::ssize_t rows = -1, bool finite = true) {
  return snh::Points::from_xyz(to_doubles(array, what, 3, rows, finite), what);
}

// Points the engine keeps as a float64 (n, 3) copy.
inline py::array_t<double> xyz_array(const snh::Points& points) {
  return copy_array(points.xyz(), {static_cast<py::ssize_t>(points.size()), 3});
}

// Points the engine returned as float64 (n, 3), their buffer handed to
// NumPy without another copy.
inline py::array_t<double> to_array(snh::Points&& points) {
  const auto n = static_cast<py::ssize_t>(points.size());
  return to_array(points.release(), {n, 3});
}

// 3x3 row-major matrices (nine values each, as the API stores them) as an
// (m, 3, 3) array indexed [element, row, column].
py::array_t<double> matrices_array(const std::vector<double>& row_major);

// An instance of T built by setting each keyword argument as an attribute:
// Python keyword constructors for option structs (an unknown name raises
// AttributeError).
template <class T>
T from_kwargs(const py::kwargs& kwargs) {
  py::object object = py::cast(T{});
  for (const auto& item : kwargs) py::setattr(object, item.first, item.second);
  return object.cast<T>();
}

void bind_mesh(py::module_& m);
void bind_material(py::module_& m);
void bind_selection(py::module_& m);
void bind_solver_enums(py::module_& m);
void bind_results(py::module_& m);
void bind_resolved_configuration(py::module_& m);
void bind_simulation(py::module_& m);
void bind_io(py::module_& m);
void bind_rig(py::module_& m);
void bind_character(py::module_& m);
void bind_scene_results(py::module_& m);
void bind_scene(py::module_& m);

}  // namespace snh_python
