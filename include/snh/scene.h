// Scene files: a simulation described in JSON (docs/scene-files.md lists
// every key). A scene gives a mesh (a file or a generator) or a closed
// surface to voxelize and embed, the materials and their regions,
// constraint vertex sets with rigid or keyframed motions, a rig of bones and
// its animation, body force, dynamics, obstacles and contact, solver
// settings and outputs.
//
// load_scene reads a file into a SceneFile; a program may change its solve
// options (a command line's overrides) and hand it to run_scene, which runs
// its load steps (or time steps), or its animation frame by frame for a rig,
// and returns a record per step or frame. The writers below turn a run into
// the files "output" names: a .vtu series with a .pvd, a JSON summary, and
// the embedded surface as OBJ per step or frame.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "snh/animation.h"
#include "snh/character.h"
#include "snh/configuration.h"
#include "snh/fields.h"
#include "snh/frames.h"
#include "snh/io.h"
#include "snh/pieces.h"
#include "snh/regions.h"
#include "snh/rig.h"
#include "snh/scenes.h"
#include "snh/simulation.h"
#include "snh/surface.h"
#include "snh/surface_intersections.h"

namespace snh {

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
  // "output.check_intersections": count the output surface's intersecting
  // triangle pairs exactly at the end of each step or frame
  // (SceneRun::surface_intersections).
  bool check_intersections = false;

  // "embed": the surface, the lattice's grid (scene.mesh is its lattice) and
  // the surface's embedding in it.
  struct Embedded {
    TriangleSurface surface;
    Voxelization voxels;
    Embedding embedding;
    // "embed.pieces": the rule for lattice pieces nothing holds, the pieces
    // as found (what holds each, what the rule did) and the warnings
    // (snh/pieces.h). voxels and embedding are the lattice after the rule.
    PieceRule piece_rule = PieceRule::error;
    std::vector<LatticePiece> pieces;
    std::vector<std::string> piece_warnings;
  };
  std::optional<Embedded> embedded;

  // "rig": the bones (their sets are the last entries of scene.constraints)
  // and the animation. The scene then runs frame by frame, solver.steps load
  // steps per frame.
  struct Rig {
    std::vector<Bone> bones;
    Animation animation;
  };
  std::optional<Rig> rig;

  // "character": a skinned character (snh/character.h) in place of "mesh",
  // "embed" and "rig". The loader also fills `embedded` (the character's
  // surface in the file's vertex order, the welded surface's lattice and
  // the embedding) and `rig` (a bone per kept joint, the sampled clip), so
  // that the rig's writers serve it too.
  struct CharacterSection {
    Character character;
    CharacterRig rig;
    bool skinned_guess = false;     // "character.skinned_guess"
    std::optional<int> resolution;  // "character.resolution" (rig.cell is the cell chosen); empty: "cell" given
  };
  std::optional<CharacterSection> character;
  // "output.pc2", "output.mdd": the character's simulated surface per frame
  // as point caches; "output.lbs": its linear-blend-skinned surface (.pc2 or
  // .mdd). Empty for none; they need "character".
  std::string pc2_path, mdd_path, lbs_path;

  // The file sets solver.strain_tolerance or solver.absolute_tolerance;
  // without them the strain tolerance is the precision's default
  // (strain_tolerance_default), set again when a program changes the
  // precision.
  bool tolerance_given = false;
};

// Reads a scene file. Paths inside it (meshes, surfaces, animations) are
// relative to the file's folder. Unknown keys and wrong types are errors:
// snh::Error "<file>: <key path>: <what>", the file as given; a referenced
// file that cannot be read is named by its resolved path.
SceneFile load_scene(const std::string& path);

// Every key a scene file accepts, as a path from the root: dot-separated,
// "[]" for an array's elements (e.g. "mesh.file", "regions[].select.box.min",
// "constraints[].motion.keys[].t"), the objects' own keys included
// ("mesh", "regions[].select"). Sorted, no duplicates.
std::vector<std::string> scene_file_keys();

// The default stopping strain for a precision: 1e-6 in double, 1e-4 in float
// (which resolves J - alpha only to about FLT_EPSILON lambda / mu), as for the
// named scenes.
inline double strain_tolerance_default(Precision precision) { return defaults::strain_tolerance(precision); }

// The OBJ of step or frame `index` under a surface prefix ("output.surface").
std::string surface_obj_path(const std::string& prefix, const std::string& scene, int index);

// How far the body is from its rest shape after a step: volume, smallest J,
// and the RMS vertex distance after the best rigid fit (snh/shape.h),
// absolute and relative to the rest radius of gyration. Undefined for a
// non-finite state.
struct StepShape {
  bool defined = false;
  double volume_ratio = 0.0, min_j = 0.0, rigid_fit_rms = 0.0, rigid_fit_rms_relative = 0.0;
};

// What a load-step run measured after each completed step, besides the
// solver's StepResult (SceneRun::result.steps, in the same order).
struct SceneStep {
  StepShape shape;
  // A contact stiffness with self-contact off: the self-penetration the
  // penalty would see, measured (not resisted) outside the solve's time.
  bool self_contact_measured = false;
  int unresolved_self_contacts = 0;
  double max_self_penetration = 0.0;
  // Each constraint set's force and torque on the body (fields.h); absent
  // where the forces are undefined (a non-finite state) or reactions were
  // not asked for.
  std::optional<std::vector<Reaction>> reactions;
};

