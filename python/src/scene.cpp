// Built-in scenes and scene files: load a JSON scene, change its options,
// run it and write what it names (snh/scenes.h, scene.h).
#include "snh/scene.h"

#include "callbacks.h"
#include "common.h"
#include "snh/scenes.h"

namespace snh_python {

void bind_scene(py::module_& m) {
  py::class_<snh::SceneParameters>(m, "SceneParameters", "Size, material and steps of a built-in scene.")
      .def(py::init([](const py::kwargs& kw) { return from_kwargs<snh::SceneParameters>(kw); }),
           "Keyword arguments set the fields of the same names.")
      .def_readwrite("resolution", &snh::SceneParameters::resolution, "Cells across; None: the scene's default.")
      .def_readwrite("youngs_modulus", &snh::SceneParameters::youngs_modulus)
      .def_readwrite("poisson_ratio", &snh::SceneParameters::poisson_ratio)
      .def_readwrite("barrier", &snh::SceneParameters::barrier)
      .def_readwrite("steps", &snh::SceneParameters::steps, "Load steps; None: the scene's default.")
      .def_readwrite("seed", &snh::SceneParameters::seed)
      .def_readwrite("element_type", &snh::SceneParameters::element_type, "hex8 or tet4 (each hex split in six).")
      .def_readwrite("strain_tolerance", &snh::SceneParameters::strain_tolerance);

  py::class_<snh::Scene>(m, "Scene", "A mesh, a material, constraints and solve options, ready to simulate.")
      .def_readwrite("name", &snh::Scene::name)
      .def_readwrite("description", &snh::Scene::description)
      .def_readwrite("mesh", &snh::Scene::mesh, "The Mesh.")
      .def_readwrite("material", &snh::Scene::material, "The StableNeoHookean material.")
      .def_readwrite("constraints", &snh::Scene::constraints, "ConstraintSet list (a copy: assign a new list).")
      .def_readwrite("options", &snh::Scene::options, "SolveOptions (fields can be set in place).")
      .def(
          "simulation",
          [](const snh::Scene& scene, std::optional<snh::SolveOptions> options) {
            const snh::SolveOptions used = options.value_or(scene.options);
            py::gil_scoped_release release;
            return std::make_unique<snh::Simulation>(scene.mesh, snh::Material(scene.material), scene.constraints,
                                                     used);
          },
          py::arg("options") = py::none(), "A Simulation of the scene (options: the scene's unless given).");
  m.def("scene_names", &snh::scene_names, "The built-in scenes' names.");
  m.def("scene_defaults", &snh::scene_defaults, py::arg("name"), "A built-in scene's default parameters.");
  m.def(
      "make_scene",
      [](const std::string& name, std::optional<snh::SceneParameters> parameters) {
        return snh::make_scene(name, parameters ? *parameters : snh::scene_defaults(name));
      },
      py::arg("name"), py::arg("parameters") = py::none(),
      "A built-in scene (scene_names()) with parameters (default: scene_defaults(name)).");

  py::class_<snh::SceneFile>(m, "SceneFile", "A scene file as read: the scene, its materials, rig and outputs.")
      .def_readwrite("scene", &snh::SceneFile::scene, "The Scene (its options are the file's).")
      .def_readwrite("material", &snh::SceneFile::material, "The base Material.")
      .def_readwrite("materials", &snh::SceneFile::materials, "Every element's material (MaterialMap).")
      .def_readwrite("vtu_dir", &snh::SceneFile::vtu_dir, "Output folder of the .vtu series, or ''.")
      .def_readwrite("json_path", &snh::SceneFile::json_path, "Output JSON summary, or ''.")
      .def_readwrite("surface_prefix", &snh::SceneFile::surface_prefix, "Output OBJ prefix, or ''.")
      .def_property_readonly(
          "surface",
          [](const snh::SceneFile& f) -> py::object { return f.embedded ? py::cast(f.embedded->surface) : py::none(); },
          "The embedded TriangleSurface, or None.")
      .def_property_readonly(
          "voxels",
          [](const snh::SceneFile& f) -> py::object { return f.embedded ? py::cast(f.embedded->voxels) : py::none(); },
          "The Voxelization of the surface, or None.")
      .def_property_readonly(
          "embedding",
          [](const snh::SceneFile& f) -> py::object {
            return f.embedded ? py::cast(f.embedded->embedding) : py::none();
          },
          "The surface's Embedding, or None.")
      .def_property_readonly(
          "bones", [](const snh::SceneFile& f) -> py::object { return f.rig ? py::cast(f.rig->bones) : py::none(); },
          "The rig's Bone list, or None.")
      .def_property_readonly(
          "animation",
          [](const snh::SceneFile& f) -> py::object { return f.rig ? py::cast(f.rig->animation) : py::none(); },
          "The rig's Animation, or None.");
  m.def("load_scene", &snh::load_scene, py::arg("path"),
        "Reads a scene file (docs/scene-files.md); snh.Error names the key at fault.");
  m.def("scene_file_keys", &snh::scene_file_keys, "Every key a scene file may hold.");
  m.def(
      "run_scene",
      [](const snh::SceneFile& file, std::optional<snh::SolveOptions> options, int max_frames, bool reactions,
         const py::object& progress, std::optional<std::string> vtu_dir) {
        const snh::SolveOptions used = options.value_or(file.scene.options);
        snh::SceneRunOptions run;
        run.max_frames = max_frames;
        run.reactions = reactions;
        std::shared_ptr<py::object> held = progress.is_none() ? nullptr : hold(progress);
        // Always called, so that Ctrl-C (a pending signal) stops the run.
        run.progress = [held](const snh::SceneProgress& p) {
          py::gil_scoped_acquire gil;
          if (PyErr_CheckSignals() != 0) throw py::error_already_set();
          if (held) (*held)(p);
        };
        std::optional<snh::SceneVtuSeries> series;
        if (vtu_dir) {
          series.emplace(*vtu_dir, file, used);
          run.writers.push_back(series->writer());
        }
        py::gil_scoped_release release;
        snh::SceneRun result = snh::run_scene(file, used, run);
        if (series) series->finish();
        return result;
      },
      py::arg("file"), py::arg("options") = py::none(), py::arg("max_frames") = 0, py::arg("reactions") = true,
      py::arg("progress") = py::none(), py::arg("vtu_dir") = py::none(),
      "Runs the scene's load steps, time steps or rig frames (options: the file's unless given); "
      "progress(SceneProgress) after each step or frame; vtu_dir: write a .vtu series and .pvd there. "
      "Runs without the GIL. Returns a SceneRun.");
  m.def("write_scene_json", &snh::write_scene_json, py::arg("path"), py::arg("file"), py::arg("run"),
        "The run's JSON summary (docs/cli.md).");
}

}  // namespace snh_python
