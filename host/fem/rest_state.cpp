#include "fem/rest_state.h"

#include <cmath>
#include <sstream>

#include "snh/error.h"

namespace snh::fem {

const double kHexNodeSigns[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                    {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

namespace {

// Inverse transpose and determinant of a column-major 3x3.
double inverse_transpose(const double j[9], double out[9]) {
  const double det =
      j[0] * (j[4] * j[8] - j[5] * j[7]) - j[3] * (j[1] * j[8] - j[2] * j[7]) + j[6] * (j[1] * j[5] - j[2] * j[4]);
  // Cofactor matrix / det = inverse transpose.
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) {
      const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
      out[3 * c + r] = (j[3 * c1 + r1] * j[3 * c2 + r2] - j[3 * c1 + r2] * j[3 * c2 + r1]) / det;
    }
  return det;
}

void fail(size_t element, int q, double volume) {
  std::ostringstream s;
  s << "mesh: element " << element << " has " << (volume == 0.0 ? "zero" : (volume < 0.0 ? "negative" : "non-finite"))
    << " rest volume (" << volume << ") at quadrature point " << q
    << (volume < 0.0 ? ": it is inverted or its nodes are not in the expected order" : ": it is degenerate");
  throw Error(s.str());
}

// Gradients and weights of one element into the given slots.
void element_rest_state(const Mesh& mesh, size_t e, double* gradients, double* weights) {
  const int n = nodes_per_element(mesh.type);
  const int32_t* nodes = mesh.elements.data() + n * e;
  if (mesh.type == ElementType::tet4) {
    double dm[9];
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) dm[3 * c + r] = mesh.positions(nodes[c + 1], r) - mesh.positions(nodes[0], r);
    double it[9];
    const double det = inverse_transpose(dm, it);
    const double volume = det / 6.0;
    if (!(volume > 0.0) || !std::isfinite(volume)) fail(e, 0, volume);
    // dN_{c+1}/dX = row c of Dm^{-1} = column c of Dm^{-T}.
    for (int d = 0; d < 3; ++d) gradients[d] = 0.0;
    for (int a = 1; a < 4; ++a)
      for (int d = 0; d < 3; ++d) {
        gradients[3 * a + d] = it[3 * (a - 1) + d];
        gradients[d] -= it[3 * (a - 1) + d];
      }
    weights[0] = volume;
    return;
  }
  const double g = 1.0 / std::sqrt(3.0);
  for (int q = 0; q < 8; ++q) {
    const double xi[3] = {(q & 1) ? g : -g, (q & 2) ? g : -g, (q & 4) ? g : -g};
    double dn[8][3];  // dN_a / dxi
    for (int a = 0; a < 8; ++a) {
      const double* s = kHexNodeSigns[a];
      const double f[3] = {1.0 + s[0] * xi[0], 1.0 + s[1] * xi[1], 1.0 + s[2] * xi[2]};
      dn[a][0] = 0.125 * s[0] * f[1] * f[2];
      dn[a][1] = 0.125 * f[0] * s[1] * f[2];
      dn[a][2] = 0.125 * f[0] * f[1] * s[2];
    }
    double jac[9] = {0};  // dX/dxi, column-major
    for (int a = 0; a < 8; ++a)
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) jac[3 * c + r] += mesh.positions(nodes[a], r) * dn[a][c];
    double it[9];
    const double det = inverse_transpose(jac, it);
    if (!(det > 0.0) || !std::isfinite(det)) fail(e, q, det);
    weights[q] = det;  // Gauss weights are 1
    for (int a = 0; a < 8; ++a)
      for (int d = 0; d < 3; ++d)
        gradients[3 * (8 * q + a) + d] = it[3 * 0 + d] * dn[a][0] + it[3 * 1 + d] * dn[a][1] + it[3 * 2 + d] * dn[a][2];
  }
}

// Every element is a translate of element 0 (to rounding of the coordinates).
bool is_uniform(const Mesh& mesh) {
  const int n = nodes_per_element(mesh.type);
  const size_t count = mesh.element_count();
  if (count == 0) return false;
  const int32_t* first = mesh.elements.data();
  double size = 0.0;
  for (int a = 1; a < n; ++a)
    for (int d = 0; d < 3; ++d)
      size = std::max(size, std::abs(mesh.positions(first[a], d) - mesh.positions(first[0], d)));
  const double tolerance = 1e-12 * size;
  for (size_t e = 1; e < count; ++e) {
    const int32_t* nodes = mesh.elements.data() + n * e;
    for (int a = 1; a < n; ++a)
      for (int d = 0; d < 3; ++d) {
        const double here = mesh.positions(nodes[a], d) - mesh.positions(nodes[0], d);
        const double there = mesh.positions(first[a], d) - mesh.positions(first[0], d);
        if (std::abs(here - there) > tolerance) return false;
      }
  }
  return true;
}

}  // namespace

RestState compute_rest_state(const Mesh& mesh) {
  RestState rest;
  rest.type = mesh.type;
  rest.nodes = nodes_per_element(mesh.type);
  rest.quadrature = quadrature_points(mesh.type);
  const size_t count = mesh.element_count();
  const size_t per_element = static_cast<size_t>(rest.quadrature) * rest.nodes * 3;
  // Every element is checked (validity), but a lattice keeps only element 0.
  rest.uniform = is_uniform(mesh);
  std::vector<double> g(per_element), w(rest.quadrature);
  if (!rest.uniform) {
    rest.gradients.resize(per_element * count);
    rest.weights.resize(static_cast<size_t>(rest.quadrature) * count);
  }
  for (size_t e = 0; e < count; ++e) {
    double* ge = rest.uniform ? g.data() : rest.gradients.data() + per_element * e;
    double* we = rest.uniform ? w.data() : rest.weights.data() + static_cast<size_t>(rest.quadrature) * e;
    element_rest_state(mesh, e, ge, we);
    for (int q = 0; q < rest.quadrature; ++q) rest.rest_volume += we[q];
    if (rest.uniform && e == 0) {
      rest.gradients = g;
      rest.weights = w;
    }
  }
  return rest;
}

void deformation_gradient(const Mesh& mesh, const RestState& rest, const double* x, size_t element, int q,
                          double f[9]) {
  for (int i = 0; i < 9; ++i) f[i] = 0.0;
  const int32_t* nodes = mesh.elements.data() + rest.nodes * element;
  for (int a = 0; a < rest.nodes; ++a) {
    const double* g = rest.gradient(element, q, a);
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) f[3 * c + r] += x[3 * nodes[a] + r] * g[c];
  }
}

}  // namespace snh::fem
