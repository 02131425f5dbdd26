// Rotation-variant SVD: F = U diag(sigma) V^T, U and V rotations,
// sigma0 >= sigma1 >= |sigma2|, sign(sigma2) = sign(det F).
#include <gtest/gtest.h>

#include <cfloat>

#include "hard_deformations.h"
#include "reference/element_reference.h"

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

TEST(Svd, NonFiniteInputTerminates) {
  std::array<double, 9> f{};
  f[4] = std::numeric_limits<double>::quiet_NaN();
  const auto svd = reference::svd_rotation_variant<double>(f);
  EXPECT_FALSE(std::isfinite(svd.sigma[0]) && std::isfinite(svd.sigma[1]) && std::isfinite(svd.sigma[2]));
}

}  // namespace
}  // namespace snh::test
