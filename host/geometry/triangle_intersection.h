// Whether two closed triangles of a surface meet, decided exactly (every
// branch is a sign of exact_predicates.h). Triangles that share vertices
// (the same vertex index, not merely the same position) meet only where
// they meet away from what they share:
//   - no shared vertex: the closed triangles have a common point (touching
//     at a point or along a segment counts, coplanar overlap counts);
//   - one shared vertex v: they have a common point other than v;
//   - a shared edge: they are coplanar with their third corners on the same
//     side of the edge (folded onto each other); two triangles that share an
//     edge and are not coplanar meet only along it;
//   - three shared vertices: the same triangle twice, which always meets.
// Both triangles must be non-degenerate (triangle_degenerate false).
#pragma once

#include <cstdint>

namespace snh::geometry {

struct IndexedTriangle {
  const double* corner[3];  // xyz of each corner
  int32_t vertex[3];        // the corners' vertex indices
};

// The corners are collinear (zero area, exactly) or two indices repeat.
bool triangle_degenerate(const IndexedTriangle& t);

bool triangles_intersect(const IndexedTriangle& s, const IndexedTriangle& t);

// The closed segment pq and the closed, non-degenerate triangle abc share a point.
bool segment_meets_triangle(const double* p, const double* q, const double* a, const double* b, const double* c);

}  // namespace snh::geometry
