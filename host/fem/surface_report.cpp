// Welding coincident vertices and counting what keeps a triangle surface
// from being closed and consistently oriented (surface.h): the checks an
// artist's surface gets before it is voxelized by winding numbers.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "fem/union_find.h"
#include "snh/error.h"
#include "snh/surface.h"

namespace snh {
namespace {

void check_input(const TriangleSurface& s, const std::string& name) {
  if (s.positions.xyz().size() % 3 != 0 || s.triangles.size() % 3 != 0) {
    std::ostringstream m;
    m << name << ": the surface arrays hold " << s.positions.xyz().size() << " coordinates and " << s.triangles.size()
      << " indices (multiples of 3 expected)";
    throw Error(m.str());
  }
  const std::vector<double>& xyz = s.positions.xyz();
  for (size_t i = 0; i < xyz.size(); ++i)
    if (!std::isfinite(xyz[i])) {
      std::ostringstream m;
      m << name << ": vertex " << i / 3 << " has a non-finite coordinate ("
        << "xyz"[i % 3] << " = " << xyz[i] << ")";
      throw Error(m.str());
    }
  for (size_t i = 0; i < s.triangles.size(); ++i)
    if (s.triangles[i] < 0 || static_cast<size_t>(s.triangles[i]) >= s.vertex_count()) {
      std::ostringstream m;
      m << name << ": triangle " << i / 3 << " refers to vertex " << s.triangles[i] << ", but the surface has "
        << s.vertex_count() << " vertices";
      throw Error(m.str());
    }
}

struct Cell {
  int64_t i, j, k;
  bool operator==(const Cell& o) const { return i == o.i && j == o.j && k == o.k; }
};
struct CellHash {
  size_t operator()(const Cell& c) const {
    // Unsigned: the products wrap instead of overflowing.
    return static_cast<size_t>(uint64_t(c.i) * 73856093u ^ uint64_t(c.j) * 19349663u ^ uint64_t(c.k) * 83492791u);
  }
};

}  // namespace

WeldedSurface weld_vertices(const TriangleSurface& surface, double tolerance) {
  check_input(surface, "surface");
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance)) {
    std::ostringstream m;
    m << "weld_vertices: the tolerance must be finite and >= 0, got " << tolerance;
    throw Error(m.str());
  }
  const size_t n = surface.vertex_count();
  const double* p = surface.positions.data();
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0};
  for (size_t v = 0; v < n; ++v)
    for (int d = 0; d < 3; ++d) {
      lo[d] = v == 0 ? p[d] : std::min(lo[d], p[3 * v + d]);
      hi[d] = v == 0 ? p[d] : std::max(hi[d], p[3 * v + d]);
    }
  // The diagonal scaled against overflow (coordinates up to 1e308).
  const double scale = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 0.0});
  double diagonal = 0.0;
  if (scale > 0.0 && std::isfinite(scale)) {
    double sum = 0.0;
    for (int d = 0; d < 3; ++d) sum += ((hi[d] - lo[d]) / scale) * ((hi[d] - lo[d]) / scale);
    diagonal = scale * std::sqrt(sum);
  }
  double radius = tolerance * diagonal;
  // Hash cells of the radius need (extent / radius) to fit an int64 with room:
  // otherwise (radius 0, or below 1e-12 of the box) only equal positions merge.
  if (!(radius > 0.0) || !std::isfinite(diagonal) || !(diagonal / radius < 1e12)) radius = 0.0;

  WeldedSurface out;
  out.vertex_of.assign(n, -1);
  std::vector<int32_t> kept;  // original index of each kept vertex
  if (radius == 0.0) {
    std::map<std::array<double, 3>, int32_t> seen;
    for (size_t v = 0; v < n; ++v) {
      const std::array<double, 3> x{p[3 * v], p[3 * v + 1], p[3 * v + 2]};
      const auto it = seen.emplace(x, static_cast<int32_t>(kept.size()));
      if (it.second) kept.push_back(static_cast<int32_t>(v));
      out.vertex_of[v] = it.first->second;
    }
  } else {
    std::unordered_map<Cell, std::vector<int32_t>, CellHash> buckets;  // kept vertices per cell of side radius
    const auto cell_of = [&](size_t v) {
      return Cell{static_cast<int64_t>(std::floor((p[3 * v] - lo[0]) / radius)),
                  static_cast<int64_t>(std::floor((p[3 * v + 1] - lo[1]) / radius)),
                  static_cast<int64_t>(std::floor((p[3 * v + 2] - lo[2]) / radius))};
    };
    for (size_t v = 0; v < n; ++v) {
      const Cell c = cell_of(v);
      int32_t best = -1;
      double best_distance = 0.0;
      for (int64_t dk = -1; dk <= 1; ++dk)
        for (int64_t dj = -1; dj <= 1; ++dj)
          for (int64_t di = -1; di <= 1; ++di) {
            const auto it = buckets.find({c.i + di, c.j + dj, c.k + dk});
            if (it == buckets.end()) continue;
            for (int32_t w : it->second) {
              const double* a = p + 3 * kept[w];
              const double dx = a[0] - p[3 * v], dy = a[1] - p[3 * v + 1], dz = a[2] - p[3 * v + 2];
              const double distance = std::sqrt(dx * dx + dy * dy + dz * dz);
              // The nearest kept vertex, the lowest index on ties: independent of the bucket order.
              if (distance <= radius &&
                  (best < 0 || distance < best_distance || (distance == best_distance && w < best))) {
                best = w;
                best_distance = distance;
              }
            }
          }
      if (best < 0) {
        best = static_cast<int32_t>(kept.size());
        kept.push_back(static_cast<int32_t>(v));
        buckets[c].push_back(best);
      }
      out.vertex_of[v] = best;
    }
  }
  out.surface.positions.reserve(kept.size());
  for (int32_t v : kept) out.surface.positions.push_back({p[3 * v], p[3 * v + 1], p[3 * v + 2]});
  out.surface.triangles.resize(surface.triangles.size());
  for (size_t i = 0; i < surface.triangles.size(); ++i) out.surface.triangles[i] = out.vertex_of[surface.triangles[i]];
  return out;
}

