// Disjoint sets over 0..n-1 with path halving. The smaller index represents
// each set, so the sets' representatives do not depend on the order of the
// unions: deterministic numbering for the voxelizer's glued cells and the
// multigrid hierarchy's coarse vertices.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace snh::fem {

struct UnionFind {
  std::vector<int32_t> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int32_t find(int32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(int32_t x, int32_t y) {
    x = find(x);
    y = find(y);
    if (x != y) parent[std::max(x, y)] = std::min(x, y);
  }
};

}  // namespace snh::fem
