// Hierarchical generalized winding numbers (fast_winding_number.h).
#include "fem/fast_winding_number.h"

#include <algorithm>
#include <sstream>

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

}  // namespace snh::fem
