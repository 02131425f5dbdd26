// Vertex -> (element * nodes + node) slots of an element array, in CSR form
// and increasing slot order, so that every per-vertex gather sums in the same
// order on every run (deterministic, no atomics).
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace snh::fem {

struct VertexSlots {
  std::vector<int> offsets;    // vertex_count + 1
  std::vector<int> adjacency;  // slots of vertex v between offsets[v] and offsets[v + 1]
};

template <typename Index>
VertexSlots vertex_slots(const std::vector<Index>& elements, size_t vertex_count) {
  VertexSlots s;
  s.offsets.assign(vertex_count + 1, 0);
  s.adjacency.resize(elements.size());
  for (Index v : elements) ++s.offsets[v + 1];
  for (size_t v = 0; v < vertex_count; ++v) s.offsets[v + 1] += s.offsets[v];
  std::vector<int> fill(s.offsets.begin(), s.offsets.end() - 1);
  for (size_t slot = 0; slot < elements.size(); ++slot) s.adjacency[fill[elements[slot]]++] = static_cast<int>(slot);
  return s;
}

// Per vertex, the vertices that share an element with it, `width` each (the
// most any vertex has): the vertex itself first, the others in increasing
// order, then the vertex again as padding (kernels/multigrid.cl's stencils).
struct VertexNeighbours {
  int width = 1;
  std::vector<int> table;  // vertex_count * width
  std::vector<int> sizes;  // per vertex: 1 + its neighbours (the rest is padding)
};

template <typename Index>
VertexNeighbours vertex_neighbours(const std::vector<Index>& elements, size_t vertex_count, int nodes_per_element) {
  std::vector<std::vector<int>> around(vertex_count);
  for (size_t e = 0; e + nodes_per_element <= elements.size(); e += nodes_per_element)
    for (int a = 0; a < nodes_per_element; ++a)
      for (int b = 0; b < nodes_per_element; ++b)
        if (elements[e + a] != elements[e + b]) around[elements[e + a]].push_back(static_cast<int>(elements[e + b]));
  VertexNeighbours n;
  for (auto& list : around) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    n.width = std::max(n.width, static_cast<int>(list.size()) + 1);
  }
  n.table.resize(vertex_count * n.width);
  n.sizes.resize(vertex_count);
  for (size_t v = 0; v < vertex_count; ++v) {
    n.sizes[v] = static_cast<int>(around[v].size()) + 1;
    int* row = n.table.data() + v * n.width;
    std::fill(row, row + n.width, static_cast<int>(v));
    std::copy(around[v].begin(), around[v].end(), row + 1);
  }
  return n;
}

}  // namespace snh::fem
