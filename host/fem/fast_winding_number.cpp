// Hierarchical generalized winding numbers (fast_winding_number.h).
#include "fem/fast_winding_number.h"

#include <algorithm>
#include <limits>
#include <sstream>
#include <unordered_map>

#include "fem/surface_cells.h"
#include "snh/error.h"

namespace snh::fem {
namespace {

constexpr int32_t kLeafTriangles = 8;

}  // namespace

FastWindingNumber::FastWindingNumber(const TriangleSurface& surface, double beta) : beta_(beta) {
  if (!(beta > 0.0) || !std::isfinite(beta)) {
    std::ostringstream m;
    m << "fast winding number: beta must be positive and finite, got " << beta;
    throw Error(m.str());
  }
  std::vector<int32_t> order;
  std::vector<double> centroids(3 * surface.triangle_count()), areas(3 * surface.triangle_count());
  for (size_t t = 0; t < surface.triangle_count(); ++t) {
    const int32_t* v = surface.triangles.data() + 3 * t;
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
    const double* a = surface.positions.data() + 3 * v[0];
    const double* b = surface.positions.data() + 3 * v[1];
    const double* c = surface.positions.data() + 3 * v[2];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    areas[3 * t] = 0.5 * (u[1] * w[2] - u[2] * w[1]);
    areas[3 * t + 1] = 0.5 * (u[2] * w[0] - u[0] * w[2]);
    areas[3 * t + 2] = 0.5 * (u[0] * w[1] - u[1] * w[0]);
    for (int d = 0; d < 3; ++d) centroids[3 * t + d] = (a[d] + b[d] + c[d]) / 3.0;
    order.push_back(static_cast<int32_t>(t));
  }
  if (!order.empty()) build(order, 0, static_cast<int32_t>(order.size()), centroids, areas, surface);
  corners_.reserve(9 * order.size());
  for (int32_t t : order)
    for (int k = 0; k < 3; ++k) {
      const double* x = surface.positions.data() + 3 * surface.triangles[3 * t + k];
      corners_.insert(corners_.end(), x, x + 3);
    }
}

int32_t FastWindingNumber::build(std::vector<int32_t>& order, int32_t first, int32_t count,
                                 const std::vector<double>& centroids, const std::vector<double>& areas,
                                 const TriangleSurface& surface) {
  const int32_t index = static_cast<int32_t>(nodes_.size());
  nodes_.push_back({});
  Node node{};
  node.first = first;
  node.count = count;
  node.child[0] = node.child[1] = -1;
  // The expansion centre: the area-weighted centroid (the mean of the
  // centroids where the triangles have no area).
  double total = 0.0, weighted[3] = {0, 0, 0}, mean[3] = {0, 0, 0};
  for (int32_t i = first; i < first + count; ++i) {
    const int32_t t = order[i];
    const double* A = &areas[3 * t];
    const double area = std::sqrt(A[0] * A[0] + A[1] * A[1] + A[2] * A[2]);
    total += area;
    for (int d = 0; d < 3; ++d) {
      weighted[d] += area * centroids[3 * t + d];
      mean[d] += centroids[3 * t + d] / count;
      node.normal[d] += A[d];
    }
  }
  for (int d = 0; d < 3; ++d) node.centre[d] = total > 0.0 ? weighted[d] / total : mean[d];
  for (int32_t i = first; i < first + count; ++i) {
    const int32_t t = order[i];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) node.moment[3 * r + c] += areas[3 * t + r] * (centroids[3 * t + c] - node.centre[c]);
    for (int k = 0; k < 3; ++k) {
      const double* x = surface.positions.data() + 3 * surface.triangles[3 * t + k];
      const double dx = x[0] - node.centre[0], dy = x[1] - node.centre[1], dz = x[2] - node.centre[2];
      node.radius = std::max(node.radius, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
  }
  if (count > kLeafTriangles) {
    // Median split of the centroids along the box's longest side (ties by
    // triangle index, so the hierarchy does not depend on the sort).
    double lo[3], hi[3];
    for (int d = 0; d < 3; ++d) lo[d] = hi[d] = centroids[3 * order[first] + d];
    for (int32_t i = first; i < first + count; ++i)
      for (int d = 0; d < 3; ++d) {
        lo[d] = std::min(lo[d], centroids[3 * order[i] + d]);
        hi[d] = std::max(hi[d], centroids[3 * order[i] + d]);
      }
    int axis = 0;
    for (int d = 1; d < 3; ++d)
      if (hi[d] - lo[d] > hi[axis] - lo[axis]) axis = d;
    const int32_t half = count / 2;
    std::nth_element(order.begin() + first, order.begin() + first + half, order.begin() + first + count,
                     [&](int32_t a, int32_t b) {
                       const double x = centroids[3 * a + axis], y = centroids[3 * b + axis];
                       return x != y ? x < y : a < b;
                     });
    node.child[0] = build(order, first, half, centroids, areas, surface);
    node.child[1] = build(order, first + half, count - half, centroids, areas, surface);
  }
  nodes_[index] = node;
  return index;
}

double FastWindingNumber::operator()(const std::array<double, 3>& q) const {
  if (nodes_.empty()) return 0.0;
  double w = 0.0;
  int32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    const double r[3] = {n.centre[0] - q[0], n.centre[1] - q[1], n.centre[2] - q[2]};
    const double d2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    if (d2 > beta_ * beta_ * n.radius * n.radius) {
      // Far field: with f(x) = (x - q) / |x - q|^3 and x = centre + delta,
      // sum over triangles of the integral of f . n dA ~ f(centre) . N +
      // sum_ij J_ij M_ij, J = I / |r|^3 - 3 r r^T / |r|^5 (Barill et al.
      // 2018, Eq. 11-12, to second order).
      const double d = std::sqrt(d2), inv3 = 1.0 / (d2 * d), inv5 = inv3 / d2;
      const double* M = n.moment;
      double rMr = 0.0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) rMr += r[i] * M[3 * i + j] * r[j];
      const double first = (r[0] * n.normal[0] + r[1] * n.normal[1] + r[2] * n.normal[2]) * inv3;
      const double second = (M[0] + M[4] + M[8]) * inv3 - 3.0 * rMr * inv5;
      w += (first + second) / (4.0 * M_PI);
    } else if (n.child[0] < 0) {
      for (int32_t t = n.first; t < n.first + n.count; ++t) {
        const double* x = &corners_[9 * static_cast<size_t>(t)];
        const double a[3] = {x[0] - q[0], x[1] - q[1], x[2] - q[2]};
        const double b[3] = {x[3] - q[0], x[4] - q[1], x[5] - q[2]};
        const double c[3] = {x[6] - q[0], x[7] - q[1], x[8] - q[2]};
        w += triangle_winding(a, b, c);
      }
    } else {
      // Depth is at most log2(triangles / 8) + 1 (median splits): 128 is ample.
      stack[top++] = n.child[1];
      stack[top++] = n.child[0];
    }
  }
  return w;
}

