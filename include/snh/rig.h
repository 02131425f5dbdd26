// A character's skeleton in the simulation's terms: bones are solids (a
// capsule, or a closed triangle surface) whose lattice vertices move with
// them; each bone becomes one constraint set of the vertices inside it, and
// each frame's bone transform (a 4x4 matrix, rigid or not) becomes that
// set's target.
#pragma once

#include <array>
#include <string>
#include <variant>
#include <vector>

#include "snh/mesh.h"
#include "snh/simulation.h"
#include "snh/surface.h"

namespace snh {

// The points within `radius` of the segment from a to b.
struct Capsule {
  std::array<double, 3> a{0, 0, 0};
  std::array<double, 3> b{0, 0, 0};
  double radius = 0.0;
};

struct Bone {
  std::string name;
  // A capsule, or a closed surface (outward normals) holding the points of
  // winding number >= 1/2 (inside, whatever the triangles' orientation
  // errors at isolated spots).
  std::variant<Capsule, TriangleSurface> shape;
};

// Whether rest position p is inside the bone (on its boundary counts as
// inside for a capsule).
bool bone_contains(const Bone& bone, const std::array<double, 3>& p);

// The distance from rest point p to the bone's solid: 0 inside it, else to
// the capsule's round surface or the nearest of the surface's triangles.
double bone_distance(const Bone& bone, const std::array<double, 3>& p);

// One constraint set per bone, named as the bone, of the lattice vertices
// inside it (rest positions), in the bones' order, with no motion (they stay
// at rest until Simulation::set_transform moves them). A vertex inside
// several bones goes to the first of them in `bones`, so that the sets never
// share a vertex: list the bone that should win at a joint first. Throws
// snh::Error for an empty or repeated bone name, a capsule with a radius not
// > 0 or non-finite ends, a surface bone without triangles, and a bone left
// with no vertex (naming it, and the bone that took its vertices if any).
std::vector<ConstraintSet> bone_constraints(const Mesh& lattice, const std::vector<Bone>& bones);

// A 4x4 affine bone transform, row-major: x' = M [x; 1] for rest point x, so
// m[0..3] is the first row and m[3], m[7], m[11] the translation. Its last
// row must be 0 0 0 1. The upper-left 3x3 may be any invertible matrix
// (scale, shear): Simulation interpolates such transforms linearly.
using Matrix4 = std::array<double, 16>;

Matrix4 identity_matrix4();

// The same map as a RigidTransform about `center` (its `rotation` holds the
// upper-left 3x3, row-major like m; translation = M c + t - c): the centre is
// the point Simulation's rigid interpolation rotates about, e.g. a bone's
// centroid. Throws snh::Error for a last row other than 0 0 0 1 or
// non-finite entries.
RigidTransform to_rigid_transform(const Matrix4& m, const std::array<double, 3>& center = {0, 0, 0});

// The bones as one triangle surface, to be seen beside the lattice: a
// capsule as a closed tessellated capsule (`segments` around its axis,
// segments / 4 rings per round end), a surface bone as it is. `transforms`
// (one per bone, or empty: rest) place each bone's vertices by x' = M [x; 1].
struct BoneMesh {
  TriangleSurface surface;
  std::vector<int32_t> triangle_bone;  // per triangle: its bone's index in `bones`
  std::vector<int32_t> vertex_bone;    // per vertex: likewise
};
BoneMesh bone_mesh(const std::vector<Bone>& bones, const std::vector<Matrix4>& transforms = {}, int segments = 16);

// The mesh as an ASCII .vtu of triangles with the cell array "bone" (the
// bone's index) for ParaView; snh::Error naming the file when it cannot be
// written.
void write_bone_mesh_vtu(const std::string& path, const BoneMesh& mesh);

// Each animated bone's matrix at frame `frame` of `animation`, the identity
// for the bones it does not move, in the order of `bones`.
struct Animation;
std::vector<Matrix4> bone_transforms_at(const std::vector<Bone>& bones, const Animation& animation, size_t frame);

}  // namespace snh
