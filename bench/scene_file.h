// Scenes described in JSON files (`snh-gpu-bench scene --file F`): mesh (a
// file or a generator) or an embedded surface, material, regions with their
// own materials (element selectors: scene_selection.h), constraint vertex
// sets (selectors: scene_selection.h) with rigid or keyframed motion, a rig of
// bones and its animation, body force, solver options, output.
// Unknown keys and wrong types are errors naming the key's path.
//
// Dynamics and obstacles (docs/design.md):
//   "dynamics": {"time_step": s, "density": kg/m^3,
//                "damping": {"mass": a, "stiffness": b}, "substeps": n}
//       implicit Euler (snh::DynamicsOptions); absent: quasistatic.
//       solver.steps then counts time steps.
//   "obstacles": [{"type": "plane", "point": [x, y, z], "normal": [x, y, z]},
//                 {"type": "sphere", "center": [x, y, z], "radius": r},
//                 {"type": "cylinder", "point": [x, y, z], "axis": [x, y, z], "radius": r}]
//       each with optional "keyframes": [{"t", "angle", "translation"}, ...]
//       (a constraint's keyframed motion keys, rotation about z through the
//       origin) or an object as a constraint's "motion" (axis, center).
//   "contact": {"stiffness": k, "thickness": d, "self": false}
//       the obstacles' penalty; "self": true is refused (not implemented).
//
// Surfaces and rigs:
//   "embed": {"surface": "arm.obj", "cell": 0.125}
//       the mesh is the voxelization of that closed surface (.obj, .ply,
//       .stl) with cubes of side `cell`, and the surface is embedded in it
//       (instead of "mesh"); "cover_surface": true keeps also the cells the
//       surface passes through (VoxelizeOptions::cover_surface).
//   "rig": {"bones": [{"name": "upper", "capsule": {"a": [x, y, z], "b": [x, y, z], "radius": r}},
//                     {"name": "fore", "surface": "fore_bone.obj"}],
//           "animation": "flexion.json"}
//       each bone a constraint set of the vertices inside it (snh/rig.h: the
//       first listed bone wins a vertex inside two), after "constraints";
//       the animation (snh/animation.h, .json or .csv) gives each frame's
//       bone matrices. The scene then runs frame by frame, solver.steps load
//       steps per frame.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "snh/animation.h"
#include "snh/regions.h"
#include "snh/rig.h"
#include "snh/scenes.h"
#include "snh/surface.h"

namespace snh::bench {

struct SceneFile {
  Scene scene;
  Material material;      // the base material ("material")
  MaterialMap materials;  // every element's: the base and the "regions"
  // "output.vtu": a folder for a .vtu per step (displacement and the element
  // fields of snh/fields.h) and a .pvd; empty for none.
  std::string vtu_dir;
  // "output.json": the run's JSON summary, each step with its constraint
  // sets' reactions; empty for none.
  std::string json_path;
  // "output.surface": where the embedded surface goes per step or frame as
  // OBJ: a folder (ending in '/', or an existing folder) for
  // <folder>/<scene>_NNNN.obj, else a prefix for <prefix>_NNNN.obj; empty
  // for none. Needs "embed".
  std::string surface_prefix;

  // "embed": the surface, the lattice's grid (scene.mesh is its lattice) and
  // the surface's embedding in it.
  struct Embedded {
    TriangleSurface surface;
    Voxelization voxels;
    Embedding embedding;
  };
  std::optional<Embedded> embedded;

  // "rig": the bones (their sets are the last entries of scene.constraints)
  // and the animation.
  struct Rig {
    std::vector<Bone> bones;
    Animation animation;
  };
  std::optional<Rig> rig;

  // The file sets solver.strain_tolerance or solver.absolute_tolerance;
  // without them the strain tolerance is the precision's default
  // (strain_tolerance_default), set again when the command line changes the
  // precision.
  bool tolerance_given = false;
};

// The default stopping strain for a precision: 1e-6 in double, 1e-4 in float
// (which resolves J - alpha only to about FLT_EPSILON lambda / mu), as for the
// named scenes.
inline double strain_tolerance_default(Precision precision) { return precision == Precision::single ? 1e-4 : 1e-6; }

// The OBJ of step or frame `index` under a surface prefix ("output.surface").
std::string surface_obj_path(const std::string& prefix, const std::string& scene, int index);

// Paths inside the file (mesh files) are relative to the file's folder.
// Throws snh::Error "<file>: <key path>: <what>".
SceneFile load_scene_file(const std::string& path);

}  // namespace snh::bench
