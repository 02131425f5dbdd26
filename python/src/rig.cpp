// From a surface to a rigged lattice: surfaces, voxelization, embedding,
// bones, animations and the frame driver (snh/surface.h, rig.h,
// animation.h, frames.h).
#include "snh/rig.h"

#include "callbacks.h"
#include "common.h"
#include "snh/animation.h"
#include "snh/frames.h"
#include "snh/io.h"
#include "snh/surface.h"

namespace snh_python {

namespace {

py::array_t<double> matrix4_array(const snh::Matrix4& m) {
  return copy_array(std::vector<double>(m.begin(), m.end()), {4, 4});
}

snh::Matrix4 to_matrix4(py::handle value) {
  const std::vector<double> v = to_doubles(value, "matrix", 4, 4);
  snh::Matrix4 m{};
  std::copy(v.begin(), v.end(), m.begin());
  return m;
}

void bind_surfaces(py::module_& m) {
  py::class_<snh::TriangleSurface>(m, "TriangleSurface", "A triangle surface: positions (n, 3), triangles (t, 3).")
      .def(py::init([](py::handle positions, py::handle triangles) {
             snh::TriangleSurface s;
             s.positions = to_points(positions, "positions");
             s.triangles = to_indices(triangles, "triangles", 3, static_cast<int64_t>(s.vertex_count()));
             return s;
           }),
           py::arg("positions"), py::arg("triangles"), "From positions (n, 3) and triangles (t, 3).")
      .def_property_readonly(
          "positions", [](const snh::TriangleSurface& s) { return xyz_array(s.positions); }, "float64 (n, 3).")
      .def_property_readonly(
          "triangles",
          [](const snh::TriangleSurface& s) {
            return copy_array(s.triangles, {static_cast<py::ssize_t>(s.triangle_count()), 3});
          },
          "int32 (t, 3), outward by the right-hand rule.")
      .def_property_readonly("vertex_count", &snh::TriangleSurface::vertex_count)
      .def_property_readonly("triangle_count", &snh::TriangleSurface::triangle_count);

  m.def(
      "boundary_surface",
      [](const snh::Mesh& mesh, py::handle x) {
        snh::Points positions;
        if (!x.is_none()) positions = to_points(x, "positions", mesh.vertex_count());
        snh::MeshBoundary b = snh::boundary_surface(mesh, positions);
        return py::make_tuple(std::move(b.surface), copy_array(b.vertices, {py::ssize_t(b.vertices.size())}));
      },
      py::arg("mesh"), py::arg("positions") = py::none(),
      "The mesh's boundary as (TriangleSurface, vertices): outward triangles over the boundary vertices at "
      "positions (n, 3; None: rest), and the mesh vertex (int32) of each surface vertex.");
  m.def("read_surface", &snh::read_surface, py::arg("path"), "Reads .obj, .ply or .stl (polygons fanned).");
  m.def(
      "write_obj",
      [](const std::string& path, const snh::TriangleSurface& s, py::handle x) {
        snh::write_obj(path, s, x.is_none() ? snh::Points{} : to_points(x, "positions", s.vertex_count()));
      },
      py::arg("path"), py::arg("surface"), py::arg("positions") = py::none(), "Writes the surface as OBJ.");
  m.def(
      "write_surface_vtu",
      [](const std::string& path, const snh::TriangleSurface& s, py::handle x) {
        snh::write_surface_vtu(path, s, x.is_none() ? snh::Points{} : to_points(x, "positions", s.vertex_count()));
      },
      py::arg("path"), py::arg("surface"), py::arg("positions") = py::none(), "Writes the surface as .vtu.");
  m.def("validate_closed_surface", &snh::validate_closed_surface, py::arg("surface"), py::arg("name") = "surface",
        "snh.Error (starting with name) unless closed and consistently oriented.");
  m.def("enclosed_volume", &snh::enclosed_volume, py::arg("surface"), "Volume by the divergence theorem.");
  m.def("surface_area", &snh::surface_area, py::arg("surface"), "Sum of the triangles' areas.");
}

void bind_voxelization(py::module_& m) {
  py::class_<snh::VoxelizeOptions>(m, "VoxelizeOptions", "Voxelizer settings.")
      .def(py::init([](const py::kwargs& kw) { return from_kwargs<snh::VoxelizeOptions>(kw); }))
      .def_readwrite("max_grid_cells", &snh::VoxelizeOptions::max_grid_cells, "Refuse larger grids.")
      .def_readwrite("cover_surface", &snh::VoxelizeOptions::cover_surface, "Also keep cells the surface crosses.")
      .def_readwrite("strict", &snh::VoxelizeOptions::strict,
                     "Refuse surfaces that are not closed; inside by crossing counts.")
      .def_readwrite("weld_tolerance", &snh::VoxelizeOptions::weld_tolerance,
                     "Weld vertices closer than this times the bounding box's diagonal.")
      .def_readwrite("winding_beta", &snh::VoxelizeOptions::winding_beta, "Accuracy of the fast winding number.")
      .def_readwrite("name", &snh::VoxelizeOptions::name, "The surface's file, for errors and warnings.");
  py::class_<snh::Voxelization>(m, "Voxelization", "A hex8 lattice covering a closed surface's interior.")
      .def_readonly("lattice", &snh::Voxelization::lattice, "The hex8 Mesh.")
      .def_readonly("cell", &snh::Voxelization::cell, "Cube side.")
      .def_readonly("origin", &snh::Voxelization::origin, "Corner of grid cell (0, 0, 0).")
      .def_readonly("dims", &snh::Voxelization::dims, "Grid cells per axis.")
      .def_property_readonly(
          "element_cell",
          [](const snh::Voxelization& v) {
            std::vector<int32_t> cells;
            cells.reserve(3 * v.element_cell.size());
            for (const auto& c : v.element_cell) cells.insert(cells.end(), c.begin(), c.end());
            return to_array(std::move(cells), {static_cast<py::ssize_t>(v.element_cell.size()), 3});
          },
          "Grid cell (i, j, k) per element, int32 (m, 3).")
      .def_readonly("components", &snh::Voxelization::components, "Connected pieces.")
      .def_readonly("warnings", &snh::Voxelization::warnings, "The surface's defects, one line per class.");
  m.def(
      "voxelize",
      [](const snh::TriangleSurface& surface, double cell, std::optional<snh::VoxelizeOptions> options) {
        return snh::voxelize(surface, cell, options.value_or(snh::VoxelizeOptions{}));
      },
      py::arg("surface"), py::arg("cell"), py::arg("options") = py::none(),
      "Voxelizes a closed surface into a hex8 lattice of cubes of side cell.");
}

void bind_embedding(py::module_& m) {
  py::class_<snh::Embedding>(m, "Embedding", "Each surface vertex's element and trilinear weights.")
      .def_property_readonly(
          "element", [](const snh::Embedding& e) { return copy_array(e.element, {py::ssize_t(e.element.size())}); },
          "int32 (k,).")
      .def_property_readonly(
          "weights",
          [](const snh::Embedding& e) {
            return copy_array(e.weights, {py::ssize_t(e.weights.size() / 8), 8});
          },
          "float64 (k, 8).");
  m.def("embed", &snh::embed, py::arg("voxels"), py::arg("surface"), "Embeds the surface in the voxel lattice.");
  m.def(
      "embedded_positions",
      [](const snh::Embedding& e, const snh::Mesh& lattice, py::handle x) {
        return to_array(snh::embedded_positions(e, lattice, to_points(x, "positions", lattice.vertex_count())));
      },
      py::arg("embedding"), py::arg("lattice"), py::arg("positions"),
      "Surface positions (k, 3) for lattice positions (n, 3).");
}

void bind_bones(py::module_& m) {
  py::class_<snh::Capsule>(m, "Capsule", "Points within radius of the segment a-b.")
      .def(py::init([](std::array<double, 3> a, std::array<double, 3> b, double radius) {
             return snh::Capsule{a, b, radius};
           }),
           py::arg("a"), py::arg("b"), py::arg("radius"))
      .def_readwrite("a", &snh::Capsule::a)
      .def_readwrite("b", &snh::Capsule::b)
      .def_readwrite("radius", &snh::Capsule::radius);
  py::class_<snh::Bone>(m, "Bone", "A named solid (Capsule or closed TriangleSurface) whose vertices move with it.")
      .def(py::init([](std::string name, std::variant<snh::Capsule, snh::TriangleSurface> shape) {
             return snh::Bone{std::move(name), std::move(shape)};
           }),
           py::arg("name"), py::arg("shape"))
      .def_readwrite("name", &snh::Bone::name)
      .def_readwrite("shape", &snh::Bone::shape);
  m.def("bone_contains", &snh::bone_contains, py::arg("bone"), py::arg("point"), "Whether the rest point is inside.");
  m.def("bone_constraints", &snh::bone_constraints, py::arg("lattice"), py::arg("bones"),
        "One ConstraintSet per bone of the lattice vertices inside it (first bone wins at joints).");
  m.def(
      "to_rigid_transform",
      [](py::handle matrix, const std::array<double, 3>& center) {
        return snh::to_rigid_transform(to_matrix4(matrix), center);
      },
      py::arg("matrix"), py::arg("center") = std::array<double, 3>{0, 0, 0},
      "A 4x4 affine bone matrix (last row 0 0 0 1) as a RigidTransform about center.");
}

void bind_animation(py::module_& m) {
  py::class_<snh::Animation>(m, "Animation", "Per frame, a 4x4 transform for each animated bone.")
      .def(py::init([](std::vector<std::string> bones, py::handle times, py::handle transforms) {
             snh::Animation a;
             a.bones = std::move(bones);
             const std::vector<double> t =
                 to_doubles(py::module_::import("numpy").attr("asarray")(times).attr("reshape")(-1, 1), "times", 1);
             a.times = t;
             const py::ssize_t frames = static_cast<py::ssize_t>(t.size());
             const py::ssize_t nb = static_cast<py::ssize_t>(a.bones.size());
             const std::vector<double> m4 =
                 to_doubles(py::module_::import("numpy").attr("asarray")(transforms).attr("reshape")(-1, 16),
                            "transforms", 16, frames * nb);
             for (py::ssize_t f = 0; f < frames; ++f) {
               std::vector<snh::Matrix4> row(static_cast<size_t>(nb));
               for (py::ssize_t b = 0; b < nb; ++b) std::copy_n(m4.begin() + 16 * (f * nb + b), 16, row[b].begin());
               a.transforms.push_back(row);
             }
             return a;
           }),
           py::arg("bones"), py::arg("times"), py::arg("transforms"),
           "bones: names; times: (frames,); transforms: (frames, bones, 4, 4).")
      .def_readonly("bones", &snh::Animation::bones, "Animated bone names.")
      .def_readonly("times", &snh::Animation::times, "Per-frame times.")
      .def_property_readonly(
          "transforms",
          [](const snh::Animation& a) {
            std::vector<double> v;
            for (const auto& frame : a.transforms)
              for (const auto& mat : frame) v.insert(v.end(), mat.begin(), mat.end());
            return to_array(std::move(v), {static_cast<py::ssize_t>(a.transforms.size()),
                                           static_cast<py::ssize_t>(a.bones.size()), 4, 4});
          },
          "float64 (frames, bones, 4, 4), row-major matrices.")
      .def_property_readonly("frame_count", &snh::Animation::frame_count);
  m.def("read_animation", &snh::read_animation, py::arg("path"), "Reads a .json or .csv animation.");
  m.def("parse_animation_json", &snh::parse_animation_json, py::arg("text"), py::arg("name") = "<string>");
  m.def("parse_animation_csv", &snh::parse_animation_csv, py::arg("text"), py::arg("name") = "<string>");
  m.def(
      "identity_matrix4", []() { return matrix4_array(snh::identity_matrix4()); }, "The 4x4 identity.");
}

void bind_frame_driver(py::module_& m) {
  py::class_<snh::FrameOptions>(m, "FrameOptions", "Frame driver settings.")
      .def(py::init([](const py::kwargs& kw) { return from_kwargs<snh::FrameOptions>(kw); }))
      .def_readwrite("load_steps", &snh::FrameOptions::load_steps, "Load steps per frame.")
      .def_readwrite("stop_on_failure", &snh::FrameOptions::stop_on_failure, "Stop at the first failed frame.")
      .def_readwrite("fail_on_inverted", &snh::FrameOptions::fail_on_inverted,
                     "A frame ending with inverted elements fails (StepStatus.inverted_elements) and is the last.");
  m.def(
      "run_frames",
      [](snh::Simulation& sim, const snh::Animation& animation, const snh::Embedding* embedding,
         std::optional<snh::FrameOptions> frame_options, const py::object& on_frame) {
        const snh::FrameOptions options = frame_options.value_or(snh::FrameOptions{});
        std::shared_ptr<py::object> held = on_frame.is_none() ? nullptr : hold(on_frame);
        // Always called, so that Ctrl-C (a pending signal) stops after the frame.
        const snh::FrameCallback callback = [held](const snh::FrameRecord& r, const snh::Points& lattice,
                                                   const snh::Points& surface) {
          py::gil_scoped_acquire gil;
          if (PyErr_CheckSignals() != 0) throw py::error_already_set();
          if (!held) return true;
          py::object s = surface.empty() ? py::object(py::none()) : py::object(xyz_array(surface));
          return keep_going((*held)(r, xyz_array(lattice), s));
        };
        py::gil_scoped_release release;
        return snh::run_frames(sim, animation, embedding, options, callback);
      },
      py::arg("simulation"), py::arg("animation"), py::arg("embedding") = nullptr, py::arg("options") = py::none(),
      py::arg("on_frame") = py::none(),
      "Runs every frame: each bone's matrix to its constraint set, a warm-started solve. "
      "on_frame(record, lattice (n, 3), surface (k, 3) or None) returning False stops. Returns FrameRecords.");
}

}  // namespace

void bind_rig(py::module_& m) {
  bind_surfaces(m);
  bind_voxelization(m);
  bind_embedding(m);
  bind_bones(m);
  bind_animation(m);
  bind_frame_driver(m);
}

}  // namespace snh_python
