// Lattices whose elements differ, for tests that a uniform lattice would
// pass by symmetry.
#pragma once

#include <cmath>
#include <random>

#include "snh/mesh.h"

namespace snh::test {

// `mesh` with every vertex moved by up to 0.1 h (a fixed seed): no two
// elements share a rest shape.
inline Mesh jittered(Mesh mesh, double h) {
  std::mt19937_64 rng(4711);
  std::uniform_real_distribution<double> u(-0.1 * h, 0.1 * h);
  double* c = mesh.positions.data();
  for (size_t i = 0; i < 3 * mesh.positions.size(); ++i) c[i] += u(rng);
  return mesh;
}

// An n x n x n lattice of the unit cube with its interior vertices moved by
// up to 15% of a cell; the boundary stays on the cube's faces.
inline Mesh jittered_unit_cube(int n, unsigned seed) {
  Mesh mesh = make_box_lattice(n, n, n, 1.0 / n);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.15 / n, 0.15 / n);
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    bool interior = true;
    for (int d = 0; d < 3; ++d) {
      const double c = mesh.positions(v, d);
      interior = interior && c > 1e-9 && c < 1.0 - 1e-9;
    }
    if (interior)
      for (int d = 0; d < 3; ++d) mesh.positions(v, d) += u(rng);
  }
  return mesh;
}

// Every coordinate moved by amount * sin(1.7 i + 0.3): irregular but the same
// on every platform, so that a swapped coordinate or node shows.
inline Mesh sine_jiggled(Mesh mesh, double amount) {
  double* c = mesh.positions.data();
  for (size_t i = 0; i < 3 * mesh.positions.size(); ++i) c[i] += amount * std::sin(1.7 * double(i) + 0.3);
  return mesh;
}

}  // namespace snh::test
