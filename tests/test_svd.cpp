// Rotation-variant SVD: F = U diag(sigma) V^T, U and V rotations,
// sigma0 >= sigma1 >= |sigma2|, sign(sigma2) = sign(det F).
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <random>

#include "material/element_reference.h"
#include "support/hard_deformations.h"

namespace snh::test {
namespace {

template <typename Real>
void check_svd(const NamedDeformation& d, double tol) {
  SCOPED_TRACE(d.name);
  const Eigen::Matrix3d f = to_eigen(to_array<Real>(d.F));  // F as the precision sees it
  const auto svd = reference::svd_rotation_variant<Real>(to_array<Real>(d.F));
  const Eigen::Matrix3d u = to_eigen(svd.u), v = to_eigen(svd.v);
  const Eigen::Vector3d s(svd.sigma[0], svd.sigma[1], svd.sigma[2]);
  const double scale = std::max(f.norm(), 1e-300);
  EXPECT_LE((u * s.asDiagonal() * v.transpose() - f).norm(), tol * scale);
  EXPECT_LE((u.transpose() * u - Eigen::Matrix3d::Identity()).norm(), tol);
  EXPECT_LE((v.transpose() * v - Eigen::Matrix3d::Identity()).norm(), tol);
  EXPECT_NEAR(u.determinant(), 1.0, tol);
  EXPECT_NEAR(v.determinant(), 1.0, tol);
  // Ordered up to rounding: equal singular values may come out an ulp apart.
  EXPECT_GE(s[0], s[1] - tol * scale);
  EXPECT_GE(s[1], std::abs(s[2]) - tol * scale);
  EXPECT_GE(s[1], 0.0);
  // Singular values agree with Eigen's (unsigned) ones.
  const Eigen::Vector3d ref = Eigen::JacobiSVD<Eigen::Matrix3d>(f).singularValues();
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(std::abs(s[i]), ref[i], tol * scale);
  if (std::abs(f.determinant()) > tol * scale * scale * scale) {
    EXPECT_EQ(s[2] < 0, f.determinant() < 0);
  }
}

TEST(Svd, HardDeformationsDouble) {
  for (const auto& d : hard_deformations()) check_svd<double>(d, 1e-13);
}

TEST(Svd, HardDeformationsFloat) {
  for (const auto& d : hard_deformations()) check_svd<float>(d, 2e-6);
}

TEST(Svd, ManyRandomMatricesIncludingNearSingular) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n = 0; n < 2000; ++n) {
    Eigen::Matrix3d f;
    for (int k = 0; k < 9; ++k) f(k) = u(rng);
    if (n % 3 == 0) f.col(2) = 0.5 * f.col(0) - 0.25 * f.col(1) + 1e-9 * f.col(2);  // nearly rank two
    if (n % 5 == 0) f *= 1e3;
    check_svd<double>({"random", f}, 1e-12);
    check_svd<float>({"random", f}, 4e-6);
  }
}

// The fixed sweep count (math/svd3.h) against extreme spectra: singular
// values log-uniform over 1e-12..1e2 with either sign of det, repeated
// (a, a, a), (a, a, b), (a, a, -a), one tiny singular value, and F = I + 1e-6 X.
// Bounds: about twice the worst errors measured over 10^5 such F per family
// with the data-dependent loop the fixed sweeps replaced (in parentheses,
// then the closed-form rotations' over 6 x 10^5 F): reconstruction
// / |F| double 4e-15 (1.8e-15; 2.09e-15), float 2e-6 (9.2e-7; 1.05e-6);
// orthogonality double 5e-15 (2.6e-15; 2.71e-15), float 2.5e-6 (1.24e-6;
// 1.37e-6); singular values / |F| against Eigen in long double, double 2e-15
// (1.0e-15; 1.2e-15), float 1.2e-6 (5.4e-7; 5.6e-7).
template <typename Real>
void check_svd_extreme(const Eigen::Matrix3d& fd, double recon_tol, double orth_tol, double sigma_tol) {
  const auto svd = reference::svd_rotation_variant<Real>(to_array<Real>(fd));
  const Eigen::Matrix3d f = to_eigen(to_array<Real>(fd));
  const Eigen::Matrix3d u = to_eigen(svd.u), v = to_eigen(svd.v);
  const Eigen::Vector3d s(svd.sigma[0], svd.sigma[1], svd.sigma[2]);
  const double scale = std::max(f.norm(), 1e-300);
  EXPECT_LE((u * s.asDiagonal() * v.transpose() - f).norm(), recon_tol * scale);
  EXPECT_LE((u.transpose() * u - Eigen::Matrix3d::Identity()).norm(), orth_tol);
  EXPECT_LE((v.transpose() * v - Eigen::Matrix3d::Identity()).norm(), orth_tol);
  EXPECT_GT(u.determinant(), 0.0);
  EXPECT_GT(v.determinant(), 0.0);
  const Eigen::Matrix<long double, 3, 1> ref =
      Eigen::JacobiSVD<Eigen::Matrix<long double, 3, 3>>(f.cast<long double>()).singularValues();
  for (int i = 0; i < 3; ++i) EXPECT_LE(std::abs(std::abs(s[i]) - static_cast<double>(ref[i])), sigma_tol * scale);
}

