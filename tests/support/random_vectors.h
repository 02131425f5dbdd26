// Seeded random vectors and positions for the operator tests.
#pragma once

#include <random>
#include <vector>

#include "snh/mesh.h"

namespace snh::test {

// n values uniform in [-amplitude, amplitude].
inline std::vector<double> random_vector(size_t n, double amplitude, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  std::vector<double> v(n);
  for (double& c : v) c = u(rng);
  return v;
}

// The mesh's rest positions, each coordinate moved by random_vector.
inline std::vector<double> perturbed(const Mesh& mesh, double amplitude, unsigned seed) {
  std::vector<double> x = mesh.positions.xyz();
  const std::vector<double> d = random_vector(x.size(), amplitude, seed);
  for (size_t i = 0; i < x.size(); ++i) x[i] += d[i];
  return x;
}

}  // namespace snh::test
