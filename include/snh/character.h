// Skinned characters: a skin mesh with its skeleton, skin weights and
// animation clips read from glTF 2.0, Collada (through assimp) or FBX (through ufbx), turned
// into bones that drive an embedded flesh lattice, run frame by frame, and the
// character's own surface written per frame, in the input's vertex order, as
// point caches (PC2, MDD) beside its linear-blend-skinned counterpart.
//
// The steps, each usable alone:
//   read_character      the file: surface, joints, weights, a clip sampled at fps
//   character_bones     a capsule per joint segment and its per-frame transform
//   prepare_character   voxelize the welded surface, embed it, make the bone sets
//   run_character_frames the frames on a Simulation, optionally from a skinned guess
//   write_pc2/write_mdd  the caches (docs/formats.md gives their byte layout)
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "snh/animation.h"
#include "snh/frames.h"
#include "snh/pieces.h"
#include "snh/rig.h"
#include "snh/simulation.h"
#include "snh/surface.h"

namespace snh {

// What read_character does with skin weights that do not sum to 1 (most
// exporters write sums a few percent off; Blender, Maya, Unity and three.js
// normalize on import): `normalize` divides each vertex's weights by their
// sum (one warning gives the count and the worst sum); `strict` refuses the
// file, naming the first such vertex.
enum class WeightPolicy { normalize, strict };

struct CharacterReadOptions {
  // The clip to sample: by name, else by index (clip_index set, >= 0), else
  // the first clip. With require_clip false a file without animation reads
  // as a character without a clip.
  std::string clip;
  std::optional<int> clip_index;
  bool require_clip = true;
  double fps = 30.0;
  // Frames first..last (inclusive) at times frame / fps seconds from the
  // clip's start; last unset: up to the clip's last key.
  int first_frame = 0;
  std::optional<int> last_frame;
  // Weights summing to 1 within weight_tolerance are taken as they are;
  // others are normalized or refused (WeightPolicy). A vertex with no weight
  // at all takes the weights of the nearest weighted vertex (a warning
  // counts them) under either policy.
  WeightPolicy weights = WeightPolicy::normalize;
  double weight_tolerance = 1e-3;
  // Positions closer than this (absolute; unset: 1e-9 of the bounding box's
  // diagonal) are welded into one vertex of the simulated surface.
  std::optional<double> weld_distance;
};

// A joint of the skeleton: a node that skins vertices.
struct Joint {
  std::string name;
  int parent = -1;                               // the nearest ancestor that is also a joint, or -1
  Matrix4 inverse_bind;                          // the offset matrix: rest (mesh) space -> joint space
  std::array<double, 3> rest_position{0, 0, 0};  // the joint's origin at rest, inverse_bind^-1 (0, 0, 0)
};

// Skin weights per vertex, compressed rows: vertex v's joints are
// joint[offset[v] .. offset[v + 1]) with weight[...].
struct SkinWeights {
  std::vector<int32_t> offset{0};
  std::vector<int32_t> joint;
  std::vector<double> weight;
  size_t vertex_count() const { return offset.size() - 1; }
};

// A clip sampled at fps: per frame, per joint, the skinning matrix
// world(t) * inverse_bind (rest point -> posed point).
struct CharacterClip {
  std::string name;
  int index = -1;  // among the file's clips
  double fps = 30.0;
  int first_frame = 0;
  std::vector<double> times;                   // seconds, frame / fps
  std::vector<std::vector<Matrix4>> skinning;  // [frame][joint]
  size_t frame_count() const { return times.size(); }
};

struct Character {
  std::string file;
  // The skin as the file gives it (every mesh that has bones, in the
  // scene's mesh order; one vertex per vertex of the file, seams kept): the
  // output's vertex list and order.
  TriangleSurface surface;
  // The same with coincident positions welded (the surface voxelized and
  // embedded); welded_index maps each surface vertex to its welded vertex.
  TriangleSurface welded;
  std::vector<int32_t> welded_index;
  std::vector<Joint> joints;  // parents before children
  SkinWeights weights;        // per surface vertex
  std::vector<std::string> clip_names;
  bool has_clip = false;
  CharacterClip clip;
  // What was repaired on reading, one line per kind: weights normalized or
  // borrowed, joints named by weights but missing from the hierarchy (held
  // at their bind pose). Empty for a clean file.
  std::vector<std::string> warnings;
};

// Reads a skinned character: FBX through ufbx (the surface in the file's
// control-point order, as Blender, Maya and 3ds Max import it), every other
// format assimp reads through assimp (Collada with assimp's polygon corners
// collapsed onto the file's <vertices>, the order Blender and Maya import;
// a warning where that fails). snh::Error naming the file and the item
// for a file that cannot be read, no mesh with bones, no animation (when a
// clip is required), an unknown clip name or index (listing the clips), a
// frame range outside the clip, non-finite positions, matrices or keys, and,
// with WeightPolicy::strict, a vertex whose weights do not sum to 1 (naming
// it). Repairs are listed in Character::warnings.
Character read_character(const std::string& path, const CharacterReadOptions& options = {});

// Linear blend skinning: sum_j w_j M_j x for each vertex of rest positions
// x with `weights` and one matrix per joint.
Points linear_blend_skinning(const Points& rest, const SkinWeights& weights, const std::vector<Matrix4>& matrices);

// The 4x4 matrix T * R * S of a translation, a unit quaternion (w, x, y, z)
// and a scale, as glTF and assimp compose a node's transform.
Matrix4 compose_trs(const std::array<double, 3>& t, const std::array<double, 4>& q, const std::array<double, 3>& s);
Matrix4 multiply_matrix4(const Matrix4& a, const Matrix4& b);
Matrix4 inverse_matrix4(const Matrix4& m);  // snh::Error for a singular matrix

struct CharacterBoneOptions {
  // A bone's radius: this fraction of the distance from its segment to the
  // skin surface, unless `radius` gives the joint's radius (absolute).
  double radius_fraction = 0.5;
  std::map<std::string, double> radius;
  // Joints that get no bone, by name or glob pattern (fnmatch: * ? [..]),
  // e.g. "*finger*", "face_*", "*twist*".
  std::vector<std::string> exclude;
  // Flesh left free around each end of a segment, as a fraction of its
  // length: the capsule's axis is trimmed by this fraction of the length
  // plus the radius at both ends, so that its rounded ends stay that far
  // from the joints (bones meeting at a joint would crush the flesh
  // between them as it bends). Negative: the full segment, joint to joint.
  double joint_clearance = 0.1;
  // A joint without child joints (a head, a hand, a tail's tip): a segment
  // of this fraction of its parent's segment length, continuing the
  // parent's direction. 0: with leaf_from_skin, a segment along the
  // parent's direction reaching three quarters of the way to the farthest
  // skin vertex that the joint weighs most (none weighed: no bone);
  // without, no bone.
  double leaf_fraction = 0.0;
  bool leaf_from_skin = true;
  // The radius of a bone whose segment touches or crosses the skin (a thin
  // limb, a tail) and that `radius` does not give: absolute; 0 leaves such
  // bones out. prepare_character sets it to touching_radius_cells cells.
  // Either way one warning lists the bones affected.
  double touching_radius = 0.0;
};

// Bones and their animation from the skeleton: each kept joint's segment
// runs from the joint to its child joint (the centroid of its children's
// positions when it has several) at rest, trimmed by joint_clearance. Bones are named as their joints,
// in joint order; the animation gives every bone, every frame, its skinning
// matrix. snh::Error for a bone option naming no joint, a non-positive
// fraction or radius, a segment of zero length, and no bone left.
struct CharacterBones {
  std::vector<Bone> bones;
  std::vector<int> joint;             // per bone, its joint's index
  Animation animation;                // empty frames without a clip
  std::vector<std::string> warnings;  // bones given the floor radius or left out
};
CharacterBones character_bones(const Character& character, const CharacterBoneOptions& options = {});

// What a character's simulation needs: the welded surface's lattice, the
// embedding of every surface vertex (input order), the bones, their
// constraint sets, and skin weights carried to the lattice vertices
// (inverse-distance average of the 4 nearest welded surface vertices), for
// the skinned initial guess.
struct CharacterRig {
  double cell = 0.0;  // the lattice's cube side
  Voxelization voxels;
  Embedding embedding;  // per vertex of Character::surface
  CharacterBones bones;
  std::vector<ConstraintSet> constraints;  // one per bone (bone_constraints)
  SkinWeights lattice_weights;
  std::vector<LatticePiece> pieces;  // as found, when there were several (CharacterPrepareOptions::pieces)
  // Surface vertices outside every element (open sheets, flaps thinner than
  // a cell, loose points and edges) follow their nearest element, extended
  // to first order (CharacterPrepareOptions): their count and the largest
  // distance from their element.
  int vertices_outside = 0;
  double max_outside_distance = 0.0;
  // What was repaired (shells turned outwards, vertices carried, bones given
  // a floor radius or left out), one line per kind, and the voxelizer's
  // surface warnings.
  std::vector<std::string> warnings;
};

struct CharacterPrepareOptions {
  CharacterBoneOptions bones;
  VoxelizeOptions voxelize;
  // A bone whose segment touches the skin gets this many cells as its
  // radius unless CharacterBoneOptions::touching_radius is set (> 0): more
  // than sqrt(3) / 2, so that a lattice vertex lies within it wherever its
  // segment runs through the lattice.
  double touching_radius_cells = 0.9;
  // A surface vertex farther than this from every element (as a fraction
  // of the bounding box's diagonal, and more than 4 cells) is an error
  // naming it: geometry far from everything else.
  double max_outside_fraction = 0.25;
  // Lattice pieces no bone holds (a thin tail or ear that voxelizes apart
  // from the body): joined to the nearest held piece along the surface by
  // default, as resolve_pieces does (snh/pieces.h), with a warning.
  PieceRule pieces = PieceRule::attach;
};

// The cube side that puts `resolution` cells along the longest side of the
// character's bind-pose bounding box. snh::Error naming the file for
// resolution < 1 or an empty or flat surface.
double character_cell(const Character& character, int resolution);

CharacterRig prepare_character(const Character& character, double cell, const CharacterPrepareOptions& options);
CharacterRig prepare_character(const Character& character, double cell, const CharacterBoneOptions& bones = {},
                               const VoxelizeOptions& voxelize_options = {});

// How far the simulated surface is from the linear-blend-skinned one in a
// frame, over all surface vertices.
struct SkinDeviation {
  double max_distance = 0.0;
  double mean_distance = 0.0;
};

struct CharacterFrame {
  FrameRecord record;  // frame and time as in the clip
  SkinDeviation lbs;
};

struct CharacterFrameOptions {
  FrameOptions frames;
  // Start each frame's solve from the previous frame's state moved by the
  // change of the lattice's linear blend skinning (CharacterRig::
  // lattice_weights) since that frame, instead of the previous frame's
  // state as it is. (Starting from the skinned lattice itself loses what
  // the solve restored, e.g. the volume inside a bend, and measured worse:
  // docs/characters.md.)
  bool skinned_guess = false;
};

// Called after each frame with its record, the lattice positions, the
// character's simulated surface and its skinned surface (one point per vertex of
// Character::surface). Return false to stop.
using CharacterFrameCallback =
    std::function<bool(const CharacterFrame&, const Points& lattice, const Points& surface, const Points& skinned)>;

// Runs the clip's frames (run_frames, one frame at a time) on a simulation
// of rig.voxels.lattice with rig.constraints.
std::vector<CharacterFrame> run_character_frames(Simulation& simulation, const Character& character,
                                                 const CharacterRig& rig, const CharacterFrameOptions& options = {},
                                                 const CharacterFrameCallback& on_frame = {});

// The surface with positions x (empty: its own) as binary
// little-endian PLY (float x, y, z; triangles as uchar-counted int lists),
// vertices in the surface's order (write_obj, snh/surface.h, writes OBJ).
void write_surface_ply(const std::string& path, const TriangleSurface& surface, const Points& x = {});

// A point cache: the same points sampled over frames.
struct PointCache {
  size_t point_count = 0;
  double start_frame = 0.0;                 // PC2: the first sample's frame
  double sample_rate = 1.0;                 // PC2: frames between samples
  std::vector<double> times;                // MDD: seconds per sample
  std::vector<std::vector<float>> samples;  // per sample, xyz per point
};

// PC2 (little-endian): "POINTCACHE2\0", int32 version 1, int32 points,
// float32 start frame, float32 sample rate, int32 samples, then float32 xyz
// per point per sample. MDD (big-endian): int32 frames, int32 points,
// float32 time per frame, then float32 xyz per point per frame. Writers
// throw snh::Error (naming the file) for samples of the wrong size, an MDD
// whose times are not one per sample, or a file that cannot be written;
// readers for a short or malformed file.
void write_pc2(const std::string& path, const PointCache& cache);
void write_mdd(const std::string& path, const PointCache& cache);
PointCache read_pc2(const std::string& path);
PointCache read_mdd(const std::string& path);
// By extension: .pc2 or .mdd (any case); snh::Error for another.
void write_point_cache(const std::string& path, const PointCache& cache);

// Collects a character's frames and writes its caches: the simulated
// surface to `pc2` and/or `mdd`, the skinned surface to `lbs` (.pc2 or
// .mdd); empty paths are skipped. Frames are numbered as in the clip
// (start frame = the clip's first frame, one sample per frame, times
// frame / fps).
class CharacterCacheSeries {
 public:
  CharacterCacheSeries(const Character& character, std::string pc2, std::string mdd, std::string lbs);
  // A frame (numbered as CharacterFrame::record.frame: the clip's frame
  // number) with the simulated surface (one point per vertex of
  // Character::surface); frames are written in the order added.
  void add(int clip_frame, const Points& surface);
  void finish();  // writes the files

 private:
  const Character* character_;
  std::string pc2_, mdd_, lbs_;
  PointCache simulated_, skinned_;
};

}  // namespace snh