TEST(Svd, FixedSweepsOnExtremeSpectra) {
  std::mt19937_64 rng(2011);
  std::uniform_real_distribution<double> u(-1.0, 1.0), exponent(-12.0, 2.0);
  for (int n = 0; n < 4000; ++n) {
    Eigen::Vector3d s;
    const double a = 1.5 + u(rng);
    switch (n % 6) {
      case 0:
        s = {std::pow(10.0, exponent(rng)), std::pow(10.0, exponent(rng)),
             (u(rng) < 0 ? -1.0 : 1.0) * std::pow(10.0, exponent(rng))};
        break;
      case 1:
        s = {a, a, a};
        break;
      case 2:
        s = {a, a, 0.3};
        break;
      case 3:
        s = {a, a, -a};
        break;
      case 4:
        s = {1.0 + 0.5 * u(rng), 1.0 + 0.5 * u(rng), std::pow(10.0, exponent(rng))};
        break;
      default:
        s = {0.0, 0.0, 0.0};
        break;
    }
    Eigen::Matrix3d f = random_rotation(rng) * s.asDiagonal() * random_rotation(rng).transpose();
    if (n % 6 == 5) {
      for (int k = 0; k < 9; ++k) f(k) = 1e-6 * u(rng);
      f += Eigen::Matrix3d::Identity();
    }
    SCOPED_TRACE(n);
    check_svd_extreme<double>(f, 4e-15, 5e-15, 2e-15);
    check_svd_extreme<float>(f, 2e-6, 2.5e-6, 1.2e-6);
  }
}

// The exact power-of-two scale of the Jacobi rotations (snh_pow2_inverse):
// m times it lies in [1, 2), for m over every binade of normal numbers.
template <typename Real>
void check_pow2_inverse() {
  std::mt19937_64 rng(24);
  std::uniform_real_distribution<double> mantissa(1.0, 2.0);
  const int low = std::numeric_limits<Real>::min_exponent - 1, high = std::numeric_limits<Real>::max_exponent - 2;
  for (int e = low; e <= high; ++e)
    for (int n = 0; n < 20; ++n) {
      const Real below_two = std::nextafter(Real(2), Real(1));
      const Real x = n == 0 ? Real(1) : n == 1 ? below_two : std::min(static_cast<Real>(mantissa(rng)), below_two);
      const Real m = std::ldexp(x, e);
      const Real k = reference::pow2_inverse<Real>(m);
      ASSERT_EQ(k, std::ldexp(Real(1), -e)) << m;
      const Real scaled = m * k;
      EXPECT_GE(scaled, Real(1));
      EXPECT_LT(scaled, Real(2));
      EXPECT_EQ(std::ldexp(scaled, e), m);  // exact
    }
}

TEST(Svd, PowerOfTwoScaleIsExact) {
  check_pow2_inverse<double>();
  check_pow2_inverse<float>();
}

TEST(Svd, NonFiniteInputTerminates) {
  std::array<double, 9> f{};
  f[4] = std::numeric_limits<double>::quiet_NaN();
  const auto svd = reference::svd_rotation_variant<double>(f);
  EXPECT_FALSE(std::isfinite(svd.sigma[0]) && std::isfinite(svd.sigma[1]) && std::isfinite(svd.sigma[2]));
}

}  // namespace
}  // namespace snh::test
