// The closed-form symmetric 3x3 eigensolver behind the 3x3 block of the
// Hessian: against Eigen, with repeated and zero eigenvalues.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "material/element_reference.h"

namespace snh::test {
namespace {

template <typename Real>
void check_eigen(const Eigen::Matrix3d& a, double tol) {
  const std::array<Real, 6> packed{Real(a(0, 0)), Real(a(0, 1)), Real(a(0, 2)),
                                   Real(a(1, 1)), Real(a(1, 2)), Real(a(2, 2))};
  const auto e = reference::symmetric_eigen<Real>(packed);
  Eigen::Matrix3d q;
  for (int i = 0; i < 9; ++i) q(i) = e.vectors[i];
  const Eigen::Vector3d ref = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(a).eigenvalues();
  const double scale = std::max(a.norm(), 1e-300);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(e.values[i], ref[i], tol * scale) << a;
  EXPECT_LE((q.transpose() * q - Eigen::Matrix3d::Identity()).norm(), tol) << a;
  for (int i = 0; i < 3; ++i) EXPECT_LE((a * q.col(i) - e.values[i] * q.col(i)).norm(), tol * scale) << a;
}

TEST(EigenSym3, RandomAndRepeated) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n = 0; n < 3000; ++n) {
    Eigen::Matrix3d b;
    for (int k = 0; k < 9; ++k) b(k) = u(rng);
    const Eigen::Matrix3d q = Eigen::HouseholderQR<Eigen::Matrix3d>(b).householderQ();
    Eigen::Vector3d values(u(rng), u(rng), u(rng));
    if (n % 4 == 1) values[1] = values[0];                          // double root
    if (n % 4 == 2) values = Eigen::Vector3d::Constant(values[0]);  // triple root
    if (n % 4 == 3) values[2] = values[1] + 1e-9;                   // nearly double
    if (n % 5 == 0) values[0] = 0.0;
    const Eigen::Matrix3d a = q * values.asDiagonal() * q.transpose();
    check_eigen<double>(0.5 * (a + a.transpose()), 1e-12);
    check_eigen<float>(0.5 * (a + a.transpose()), 2e-5);
  }
}

TEST(EigenSym3, DiagonalAndZero) {
  check_eigen<double>(Eigen::Vector3d(3.0, -1.0, 2.0).asDiagonal(), 1e-15);
  check_eigen<double>(Eigen::Matrix3d::Zero(), 1e-15);
  check_eigen<double>(Eigen::Matrix3d::Identity() * 1e-200, 1e-15);
}

}  // namespace
}  // namespace snh::test
