// Materials and independent formulas shared by the Stable Neo-Hookean tests.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "material/element_reference.h"
#include "snh/material.h"
#include "support/hard_deformations.h"

namespace snh::test {

using Matrix9 = Eigen::Matrix<double, 9, 9>;
using Vector9 = Eigen::Matrix<double, 9, 1>;

struct TestMaterial {
  std::string name;
  StableNeoHookean material;
  reference::SnhParameters params() const { return {material.mu, material.lambda, material.barrier}; }
};

inline std::vector<TestMaterial> test_materials() {
  return {
      {"nu0.3_barrier", StableNeoHookean::from_youngs_modulus(1.0, 0.3, Barrier::on)},
      {"nu0.45_barrier", StableNeoHookean::from_youngs_modulus(1.0, 0.45, Barrier::on)},
      {"nu0.49_no_barrier", StableNeoHookean::from_youngs_modulus(1.0, 0.49, Barrier::off)},
      {"nu0.4999_barrier", StableNeoHookean::from_youngs_modulus(1.0, 0.4999, Barrier::on)},
      {"nu-0.5_barrier", StableNeoHookean::from_youngs_modulus(1.0, -0.5, Barrier::on)},
  };
}

// The hard set plus, per material, a deformation with J = alpha exactly,
// where the paper's Eq. 42 coefficients are singular.
inline std::vector<NamedDeformation> deformations_for(const TestMaterial& m) {
  std::vector<NamedDeformation> out = hard_deformations();
  const double a = m.material.alpha();
  out.push_back({"J_equals_alpha", Eigen::Vector3d(1.3, 1.0, a / 1.3).asDiagonal()});
  return out;
}

// The 9x9 Hessian written out from the paper's Eq. 41 (App. D Eq. 65 without
// the barrier), independently of the kernels:
//   mu_T I + 2 b mu / (I_C + 1)^2 f f^T + lambda g g^T + lambda (J - alpha) H_J
// with f = vec F, g = vec(dJ/dF) and H_J the Hessian of det built from the
// cross-product matrices of F's columns (Eqs. 26-29).
inline Matrix9 explicit_hessian(const Eigen::Matrix3d& f, const reference::SnhParameters& p) {
  const double ic = f.squaredNorm(), j = f.determinant();
  const double alpha = p.barrier ? 1.0 + 0.75 * p.mu / p.lambda : 1.0 + p.mu / p.lambda;
  const double mu_t = p.barrier ? p.mu * (1.0 - 1.0 / (ic + 1.0)) : p.mu;
  Eigen::Matrix3d g;
  g.col(0) = f.col(1).cross(f.col(2));
  g.col(1) = f.col(2).cross(f.col(0));
  g.col(2) = f.col(0).cross(f.col(1));
  const Vector9 fv = Eigen::Map<const Vector9>(f.data()), gv = Eigen::Map<const Vector9>(g.data());
  auto hat = [](const Eigen::Vector3d& x) {
    Eigen::Matrix3d m;
    m << 0, -x[2], x[1], x[2], 0, -x[0], -x[1], x[0], 0;
    return m;
  };
  Matrix9 hj = Matrix9::Zero();
  hj.block<3, 3>(0, 3) = -hat(f.col(2));
  hj.block<3, 3>(0, 6) = hat(f.col(1));
  hj.block<3, 3>(3, 0) = hat(f.col(2));
  hj.block<3, 3>(3, 6) = -hat(f.col(0));
  hj.block<3, 3>(6, 0) = -hat(f.col(1));
  hj.block<3, 3>(6, 3) = hat(f.col(0));
  Matrix9 h = mu_t * Matrix9::Identity() + p.lambda * gv * gv.transpose() + p.lambda * (j - alpha) * hj;
  if (p.barrier) h += 2.0 * p.mu / ((ic + 1.0) * (ic + 1.0)) * fv * fv.transpose();
  return h;
}

template <typename Real>
Matrix9 projected_hessian(const Eigen::Matrix3d& f, const reference::SnhParameters& p) {
  Matrix9 h;
  for (int c = 0; c < 9; ++c) {
    reference::Mat3<Real> unit{};
    unit[c] = Real(1);
    const auto column = reference::snh_projected_action<Real>(to_array<Real>(f), unit, p);
    for (int r = 0; r < 9; ++r) h(r, c) = column[r];
  }
  return h;
}

// Sum of eps_k vec(Q_k) vec(Q_k)^T over the closed-form eigensystem.
inline Matrix9 hessian_from_eigensystem(const reference::HessianEigensystem<double>& e) {
  Matrix9 h = Matrix9::Zero();
  for (int k = 0; k < 9; ++k) {
    const Vector9 q = Eigen::Map<const Vector9>(e.vectors[k].data());
    h += e.values[k] * q * q.transpose();
  }
  return h;
}

}  // namespace snh::test
