// Inside-out shells turned outwards (fem/shell_orientation.h).
#include "fem/shell_orientation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>

#include "fem/fast_winding_number.h"
#include "fem/union_find.h"

namespace snh::fem {
namespace {

struct Shell {
  std::vector<size_t> triangles;
  double volume = 0.0;  // signed, about the shell's centroid
  double area = 0.0;
  size_t edges = 0, open_edges = 0;
  bool encloses = false;
};

const double* at(const TriangleSurface& s, size_t t, int c) {
  return s.positions.data() + 3 * static_cast<size_t>(s.triangles[3 * t + c]);
}

// The generalized winding number at p of the triangles of every shell but
// `skip` (Jacobson et al. 2013, Eq. 4).
double winding_of_others(const TriangleSurface& s, const std::vector<Shell>& shells, size_t skip, const double p[3]) {
  double w = 0.0;
  for (size_t k = 0; k < shells.size(); ++k) {
    if (k == skip || !shells[k].encloses) continue;
    for (size_t t : shells[k].triangles) {
      double a[3], b[3], c[3];
      for (int d = 0; d < 3; ++d) {
        a[d] = at(s, t, 0)[d] - p[d];
        b[d] = at(s, t, 1)[d] - p[d];
        c[d] = at(s, t, 2)[d] - p[d];
      }
      w += triangle_winding(a, b, c);
    }
  }
  return w;
}

void reverse(TriangleSurface& s, const Shell& shell) {
  for (size_t t : shell.triangles) std::swap(s.triangles[3 * t + 1], s.triangles[3 * t + 2]);
}

}  // namespace

std::vector<std::string> orient_shells(TriangleSurface& surface, const std::string& name) {
  const size_t nt = surface.triangle_count();
  UnionFind joined(nt);
  std::map<std::pair<int32_t, int32_t>, std::vector<size_t>> edge_triangles;
  for (size_t t = 0; t < nt; ++t)
    for (int c = 0; c < 3; ++c) {
      int32_t a = surface.triangles[3 * t + c], b = surface.triangles[3 * t + (c + 1) % 3];
      if (a > b) std::swap(a, b);
      edge_triangles[{a, b}].push_back(t);
    }
  for (const auto& [edge, ts] : edge_triangles)
    for (size_t k = 1; k < ts.size(); ++k) joined.unite(static_cast<int32_t>(ts[0]), static_cast<int32_t>(ts[k]));
  std::map<int32_t, size_t> shell_of_root;
  std::vector<Shell> shells;
  std::vector<size_t> shell_of(nt);
  for (size_t t = 0; t < nt; ++t) {
    const auto [it, added] = shell_of_root.emplace(joined.find(static_cast<int32_t>(t)), shells.size());
    if (added) shells.emplace_back();
    shell_of[t] = it->second;
    shells[it->second].triangles.push_back(t);
  }
  for (const auto& [edge, ts] : edge_triangles) {
    Shell& s = shells[shell_of[ts[0]]];
    ++s.edges;
    if (ts.size() == 1) ++s.open_edges;
  }
  for (Shell& s : shells) {
    double centre[3] = {0, 0, 0};
    for (size_t t : s.triangles)
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d) centre[d] += at(surface, t, c)[d] / (3.0 * static_cast<double>(s.triangles.size()));
    for (size_t t : s.triangles) {
      double a[3], b[3], c[3];
      for (int d = 0; d < 3; ++d) {
        a[d] = at(surface, t, 0)[d] - centre[d];
        b[d] = at(surface, t, 1)[d] - centre[d];
        c[d] = at(surface, t, 2)[d] - centre[d];
      }
      const double bc[3] = {b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0]};
      s.volume += (a[0] * bc[0] + a[1] * bc[1] + a[2] * bc[2]) / 6.0;
      const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
      s.area += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
    // The sphere of the same area holds A^(3/2) / (6 sqrt(pi)).
    const double sphere = std::pow(s.area, 1.5) / (6.0 * std::sqrt(M_PI));
    s.encloses = 10 * s.open_edges <= s.edges && std::abs(s.volume) >= 0.01 * sphere && sphere > 0.0;
  }

  std::vector<std::string> warnings;
  size_t reversed = 0;
  const auto note = [&](size_t k, const char* why) {
    ++reversed;
    if (warnings.size() < 8)
      warnings.push_back(
          name + ": shell " + std::to_string(k) + " (from triangle " + std::to_string(shells[k].triangles.front()) +
          ", " + std::to_string(shells[k].triangles.size()) + " triangles) " + why + "; voxelized as its outward twin");
  };
  double total = 0.0;
  for (const Shell& s : shells)
    if (s.encloses) total += s.volume;
  if (total < 0.0)
    for (size_t k = 0; k < shells.size(); ++k)
      if (shells[k].encloses) {
        reverse(surface, shells[k]);
        shells[k].volume = -shells[k].volume;
        if (shells[k].volume > 0.0) note(k, "faces inwards (the whole surface is inside out or mirrored)");
      }
  // Largest first, so that a shell is judged against the others as they
  // will be voxelized.
  std::vector<size_t> order;
  for (size_t k = 0; k < shells.size(); ++k)
    if (shells[k].encloses && shells[k].volume < 0.0) order.push_back(k);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return shells[a].volume < shells[b].volume; });
  for (size_t k : order) {
    const Shell& s = shells[k];
    const size_t samples = std::min<size_t>(9, s.triangles.size());
    size_t inside = 0;
    for (size_t i = 0; i < samples; ++i) {
      const size_t t = s.triangles[i * s.triangles.size() / samples];
      double p[3];
      for (int d = 0; d < 3; ++d) p[d] = (at(surface, t, 0)[d] + at(surface, t, 1)[d] + at(surface, t, 2)[d]) / 3.0;
      if (winding_of_others(surface, shells, k, p) >= 0.5) ++inside;
    }
    if (2 * inside > samples) continue;  // a cavity of another shell
    reverse(surface, s);
    shells[k].volume = -shells[k].volume;
    note(k, "faces inwards");
  }
  if (reversed > warnings.size())
    warnings.push_back(name + ": " + std::to_string(reversed - warnings.size()) +
                       " more shells faced inwards and were voxelized as their outward twins");
  return warnings;
}

}  // namespace snh::fem