SurfaceReport surface_report(const TriangleSurface& surface, const std::string& name, double weld_tolerance) {
  check_input(surface, name);
  const WeldedSurface welded = weld_vertices(surface, weld_tolerance);
  const TriangleSurface& s = welded.surface;
  SurfaceReport r;
  r.vertices = surface.vertex_count();
  r.triangles = surface.triangle_count();
  r.welded_vertices = welded.merged();

  struct HalfEdge {
    int32_t low, high;
    bool forward;
  };
  std::vector<HalfEdge> edges;
  edges.reserve(s.triangles.size());
  fem::UnionFind pieces(s.vertex_count());
  std::vector<char> used(s.vertex_count(), 0);
  double volume = 0.0;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    const int32_t* v = s.triangles.data() + 3 * t;
    for (int a = 0; a < 3; ++a) used[v[a]] = 1;
    pieces.unite(v[0], v[1]);
    pieces.unite(v[1], v[2]);
    const double* a = s.positions.data() + 3 * v[0];
    const double* b = s.positions.data() + 3 * v[1];
    const double* c = s.positions.data() + 3 * v[2];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0] || (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0))
      ++r.degenerate_triangles;
    // A triangle with two corners welded together has no edges of its own
    // (its third edge lies along an edge of its neighbours).
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
    volume +=
        a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    for (int k = 0; k < 3; ++k) {
      const int32_t x = v[k], y = v[(k + 1) % 3];
      edges.push_back({std::min(x, y), std::max(x, y), x < y});
    }
  }
  r.enclosed_volume = volume / 6.0;
  std::sort(edges.begin(), edges.end(), [](const HalfEdge& a, const HalfEdge& b) {
    return a.low != b.low ? a.low < b.low : a.high != b.high ? a.high < b.high : a.forward < b.forward;
  });
  for (size_t i = 0; i < edges.size();) {
    size_t j = i + 1;
    while (j < edges.size() && edges[j].low == edges[i].low && edges[j].high == edges[i].high) ++j;
    if (j - i == 1)
      ++r.open_edges;
    else if (j - i > 2)
      ++r.non_manifold_edges;
    else if (edges[i].forward == edges[i + 1].forward)
      ++r.inconsistent_edges;
    i = j;
  }
  for (size_t v = 0; v < s.vertex_count(); ++v)
    if (used[v] && pieces.find(static_cast<int32_t>(v)) == static_cast<int32_t>(v)) ++r.shells;

  const auto warn = [&](size_t count, const std::string& what) {
    if (count == 0) return;
    std::ostringstream m;
    m << name << ": " << count << " " << what;
    r.warnings.push_back(m.str());
  };
  warn(r.welded_vertices, "vertices welded to a coincident vertex (seams)");
  warn(r.open_edges, "open edges, used by one triangle (holes or cracks)");
  warn(r.non_manifold_edges, "non-manifold edges, used by more than two triangles");
  warn(r.inconsistent_edges, "edges traversed in the same direction by both their triangles (flipped triangles)");
  warn(r.degenerate_triangles, "degenerate triangles (zero area or two corners welded together)");
  if (r.shells > 1) warn(r.shells, "shells (separate pieces); overlapping ones are united");
  if (r.closed() && !(r.enclosed_volume > 0.0)) {
    std::ostringstream m;
    m << name << ": the enclosed volume is " << r.enclosed_volume
      << " (not positive): the triangles face inwards (the voxelizer turns inside-out shells outwards)";
    r.warnings.push_back(m.str());
  }
  return r;
}

}  // namespace snh
