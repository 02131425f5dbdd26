// Whether a triangle surface passes through itself: the number of pairs of
// its triangles that intersect, decided exactly (no tolerance), so that
// "0" proves a deformed surface free of self-intersection.
//
// Two triangles intersect when their closed point sets share a point, except
// that triangles sharing vertices (the same vertex index) must share a point
// other than what they share: a shared vertex or a shared edge alone is
// adjacency, not intersection, but a triangle folded flat onto its neighbour
// across their edge (coplanar, on the same side) is an intersection.
// Touching counts (a corner resting exactly on another triangle); a gap of
// one ulp does not. Coplanar overlaps count. Vertices with different indices
// at the same position are different vertices: weld a surface first
// (weld_vertices in surface.h) when its seams repeat positions.
//
// Degenerate triangles (zero area exactly, or a vertex index repeated) have
// no orientation and are left out of the pairs; they are counted apart, and
// a surface with any is not clean.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "snh/surface.h"

namespace snh {

struct SelfIntersections {
  size_t triangles = 0;
  size_t intersecting_pairs = 0;    // pairs of triangles that intersect
  size_t degenerate_triangles = 0;  // left out of the pairs
  // The first intersecting pairs (i < j, in increasing order of i, then j),
  // at most SelfIntersectionOptions::max_pairs of them.
  std::vector<std::array<int32_t, 2>> first_pairs;
  std::vector<int32_t> first_degenerate;  // the first degenerate triangles, as many as first_pairs may hold
  bool clean() const { return intersecting_pairs == 0 && degenerate_triangles == 0; }
};

struct SelfIntersectionOptions {
  size_t max_pairs = 10;
  std::string name = "surface";  // starts every error message (the file)
};

// positions: one per vertex; triangles: three vertex indices each. Throws
// snh::Error naming `options.name` for arrays of the wrong length, indices
// out of range and non-finite positions. Deterministic, and the count does
// not depend on the order of the triangles or of their corners.
SelfIntersections count_self_intersections(const Points& positions, const std::vector<int32_t>& triangles,
                                           const SelfIntersectionOptions& options = {});
SelfIntersections count_self_intersections(const TriangleSurface& surface, const SelfIntersectionOptions& options = {});

}  // namespace snh
