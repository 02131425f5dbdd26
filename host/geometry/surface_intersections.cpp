// The exact pair test (triangle_intersection.h) behind a uniform-grid broad
// phase: each triangle's bounding box is binned into the cells it overlaps;
// two triangles are tested in the one cell where their cell ranges first
// overlap, so that every candidate pair is tested once, in an order fixed
// by the triangle indices alone.
#include "snh/surface_intersections.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "geometry/triangle_intersection.h"
#include "snh/error.h"

namespace snh {
namespace {

using geometry::IndexedTriangle;

struct Box {
  double lo[3], hi[3];
};

bool boxes_overlap(const Box& a, const Box& b) {
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  return true;
}

// A triangle spanning more cells than this is tested against every other
// triangle instead of being binned (a few large triangles among small ones).
constexpr int64_t max_cells_per_triangle = 64;
constexpr int64_t max_cells_per_axis = int64_t(1) << 21;

}  // namespace

SelfIntersections count_self_intersections(const Points& points, const std::vector<int32_t>& triangles,
                                           const SelfIntersectionOptions& options) {
  const std::string& name = options.name;
  const std::vector<double>& positions = points.xyz();
  if (positions.size() % 3 != 0)
    throw Error(name + ": " + std::to_string(positions.size()) + " position values are not xyz triples");
  if (triangles.size() % 3 != 0)
    throw Error(name + ": " + std::to_string(triangles.size()) + " triangle indices are not triples");
  const size_t vertex_count = positions.size() / 3;
  for (size_t v = 0; v < positions.size(); ++v)
    if (!std::isfinite(positions[v])) {
      std::ostringstream m;
      m << name << ": vertex " << v / 3 << " has a non-finite coordinate (" << positions[v] << ")";
      throw Error(m.str());
    }
  for (size_t i = 0; i < triangles.size(); ++i)
    if (triangles[i] < 0 || size_t(triangles[i]) >= vertex_count)
      throw Error(name + ": triangle " + std::to_string(i / 3) + " names vertex " + std::to_string(triangles[i]) +
                  " of " + std::to_string(vertex_count));

  const size_t count = triangles.size() / 3;
  SelfIntersections result;
  result.triangles = count;
  const auto triangle = [&](size_t t) {
    IndexedTriangle tri;
    for (int c = 0; c < 3; ++c) {
      tri.vertex[c] = triangles[3 * t + c];
      tri.corner[c] = &positions[3 * size_t(tri.vertex[c])];
    }
    return tri;
  };

  std::vector<Box> box(count);
  std::vector<char> live(count, 0);
  std::vector<size_t> kept;
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  double extent_sum = 0.0;
  for (size_t t = 0; t < count; ++t) {
    const IndexedTriangle tri = triangle(t);
    if (geometry::triangle_degenerate(tri)) {
      if (result.first_degenerate.size() < options.max_pairs) result.first_degenerate.push_back(int32_t(t));
      ++result.degenerate_triangles;
      continue;
    }
    live[t] = 1;
    kept.push_back(t);
    double extent = 0.0;
    for (int k = 0; k < 3; ++k) {
      box[t].lo[k] = std::min({tri.corner[0][k], tri.corner[1][k], tri.corner[2][k]});
      box[t].hi[k] = std::max({tri.corner[0][k], tri.corner[1][k], tri.corner[2][k]});
      lo[k] = std::min(lo[k], box[t].lo[k]);
      hi[k] = std::max(hi[k], box[t].hi[k]);
      extent = std::max(extent, box[t].hi[k] - box[t].lo[k]);
    }
    extent_sum += extent;
  }
  if (kept.size() < 2) return result;

  // Cells about as large as a triangle. The cell of a coordinate is a
  // monotone function of it, so boxes that overlap share a cell.
  // A non-degenerate triangle has a positive extent, so the cell is too.
  const double cell = extent_sum / double(kept.size());
  int64_t dims[3];
  for (int k = 0; k < 3; ++k) {
    const double n = std::floor((hi[k] - lo[k]) / cell) + 1.0;
    dims[k] = std::isfinite(n) ? std::clamp(int64_t(std::min(n, 1e18)), int64_t(1), max_cells_per_axis) : 1;
  }
  const auto cell_of = [&](double x, int k) {
    if (dims[k] == 1) return int64_t(0);
    const double c = std::floor((x - lo[k]) / cell);
    return std::clamp(int64_t(std::min(std::max(c, 0.0), 1e18)), int64_t(0), dims[k] - 1);
  };
  std::vector<std::array<int64_t, 6>> range(count);
  struct Entry {
    uint64_t key;
    int32_t triangle;
  };
  std::vector<Entry> entries;
  std::vector<size_t> large;
  for (size_t t : kept) {
    int64_t cells = 1;
    for (int k = 0; k < 3; ++k) {
      range[t][k] = cell_of(box[t].lo[k], k);
      range[t][3 + k] = cell_of(box[t].hi[k], k);
      cells *= range[t][3 + k] - range[t][k] + 1;
    }
    if (cells > max_cells_per_triangle) {
      large.push_back(t);
      live[t] = 2;
      continue;
    }
    for (int64_t x = range[t][0]; x <= range[t][3]; ++x)
      for (int64_t y = range[t][1]; y <= range[t][4]; ++y)
        for (int64_t z = range[t][2]; z <= range[t][5]; ++z)
          entries.push_back({(uint64_t(x) << 42) | (uint64_t(y) << 21) | uint64_t(z), int32_t(t)});
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return a.key != b.key ? a.key < b.key : a.triangle < b.triangle; });

  std::vector<std::array<int32_t, 2>> pairs;
  const auto test = [&](size_t a, size_t b) {
    if (!boxes_overlap(box[a], box[b])) return;
    if (geometry::triangles_intersect(triangle(a), triangle(b)))
      pairs.push_back({int32_t(std::min(a, b)), int32_t(std::max(a, b))});
  };
  for (size_t begin = 0; begin < entries.size();) {
    size_t end = begin;
    while (end < entries.size() && entries[end].key == entries[begin].key) ++end;
    const uint64_t key = entries[begin].key;
    const int64_t at[3] = {int64_t(key >> 42), int64_t((key >> 21) & (max_cells_per_axis - 1)),
                           int64_t(key & (max_cells_per_axis - 1))};
    for (size_t i = begin; i < end; ++i)
      for (size_t j = i + 1; j < end; ++j) {
        const size_t a = size_t(entries[i].triangle), b = size_t(entries[j].triangle);
        bool first = true;
        for (int k = 0; k < 3 && first; ++k) first = at[k] == std::max(range[a][k], range[b][k]);
        if (first) test(a, b);
      }
    begin = end;
  }
  for (size_t l : large)
    for (size_t t : kept)
      if (live[t] == 1 || (live[t] == 2 && t > l)) test(l, t);

  result.intersecting_pairs = pairs.size();
  const size_t shown = std::min(pairs.size(), options.max_pairs);
  std::partial_sort(pairs.begin(), pairs.begin() + shown, pairs.end());
  result.first_pairs.assign(pairs.begin(), pairs.begin() + shown);
  return result;
}

SelfIntersections count_self_intersections(const TriangleSurface& surface, const SelfIntersectionOptions& options) {
  return count_self_intersections(surface.positions, surface.triangles, options);
}

}  // namespace snh
