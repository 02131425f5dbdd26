// The extension module: the public API of snh (include/snh/) for Python,
// with snh::Error as snh.Error (a RuntimeError carrying the C++ message).
#include "common.h"
#include "snh/error.h"

PYBIND11_MODULE(_snh, m) {
  m.doc() = "Stable Neo-Hookean flesh simulation on OpenCL devices.";
  pybind11::register_exception<snh::Error>(m, "Error", PyExc_RuntimeError);
  snh_python::bind_mesh(m);
  snh_python::bind_material(m);
  snh_python::bind_selection(m);
  snh_python::bind_solver_enums(m);
  snh_python::bind_results(m);
  snh_python::bind_simulation(m);
  snh_python::bind_scene_results(m);
  snh_python::bind_io(m);
  snh_python::bind_rig(m);
  snh_python::bind_character(m);
  snh_python::bind_scene(m);
}
