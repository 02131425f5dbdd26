#include "solver/model/block_stencil.h"

#include <algorithm>
#include <limits>

#include "snh/error.h"

namespace snh::solver {

StencilTables stencil_tables(const std::vector<int>& elements, size_t vertex_count, int nodes,
                             const fem::VertexSlots& slots) {
  const int dofs = 3 * nodes, matrix = dofs * dofs;
  if (elements.size() / nodes > static_cast<size_t>(std::numeric_limits<int>::max() / matrix))
    throw Error("block stencil: too many elements for int offsets into their matrices");
  const fem::VertexNeighbours around = fem::vertex_neighbours(elements, vertex_count, nodes);
  if (vertex_count * static_cast<size_t>(around.width) >= static_cast<size_t>(std::numeric_limits<int>::max()))
    throw Error("block stencil: too many blocks for int indices");
  StencilTables t;
  t.width = around.width;
  const size_t count = vertex_count, width = static_cast<size_t>(around.width);
  t.neighbours = around.table;
  // Each (v, a, b) of an element once: its block index, where it goes.
  auto for_each_part = [&](auto&& visit) {
    for (size_t v = 0; v < count; ++v) {
      const int* row = around.table.data() + v * width;
      const int size = around.sizes[v];
      for (int k = slots.offsets[v]; k < slots.offsets[v + 1]; ++k) {
        const int slot = slots.adjacency[k], e = slot / nodes, a = slot % nodes;
        for (int b = 0; b < nodes; ++b) {
          const int n = elements[static_cast<size_t>(nodes) * e + b];
          const size_t s =
              n == static_cast<int>(v) ? 0 : static_cast<size_t>(std::lower_bound(row + 1, row + size, n) - row);
          visit(v * width + s, matrix * e + dofs * 3 * a + 3 * b);
        }
      }
    }
  };
  t.part_offsets.assign(width * count + 1, 0);
  for_each_part([&](size_t item, int) { ++t.part_offsets[item + 1]; });
  for (size_t i = 0; i < width * count; ++i) t.part_offsets[i + 1] += t.part_offsets[i];
  t.parts.resize(static_cast<size_t>(t.part_offsets.back()));
  std::vector<int> fill(t.part_offsets.begin(), t.part_offsets.end() - 1);
  for_each_part([&](size_t item, int part) { t.parts[static_cast<size_t>(fill[item]++)] = part; });
  return t;
}

StencilTables upper_stencil_tables(const StencilTables& full, size_t vertex_count) {
  if (full.lower > 0) throw Error("block stencil: the tables are in the upper layout already");
  const size_t width = static_cast<size_t>(full.width);
  // Per vertex, the full layout's slots it keeps (itself, then n > v in
  // increasing order) and its neighbours before it.
  std::vector<std::vector<int>> kept(vertex_count), before(vertex_count);
  size_t upper = 1, lower = 0;
  for (size_t v = 0; v < vertex_count; ++v) {
    const int self = static_cast<int>(v);
    for (size_t s = 0; s < width; ++s) {
      const int n = full.neighbours[width * v + s];
      if (s == 0 || n > self)
        kept[v].push_back(static_cast<int>(s));
      else if (n < self)
        before[v].push_back(n);  // (n == v past slot 0: padding)
    }
    upper = std::max(upper, kept[v].size());
    lower = std::max(lower, before[v].size());
  }
  if (vertex_count * upper >= static_cast<size_t>(std::numeric_limits<int>::max()))
    throw Error("block stencil: too many blocks for int indices");
  StencilTables t;
  t.width = static_cast<int>(upper);
  t.lower = static_cast<int>(lower);
  const size_t row = upper + 2 * lower;
  const int zero_block = static_cast<int>(vertex_count * upper);
  t.neighbours.assign(vertex_count * row, 0);
  t.part_offsets.assign(vertex_count * upper + 1, 0);
  for (size_t v = 0; v < vertex_count; ++v) {
    int* out = t.neighbours.data() + v * row;
    for (size_t u = 0; u < upper; ++u) {
      if (u < kept[v].size()) {
        const size_t item = width * v + static_cast<size_t>(kept[v][u]);
        out[u] = full.neighbours[item];
        t.parts.insert(t.parts.end(), full.parts.begin() + full.part_offsets[item],
                       full.parts.begin() + full.part_offsets[item + 1]);
      } else {
        out[u] = static_cast<int>(v);
      }
      t.part_offsets[v * upper + u + 1] = static_cast<int>(t.parts.size());
    }
    for (size_t s = 0; s < lower; ++s) {
      if (s >= before[v].size()) {
        out[upper + s] = static_cast<int>(v);
        out[upper + lower + s] = zero_block;
        continue;
      }
      // Block (n, v) in n's row: v is among n's kept neighbours (n < v).
      const int n = before[v][s];
      const int* n_row = full.neighbours.data() + width * static_cast<size_t>(n);
      size_t u = 0;
      while (u < kept[n].size() && n_row[kept[n][u]] != static_cast<int>(v)) ++u;
      if (u == kept[n].size()) throw Error("block stencil: an asymmetric neighbour table");
      out[upper + s] = n;
      out[upper + lower + s] = static_cast<int>(static_cast<size_t>(n) * upper + u);
    }
  }
  return t;
}

StencilTables device_stencil_tables(const std::vector<int>& elements, size_t vertex_count, int nodes,
                                    const fem::VertexSlots& slots, size_t tile) {
  StencilTables full = stencil_tables(elements, vertex_count, nodes, slots);
  return tile == 1 ? upper_stencil_tables(full, vertex_count) : full;
}

std::vector<int> tiled_neighbours(const StencilTables& t, size_t vertex_count, size_t tile) {
  if (t.lower > 0 && tile > 1) throw Error("block stencil: the upper layout is per vertex (tile 1)");
  if (tile <= 1) return t.neighbours;
  const size_t width = static_cast<size_t>(t.width);
  std::vector<int> out(stencil_entries(t.width, vertex_count, tile) / 9, 0);
  for (size_t v = 0; v < vertex_count; ++v)
    for (size_t s = 0; s < width; ++s)
      out[width * tile * (v / tile) + tile * s + v % tile] = t.neighbours[width * v + s];
  return out;
}

}  // namespace snh::solver
