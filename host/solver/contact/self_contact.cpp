#include "solver/contact/self_contact.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>

#include "snh/error.h"

namespace snh::solver {

namespace {

using Clock = std::chrono::steady_clock;
using Vec3 = std::array<double, 3>;

// Faces as local nodes: hex8 in VTK_HEXAHEDRON order (snh/mesh.h), tet4.
constexpr int kHexFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
constexpr int kTetFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
// The Kuhn split of a hex (as snh::split_hexes_into_tets): six tets from
// corner 0 to corner 7 adding one axis at a time; corners (bit 0: +x, bit 1:
// +y, bit 2: +z) to VTK nodes by kCornerNode.
constexpr int kCornerNode[8] = {0, 1, 3, 2, 4, 5, 7, 6};
constexpr int kKuhn[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

Vec3 sub(const double* a, const double* b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Closest point of triangle (a, b, c) to p as barycentric weights (Ericson,
// Real-Time Collision Detection, 5.1.5).
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = sub(b.data(), a.data()), ac = sub(c.data(), a.data()), ap = sub(p.data(), a.data());
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {1, 0, 0};
  const Vec3 bp = sub(p.data(), b.data());
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Vec3 cp = sub(p.data(), c.data());
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

// Barycentric coordinates (b1, b2, b3) of p in tet (x0..x3); false when the
// tet is degenerate or p is outside. *orientation: the sign of its volume.
bool in_tet(const double* p, const double* x0, const double* x1, const double* x2, const double* x3, Vec3& b,
            int* orientation = nullptr) {
  const Vec3 e1 = sub(x1, x0), e2 = sub(x2, x0), e3 = sub(x3, x0), r = sub(p, x0);
  const Vec3 c23{e2[1] * e3[2] - e2[2] * e3[1], e2[2] * e3[0] - e2[0] * e3[2], e2[0] * e3[1] - e2[1] * e3[0]};
  const Vec3 c31{e3[1] * e1[2] - e3[2] * e1[1], e3[2] * e1[0] - e3[0] * e1[2], e3[0] * e1[1] - e3[1] * e1[0]};
  const Vec3 c12{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const double det = dot(e1, c23);
  const double scale = std::sqrt(dot(e1, e1) * dot(e2, e2) * dot(e3, e3));
  if (!(std::abs(det) > 1e-12 * scale)) return false;
  if (orientation) *orientation = det > 0.0 ? 1 : -1;
  b = {dot(r, c23) / det, dot(r, c31) / det, dot(r, c12) / det};
  return b[0] >= 0.0 && b[1] >= 0.0 && b[2] >= 0.0 && b[0] + b[1] + b[2] <= 1.0;
}

}  // namespace

SelfContactDetector::SelfContactDetector(const Mesh& mesh)
    : type_(mesh.type), nodes_(nodes_per_element(mesh.type)), elements_(mesh.elements), rest_(mesh.positions.xyz()) {
  const size_t elements = elements_.size() / nodes_, vertices = rest_.size() / 3;
  // Boundary faces: those of exactly one element, kept in element and face order.
  std::map<std::array<int, 4>, int> count;
  auto key = [](const int* f, int n) {
    std::array<int, 4> k{-1, -1, -1, -1};
    std::copy(f, f + n, k.begin());
    std::sort(k.begin(), k.begin() + n);
    return k;
  };
  const int faces = type_ == ElementType::hex8 ? 6 : 4, corners = type_ == ElementType::hex8 ? 4 : 3;
  auto face = [&](size_t e, int f, int* out) {
    for (int i = 0; i < corners; ++i)
      out[i] = elements_[nodes_ * e + (type_ == ElementType::hex8 ? kHexFaces[f][i] : kTetFaces[f][i])];
  };
  for (size_t e = 0; e < elements; ++e)
    for (int f = 0; f < faces; ++f) {
      int n[4];
      face(e, f, n);
      ++count[key(n, corners)];
    }
  std::vector<char> on_surface(vertices, 0);
  for (size_t e = 0; e < elements; ++e)
    for (int f = 0; f < faces; ++f) {
      int n[4];
      face(e, f, n);
      if (count[key(n, corners)] != 1) continue;
      triangles_.insert(triangles_.end(), {n[0], n[1], n[2]});
      if (corners == 4) triangles_.insert(triangles_.end(), {n[0], n[2], n[3]});
      for (int i = 0; i < corners; ++i) on_surface[n[i]] = 1;
    }
  sample_of_vertex_.assign(vertices, -1);
  for (size_t v = 0; v < vertices; ++v)
    if (on_surface[v]) {
      sample_of_vertex_[v] = static_cast<int>(samples_.size());
      samples_.push_back(static_cast<int>(v));
    }
  // Near set per sample: the vertices of its elements.
  std::vector<std::vector<int>> incident(vertices);
  for (size_t e = 0; e < elements; ++e)
    for (int a = 0; a < nodes_; ++a) incident[elements_[nodes_ * e + a]].push_back(static_cast<int>(e));
  near_offsets_.push_back(0);
  for (int s : samples_) {
    std::vector<int> near;
    for (int e : incident[s])
      for (int a = 0; a < nodes_; ++a) near.push_back(elements_[nodes_ * e + a]);
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    if (type_ == ElementType::tet4) {
      // A tet's one-ring spans about one lattice cell where a hex's spans
      // two: one ring more, so that tets and the hexes they split exclude
      // about the same neighbourhood. Measured on the elbow as tet4
      // (`scene elbow --element tet4`): with one ring steps 22 and 23
      // stagnated and a sample ended 0.197 deep; with two, step 21 stagnates
      // and the deepest is 0.081 (thickness 0.025): better, not resolved
      // (docs/design.md).
      const std::vector<int> first = near;
      for (int v : first)
        for (int e : incident[v])
          for (int a = 0; a < nodes_; ++a) near.push_back(elements_[nodes_ * e + a]);
      std::sort(near.begin(), near.end());
      near.erase(std::unique(near.begin(), near.end()), near.end());
    }
    near_.insert(near_.end(), near.begin(), near.end());
    near_offsets_.push_back(static_cast<int>(near_.size()));
  }
  // Cell width: the mean largest extent of the elements at rest.
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  double extent = 0.0;
  for (size_t e = 0; e < elements; ++e) {
    Vec3 a{1e300, 1e300, 1e300}, b{-1e300, -1e300, -1e300};
    for (int n = 0; n < nodes_; ++n)
      for (int d = 0; d < 3; ++d) {
        const double p = rest_[3 * elements_[nodes_ * e + n] + d];
        a[d] = std::min(a[d], p);
        b[d] = std::max(b[d], p);
      }
    extent += std::max({b[0] - a[0], b[1] - a[1], b[2] - a[2]});
    for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], a[d]), hi[d] = std::max(hi[d], b[d]);
  }
  if (elements == 0) throw Error("self-contact: the mesh has no elements");
  cell_ = extent / static_cast<double>(elements);
  if (!(cell_ > 0.0)) throw Error("self-contact: the mesh's elements have no extent");
  // Rest grid over the triangles: count, prefix sum, fill in triangle order.
  rest_origin_ = lo;
  for (int d = 0; d < 3; ++d) rest_dims_[d] = std::max(1, static_cast<int>(std::ceil((hi[d] - lo[d]) / cell_)));
  const size_t cells = static_cast<size_t>(rest_dims_[0]) * rest_dims_[1] * rest_dims_[2];
  rest_offsets_.assign(cells + 1, 0);
  auto range = [&](const int* t, std::array<int, 3>& a, std::array<int, 3>& b) {
    for (int d = 0; d < 3; ++d) {
      double mn = 1e300, mx = -1e300;
      for (int i = 0; i < 3; ++i) mn = std::min(mn, rest_[3 * t[i] + d]), mx = std::max(mx, rest_[3 * t[i] + d]);
      a[d] = std::clamp(static_cast<int>(std::floor((mn - lo[d]) / cell_)), 0, rest_dims_[d] - 1);
      b[d] = std::clamp(static_cast<int>(std::floor((mx - lo[d]) / cell_)), 0, rest_dims_[d] - 1);
    }
  };
  auto each_cell = [&](const std::array<int, 3>& a, const std::array<int, 3>& b, auto&& f) {
    for (int k = a[2]; k <= b[2]; ++k)
      for (int j = a[1]; j <= b[1]; ++j)
        for (int i = a[0]; i <= b[0]; ++i) f(i + static_cast<size_t>(rest_dims_[0]) * (j + size_t(rest_dims_[1]) * k));
  };
  const size_t tris = triangle_count();
  for (size_t t = 0; t < tris; ++t) {
    std::array<int, 3> a, b;
    range(&triangles_[3 * t], a, b);
    each_cell(a, b, [&](size_t c) { ++rest_offsets_[c + 1]; });
  }
  for (size_t c = 0; c < cells; ++c) rest_offsets_[c + 1] += rest_offsets_[c];
  rest_cells_.resize(rest_offsets_[cells]);
  std::vector<int> fill(rest_offsets_.begin(), rest_offsets_.end() - 1);
  for (size_t t = 0; t < tris; ++t) {
    std::array<int, 3> a, b;
    range(&triangles_[3 * t], a, b);
    each_cell(a, b, [&](size_t c) { rest_cells_[fill[c]++] = static_cast<int>(t); });
  }
}

bool SelfContactDetector::near_sample(int sample, int vertex) const {
  return std::binary_search(near_.begin() + near_offsets_[sample], near_.begin() + near_offsets_[sample + 1], vertex);
}

bool SelfContactDetector::excluded(int sample, int element) const {
  for (int a = 0; a < nodes_; ++a)
    if (near_sample(sample, elements_[nodes_ * element + a])) return true;
  return false;
}

bool SelfContactDetector::closest_rest_point(const Vec3& X, int sample, std::array<int, 3>& vertex,
                                             Vec3& weight) const {
  std::array<int, 3> home;
  for (int d = 0; d < 3; ++d)
    home[d] = std::clamp(static_cast<int>(std::floor((X[d] - rest_origin_[d]) / cell_)), 0, rest_dims_[d] - 1);
  const int max_ring = std::max({rest_dims_[0], rest_dims_[1], rest_dims_[2]});
  double best = std::numeric_limits<double>::infinity();
  bool found = false;
  for (int r = 0; r <= max_ring; ++r) {
    for (int k = home[2] - r; k <= home[2] + r; ++k)
      for (int j = home[1] - r; j <= home[1] + r; ++j)
        for (int i = home[0] - r; i <= home[0] + r; ++i) {
          if (std::max({std::abs(i - home[0]), std::abs(j - home[1]), std::abs(k - home[2])}) != r) continue;
          if (i < 0 || j < 0 || k < 0 || i >= rest_dims_[0] || j >= rest_dims_[1] || k >= rest_dims_[2]) continue;
          const size_t c = i + static_cast<size_t>(rest_dims_[0]) * (j + size_t(rest_dims_[1]) * k);
          for (int q = rest_offsets_[c]; q < rest_offsets_[c + 1]; ++q) {
            const int* t = &triangles_[3 * rest_cells_[q]];
            if (sample >= 0 && (near_sample(sample, t[0]) || near_sample(sample, t[1]) || near_sample(sample, t[2])))
              continue;
            const Vec3 a{rest_[3 * t[0]], rest_[3 * t[0] + 1], rest_[3 * t[0] + 2]};
            const Vec3 b{rest_[3 * t[1]], rest_[3 * t[1] + 1], rest_[3 * t[1] + 2]};
            const Vec3 cc{rest_[3 * t[2]], rest_[3 * t[2] + 1], rest_[3 * t[2] + 2]};
            const Vec3 w = closest_on_triangle(X, a, b, cc);
            Vec3 y;
            for (int d = 0; d < 3; ++d) y[d] = w[0] * a[d] + w[1] * b[d] + w[2] * cc[d];
            const Vec3 e = sub(X.data(), y.data());
            const double dist = dot(e, e);
            if (dist < best) {
              best = dist;
              found = true;
              vertex = {t[0], t[1], t[2]};
              weight = w;
            }
          }
        }
    // Cells beyond ring r are at least r cells away from X's cell.
    if (found && std::sqrt(best) <= r * cell_) break;
  }
  return found;
}

bool SelfContactDetector::locate(int element, const double* p, const std::vector<double>& x, Vec3& X) const {
  const int32_t* n = &elements_[nodes_ * element];
  const int tets = type_ == ElementType::hex8 ? 6 : 1;
  for (int t = 0; t < tets; ++t) {
    int v[4];
    for (int i = 0; i < 4; ++i) v[i] = type_ == ElementType::hex8 ? n[kCornerNode[kKuhn[t][i]]] : n[i];
    Vec3 b;
    int deformed = 0, rest = 0;
    if (!in_tet(p, &x[3 * v[0]], &x[3 * v[1]], &x[3 * v[2]], &x[3 * v[3]], b, &deformed)) continue;
    // Only through a tet that keeps its rest orientation: an inverted tet's
    // map to rest space is no reference map (measured: on the elbow, the
    // first Newton iterates of a load step, where the bones have moved and
    // the flesh not yet, invert elements next to the bones, and samples
    // located in them were glued to far-off surface points).
    Vec3 unused;
    in_tet(&rest_[3 * v[0]], &rest_[3 * v[0]], &rest_[3 * v[1]], &rest_[3 * v[2]], &rest_[3 * v[3]], unused, &rest);
    if (deformed != rest) continue;
    const double b0 = 1.0 - b[0] - b[1] - b[2];
    for (int d = 0; d < 3; ++d)
      X[d] = b0 * rest_[3 * v[0] + d] + b[0] * rest_[3 * v[1] + d] + b[1] * rest_[3 * v[2] + d] +
             b[2] * rest_[3 * v[3] + d];
    return true;
  }
  return false;
}

std::vector<SelfContactPair> SelfContactDetector::detect(const std::vector<double>& x) const {
  const auto start = Clock::now();
  const size_t elements = elements_.size() / nodes_;
  // Deformed grid over the elements' bounding boxes: count, prefix sum, fill
  // in element order. Cells one rest element wide, coarser if the deformed
  // box would need more than 8 cells per element (a blown-up state).
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  std::vector<double> boxes(6 * elements);
  for (size_t e = 0; e < elements; ++e) {
    double* bx = &boxes[6 * e];
    for (int d = 0; d < 3; ++d) bx[d] = 1e300, bx[3 + d] = -1e300;
    for (int a = 0; a < nodes_; ++a)
      for (int d = 0; d < 3; ++d) {
        const double p = x[3 * elements_[nodes_ * e + a] + d];
        bx[d] = std::min(bx[d], p);
        bx[3 + d] = std::max(bx[3 + d], p);
      }
    for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], bx[d]), hi[d] = std::max(hi[d], bx[3 + d]);
  }
  for (int d = 0; d < 3; ++d)
    if (!std::isfinite(lo[d]) || !std::isfinite(hi[d])) return {};
  double cell = cell_;
  auto cells_for = [&](double c) {
    double n = 1.0;
    for (int d = 0; d < 3; ++d) n *= std::floor((hi[d] - lo[d]) / c) + 1.0;
    return n;
  };
  while (cells_for(cell) > 8.0 * static_cast<double>(elements) + 64.0) cell *= 2.0;
  std::array<int, 3> dims;
  for (int d = 0; d < 3; ++d) dims[d] = static_cast<int>(std::floor((hi[d] - lo[d]) / cell)) + 1;
  const size_t cells = static_cast<size_t>(dims[0]) * dims[1] * dims[2];
  auto index = [&](double p, int d) {
    return std::clamp(static_cast<int>(std::floor((p - lo[d]) / cell)), 0, dims[d] - 1);
  };
  auto each_cell = [&](const double* bx, auto&& f) {
    const int i0 = index(bx[0], 0), i1 = index(bx[3], 0), j0 = index(bx[1], 1), j1 = index(bx[4], 1),
              k0 = index(bx[2], 2), k1 = index(bx[5], 2);
    for (int k = k0; k <= k1; ++k)
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) f(i + static_cast<size_t>(dims[0]) * (j + size_t(dims[1]) * k));
  };
  std::vector<int> offsets(cells + 1, 0);
  for (size_t e = 0; e < elements; ++e) each_cell(&boxes[6 * e], [&](size_t c) { ++offsets[c + 1]; });
  for (size_t c = 0; c < cells; ++c) offsets[c + 1] += offsets[c];
  std::vector<int> list(offsets[cells]);
  {
    std::vector<int> fill(offsets.begin(), offsets.end() - 1);
    for (size_t e = 0; e < elements; ++e)
      each_cell(&boxes[6 * e], [&](size_t c) { list[fill[c]++] = static_cast<int>(e); });
  }
  const auto built = Clock::now();
  std::vector<SelfContactPair> out;
  for (size_t s = 0; s < samples_.size(); ++s) {
    const double* p = &x[3 * samples_[s]];
    const size_t c =
        index(p[0], 0) + static_cast<size_t>(dims[0]) * (index(p[1], 1) + size_t(dims[1]) * index(p[2], 2));
    for (int q = offsets[c]; q < offsets[c + 1]; ++q) {
      const int e = list[q];
      const double* bx = &boxes[6 * e];
      if (p[0] < bx[0] || p[1] < bx[1] || p[2] < bx[2] || p[0] > bx[3] || p[1] > bx[4] || p[2] > bx[5]) continue;
      if (excluded(static_cast<int>(s), e)) continue;
      Vec3 X;
      if (!locate(e, p, x, X)) continue;
      SelfContactPair pair;
      pair.sample = samples_[s];
      pair.element = e;
      if (!closest_rest_point(X, static_cast<int>(s), pair.vertex, pair.weight)) continue;
      out.push_back(pair);
      break;
    }
  }
  const auto done = Clock::now();
  last_grid_seconds_ = std::chrono::duration<double>(built - start).count();
  last_location_seconds_ = std::chrono::duration<double>(done - built).count();
  return out;
}

