#include <cmath>
#include <cstring>

#include "common.h"

namespace snh_python {

namespace {

py::module_ numpy() { return py::module_::import("numpy"); }

std::string shape_text(const py::array& a) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) text += (d ? ", " : "") + std::to_string(a.shape(d));
  return text + (a.ndim() == 1 ? ",)" : ")");
}

std::string dtype_text(const py::array& a) { return py::str(a.dtype()).cast<std::string>(); }

// A NumPy view of `data` (no copy, no owner: used only while `data` lives).
template <class T>
py::array_t<T> view(T* data, const std::vector<py::ssize_t>& shape) {
  return py::array_t<T>(shape, data, py::none());
}

}  // namespace

std::vector<double> to_doubles(py::handle array, const std::string& what, py::ssize_t cols, py::ssize_t rows,
                               bool finite) {
  const py::module_ np = numpy();
  const py::array a = np.attr("asarray")(array);
  if (!np.attr("can_cast")(a.dtype(), np.attr("float64"), "safe").cast<bool>())
    throw py::value_error(what + ": dtype " + dtype_text(a) + " cannot be converted safely to float64");
  if (a.ndim() != 2 || a.shape(1) != cols || (rows >= 0 && a.shape(0) != rows))
    throw py::value_error(what + ": expected shape (" + (rows >= 0 ? std::to_string(rows) : std::string("n")) + ", " +
                          std::to_string(cols) + "), got " + shape_text(a));
  std::vector<double> values(static_cast<size_t>(a.shape(0) * cols));
  np.attr("copyto")(view(values.data(), {a.shape(0), cols}), a, py::arg("casting") = "safe");
  if (finite)
    for (size_t i = 0; i < values.size(); ++i)
      if (!std::isfinite(values[i]))
        throw py::value_error(what + ": row " + std::to_string(i / static_cast<size_t>(cols)) +
                              " holds a non-finite value (NaN or Inf)");
  return values;
}

std::vector<int32_t> to_indices(py::handle array, const std::string& what, py::ssize_t cols, int64_t bound) {
  const py::module_ np = numpy();
  const py::array a = np.attr("asarray")(array);
  const char kind = a.dtype().kind();
  // An empty list comes in as float64: no index in it to be wrong.
  if (!(kind == 'i' || kind == 'u' || (a.size() == 0 && kind == 'f')))
    throw py::value_error(what + ": expected an integer array, got dtype " + dtype_text(a));
  const bool flat = cols == 0;
  if (flat ? a.ndim() != 1 : (a.ndim() != 2 || a.shape(1) != cols))
    throw py::value_error(what + ": expected shape " +
                          (flat ? std::string("(n,)") : "(n, " + std::to_string(cols) + ")") + ", got " +
                          shape_text(a));
  std::vector<int64_t> wide(static_cast<size_t>(a.size()));
  np.attr("copyto")(view(wide.data(), {a.size()}), a.attr("reshape")(-1), py::arg("casting") = "unsafe");
  std::vector<int32_t> indices(wide.size());
  for (size_t i = 0; i < wide.size(); ++i) {
    if (wide[i] < 0 || (bound >= 0 && wide[i] >= bound) || wide[i] > INT32_MAX)
      throw py::value_error(what + ": index " + std::to_string(wide[i]) + " at position " + std::to_string(i) +
                            (bound >= 0 ? " is outside [0, " + std::to_string(bound) + ")" : " is negative"));
    indices[i] = static_cast<int32_t>(wide[i]);
  }
  return indices;
}

std::array<double, 3> to_vec3(py::handle value, const std::string& what) {
  const std::vector<double> v = to_doubles(numpy().attr("asarray")(value).attr("reshape")(1, -1), what, 3, 1);
  return {v[0], v[1], v[2]};
}

template <class T>
static py::array_t<T> owned(std::vector<T>&& values, const std::vector<py::ssize_t>& shape) {
  auto* held = new std::vector<T>(std::move(values));
  py::capsule owner(held, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, held->data(), owner);
}

py::array_t<double> to_array(std::vector<double>&& values, std::vector<py::ssize_t> shape) {
  return owned(std::move(values), shape);
}
py::array_t<int32_t> to_array(std::vector<int32_t>&& values, std::vector<py::ssize_t> shape) {
  return owned(std::move(values), shape);
}

template <class T>
static py::array_t<T> copied(const std::vector<T>& values, const std::vector<py::ssize_t>& shape) {
  py::array_t<T> a(shape);
  if (!values.empty()) std::memcpy(a.mutable_data(), values.data(), values.size() * sizeof(T));
  return a;
}

py::array_t<double> copy_array(const std::vector<double>& values, std::vector<py::ssize_t> shape) {
  return copied(values, shape);
}
py::array_t<int32_t> copy_array(const std::vector<int32_t>& values, std::vector<py::ssize_t> shape) {
  return copied(values, shape);
}

py::array_t<double> matrices_array(const std::vector<double>& row_major) {
  return copied(row_major, {static_cast<py::ssize_t>(row_major.size() / 9), 3, 3});
}

}  // namespace snh_python
