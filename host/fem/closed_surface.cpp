// Checks that a triangle surface bounds a volume (closed, manifold at its
// edges, consistently oriented, facing outwards) and the measures the
// voxelizer reports: enclosed volume and area.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <vector>

#include "snh/error.h"
#include "snh/surface.h"

namespace snh {
namespace {

constexpr size_t kNamed = 5;  // edges named per kind in an error message

void check_arrays(const TriangleSurface& s, const std::string& name = "surface") {
  if (s.positions.xyz().size() % 3 != 0) {
    std::ostringstream m;
    m << name << ": the position array has " << s.positions.xyz().size()
      << " values, not a multiple of 3 (xyz per vertex)";
    throw Error(m.str());
  }
  if (s.triangles.size() % 3 != 0) {
    std::ostringstream m;
    m << name << ": the triangle array has " << s.triangles.size() << " indices, not a multiple of 3";
    throw Error(m.str());
  }
  if (s.triangle_count() == 0) throw Error(name + ": it has no triangles");
  const std::vector<double>& xyz = s.positions.xyz();
  for (size_t i = 0; i < xyz.size(); ++i)
    if (!std::isfinite(xyz[i])) {
      std::ostringstream m;
      m << name << ": vertex " << i / 3 << " has a non-finite coordinate ("
        << "xyz"[i % 3] << " = " << xyz[i] << ")";
      throw Error(m.str());
    }
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    const int32_t* v = s.triangles.data() + 3 * t;
    for (int a = 0; a < 3; ++a)
      if (v[a] < 0 || static_cast<size_t>(v[a]) >= s.vertex_count()) {
        std::ostringstream m;
        m << name << ": triangle " << t << " refers to vertex " << v[a] << ", but the surface has " << s.vertex_count()
          << " vertices";
        throw Error(m.str());
      }
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) {
      std::ostringstream m;
      m << name << ": triangle " << t << " repeats a vertex (" << v[0] << ", " << v[1] << ", " << v[2] << ")";
      throw Error(m.str());
    }
  }
}

std::string vertex_text(const TriangleSurface& s, int32_t v) {
  std::ostringstream m;
  m << v << " (" << s.positions(v, 0) << ", " << s.positions(v, 1) << ", " << s.positions(v, 2) << ")";
  return m.str();
}

struct HalfEdge {
  int32_t low, high;  // the edge's vertices, sorted
  int32_t triangle;
  bool forward;  // the triangle goes low -> high
};

}  // namespace

double enclosed_volume(const TriangleSurface& surface) {
  check_arrays(surface);
  double volume = 0.0;
  const double* p = surface.positions.data();
  for (size_t t = 0; t < surface.triangle_count(); ++t) {
    const double* a = p + 3 * surface.triangles[3 * t];
    const double* b = p + 3 * surface.triangles[3 * t + 1];
    const double* c = p + 3 * surface.triangles[3 * t + 2];
    volume +=
        a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return volume / 6.0;
}

double surface_area(const TriangleSurface& surface) {
  check_arrays(surface);
  double area = 0.0;
  const double* p = surface.positions.data();
  for (size_t t = 0; t < surface.triangle_count(); ++t) {
    const double* a = p + 3 * surface.triangles[3 * t];
    const double* b = p + 3 * surface.triangles[3 * t + 1];
    const double* c = p + 3 * surface.triangles[3 * t + 2];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    area += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }
  return area;
}

void validate_closed_surface(const TriangleSurface& surface, const std::string& name) {
  check_arrays(surface, name);
  std::vector<HalfEdge> edges;
  edges.reserve(surface.triangles.size());
  for (size_t t = 0; t < surface.triangle_count(); ++t)
    for (int a = 0; a < 3; ++a) {
      const int32_t u = surface.triangles[3 * t + a], v = surface.triangles[3 * t + (a + 1) % 3];
      edges.push_back({std::min(u, v), std::max(u, v), static_cast<int32_t>(t), u < v});
    }
  std::sort(edges.begin(), edges.end(), [](const HalfEdge& a, const HalfEdge& b) {
    return a.low != b.low ? a.low < b.low : a.high != b.high ? a.high < b.high : a.triangle < b.triangle;
  });

  size_t open = 0, non_manifold = 0, same_direction = 0;
  std::ostringstream open_text, non_manifold_text, same_text;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i + 1;
    while (j < edges.size() && edges[j].low == edges[i].low && edges[j].high == edges[i].high) ++j;
    const HalfEdge& e = edges[i];
    const std::string edge = vertex_text(surface, e.low) + " - " + vertex_text(surface, e.high);
    if (j - i == 1) {
      if (open++ < kNamed) open_text << "\n  " << edge << " of triangle " << e.triangle;
    } else if (j - i > 2) {
      if (non_manifold++ < kNamed) {
        non_manifold_text << "\n  " << edge << " shared by " << j - i << " triangles:";
        for (size_t k = i; k < j && k < i + 6; ++k) non_manifold_text << ' ' << edges[k].triangle;
      }
    } else if (edges[i].forward == edges[i + 1].forward) {
      if (same_direction++ < kNamed)
        same_text << "\n  " << edge << " of triangles " << e.triangle << " and " << edges[i + 1].triangle;
    }
    i = j;
  }
  if (open + non_manifold + same_direction > 0) {
    std::ostringstream m;
    m << name
      << ": it is not closed and consistently oriented (every edge must be shared by exactly two triangles "
         "that traverse it in opposite directions); "
      << surface.triangle_count() << " triangles, " << surface.vertex_count() << " vertices";
    const auto kind = [&](size_t count, const char* what, const std::ostringstream& named) {
      if (count == 0) return;
      m << "\n"
        << count << " " << what << (count > kNamed ? " (the first " + std::to_string(kNamed) + ")" : "") << ":"
        << named.str();
    };
    kind(open, "open edges, used by one triangle (a hole)", open_text);
    kind(non_manifold, "non-manifold edges, used by more than two triangles", non_manifold_text);
    kind(same_direction,
         "edges traversed in the same direction by both their triangles (inconsistent orientation: a flipped "
         "triangle)",
         same_text);
    throw Error(m.str());
  }
  const double volume = enclosed_volume(surface);
  if (!(volume > 0.0)) {
    std::ostringstream m;
    m << name << ": its enclosed volume is " << volume
      << " (not positive): its triangles face inwards (reverse their vertex order) or it encloses nothing";
    throw Error(m.str());
  }
}

}  // namespace snh
