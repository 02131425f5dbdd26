// The tables of a block stencil (kernels/fem/block_stencil.h): an operator
// stored as the 3x3 blocks of each vertex pair that shares an element,
// assembled on the device from element matrices (kernels/stencil.cl,
// snh_stencil_assemble). Used by the assembled product variant
// (solver/model/elastic_model.h) and the multigrid's assembled levels
// (solver/multigrid/multigrid.h). Internal to the library.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "device/kernel_config.h"
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
// assembled faster than block (a, b) read across the columns of every node
// b: docs/performance.md, "Block stencil layout"); between
// part_offsets[width v + s] and the next, in increasing element order
// (deterministic sums, exactly transposed blocks (v, n) and (n, v) from
// symmetric element matrices).
//
// The upper layout (upper_stencil_tables, lower > 0): per vertex v its
// blocks against itself and the neighbours after it (n > v), `width` of
// them (v first; padding: v, a zero block), and `lower` neighbours before it
// (n < v) whose block (v, n) is read as the transpose of the stored (n, v):
// neighbours[(width + 2 lower) v + width + s] is that neighbour and
// [... + lower + s] the index of block (n, v) among the stored blocks
// (padding: v and the zero block after the last vertex's, `width` count
// + 1 blocks stored; no assembly writes it, and device buffers are made
// zero-filled, device::OpenClContext::buffer). Half the full layout's
// blocks; the kernels add the same terms in the same order as from the full
// layout (v, the neighbours before it, those after it), so the products
// are the same bit for bit.
struct StencilTables {
  int width = 1;
  int lower = 0;  // 0: the full layout
  std::vector<int> neighbours, part_offsets, parts;
};

// slots: fem::vertex_slots(elements, vertex_count). snh::Error when the
// offsets would not fit an int.
StencilTables stencil_tables(const std::vector<int>& elements, size_t vertex_count, int nodes,
                             const fem::VertexSlots& slots);

// The same operator in the upper layout (above), for per-vertex blocks (tile
// 1, CPUs: the assembled variant and the multigrid's levels): its parts
// list those of the full layout's blocks it keeps. On pocl its stencil passes
// and assemblies measured faster than the full layout's (docs/performance.md,
// "Block stencil layout").
StencilTables upper_stencil_tables(const StencilTables& full, size_t vertex_count);

// The tables in the layout for blocks in tiles of `tile` vertices: the
// upper layout per vertex (tile 1, CPUs), else the full one.
StencilTables device_stencil_tables(const std::vector<int>& elements, size_t vertex_count, int nodes,
                                    const fem::VertexSlots& slots, size_t tile);

// The device's layout of the blocks and the neighbour table: per vertex as
// in the tables (tile 1, CPUs), or in tiles of `tile` vertices
// (SNH_STENCIL_TILE, GPUs: kernels/fem/block_stencil.h), the last tile
// whole. Block entries stored: 9 per block, `width` blocks per vertex (and
// the upper layout's zero block).
inline size_t stencil_entries(int width, size_t vertex_count, size_t tile, int lower = 0) {
  if (lower > 0) return 9 * (static_cast<size_t>(width) * vertex_count + 1);
  return 9 * static_cast<size_t>(width) * ((vertex_count + tile - 1) / tile * tile);
}
inline size_t stencil_entries(const StencilTables& t, size_t vertex_count, size_t tile) {
  return stencil_entries(t.width, vertex_count, tile, t.lower);
}
// The neighbour table in that layout (padding of the last tile: 0).
std::vector<int> tiled_neighbours(const StencilTables& t, size_t vertex_count, size_t tile);

// The build that makes a stencil's width a constant of the kernels
// that read it (SNH_STENCIL_WIDTH: their loop over a vertex's blocks
// unrolled), with the per-vertex blocks (tile 1, CPUs; measured faster there:
// docs/performance.md, "Block stencil rows"). The
// tiled layout (GPUs) keeps the width an argument: `config` unchanged.
inline device::KernelConfig stencil_build(const device::KernelConfig& config, int width, size_t tile, int lower = 0) {
  return tile == 1 && width > 0 ? config.with_stencil(width, lower) : config;
}

}  // namespace snh::solver
