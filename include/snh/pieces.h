// The pieces of a voxelized lattice and what holds each of them. A lattice
// falls apart into pieces (elements joined through shared vertices) where a
// thin part of the surface, a fingertip or a tail's tip, keeps no cell
// centre inside it near its root. A piece that no constraint set, obstacle
// or inertia holds does not follow the rest: a quasistatic solve leaves it at
// rest while the body moves (the surface embedded in it stretches across the
// gap), and under a load it has no equilibrium at all.
//
// resolve_pieces finds the pieces, decides which are held, and by the rule
// either refuses the unheld ones (an snh::Error naming each, its size, place
// and nearest bone, and the remedies), joins each to its nearest held piece
// through the cells the surface crosses, or leaves it out of the lattice.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "snh/rig.h"
#include "snh/simulation.h"
#include "snh/surface.h"

namespace snh {

// What to do with a piece nothing holds ("embed.pieces" in scene files).
enum class PieceRule {
  error,   // an snh::Error naming each unheld piece (quasistatic scenes; a dynamic one warns)
  attach,  // add the cells the surface crosses between it and its nearest held piece, so that the two are one
  drop,    // leave its elements out; the surface they carried follows the nearest kept cell
};

// "error", "attach", "drop".
const char* to_string(PieceRule rule);
// The inverse of to_string; snh::Error listing the names for anything else.
PieceRule parse_piece_rule(const std::string& name);

// What holds a piece.
enum class PieceHold {
  none,        // nothing
  constraint,  // a vertex of it is in a constraint set (a bone's or another), with a prescribed component
  obstacle,    // a vertex of it lies within the contact layer of an obstacle at rest
  inertia,     // nothing else, but the scene is dynamic (a free piece moves with its momentum, and falls)
  largest,     // nothing, and no piece is held: the largest piece is kept as the body (the solver's own
               // rigid-motion check then decides)
};
const char* to_string(PieceHold hold);

struct LatticePiece {
  std::vector<int32_t> elements;  // ascending
  int vertices = 0;
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0};  // rest bounding box of its vertices
  PieceHold hold = PieceHold::none;
  std::string held_by;  // the constraint set's name, "obstacles[k]", or empty
  // The bone nearest to its vertices at rest, and that distance (0 when a
  // vertex is inside it); empty without bones.
  std::string nearest_bone;
  double nearest_bone_distance = 0.0;
  // What the rule did: "" (kept as it is), "attached" or "dropped".
  std::string outcome;
  int added_cells = 0;  // attach: the cells added to join it
  // attach: "surface" (through cells the surface crosses) or "straight line"
  // (no such path: the straight line of cells to the nearest held cell).
  std::string joined_through;
};

// The pieces of a mesh: elements joined through shared vertices, each piece's
// elements ascending, the pieces ordered by their first element.
std::vector<std::vector<int32_t>> mesh_pieces(const Mesh& mesh);

struct PieceOptions {
  PieceRule rule = PieceRule::error;
  bool dynamic = false;  // the scene has inertia (SolveOptions::dynamics)
  bool loaded = false;   // a body or external force acts (dynamic scenes: a free piece falls: a warning)
  // A piece touching an obstacle's contact layer at rest (signed distance
  // <= thickness, the obstacle placed at motion(0)) counts as held.
  std::vector<Obstacle> obstacles;
  double contact_thickness = 0.0;
  // Named in the error as where the rule is set (a scene file's key path).
  std::string rule_name = "PieceOptions::rule";
};

// The lattice after the rule, and how it maps to the one given.
struct PiecedLattice {
  Voxelization voxels;                  // element_cell, vertices and components consistent with the new lattice
  Embedding embedding;                  // the surface in the new lattice
  std::vector<LatticePiece> pieces;     // as found before the rule, with what holds each and what was done
  std::vector<int32_t> vertex_map;      // per vertex of the given lattice: its vertex now, -1 where dropped
  std::vector<int32_t> element_source;  // per element now: the given element it is, or (attach) grew from
  std::vector<std::string> warnings;    // e.g. a free piece of a dynamic scene under a load
  bool changed = false;                 // the lattice differs from the one given
};

// Finds the pieces of voxels.lattice and what holds them (`constraints`:
// the sets on that lattice, bones' included; `bones` only name the nearest
// bone). With one piece nothing is decided: the solver checks the whole
// body. Otherwise the held pieces are those with a constrained vertex
// (PieceHold::constraint) or one within an obstacle's contact layer; when
// none is, the largest piece stands for the body (PieceHold::largest). Each
// other piece is, by options.rule:
//   error:  snh::Error naming every such piece (cells, bounding box, nearest
//           bone and its distance) and the remedies, unless the scene is
//           dynamic (PieceHold::inertia; a warning when a load acts);
//   attach: joined to the nearest held piece along the surface: the fewest
//           face-connected grid cells that the surface's triangles cross
//           (and no element occupies) from a cell of the piece to a held
//           cell (breadth-first, ties to the lowest grid index); where no
//           such path exists, the straight line of grid cells between their
//           nearest cells (3D DDA from centre to centre; joined_through
//           says which). The added cells share vertices only with the cells
//           before and after them on the path, and never glue vertices of
//           two different constraint sets (the sets stay apart); the
//           embedding is computed again on the new lattice (snh::embed);
//   drop:   its elements and the vertices only they use are left out; the
//           surface vertices embedded in it follow the kept cell nearest to
//           the piece, extrapolated (the cell's trilinear functions at their
//           unclamped local coordinates: rigid and affine motions of that
//           cell carry them exactly).
// `constraints` are renumbered to the new lattice (vertex_map) in place; a
// set that drop would leave with no vertex (one that prescribes no
// component, so held nothing) is an snh::Error naming it.
// Vertices and elements of the given lattice keep their order; attached
// cells and their new vertices come after them.
PiecedLattice resolve_pieces(const Voxelization& voxels, const Embedding& embedding, const TriangleSurface& surface,
                             std::vector<ConstraintSet>& constraints, const std::vector<Bone>& bones,
                             const PieceOptions& options = {});

}  // namespace snh