struct SceneRun {
  SolveOptions options;  // as run
  // Every unset option chosen, with its reason (snh/configuration.h).
  ResolvedConfiguration resolved;
  // Load steps (no rig): the solve and a record per completed step.
  SolveResult result;
  std::vector<SceneStep> steps;
  // A rig: a record per frame, and the device they ran on.
  std::vector<FrameRecord> frames;
  // A character: per frame, the simulated surface's distance from the
  // linear-blend-skinned one.
  std::vector<SkinDeviation> skin_deviation;
  DeviceInfo device;
  bool converged = false;  // every step or frame
  // What could not be computed or written, e.g. a step without reactions.
  std::vector<std::string> warnings;
  // "output.check_intersections": per step or frame, in their order, the
  // exact self-intersection count of the output surface at its end (the
  // embedded surface, else the mesh's boundary); empty when not asked. One
  // that is not clean is also a warning of its step (run.warnings) or frame.
  std::vector<SelfIntersections> surface_intersections;
};

// Reported after each load step or frame.
struct SceneProgress {
  bool frame = false;  // a rig's frame, else a load step
  int index = 0;       // 1-based
  int count = 0;
  int newton_iterations = 0;
  int cg_iterations = 0;
  double residual_norm = 0.0;            // frames: the frame's; steps: before the last Newton update
  StepStatus status = StepStatus::none;  // FrameRecord::status or StepResult::status
  double seconds = 0.0;
  double time = 0.0;                  // a frame's animation time or a dynamic step's simulated time
  double min_j = 0.0;                 // at the end of the frame or step
  int inverted_elements = 0;          // at the end of the frame or step
  std::vector<std::string> warnings;  // FrameRecord::warnings or StepResult::warnings
};

// Called with each step's or frame's lattice positions and the embedded
// surface's (empty without "embed"), after its record; writers use it.
using SceneStepWriter = std::function<void(int index, double time, const Points& lattice, const Points& surface)>;

struct SceneRunOptions {
  // A rig: run only the first frames; 0: all (a concrete limit, none, not a
  // choice left to the library, so no std::optional).
  int max_frames = 0;
  bool reactions = true;  // load steps: each step's constraint reactions (kept positions, computed after the solve)
  std::function<void(const SceneProgress&)> progress;
  std::vector<SceneStepWriter> writers;  // e.g. SceneVtuSeries::writer, surface_obj_writer
};

// Runs a loaded scene with `options` (the file's scene.options, changed as
// the caller likes): load steps (or time steps with dynamics) on one solve,
// or, with a rig, the animation's frames (snh/frames.h), or a character's
// frames (run_character_frames; writers get its surface in the file's
// vertex order, frames numbered as in the clip). Step 0 (the start)
// of a load-step run goes to the writers before the solve; frames are
// numbered from 0.
SceneRun run_scene(const SceneFile& file, const SolveOptions& options, const SceneRunOptions& run = {});

// What the set-up made of a loaded scene, as lines for a log: with "embed",
// the lattice's pieces (count; each piece's cells, what holds it and what
// embed.pieces did to it) and their warnings (prefixed "warning: "); with a
// character, its bounding box, the cell and what reading and preparing it
// repaired (Character::warnings, CharacterRig::warnings but the voxelizer's,
// prefixed "warning: "); with a rig, each bone's captured lattice-vertex
// count.
std::vector<std::string> scene_setup_report(const SceneFile& file);

// The writers of a scene's outputs.
//
// A .vtu per step or frame into `folder` (<scene>_NNNN.vtu: displacement and
// the element fields of snh/fields.h), the obstacles as surfaces
// (<scene>_obstacles_NNNN.vtu, part 1) or a rig's embedded surface
// (<scene>_surface_NNNN.vtu, part 1) and its bones placed by the frame's
// transforms (<scene>_bones_NNNN.vtu, part 2: write_bone_mesh_vtu), and
// <scene>.pvd on finish(). `file` must outlive the series.
class SceneVtuSeries {
 public:
  SceneVtuSeries(std::string folder, const SceneFile& file, const SolveOptions& options);
  SceneStepWriter writer();  // refers to this series: keep it alive and in place while the writer runs
  void finish();             // writes the .pvd
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  std::string folder_;
  const SceneFile* file_;
  SolveOptions options_;
  std::array<double, 3> middle_{0, 0, 0};
  double extent_ = 0.0;
  std::vector<PvdDataSet> written_;
  std::vector<std::string> warnings_;
};

// The embedded surface per step or frame as OBJ (surface_obj_path); `file`
// must outlive the writer. Throws snh::Error for a file without "embed".
SceneStepWriter surface_obj_writer(const std::string& prefix, const SceneFile& file);

// The run's JSON summary ("output.json"): the scene, device, material and
// solver settings, each step (reactions, shape, contacts) or frame with its
// Newton history, warnings (StepResult::warnings, FrameRecord::warnings) and
// reactions.
void write_scene_json(const std::string& path, const SceneFile& file, const SceneRun& run);

}  // namespace snh
