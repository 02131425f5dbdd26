// The closed-form eigensystem (Eqs. 42-48, App. A, App. D) against Eigen's
// SelfAdjointEigenSolver of the written-out 9x9 Hessian; the projected action
// against the numerical eigen-clamp; linear elasticity at rest; invariance
// under the SVD's reflection convention; no NaN for finite F.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>

#include "support/snh_test_support.h"

namespace snh::test {
namespace {

TEST(SnhEigensystem, MatchesNumericalEigendecomposition) {
  for (const TestMaterial& m : test_materials()) {
    for (const NamedDeformation& d : deformations_for(m)) {
      SCOPED_TRACE(m.name + " / " + d.name);
      const Matrix9 h = explicit_hessian(d.F, m.params());
      const double scale = std::max(h.norm(), m.material.mu);
      const auto e = reference::snh_hessian_eigensystem<double>(to_array<double>(d.F), m.params());
      std::array<double, 9> sorted = e.values;
      std::sort(sorted.begin(), sorted.end());
      const Eigen::SelfAdjointEigenSolver<Matrix9> numeric(h);
      for (int k = 0; k < 9; ++k) EXPECT_NEAR(sorted[k], numeric.eigenvalues()[k], 1e-12 * scale) << k;
      Eigen::Matrix<double, 9, 9> q;
      for (int k = 0; k < 9; ++k) q.col(k) = Eigen::Map<const Vector9>(e.vectors[k].data());
      EXPECT_LE((q.transpose() * q - Matrix9::Identity()).norm(), 1e-12);
      for (int k = 0; k < 9; ++k) EXPECT_LE((h * q.col(k) - e.values[k] * q.col(k)).norm(), 1e-12 * scale) << k;
    }
  }
}

TEST(SnhEigensystem, ProjectedActionEqualsNumericalClamp) {
  for (const TestMaterial& m : test_materials()) {
    for (const NamedDeformation& d : deformations_for(m)) {
      SCOPED_TRACE(m.name + " / " + d.name);
      const Matrix9 h = explicit_hessian(d.F, m.params());
      const Eigen::SelfAdjointEigenSolver<Matrix9> numeric(h);
      const Matrix9 clamped = numeric.eigenvectors() * numeric.eigenvalues().cwiseMax(0.0).asDiagonal() *
                              numeric.eigenvectors().transpose();
      const double scale = std::max(h.norm(), m.material.mu);
      EXPECT_LE((projected_hessian<double>(d.F, m.params()) - clamped).norm(), 1e-12 * scale);
    }
  }
}

// Eq. 42-43 (App. D: Eq. 66): the block's eigenvalues are mu_T plus
// lambda (J - alpha) times the roots of the paper's cubic. Checks our
// re-derivation by comparing the cubic's coefficients with the symmetric
// functions of our roots (well conditioned even for repeated roots, where
// solving the cubic itself is not). The extracted text's c2 reads
// "-|g|^2 rho - 2 I_C eta"; the symbolic characteristic polynomial of
// eta s s^T + rho g g^T + H_J gives -|g|^2 rho - I_C eta, used here.
TEST(SnhEigensystem, BlockEigenvaluesAreRootsOfPaperCubic) {
  for (const TestMaterial& m : test_materials()) {
    for (const NamedDeformation& d : hard_deformations()) {
      SCOPED_TRACE(m.name + " / " + d.name);
      const auto p = m.params();
      const auto svd = reference::svd_rotation_variant<double>(to_array<double>(d.F));
      const double s0 = svd.sigma[0], s1 = svd.sigma[1], s2 = svd.sigma[2];
      const double ic = s0 * s0 + s1 * s1 + s2 * s2, j = s0 * s1 * s2;
      const double g2 = s1 * s1 * s2 * s2 + s0 * s0 * s2 * s2 + s0 * s0 * s1 * s1;
      const double alpha = m.material.alpha();
      const double denom = p.lambda * (j - alpha);  // lambda (J - 1) - 3 mu / 4 with the barrier
      if (std::abs(denom) < 1e-3 * p.lambda) continue;
      const double eta = p.barrier ? 2.0 * p.mu / ((ic + 1.0) * (ic + 1.0) * denom) : 0.0;
      const double rho = p.lambda / denom;
      const double c2 = -g2 * rho - ic * eta;
      const double c1 = -(1.0 + 2.0 * j * rho) * ic - 6.0 * j * eta + (g2 * ic - 9.0 * j * j) * rho * eta;
      const double c0 =
          -(2.0 + 3.0 * j * rho) * j + (ic * ic - 4.0 * g2) * eta + 2.0 * j * (ic * ic - 3.0 * g2) * rho * eta;
      const double mu_t = p.barrier ? p.mu * (1.0 - 1.0 / (ic + 1.0)) : p.mu;
      const auto e = reference::snh_hessian_eigensystem<double>(to_array<double>(d.F), p);
      double r[3];
      for (int k = 0; k < 3; ++k) r[k] = (e.values[k] - mu_t) / denom;  // Eq. 45 inverted
      const double big = 1.0 + std::max({std::abs(r[0]), std::abs(r[1]), std::abs(r[2])});
      const double tol = 1e-11 * (1.0 + p.lambda / p.mu);
      EXPECT_NEAR(c2, -(r[0] + r[1] + r[2]), tol * big);
      EXPECT_NEAR(c1, r[0] * r[1] + r[0] * r[2] + r[1] * r[2], tol * big * big);
      EXPECT_NEAR(c0, -r[0] * r[1] * r[2], tol * big * big * big);
      // Twists and flips, Eqs. 46-48: mu_T +- lambda (J - alpha) sigma_k.
      const double scale = std::max(explicit_hessian(d.F, p).norm(), p.mu);
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(e.values[3 + k], mu_t + denom * svd.sigma[k], 1e-12 * scale);
        EXPECT_NEAR(e.values[6 + k], mu_t - denom * svd.sigma[k], 1e-12 * scale);
      }
    }
  }
}

TEST(SnhEigensystem, RestHessianIsLinearElasticity) {
  for (const TestMaterial& m : test_materials()) {
    SCOPED_TRACE(m.name);
    const LameParameters lame = m.material.lame();
    Matrix9 c = Matrix9::Zero();  // dP_ij = C_ijkl dF_kl at vec indices (3j + i, 3l + k)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l)
            c(3 * j + i, 3 * l + k) =
                lame.lambda * (i == j) * (k == l) + lame.mu * ((i == k) * (j == l) + (i == l) * (j == k));
    const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
    const double scale = c.norm();
    EXPECT_LE((explicit_hessian(identity, m.params()) - c).norm(), 1e-13 * scale);
    EXPECT_LE(
        (hessian_from_eigensystem(reference::snh_hessian_eigensystem<double>(to_array<double>(identity), m.params())) -
         c)
            .norm(),
        1e-13 * scale);
    EXPECT_LE((projected_hessian<double>(identity, m.params()) - c).norm(), 1e-13 * scale);
  }
}

TEST(SnhEigensystem, IndependentOfReflectionConvention) {
  for (const TestMaterial& m : test_materials()) {
    for (const NamedDeformation& d : deformations_for(m)) {
      SCOPED_TRACE(m.name + " / " + d.name);
      const auto svd = reference::svd_rotation_variant<double>(to_array<double>(d.F));
      // The same F with U still a rotation but the signs moved: U diag(-1, 1, -1)
      // puts the reflection on sigma0, U diag(-1, -1, 1) negates sigma0 and
      // sigma1 as well. (Formulas in J = sigma0 sigma1 sigma2 need det U det V
      // = 1, so a reflection kept in U is not a valid input.)
      reference::Svd<double> moved = svd, negated = svd;
      for (int r = 0; r < 3; ++r) {
        moved.u[r] = -svd.u[r];
        moved.u[6 + r] = -svd.u[6 + r];
        negated.u[r] = -svd.u[r];
        negated.u[3 + r] = -svd.u[3 + r];
      }
      moved.sigma = {-svd.sigma[0], svd.sigma[1], -svd.sigma[2]};
      negated.sigma = {-svd.sigma[0], -svd.sigma[1], svd.sigma[2]};
      const double scale = std::max(explicit_hessian(d.F, m.params()).norm(), m.material.mu);
      for (int c = 0; c < 9; ++c) {
        reference::Mat3<double> unit{};
        unit[c] = 1.0;
        const Eigen::Matrix3d base = to_eigen(reference::snh_projected_action_from_svd<double>(svd, unit, m.params()));
        EXPECT_LE((to_eigen(reference::snh_projected_action_from_svd<double>(moved, unit, m.params())) - base).norm(),
                  1e-12 * scale);
        EXPECT_LE((to_eigen(reference::snh_projected_action_from_svd<double>(negated, unit, m.params())) - base).norm(),
                  1e-12 * scale);
      }
    }
  }
}

template <typename Real>
void expect_all_finite(const Eigen::Matrix3d& f, const reference::SnhParameters& p) {
  const auto a = to_array<Real>(f);
  EXPECT_TRUE(std::isfinite(reference::snh_energy<Real>(a, p)));
  for (Real x : reference::snh_pk1<Real>(a, p)) EXPECT_TRUE(std::isfinite(x));
  const auto e = reference::snh_hessian_eigensystem<Real>(a, p);
  for (Real x : e.values) EXPECT_TRUE(std::isfinite(x));
  for (const auto& q : e.vectors)
    for (Real x : q) EXPECT_TRUE(std::isfinite(x));
  const Matrix9 h = projected_hessian<Real>(f, p);
  EXPECT_TRUE(h.allFinite());
}

TEST(SnhEigensystem, NoNanOrInfForFiniteF) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0), exponent(-12.0, 2.0);
  for (const TestMaterial& m : test_materials()) {
    SCOPED_TRACE(m.name);
    for (const NamedDeformation& d : deformations_for(m)) {
      expect_all_finite<double>(d.F, m.params());
      expect_all_finite<float>(d.F, m.params());
    }
    for (int n = 0; n < 500; ++n) {
      Eigen::Matrix3d f;
      const double scale = std::pow(10.0, exponent(rng));
      for (int k = 0; k < 9; ++k) f(k) = scale * u(rng);
      if (n % 3 == 0) f.col(n % 9 / 3).setZero();
      expect_all_finite<double>(f, m.params());
      expect_all_finite<float>(f, m.params());
    }
  }
}

}  // namespace
}  // namespace snh::test