double self_contact_length(const SelfContactPair& c, const std::vector<double>& x) {
  double sum = 0.0;
  for (int d = 0; d < 3; ++d) {
    double v = x[3 * c.sample + d];
    for (int j = 0; j < 3; ++j) v -= c.weight[j] * x[3 * c.vertex[j] + d];
    sum += v * v;
  }
  return std::sqrt(sum);
}

double self_contact_energy(const std::vector<SelfContactPair>& contacts, double stiffness,
                           const std::vector<double>& x) {
  double sum = 0.0;
  for (const SelfContactPair& c : contacts) {
    const double l = self_contact_length(c, x);
    sum += 0.5 * stiffness * l * l;
  }
  return sum;
}

void self_contact_gradient(const std::vector<SelfContactPair>& contacts, double stiffness, const std::vector<double>& x,
                           std::vector<double>& g) {
  for (const SelfContactPair& c : contacts)
    for (int d = 0; d < 3; ++d) {
      double v = x[3 * c.sample + d];
      for (int j = 0; j < 3; ++j) v -= c.weight[j] * x[3 * c.vertex[j] + d];
      g[3 * c.sample + d] += stiffness * v;
      for (int j = 0; j < 3; ++j) g[3 * c.vertex[j] + d] -= stiffness * c.weight[j] * v;
    }
}

}  // namespace snh::solver
