// Vertex -> (element * nodes + node) slots of an element array, in CSR form
// and increasing slot order, so that every per-vertex gather sums in the same
// order on every run (deterministic, no atomics).
#pragma once

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

}  // namespace snh::fem
