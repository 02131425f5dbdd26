// The tables of a block stencil (kernels/fem/block_stencil.h): an operator
// stored as the 3x3 blocks of each vertex pair that shares an element,
// assembled on the device from element matrices (kernels/stencil.cl,
// snh_stencil_assemble). Used by the assembled product variant
// (solver/elastic_model.h) and the multigrid's assembled levels
// (solver/multigrid.h). Internal to the library.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "fem/vertex_slots.h"

namespace snh::solver {

// neighbours: [width v + s] (fem::vertex_neighbours: v first, the others in
// increasing order, v again as padding). Per block (v, s) in that order, the
// element blocks that add up to it, each as the offset of its first entry
// among the (3 nodes)^2 column-major element matrices,
// (3 nodes)^2 e + 9 nodes a + 3 b (node a of element e at v, node b at
// neighbour s): the block (b, a), in the columns of node a, which the
// kernel reads transposed, so that a vertex's blocks come from its own
// nodes' columns, contiguous (exactly block (a, b): element matrices and
// the multigrid's Galerkin cell matrices are stored exactly symmetric;
// session 26: twist res 32 block-Jacobi's
// assemblies 1.56 -> 1.15 s, against block (a, b) read across the columns
// of every node b); between part_offsets[width v + s] and the next, in
// increasing element order (deterministic sums, exactly transposed blocks
// (v, n) and (n, v) from symmetric element matrices).
struct StencilTables {
  int width = 1;
  std::vector<int> neighbours, part_offsets, parts;
};

// slots: fem::vertex_slots(elements, vertex_count). snh::Error when the
// offsets would not fit an int.
StencilTables stencil_tables(const std::vector<int>& elements, size_t vertex_count, int nodes,
                             const fem::VertexSlots& slots);

// The device's layout of the blocks and the neighbour table: per vertex as
// in the tables (tile 1, CPUs), or in tiles of `tile` vertices
// (SNH_STENCIL_TILE, GPUs: kernels/fem/block_stencil.h), the last tile
// whole. Block entries stored: 9 per block, `width` blocks per vertex.
inline size_t stencil_entries(int width, size_t vertex_count, size_t tile) {
  return 9 * static_cast<size_t>(width) * ((vertex_count + tile - 1) / tile * tile);
}
// The neighbour table in that layout (padding of the last tile: 0).
std::vector<int> tiled_neighbours(const StencilTables& t, size_t vertex_count, size_t tile);

// The build option that makes a stencil's width a constant of the kernels
// that read it (SNH_STENCIL_WIDTH: their loop over a vertex's blocks
// unrolled), with the per-vertex blocks (tile 1, CPUs; measured there). The
// tiled layout (GPUs) keeps the width an argument: "" .
inline std::string stencil_width_define(int width, size_t tile) {
  return tile == 1 && width > 0 ? " -DSNH_STENCIL_WIDTH=" + std::to_string(width) : std::string();
}

}  // namespace snh::solver