namespace {

// Whether every edge is traversed as often in one direction as in the other
// (a closed surface, manifold or not): the winding number is then an
// integer off the surface, constant between its sheets.
bool boundary_free(const TriangleSurface& surface) {
  std::unordered_map<uint64_t, int> balance;
  for (size_t t = 0; t < surface.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = static_cast<uint32_t>(surface.triangles[3 * t + k]);
      const uint32_t b = static_cast<uint32_t>(surface.triangles[3 * t + (k + 1) % 3]);
      if (a == b) continue;
      balance[(uint64_t(std::min(a, b)) << 32) | std::max(a, b)] += a < b ? 1 : -1;
    }
  return std::all_of(balance.begin(), balance.end(), [](const auto& e) { return e.second == 0; });
}

}  // namespace

std::vector<double> winding_at_cell_centres(const TriangleSurface& surface, const std::array<double, 3>& origin,
                                            double h, const std::array<int, 3>& dims, double beta, bool every_cell) {
  const FastWindingNumber winding(surface, beta);
  const size_t nx = dims[0], ny = dims[1], nz = dims[2];
  std::vector<double> w(nx * ny * nz, std::numeric_limits<double>::quiet_NaN());
  const auto at = [&](int i, int j, int k) -> double {
    double& x = w[size_t(i) + nx * (size_t(j) + ny * size_t(k))];
    if (std::isnan(x)) x = winding({origin[0] + (i + 0.5) * h, origin[1] + (j + 0.5) * h, origin[2] + (k + 0.5) * h});
    return x;
  };
  const auto evaluate_all = [&](const std::array<int, 3>& lo, const std::array<int, 3>& hi) {
    for (int k = lo[2]; k < hi[2]; ++k)
      for (int j = lo[1]; j < hi[1]; ++j)
        for (int i = lo[0]; i < hi[0]; ++i) at(i, j, k);
  };
  if (every_cell || w.empty()) {
    evaluate_all({0, 0, 0}, dims);
    return w;
  }
  // Cells whose slightly grown cubes a triangle meets, counted over boxes by
  // a summed-volume table.
  const std::vector<char> near = surface_crossed_cells(surface, origin, h, dims, 1.0 + 1e-6);
  const size_t sx = nx + 1, sy = ny + 1;
  std::vector<int32_t> sum(sx * sy * (nz + 1), 0);
  const auto S = [&](size_t i, size_t j, size_t k) -> int32_t& { return sum[i + sx * (j + sy * k)]; };
  for (size_t k = 0; k < nz; ++k)
    for (size_t j = 0; j < ny; ++j)
      for (size_t i = 0; i < nx; ++i)
        S(i + 1, j + 1, k + 1) = near[i + nx * (j + ny * k)] + S(i, j + 1, k + 1) + S(i + 1, j, k + 1) +
                                 S(i + 1, j + 1, k) - S(i, j, k + 1) - S(i, j + 1, k) - S(i + 1, j, k) + S(i, j, k);
  const auto near_in = [&](const std::array<int, 3>& lo, const std::array<int, 3>& hi) {
    return S(hi[0], hi[1], hi[2]) - S(lo[0], hi[1], hi[2]) - S(hi[0], lo[1], hi[2]) - S(hi[0], hi[1], lo[2]) +
               S(lo[0], lo[1], hi[2]) + S(lo[0], hi[1], lo[2]) + S(hi[0], lo[1], lo[2]) - S(lo[0], lo[1], lo[2]) >
           0;
  };
  if (boundary_free(surface)) {
    // Closed: one integer per face-connected region of cells clear of the
    // surface (a segment between two such centres meets no triangle).
    std::vector<int32_t> region(w.size(), -1);
    std::vector<size_t> members;
    const size_t stride[3] = {1, nx, nx * ny};
    for (size_t seed = 0; seed < w.size(); ++seed) {
      if (near[seed] || region[seed] >= 0) continue;
      members.assign(1, seed);
      region[seed] = static_cast<int32_t>(seed);
      for (size_t m = 0; m < members.size(); ++m) {
        const size_t c = members[m];
        const size_t cell[3] = {c % nx, (c / nx) % ny, c / (nx * ny)};
        for (int d = 0; d < 3; ++d)
          for (int step : {-1, 1}) {
            if ((step < 0 && cell[d] == 0) || (step > 0 && cell[d] + 1 == size_t(dims[d]))) continue;
            const size_t n = step < 0 ? c - stride[d] : c + stride[d];
            if (near[n] || region[n] >= 0) continue;
            region[n] = static_cast<int32_t>(seed);
            members.push_back(n);
          }
      }
      const double x = at(int(seed % nx), int((seed / nx) % ny), int(seed / (nx * ny))), r = std::round(x);
      for (size_t c : members) {
        if (std::abs(x - r) < 0.25)
          w[c] = r;
        else  // not an integer as it should be: no shortcut
          at(int(c % nx), int((c / nx) % ny), int(c / (nx * ny)));
      }
    }
    for (size_t c = 0; c < w.size(); ++c)
      if (near[c]) at(int(c % nx), int((c / nx) % ny), int(c / (nx * ny)));
    return w;
  }
  // Open: boxes [lo, hi) depth first; a stack, so that depth is no concern.
  std::vector<std::pair<std::array<int, 3>, std::array<int, 3>>> boxes{{{0, 0, 0}, dims}};
  while (!boxes.empty()) {
    const auto [lo, hi] = boxes.back();
    boxes.pop_back();
    const int side_min = std::min({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    const int side_max = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    if (side_min < 3) {  // no interior
      evaluate_all(lo, hi);
      continue;
    }
    if (!near_in(lo, hi)) {
      bool agree = true;
      double k0 = 0.0;
      bool first = true;
      for (int k = lo[2]; k < hi[2] && agree; ++k)
        for (int j = lo[1]; j < hi[1] && agree; ++j) {
          const bool face = k == lo[2] || k == hi[2] - 1 || j == lo[1] || j == hi[1] - 1;
          for (int i = lo[0]; i < hi[0] && agree; i += face ? 1 : std::max(1, hi[0] - lo[0] - 1)) {
            const double x = at(i, j, k), r = std::round(x);
            if (first) k0 = r, first = false;
            agree = r == k0 && std::abs(x - r) < 0.25;
          }
        }
      if (agree) {
        for (int k = lo[2] + 1; k < hi[2] - 1; ++k)
          for (int j = lo[1] + 1; j < hi[1] - 1; ++j)
            for (int i = lo[0] + 1; i < hi[0] - 1; ++i) w[size_t(i) + nx * (size_t(j) + ny * size_t(k))] = k0;
        continue;
      }
    }
    if (side_max <= 4) {
      evaluate_all(lo, hi);
      continue;
    }
    // Halve every side longer than 4 (the others stay whole).
    int cuts[3][3];
    int parts[3];
    for (int d = 0; d < 3; ++d) {
      const int n = hi[d] - lo[d];
      parts[d] = n > 4 ? 2 : 1;
      cuts[d][0] = lo[d];
      cuts[d][1] = n > 4 ? lo[d] + n / 2 : hi[d];
      cuts[d][2] = hi[d];
    }
    for (int c = parts[2] - 1; c >= 0; --c)
      for (int b = parts[1] - 1; b >= 0; --b)
        for (int a = parts[0] - 1; a >= 0; --a)
          boxes.push_back({{cuts[0][a], cuts[1][b], cuts[2][c]}, {cuts[0][a + 1], cuts[1][b + 1], cuts[2][c + 1]}});
  }
  return w;
}

}  // namespace snh::fem
