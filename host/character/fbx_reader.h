// Reading a skinned FBX character with ufbx (host/third_party/ufbx): the
// surface is the skinned meshes' control points, the vertex list Blender,
// Maya and 3ds Max import (assimp splits them per polygon corner).
#pragma once

#include <string>

#include "snh/character.h"

namespace snh::detail {

// Reads an FBX skinned character with ufbx. Fills Character::file, surface
// (vertices = the skinned meshes' control points, in the file's order, one
// mesh after another in the order ufbx lists skinned meshes; triangles from
// each polygon (ufbx_triangulate_face), offset per mesh; control points used
// by no face are kept as vertices), joints (the skin clusters' bone nodes,
// parents before children, Joint::parent = nearest ancestor that is a joint,
// inverse_bind = the cluster's geometry_to_bone, rest_position = its
// inverse's translation), weights (raw per control point, as the file stores
// them: not normalized; rows sorted by joint; a vertex may have no weight),
// clip_names, has_clip/clip (the selection rules, error texts and frame
// range rules of read_character: by name, by index, else the first; frames
// first..last at fps from the anim stack's start) and Character::warnings.
//
// Positions and skinning matrices are in the skinned mesh's own geometry
// space, as the file stores its control points (no axis or unit
// conversion): skinning_j(t) = M^-1 * bone_to_world_j(t) * geometry_to_bone_j
// with M the mesh's geometry_to_world at rest, so that at the bind pose the
// matrices are the identity. Several skinned meshes must share that space.
// A cluster whose bone node is missing is a joint held at its bind pose
// (identity every frame), listed in one warning.
//
// It does not weld (welded and welded_index stay empty) and does not check
// weight sums: read_character does both. snh::Error "<path>: <what>" naming
// the item.
Character read_fbx_character(const std::string& path, const CharacterReadOptions& options);

}  // namespace snh::detail
