#include "geometry/triangle_intersection.h"

#include <algorithm>

#include "geometry/exact_predicates.h"

namespace snh::geometry {
namespace {

// A coordinate plane (the axis dropped) onto which coplanar points project
// one to one: then every 2D orientation and incidence there is the one in
// their plane.
int projected_orient(const double* a, const double* b, const double* c, int drop) {
  const int i = drop == 0 ? 1 : 0, j = drop == 2 ? 1 : 2;
  const double pa[2] = {a[i], a[j]}, pb[2] = {b[i], b[j]}, pc[2] = {c[i], c[j]};
  return orient2d(pa, pb, pc);
}

// The axis whose dropping keeps triangle abc non-degenerate; -1 when abc is
// collinear: its cross product's components are these three orientations.
int projection_axis(const double* a, const double* b, const double* c) {
  for (int drop : {2, 0, 1})
    if (projected_orient(a, b, c, drop) != 0) return drop;
  return -1;
}

// p, collinear with a and b, lies on the closed segment ab (exact comparisons).
bool between(const double* p, const double* a, const double* b, int drop) {
  for (int k = 0; k < 3; ++k) {
    if (k == drop) continue;
    if (p[k] < std::min(a[k], b[k]) || p[k] > std::max(a[k], b[k])) return false;
  }
  return true;
}

bool segments_meet_2d(const double* p, const double* q, const double* r, const double* s, int drop) {
  const int d1 = projected_orient(p, q, r, drop), d2 = projected_orient(p, q, s, drop);
  const int d3 = projected_orient(r, s, p, drop), d4 = projected_orient(r, s, q, drop);
  if (d1 * d2 < 0 && d3 * d4 < 0) return true;
  return (d1 == 0 && between(r, p, q, drop)) || (d2 == 0 && between(s, p, q, drop)) ||
         (d3 == 0 && between(p, r, s, drop)) || (d4 == 0 && between(q, r, s, drop));
}

bool point_in_triangle_2d(const double* p, const double* a, const double* b, const double* c, int drop) {
  const int s1 = projected_orient(a, b, p, drop), s2 = projected_orient(b, c, p, drop),
            s3 = projected_orient(c, a, p, drop);
  return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

// Closed triangles in one plane, abc non-degenerate in the projection `drop`.
bool coplanar_triangles_meet(const double* const s[3], const double* const t[3], int drop) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (segments_meet_2d(s[i], s[(i + 1) % 3], t[j], t[(j + 1) % 3], drop)) return true;
  return point_in_triangle_2d(s[0], t[0], t[1], t[2], drop) || point_in_triangle_2d(t[0], s[0], s[1], s[2], drop);
}

// Closed triangles without shared vertices. Not coplanar, their common
// points lie on the line where their planes meet, where each triangle is a
// segment whose ends lie on its edges; the two segments overlap exactly
// when an end of one lies in the other: an edge of one meets the other.
bool disjoint_triangles_meet(const IndexedTriangle& s, const IndexedTriangle& t) {
  const double* const* a = s.corner;
  const double* const* b = t.corner;
  int side[3];
  for (int i = 0; i < 3; ++i) side[i] = orient3d(a[0], a[1], a[2], b[i]);
  if ((side[0] > 0 && side[1] > 0 && side[2] > 0) || (side[0] < 0 && side[1] < 0 && side[2] < 0)) return false;
  if (side[0] == 0 && side[1] == 0 && side[2] == 0)
    return coplanar_triangles_meet(a, b, projection_axis(a[0], a[1], a[2]));
  for (int i = 0; i < 3; ++i) side[i] = orient3d(b[0], b[1], b[2], a[i]);
  if ((side[0] > 0 && side[1] > 0 && side[2] > 0) || (side[0] < 0 && side[1] < 0 && side[2] < 0)) return false;
  for (int i = 0; i < 3; ++i) {
    if (segment_meets_triangle(a[i], a[(i + 1) % 3], b[0], b[1], b[2])) return true;
    if (segment_meets_triangle(b[i], b[(i + 1) % 3], a[0], a[1], a[2])) return true;
  }
  return false;
}

}  // namespace

bool triangle_degenerate(const IndexedTriangle& t) {
  if (t.vertex[0] == t.vertex[1] || t.vertex[1] == t.vertex[2] || t.vertex[0] == t.vertex[2]) return true;
  return projection_axis(t.corner[0], t.corner[1], t.corner[2]) < 0;
}

bool segment_meets_triangle(const double* p, const double* q, const double* a, const double* b, const double* c) {
  const int op = orient3d(a, b, c, p), oq = orient3d(a, b, c, q);
  if ((op > 0 && oq > 0) || (op < 0 && oq < 0)) return false;
  if (op == 0 && oq == 0) {
    const int drop = projection_axis(a, b, c);
    return point_in_triangle_2d(p, a, b, c, drop) || segments_meet_2d(p, q, a, b, drop) ||
           segments_meet_2d(p, q, b, c, drop) || segments_meet_2d(p, q, c, a, drop);
  }
  // The line pq crosses the plane once, at a point of the segment; it lies
  // in the closed triangle when pq passes no edge on the wrong side.
  const int s1 = orient3d(p, q, a, b), s2 = orient3d(p, q, b, c), s3 = orient3d(p, q, c, a);
  return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

bool triangles_intersect(const IndexedTriangle& s, const IndexedTriangle& t) {
  int shared_s[3], shared_t[3], shared = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (s.vertex[i] == t.vertex[j]) {
        shared_s[shared] = i;
        shared_t[shared] = j;
        ++shared;
      }
  if (shared == 0) return disjoint_triangles_meet(s, t);
  if (shared == 3) return true;
  if (shared == 2) {
    // Folded onto each other: coplanar, third corners on one side of the edge.
    const double* u = s.corner[shared_s[0]];
    const double* w = s.corner[shared_s[1]];
    const double* a = s.corner[3 - shared_s[0] - shared_s[1]];
    const double* b = t.corner[3 - shared_t[0] - shared_t[1]];
    if (orient3d(u, w, a, b) != 0) return false;
    const int drop = projection_axis(u, w, a);
    return projected_orient(u, w, a, drop) == projected_orient(u, w, b, drop);
  }
  // One shared vertex v: the common part is convex and holds v; if it holds
  // another point, the ray from v through it leaves the common part where it
  // leaves one triangle, through that triangle's edge opposite v.
  const int i = shared_s[0], j = shared_t[0];
  const double* s1 = s.corner[(i + 1) % 3];
  const double* s2 = s.corner[(i + 2) % 3];
  const double* t1 = t.corner[(j + 1) % 3];
  const double* t2 = t.corner[(j + 2) % 3];
  // Every point but v of a triangle whose other corners lie strictly on one
  // side of the other's plane lies strictly on that side (the common case).
  const auto one_side = [](int a, int b) { return (a > 0 && b > 0) || (a < 0 && b < 0); };
  const double* const* sc = s.corner;
  const double* const* tc = t.corner;
  if (one_side(orient3d(tc[0], tc[1], tc[2], s1), orient3d(tc[0], tc[1], tc[2], s2))) return false;
  if (one_side(orient3d(sc[0], sc[1], sc[2], t1), orient3d(sc[0], sc[1], sc[2], t2))) return false;
  return segment_meets_triangle(s1, s2, t.corner[0], t.corner[1], t.corner[2]) ||
         segment_meets_triangle(t1, t2, s.corner[0], s.corner[1], s.corner[2]);
}

}  // namespace snh::geometry
