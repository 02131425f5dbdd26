// The geometric multigrid hierarchy of a hex8 lattice, built on the host once
// per mesh and constraint mask: lattices coarsened 2x per axis, trilinear
// prolongation between them, and which coarse DOFs still reach a free fine
// DOF. A coarse cell covers whatever fine cells exist below it, one coarse
// cell per connected group of them (children sharing a vertex), so partly
// filled cells, lattices that are not boxes and the non-manifold lattices of
// the voxelizer (vertices duplicated across a thin gap) keep their topology
// (McAdams et al. 2011 duplicate coarse cells the same way). No OpenCL here.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "snh/mesh.h"

namespace snh::solver {

struct LatticeLevel {
  size_t vertex_count = 0;
  std::vector<int> elements;              // 8 vertices per cell, VTK order
  std::vector<std::array<int, 3>> cells;  // integer coordinates at this level's spacing
  std::vector<char> mask;                 // per DOF: 1 if it reaches a free fine DOF
  // Levels below the finest: per cell, the finer level's cell in each octant
  // (bits x, y, z of the octant index), or -1.
  std::vector<int> children;
  // Levels above the coarsest: the prolongation from the next coarser level,
  // 8 (coarse vertex, weight) pairs per vertex of this level (weight 0 pads),
  // and its transpose per coarse vertex: offsets, this level's vertices (in
  // increasing order) and weights.
  std::vector<int> prolongation_vertices;
  std::vector<double> prolongation_weights;
  std::vector<int> restriction_offsets, restriction_vertices;
  std::vector<double> restriction_weights;
};

struct LatticeHierarchy {
  double spacing = 0.0;              // the finest cells' edge
  std::vector<LatticeLevel> levels;  // levels[0] the mesh itself
};

// Offset (0 or 1) of hex8 node a (VTK order) along axis d.
int hex8_node_bit(int a, int d);
// Weight of coarse corner `corner` (VTK order) at node a of the child cell in
// octant o (bits x, y, z) under trilinear prolongation: a product over the
// axes of 1 - |p - c| / 2, p = octant bit + node bit and c = 2 * corner bit
// in units of the fine spacing.
double child_weight(int o, int a, int corner);
// All of them, [64 o + 8 a + corner] (what the Galerkin kernels read).
std::vector<double> octant_weights();

// True when every element of `mesh` is an axis-aligned cube of one edge
// length (relative tolerance 1e-6), nodes in VTK order.
bool is_hex8_lattice(const Mesh& mesh);

// Throws snh::Error (naming what is wrong and the alternative) unless the
// mesh is a hex8 lattice.
void require_hex8_lattice(const Mesh& mesh);

// Coarsens until a level has at most `coarsest_dofs` DOFs, stops shrinking
// (fewer than 1.5x fewer cells) or `max_levels` levels exist. fine_mask: 1
// free, 0 constrained, per DOF of the mesh. Throws snh::Error naming the
// element when the mesh is not a hex8 lattice.
LatticeHierarchy build_lattice_hierarchy(const Mesh& mesh, const std::vector<char>& fine_mask, size_t coarsest_dofs,
                                         int max_levels);

}  // namespace snh::solver
