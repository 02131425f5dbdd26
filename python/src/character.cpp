// Skinned characters: reading a skinned file, bones from its skeleton, the
// rigged lattice, the frames run against linear blend skinning, and point
// caches (snh/character.h).
#include "snh/character.h"

#include <memory>
#include <optional>

#include "callbacks.h"
#include "common.h"

namespace snh_python {

namespace {

py::array_t<double> matrix4_array(const snh::Matrix4& m) {
  return copy_array(std::vector<double>(m.begin(), m.end()), {4, 4});
}

// Matrices (count, 4, 4) from any array-like of that shape (count -1: any).
std::vector<snh::Matrix4> to_matrices(py::handle value, const std::string& what, py::ssize_t count = -1) {
  const py::array a = py::module_::import("numpy").attr("asarray")(value);
  if (a.ndim() != 3 || a.shape(1) != 4 || a.shape(2) != 4)
    throw py::value_error(what + ": expected an array of shape (" + (count < 0 ? "m" : std::to_string(count)) +
                          ", 4, 4)");
  const std::vector<double> v = to_doubles(a.attr("reshape")(-1, 16), what, 16, count);
  std::vector<snh::Matrix4> out(v.size() / 16);
  for (size_t k = 0; k < out.size(); ++k) std::copy_n(v.begin() + 16 * k, 16, out[k].begin());
  return out;
}

py::array_t<int32_t> index_array(const std::vector<int32_t>& values) {
  return copy_array(values, {static_cast<py::ssize_t>(values.size())});
}

py::array_t<double> value_array(const std::vector<double>& values) {
  return copy_array(values, {static_cast<py::ssize_t>(values.size())});
}

// One float32 value per coordinate: (samples, points, 3).
py::array_t<float> samples_array(const snh::PointCache& cache) {
  const py::ssize_t n = static_cast<py::ssize_t>(cache.point_count);
  py::array_t<float> out(std::vector<py::ssize_t>{static_cast<py::ssize_t>(cache.samples.size()), n, 3});
  float* data = out.mutable_data();
  for (const std::vector<float>& sample : cache.samples) {
    if (sample.size() != static_cast<size_t>(3 * n))
      throw py::value_error("PointCache: a sample holds " + std::to_string(sample.size() / 3) + " points, not " +
                            std::to_string(n));
    data = std::copy(sample.begin(), sample.end(), data);
  }
  return out;
}

void set_samples(snh::PointCache& cache, py::handle value) {
  const py::array a = py::module_::import("numpy").attr("asarray")(value, "float64");
  if (a.ndim() != 3 || a.shape(2) != 3)
    throw py::value_error("samples: expected an array of shape (samples, points, 3)");
  const py::ssize_t count = a.shape(0), n = a.shape(1);
  const std::vector<double> v = to_doubles(a.attr("reshape")(count * n, 3), "samples", 3, count * n);
  cache.point_count = static_cast<size_t>(n);
  cache.samples.assign(static_cast<size_t>(count), std::vector<float>(static_cast<size_t>(3 * n)));
  for (py::ssize_t s = 0; s < count; ++s)
    std::copy_n(v.begin() + 3 * n * s, 3 * n, cache.samples[static_cast<size_t>(s)].begin());
}

// Rows offset[v]..offset[v + 1] of joint and weight per vertex, checked so
// that nothing reads past the arrays.
snh::SkinWeights make_skin_weights(py::handle offset, py::handle joint, py::handle weight) {
  snh::SkinWeights w;
  w.offset = to_indices(offset, "offset", 0, -1);
  w.joint = to_indices(joint, "joint", 0, -1);
  w.weight = to_doubles(py::module_::import("numpy").attr("asarray")(weight).attr("reshape")(-1, 1), "weight", 1);
  if (w.offset.empty() || w.offset.front() != 0)
    throw py::value_error("offset: expected (vertices + 1,) entries starting at 0");
  for (size_t v = 1; v < w.offset.size(); ++v)
    if (w.offset[v] < w.offset[v - 1])
      throw py::value_error("offset: entry " + std::to_string(v) + " is smaller than the one before");
  if (static_cast<size_t>(w.offset.back()) != w.joint.size() || w.joint.size() != w.weight.size())
    throw py::value_error("offset, joint, weight: the last offset (" + std::to_string(w.offset.back()) +
                          ") must equal the number of joints (" + std::to_string(w.joint.size()) + ") and weights (" +
                          std::to_string(w.weight.size()) + ")");
  return w;
}

void bind_read_options(py::module_& m) {
  py::enum_<snh::WeightPolicy>(m, "WeightPolicy",
                               "What read_character does with skin weights that do not sum to 1: normalize divides "
                               "them by their sum (one warning), strict refuses the file naming the vertex.")
      .value("normalize", snh::WeightPolicy::normalize)
      .value("strict", snh::WeightPolicy::strict);

  py::class_<snh::CharacterReadOptions>(m, "CharacterReadOptions", "What read_character reads.")
      .def(py::init([](const py::kwargs& kw) { return from_kwargs<snh::CharacterReadOptions>(kw); }),
           "Keyword arguments set the fields of the same names.")
      .def_readwrite("clip", &snh::CharacterReadOptions::clip, "The clip by name ('': by clip_index, else the first).")
      .def_readwrite("clip_index", &snh::CharacterReadOptions::clip_index,
                     "The clip by index among the file's (>= 0), or None.")
      .def_readwrite("require_clip", &snh::CharacterReadOptions::require_clip,
                     "False: a file without animation reads as a character without a clip.")
      .def_readwrite("fps", &snh::CharacterReadOptions::fps, "Frames per second the clip is sampled at.")
      .def_readwrite("first_frame", &snh::CharacterReadOptions::first_frame, "First frame sampled (time frame / fps).")
      .def_readwrite("last_frame", &snh::CharacterReadOptions::last_frame,
                     "Last frame sampled (inclusive); None: up to the clip's last key.")
      .def_readwrite("weights", &snh::CharacterReadOptions::weights, "WeightPolicy for sums off 1.")
      .def_readwrite("weight_tolerance", &snh::CharacterReadOptions::weight_tolerance,
                     "Sums within this of 1 are taken as they are.")
      .def_readwrite("weld_distance", &snh::CharacterReadOptions::weld_distance,
                     "Positions closer than this are welded (None: 1e-9 of the bounding box's diagonal).");
}

void bind_skeleton(py::module_& m) {
  py::class_<snh::Joint>(m, "Joint", "A joint of the skeleton: a node that skins vertices (read-only).")
      .def_readonly("name", &snh::Joint::name)
      .def_readonly("parent", &snh::Joint::parent, "The nearest ancestor that is a joint, or -1.")
      .def_property_readonly(
          "inverse_bind", [](const snh::Joint& j) { return matrix4_array(j.inverse_bind); },
          "Rest (mesh) space to joint space, float64 (4, 4) [row, column].")
      .def_readonly("rest_position", &snh::Joint::rest_position, "The joint's origin at rest.")
      .def("__repr__",
           [](const snh::Joint& j) { return "Joint('" + j.name + "', parent=" + std::to_string(j.parent) + ")"; });

  py::class_<snh::SkinWeights>(m, "SkinWeights",
                               "Skin weights per vertex in compressed rows: vertex v's joints are "
                               "joint[offset[v]:offset[v + 1]] with weight[...].")
      .def(py::init(&make_skin_weights), py::arg("offset"), py::arg("joint"), py::arg("weight"),
           "From offset (vertices + 1,), joint (k,) and weight (k,).")
      .def_property_readonly(
          "offset", [](const snh::SkinWeights& w) { return index_array(w.offset); }, "int32 (vertices + 1,).")
      .def_property_readonly(
          "joint", [](const snh::SkinWeights& w) { return index_array(w.joint); }, "int32 (k,).")
      .def_property_readonly(
          "weight", [](const snh::SkinWeights& w) { return value_array(w.weight); }, "float64 (k,).")
      .def_property_readonly("vertex_count", &snh::SkinWeights::vertex_count);
}

void bind_clip_and_character(py::module_& m) {
  py::class_<snh::CharacterClip>(m, "CharacterClip", "A clip sampled at fps (read-only).")
      .def_readonly("name", &snh::CharacterClip::name)
      .def_readonly("index", &snh::CharacterClip::index, "Among the file's clips.")
      .def_readonly("fps", &snh::CharacterClip::fps)
      .def_readonly("first_frame", &snh::CharacterClip::first_frame)
      .def_property_readonly(
          "times", [](const snh::CharacterClip& c) { return value_array(c.times); },
          "Seconds per frame (frame / fps), float64 (frames,).")
      .def_property_readonly(
          "skinning",
          [](const snh::CharacterClip& c) {
            const py::ssize_t frames = static_cast<py::ssize_t>(c.skinning.size());
            const py::ssize_t joints = frames ? static_cast<py::ssize_t>(c.skinning.front().size()) : 0;
            std::vector<double> v;
            v.reserve(static_cast<size_t>(16 * frames * joints));
            for (const auto& frame : c.skinning)
              for (const snh::Matrix4& mat : frame) v.insert(v.end(), mat.begin(), mat.end());
            return to_array(std::move(v), {frames, joints, 4, 4});
          },
          "Per frame and joint, world(t) * inverse_bind (rest point to posed point), float64 (frames, joints, 4, 4).")
      .def_property_readonly("frame_count", &snh::CharacterClip::frame_count);

  py::class_<snh::Character>(m, "Character", "A skinned character as read_character reads it (read-only).")
      .def_readonly("file", &snh::Character::file)
      .def_readonly("surface", &snh::Character::surface,
                    "The skin as the file gives it (seams kept): the output's vertex order.")
      .def_readonly("welded", &snh::Character::welded, "The skin with coincident positions welded (voxelized).")
      .def_property_readonly(
          "welded_index", [](const snh::Character& c) { return index_array(c.welded_index); },
          "Each surface vertex's welded vertex, int32 (n,).")
      .def_readonly("joints", &snh::Character::joints, "Joint list, parents before children.")
      .def_readonly("weights", &snh::Character::weights, "SkinWeights per surface vertex.")
      .def_readonly("clip_names", &snh::Character::clip_names, "The file's clips.")
      .def_readonly("has_clip", &snh::Character::has_clip)
      .def_readonly("clip", &snh::Character::clip, "The sampled CharacterClip (empty without one).")
      .def_readonly("warnings", &snh::Character::warnings, "What was repaired on reading, one line per kind.")
      .def("__repr__", [](const snh::Character& c) {
        return "Character('" + c.file + "', " + std::to_string(c.surface.vertex_count()) + " vertices, " +
               std::to_string(c.joints.size()) + " joints)";
      });
}

void bind_reading_and_skinning(py::module_& m) {
  m.def(
      "read_character",
      [](const std::string& path, std::optional<snh::CharacterReadOptions> options) {
        const snh::CharacterReadOptions o = options.value_or(snh::CharacterReadOptions{});
        py::gil_scoped_release release;
        return snh::read_character(path, o);
      },
      py::arg("path"), py::arg("options") = py::none(),
      "Reads a skinned character (glTF 2.0, FBX, Collada): surface, joints, weights and a clip sampled at fps. "
      "snh.Error names the file and the item at fault.");
  m.def(
      "linear_blend_skinning",
      [](py::handle rest, const snh::SkinWeights& weights, py::handle matrices) {
        const snh::Points x = to_points(rest, "rest", static_cast<py::ssize_t>(weights.vertex_count()));
        return to_array(snh::linear_blend_skinning(x, weights, to_matrices(matrices, "matrices")));
      },
      py::arg("rest"), py::arg("weights"), py::arg("matrices"),
      "sum_j w_j M_j x per vertex of rest (n, 3) with one matrix (joints, 4, 4) per joint: (n, 3).");
}

void bind_character_bones(py::module_& m) {
  py::class_<snh::CharacterBoneOptions>(m, "CharacterBoneOptions", "How bones are made from the skeleton.")
      .def(py::init([](const py::kwargs& kw) { return from_kwargs<snh::CharacterBoneOptions>(kw); }),
           "Keyword arguments set the fields of the same names.")
      .def_readwrite("radius_fraction", &snh::CharacterBoneOptions::radius_fraction,
                     "A bone's radius as a fraction of its segment's distance from the skin.")
      .def_readwrite("radius", &snh::CharacterBoneOptions::radius,
                     "{joint: absolute radius} (a copy: assign a new dict).")
      .def_readwrite("exclude", &snh::CharacterBoneOptions::exclude,
                     "Joints without a bone, by name or glob pattern (a copy: assign a new list).")
      .def_readwrite("joint_clearance", &snh::CharacterBoneOptions::joint_clearance,
                     "Flesh left free at each end, as a fraction of the segment's length; < 0: joint to joint.")
      .def_readwrite("leaf_fraction", &snh::CharacterBoneOptions::leaf_fraction,
                     "A leaf joint's segment as a fraction of its parent's; 0: from the skin (leaf_from_skin) or none.")
      .def_readwrite(
          "leaf_from_skin", &snh::CharacterBoneOptions::leaf_from_skin,
          "With leaf_fraction 0, a leaf's segment reaches 3/4 of the way to the farthest skin it weighs most.")
      .def_readwrite("touching_radius", &snh::CharacterBoneOptions::touching_radius,
                     "Radius of a bone whose segment touches the skin (absolute); 0 leaves such bones out.");

  py::class_<snh::CharacterBones>(m, "CharacterBones", "Bones from the skeleton and their animation (read-only).")
      .def_readonly("bones", &snh::CharacterBones::bones, "Bone list, named as their joints.")
      .def_property_readonly(
          "joint", [](const snh::CharacterBones& b) { return index_array(b.joint); }, "Each bone's joint, int32.")
      .def_readonly("animation", &snh::CharacterBones::animation, "Every bone's skinning matrix per frame.")
      .def_readonly("warnings", &snh::CharacterBones::warnings, "Bones given the floor radius or left out.");
  m.def(
      "character_bones",
      [](const snh::Character& character, std::optional<snh::CharacterBoneOptions> options) {
        return snh::character_bones(character, options.value_or(snh::CharacterBoneOptions{}));
      },
      py::arg("character"), py::arg("options") = py::none(),
      "A capsule per kept joint's segment (joint to child, trimmed by joint_clearance) and its animation.");
}

void bind_character_rig(py::module_& m) {
  py::class_<snh::CharacterPrepareOptions>(m, "CharacterPrepareOptions", "How prepare_character rigs a character.")
      .def(py::init([](const py::kwargs& kw) { return from_kwargs<snh::CharacterPrepareOptions>(kw); }),
           "Keyword arguments set the fields of the same names.")
      .def_readwrite("bones", &snh::CharacterPrepareOptions::bones,
                     "CharacterBoneOptions (its fields can be set in place).")
      .def_readwrite("voxelize", &snh::CharacterPrepareOptions::voxelize,
                     "VoxelizeOptions (its fields can be set in place).")
      .def_readwrite("touching_radius_cells", &snh::CharacterPrepareOptions::touching_radius_cells,
                     "Cells of radius for a bone touching the skin, unless bones.touching_radius is set.")
      .def_readwrite("max_outside_fraction", &snh::CharacterPrepareOptions::max_outside_fraction,
                     "A surface vertex farther than this fraction of the diagonal from every element is an error.")
      .def_property(
          "pieces", [](const snh::CharacterPrepareOptions& o) { return std::string(snh::to_string(o.pieces)); },
          [](snh::CharacterPrepareOptions& o, const std::string& rule) { o.pieces = snh::parse_piece_rule(rule); },
          "Lattice pieces no bone holds: 'attach' (default), 'drop' or 'error'.");

  py::class_<snh::CharacterRig>(m, "CharacterRig", "What a character's simulation needs (read-only).")
      .def_readonly("cell", &snh::CharacterRig::cell, "The lattice's cube side.")
      .def_readonly("voxels", &snh::CharacterRig::voxels, "The welded surface's Voxelization.")
      .def_readonly("embedding", &snh::CharacterRig::embedding, "Embedding of every surface vertex (file order).")
      .def_readonly("bones", &snh::CharacterRig::bones, "CharacterBones.")
      .def_readonly("constraints", &snh::CharacterRig::constraints, "One ConstraintSet per bone.")
      .def_readonly("lattice_weights", &snh::CharacterRig::lattice_weights,
                    "SkinWeights per lattice vertex, for the skinned guess.")
      .def_readonly("vertices_outside", &snh::CharacterRig::vertices_outside,
                    "Surface vertices outside every element (they follow the nearest one).")
      .def_readonly("max_outside_distance", &snh::CharacterRig::max_outside_distance,
                    "The largest distance of those from their element.")
      .def_readonly("warnings", &snh::CharacterRig::warnings, "What was repaired, one line per kind.");
  m.def("character_cell", &snh::character_cell, py::arg("character"), py::arg("resolution"),
        "The cube side that puts resolution cells along the longest side of the bind pose's bounding box.");
  m.def(
      "prepare_character",
      [](const snh::Character& character, double cell, std::optional<snh::CharacterPrepareOptions> options) {
        const snh::CharacterPrepareOptions o = options.value_or(snh::CharacterPrepareOptions{});
        py::gil_scoped_release release;
        return snh::prepare_character(character, cell, o);
      },
      py::arg("character"), py::arg("cell"), py::arg("options") = py::none(),
      "Voxelizes the welded surface at cell, embeds every surface vertex, makes the bones and their constraint sets "
      "and carries the skin weights to the lattice.");
  m.def(
      "prepare_character",
      [](const snh::Character& character, double cell, std::optional<snh::CharacterBoneOptions> bones,
         std::optional<snh::VoxelizeOptions> voxelize) {
        const snh::CharacterBoneOptions b = bones.value_or(snh::CharacterBoneOptions{});
        const snh::VoxelizeOptions v = voxelize.value_or(snh::VoxelizeOptions{});
        py::gil_scoped_release release;
        return snh::prepare_character(character, cell, b, v);
      },
      py::arg("character"), py::arg("cell"), py::arg("bones") = py::none(), py::arg("voxelize") = py::none(),
      "The same with bone and voxelizer options alone (the other options' defaults).");
}

void bind_character_frames(py::module_& m) {
  py::class_<snh::SkinDeviation>(m, "SkinDeviation",
                                 "How far a frame's simulated surface is from the linear-blend-skinned one.")
      .def_readonly("max_distance", &snh::SkinDeviation::max_distance)
      .def_readonly("mean_distance", &snh::SkinDeviation::mean_distance);
  py::class_<snh::CharacterFrame>(m, "CharacterFrame", "One frame of a character (read-only).")
      .def_readonly("record", &snh::CharacterFrame::record, "The FrameRecord, frame and time as in the clip.")
      .def_readonly("lbs", &snh::CharacterFrame::lbs, "SkinDeviation from linear blend skinning.");
  py::class_<snh::CharacterFrameOptions>(m, "CharacterFrameOptions", "How run_character_frames runs the frames.")
      .def(py::init([](const py::kwargs& kw) { return from_kwargs<snh::CharacterFrameOptions>(kw); }),
           "Keyword arguments set the fields of the same names.")
      .def_readwrite("frames", &snh::CharacterFrameOptions::frames, "FrameOptions (its fields can be set in place).")
      .def_readwrite("skinned_guess", &snh::CharacterFrameOptions::skinned_guess,
                     "Start each frame from the last state moved by the lattice skinning's change.");
  m.def(
      "run_character_frames",
      [](snh::Simulation& sim, const snh::Character& character, const snh::CharacterRig& rig,
         std::optional<snh::CharacterFrameOptions> frame_options, const py::object& on_frame) {
        // What the engine indexes without checking: the rig's lattice is the
        // simulation's mesh, its embedding covers this character's surface.
        const snh::Mesh& mesh = sim.mesh();
        const snh::Mesh& lattice = rig.voxels.lattice;
        if (mesh.vertex_count() != lattice.vertex_count() || mesh.element_count() != lattice.element_count())
          throw py::value_error("run_character_frames: the simulation's mesh (" + std::to_string(mesh.vertex_count()) +
                                " vertices, " + std::to_string(mesh.element_count()) +
                                " elements) is not the rig's lattice (" + std::to_string(lattice.vertex_count()) +
                                " vertices, " + std::to_string(lattice.element_count()) + " elements)");
        if (rig.embedding.element.size() != character.surface.vertex_count())
          throw py::value_error("run_character_frames: the rig embeds " + std::to_string(rig.embedding.element.size()) +
                                " vertices, the character has " + std::to_string(character.surface.vertex_count()));
        const snh::CharacterFrameOptions options = frame_options.value_or(snh::CharacterFrameOptions{});
        if (!on_frame.is_none() && !PyCallable_Check(on_frame.ptr()))
          throw py::type_error("on_frame: expected a callable or None");
        std::shared_ptr<py::object> held = on_frame.is_none() ? nullptr : hold(on_frame);
        // Always called, so that Ctrl-C (a pending signal) stops after the frame.
        const snh::CharacterFrameCallback callback = [held](const snh::CharacterFrame& f, const snh::Points& lattice_x,
                                                            const snh::Points& surface, const snh::Points& skinned) {
          py::gil_scoped_acquire gil;
          if (PyErr_CheckSignals() != 0) throw py::error_already_set();
          if (!held) return true;
          return keep_going((*held)(f, xyz_array(lattice_x), xyz_array(surface), xyz_array(skinned)));
        };
        py::gil_scoped_release release;
        return snh::run_character_frames(sim, character, rig, options, callback);
      },
      py::arg("simulation"), py::arg("character"), py::arg("rig"), py::arg("options") = py::none(),
      py::arg("on_frame") = py::none(),
      "Runs the clip's frames on a Simulation of rig.voxels.lattice with rig.constraints. on_frame(frame, lattice "
      "(n, 3), surface (k, 3), skinned (k, 3)) after each frame; returning False stops (None goes on); an "
      "exception raised in it propagates. Runs without the GIL. Returns CharacterFrames.");
}

void bind_outputs(py::module_& m) {
  m.def(
      "write_surface_ply",
      [](const std::string& path, const snh::TriangleSurface& s, py::handle x) {
        snh::write_surface_ply(path, s, x.is_none() ? snh::Points{} : to_points(x, "positions", s.vertex_count()));
      },
      py::arg("path"), py::arg("surface"), py::arg("positions") = py::none(),
      "Writes the surface as binary PLY at positions (n, 3) (None: its own), vertices in its order.");

  py::class_<snh::PointCache>(m, "PointCache", "The same points sampled over frames (PC2, MDD).")
      .def(py::init([](const py::kwargs& kw) { return from_kwargs<snh::PointCache>(kw); }),
           "Keyword arguments set the fields (samples, start_frame, sample_rate, times, point_count).")
      .def_readwrite("point_count", &snh::PointCache::point_count, "Points per sample (set by samples).")
      .def_readwrite("start_frame", &snh::PointCache::start_frame, "PC2: the first sample's frame.")
      .def_readwrite("sample_rate", &snh::PointCache::sample_rate, "PC2: frames between samples.")
      .def_property(
          "times", [](const snh::PointCache& c) { return value_array(c.times); },
          [](snh::PointCache& c, py::handle v) {
            c.times = to_doubles(py::module_::import("numpy").attr("asarray")(v).attr("reshape")(-1, 1), "times", 1);
          },
          "MDD: seconds per sample, float64 (samples,).")
      .def_property("samples", &samples_array, &set_samples,
                    "float32 (samples, points, 3); setting it sets point_count.")
      .def_property_readonly(
          "sample_count", [](const snh::PointCache& c) { return c.samples.size(); }, "Samples held.");
  m.def("write_pc2", &snh::write_pc2, py::arg("path"), py::arg("cache"), "Writes a PC2 point cache (little-endian).");
  m.def("write_mdd", &snh::write_mdd, py::arg("path"), py::arg("cache"),
        "Writes an MDD point cache (big-endian; one time per sample).");
  m.def("read_pc2", &snh::read_pc2, py::arg("path"), "Reads a PC2 point cache.");
  m.def("read_mdd", &snh::read_mdd, py::arg("path"), "Reads an MDD point cache.");
  m.def("write_point_cache", &snh::write_point_cache, py::arg("path"), py::arg("cache"),
        "Writes .pc2 or .mdd by the extension.");

  py::class_<snh::CharacterCacheSeries>(m, "CharacterCacheSeries",
                                        "Collects a character's frames and writes its point caches.")
      .def(py::init<const snh::Character&, std::string, std::string, std::string>(), py::arg("character"),
           py::arg("pc2") = "", py::arg("mdd") = "", py::arg("lbs") = "", py::keep_alive<1, 2>(),
           "The simulated surface to pc2 and/or mdd, the skinned one to lbs (.pc2 or .mdd); '' skips.")
      .def(
          "add",
          [](snh::CharacterCacheSeries& series, int clip_frame, py::handle surface) {
            series.add(clip_frame, to_points(surface, "surface"));
          },
          py::arg("clip_frame"), py::arg("surface"),
          "A frame (numbered as in the clip) with the simulated surface (n, 3).")
      .def("finish", &snh::CharacterCacheSeries::finish, "Writes the files.");
}

}  // namespace

void bind_character(py::module_& m) {
  bind_read_options(m);
  bind_skeleton(m);
  bind_clip_and_character(m);
  bind_reading_and_skinning(m);
  bind_character_bones(m);
  bind_character_rig(m);
  bind_character_frames(m);
  bind_outputs(m);
}

}  // namespace snh_python
