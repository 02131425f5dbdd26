// A Collada character's surface in the file's own vertex order. assimp's
// Collada loader gives one vertex per polygon corner (ColladaParser's
// CopyVertex); Blender's and Maya's Collada importers keep the geometry's
// <vertices>, one per position index, and a point cache loads only onto a
// mesh with its vertices in that order. This reads just what is needed from
// the .dae's XML (a small parser of its own) and collapses assimp's corners
// onto those indices.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "snh/surface.h"

namespace snh::detail {

// One skinned mesh as assimp gives it: its name (the <geometry> id, assimp's
// aiMesh::mName) and the range of its per-corner vertices in the surface.
struct ColladaCornerMesh {
  std::string geometry;
  int32_t first = 0;
  int32_t count = 0;
};

// Raw skin-weight rows per surface vertex: (joint index, weight).
using WeightRows = std::vector<std::vector<std::pair<int32_t, double>>>;

// Collapses a per-corner Collada surface (the vertices of `meshes`, one after
// another, in assimp's order, with `rows` of weights each) onto the skinned
// geometries' <vertices>: each geometry's position-source entries in order
// (one geometry after another in the order its meshes first appear), the
// triangles mapped through each corner's position index (assimp's own
// triangulation, order and orientation kept), the weights of the corners.
// Every corner mapped to an index must have that entry's position (to float
// rounding) and the same weights. Entries no corner uses (loose points) are
// kept, their weights read from the controller's <vertex_weights>, the
// joint names resolved to nodes as assimp does (by name or id, else by sid;
// the node's id) and given to `joint` (-1: a joint the character lacks, the
// weight left out).
//
// Returns "" when done; otherwise nothing is changed and the reason is
// returned (a file part it cannot read, a corner that does not match).
std::string collapse_collada_corners(const std::string& path, const std::vector<ColladaCornerMesh>& meshes,
                                     const std::function<int32_t(const std::string&)>& joint, TriangleSurface& surface,
                                     WeightRows& rows);

// Checks what assimp 5.2 does not before it reads the file: each
// controller's <skin> <vertex_weights> joint and weight index in <v>,
// through its source's accessor (offset + index x stride), must lie in its
// array (the values its count attribute says: what assimp reads), and <v>
// must hold what <vcount> says (assimp only asserts, an abort, or reads
// past the array); every <p>, <vcount> and <v> must be integers only (assimp loops
// on another character, growing its lists until memory runs out).
// snh::Error naming the file and the element otherwise; nothing for a file
// this XML reader cannot parse (assimp reports it).
void check_collada_for_assimp(const std::string& path);

}  // namespace snh::detail
