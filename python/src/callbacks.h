// Python callables called from inside the engine, which runs with the GIL
// released: each call takes the GIL, and the callable is held through a
// shared owner that takes the GIL to let it go (the engine copies its
// std::functions freely, without the GIL).
#pragma once

#include <memory>

#include "common.h"

namespace snh_python {

inline std::shared_ptr<py::object> hold(py::object callable) {
  return std::shared_ptr<py::object>(new py::object(std::move(callable)), [](py::object* p) {
    py::gil_scoped_acquire gil;
    delete p;
  });
}

// A Python callable taking t and returning a RigidTransform (or None).
template <class Transform>
std::function<Transform(double)> transform_callback(const py::object& callable, const char* what) {
  if (callable.is_none()) return {};
  if (!PyCallable_Check(callable.ptr())) throw py::type_error(std::string(what) + ": expected a callable or None");
  auto held = hold(callable);
  return [held](double t) {
    py::gil_scoped_acquire gil;
    return (*held)(t).template cast<Transform>();
  };
}

// Truthiness of a callback's return value, None counting as true (go on).
inline bool keep_going(const py::object& value) {
  if (value.is_none()) return true;
  const int truth = PyObject_IsTrue(value.ptr());
  if (truth < 0) throw py::error_already_set();
  return truth != 0;
}

}  // namespace snh_python
