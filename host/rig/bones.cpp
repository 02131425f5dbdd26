// Bones as solids and the constraint sets of the lattice vertices inside
// them (snh/rig.h).
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "rig/winding_number.h"
#include "snh/error.h"
#include "snh/rig.h"

namespace snh {
namespace {

using Point = std::array<double, 3>;

// The squared distance from p to the capsule's axis segment.
double capsule_axis_distance2(const Capsule& c, const Point& p) {
  double ab[3], ap[3];
  for (int d = 0; d < 3; ++d) {
    ab[d] = c.b[d] - c.a[d];
    ap[d] = p[d] - c.a[d];
  }
  const double length2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
  const double along =
      length2 > 0.0 ? std::clamp((ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / length2, 0.0, 1.0) : 0.0;
  double distance2 = 0.0;
  for (int d = 0; d < 3; ++d) {
    const double off = ap[d] - along * ab[d];
    distance2 += off * off;
  }
  return distance2;
}

bool in_capsule(const Capsule& c, const Point& p) { return capsule_axis_distance2(c, p) <= c.radius * c.radius; }

// Axis-aligned bounds of a surface bone, to skip the winding number far away.
struct Bounds {
  Point lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  bool contains(const Point& p) const {
    return p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1] && p[2] >= lo[2] && p[2] <= hi[2];
  }
};

Bounds bounds_of(const TriangleSurface& s) {
  Bounds b;
  for (size_t v = 0; v < s.vertex_count(); ++v)
    for (int d = 0; d < 3; ++d) {
      b.lo[d] = std::min(b.lo[d], s.positions(v, d));
      b.hi[d] = std::max(b.hi[d], s.positions(v, d));
    }
  return b;
}

void check_bone(const Bone& bone, size_t index) {
  std::ostringstream s;
  s << "bone " << index << " ('" << bone.name << "'): ";
  if (bone.name.empty()) throw Error(s.str() + "has no name");
  if (const Capsule* c = std::get_if<Capsule>(&bone.shape)) {
    if (!(c->radius > 0.0) || !std::isfinite(c->radius))
      throw Error(s.str() + "the capsule's radius " + std::to_string(c->radius) + " is not > 0");
    for (int d = 0; d < 3; ++d)
      if (!std::isfinite(c->a[d]) || !std::isfinite(c->b[d]))
        throw Error(s.str() + "the capsule's ends are not finite");
  } else {
    const TriangleSurface& t = std::get<TriangleSurface>(bone.shape);
    if (t.triangle_count() == 0) throw Error(s.str() + "the surface has no triangles");
    for (int32_t i : t.triangles)
      if (i < 0 || static_cast<size_t>(i) >= t.vertex_count())
        throw Error(s.str() + "a triangle refers to vertex " + std::to_string(i) + ", but the surface has " +
                    std::to_string(t.vertex_count()));
  }
}

// The distance from p to triangle (a, b, c): the closest point by the
// triangle's Voronoi regions (Ericson, Real-Time Collision Detection, 5.1.5).
double triangle_distance(const Point& p, const double* a, const double* b, const double* c) {
  const auto sub = [](const double* x, const double* y) { return Point{x[0] - y[0], x[1] - y[1], x[2] - y[2]}; };
  const auto dot = [](const Point& x, const Point& y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
  const Point ab = sub(b, a), ac = sub(c, a), ap = sub(p.data(), a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  const auto at = [&](double v, double w) {  // a + v ab + w ac
    double s = 0.0;
    for (int d = 0; d < 3; ++d) {
      const double q = a[d] + v * ab[d] + w * ac[d] - p[d];
      s += q * q;
    }
    return std::sqrt(s);
  };
  if (d1 <= 0.0 && d2 <= 0.0) return at(0, 0);
  const Point bp = sub(p.data(), b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return at(1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return at(d1 / (d1 - d3), 0);
  const Point cp = sub(p.data(), c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return at(0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return at(0, d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return at(1 - w, w);
  }
  const double denom = va + vb + vc;
  if (!(denom > 0.0)) return std::min({at(0, 0), at(1, 0), at(0, 1)});  // a degenerate triangle
  return at(vb / denom, vc / denom);
}

double capsule_axis_distance(const Capsule& c, const Point& p) { return std::sqrt(capsule_axis_distance2(c, p)); }

}  // namespace

double bone_distance(const Bone& bone, const std::array<double, 3>& p) {
  if (const Capsule* c = std::get_if<Capsule>(&bone.shape))
    return std::max(0.0, capsule_axis_distance(*c, p) - c->radius);
  const TriangleSurface& s = std::get<TriangleSurface>(bone.shape);
  if (bone_contains(bone, p)) return 0.0;
  double best = HUGE_VAL;
  const double* x = s.positions.data();
  for (size_t t = 0; t < s.triangle_count(); ++t)
    best = std::min(best, triangle_distance(p, x + 3 * s.triangles[3 * t], x + 3 * s.triangles[3 * t + 1],
                                            x + 3 * s.triangles[3 * t + 2]));
  return best;
}

bool bone_contains(const Bone& bone, const std::array<double, 3>& p) {
  if (const Capsule* c = std::get_if<Capsule>(&bone.shape)) return in_capsule(*c, p);
  const TriangleSurface& surface = std::get<TriangleSurface>(bone.shape);
  return bounds_of(surface).contains(p) && rig::winding_number(surface, p) >= 0.5;
}

std::vector<ConstraintSet> bone_constraints(const Mesh& lattice, const std::vector<Bone>& bones) {
  std::set<std::string> names;
  for (size_t b = 0; b < bones.size(); ++b) {
    check_bone(bones[b], b);
    if (!names.insert(bones[b].name).second) throw Error("bone '" + bones[b].name + "' is named twice");
  }
  // owner[v]: the first bone holding vertex v; -1 none.
  std::vector<int> owner(lattice.vertex_count(), -1);
  std::vector<int> taken_by(bones.size(), -1);  // a bone whose vertices an earlier bone took (for the error)
  std::vector<ConstraintSet> sets(bones.size());
  for (size_t b = 0; b < bones.size(); ++b) {
    sets[b].name = bones[b].name;
    const Bone& bone = bones[b];
    Bounds box;
    const bool surface = std::holds_alternative<TriangleSurface>(bone.shape);
    if (surface) box = bounds_of(std::get<TriangleSurface>(bone.shape));
    for (size_t v = 0; v < lattice.vertex_count(); ++v) {
      const Point p = lattice.vertex(v);
      const bool inside = surface
                              ? box.contains(p) && rig::winding_number(std::get<TriangleSurface>(bone.shape), p) >= 0.5
                              : in_capsule(std::get<Capsule>(bone.shape), p);
      if (!inside) continue;
      if (owner[v] >= 0) {
        taken_by[b] = owner[v];
        continue;
      }
      owner[v] = static_cast<int>(b);
      sets[b].vertices.push_back(static_cast<int32_t>(v));
    }
    if (sets[b].vertices.empty()) {
      std::string what = "bone '" + bone.name + "' holds no lattice vertex";
      what += taken_by[b] >= 0 ? " (those inside it went to bone '" + bones[taken_by[b]].name + "', listed before it)"
                               : " (is it inside the lattice, and thicker than a cell?)";
      throw Error(what);
    }
  }
  return sets;
}

}  // namespace snh
