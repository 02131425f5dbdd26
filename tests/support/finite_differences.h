// Central differences of a point's energy and force, for the tests that
// check a force is minus the energy's gradient and a Hessian the force's
// derivative (contact, friction).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <array>

namespace snh::test {

// The best relative error of -grad(energy) at x against `force` over central
// differences with steps 1e-4 ... 1e-9 (the best step depends on the
// energy's scale and curvature).
template <typename Energy>
double best_gradient_error(const Energy& energy, const Eigen::Vector3d& x, const Eigen::Vector3d& force) {
  double best = 1e300;
  for (double h = 1e-4; h >= 1e-9; h /= 10) {
    Eigen::Vector3d fd;
    for (int d = 0; d < 3; ++d) {
      Eigen::Vector3d a = x, b = x;
      a[d] += h;
      b[d] -= h;
      fd[d] = -(energy(a) - energy(b)) / (2 * h);
    }
    best = std::min(best, (fd - force).norm() / force.norm());
  }
  return best;
}

// -d force / d x at x by central differences with step h; `force(x)` gives
// the three components (any type indexed 0..2).
template <typename Force>
Eigen::Matrix3d force_derivative(const Force& force, const Eigen::Vector3d& x, double h) {
  Eigen::Matrix3d fd;
  for (int d = 0; d < 3; ++d) {
    Eigen::Vector3d a = x, b = x;
    a[d] += h;
    b[d] -= h;
    const auto fa = force(a), fb = force(b);
    for (int i = 0; i < 3; ++i) fd(i, d) = -(fa[i] - fb[i]) / (2 * h);
  }
  return fd;
}

}  // namespace snh::test
