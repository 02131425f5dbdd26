// Finite-difference sweeps (step 1e-4 ... 1e-9, best relative error, as in
// HOBAK's tests): PK1 against psi, Hessian against PK1, over the hard set.
#include <gtest/gtest.h>

#include "support/snh_test_support.h"

namespace snh::test {
namespace {

constexpr double kSteps[] = {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9};

double relative(double diff, double norm, double floor) { return diff / std::max(norm, floor); }

TEST(SnhDerivatives, Pk1MatchesEnergyGradient) {
  for (const TestMaterial& m : test_materials()) {
    for (const NamedDeformation& d : deformations_for(m)) {
      SCOPED_TRACE(m.name + " / " + d.name);
      const auto p = reference::snh_pk1<double>(to_array<double>(d.F), m.params());
      const Eigen::Matrix3d analytic = to_eigen(p);
      double best = 1e300;
      for (double h : kSteps) {
        Eigen::Matrix3d fd;
        for (int i = 0; i < 9; ++i) {
          Eigen::Matrix3d plus = d.F, minus = d.F;
          plus(i) += h;
          minus(i) -= h;
          fd(i) = (reference::snh_energy<double>(to_array<double>(plus), m.params()) -
                   reference::snh_energy<double>(to_array<double>(minus), m.params())) /
                  (2.0 * h);
        }
        best = std::min(best, relative((fd - analytic).norm(), analytic.norm(), m.material.mu));
      }
      EXPECT_LT(best, 1e-6);
    }
  }
}

TEST(SnhDerivatives, HessianMatchesPk1Gradient) {
  for (const TestMaterial& m : test_materials()) {
    for (const NamedDeformation& d : deformations_for(m)) {
      SCOPED_TRACE(m.name + " / " + d.name);
      const Matrix9 closed_form =
          hessian_from_eigensystem(reference::snh_hessian_eigensystem<double>(to_array<double>(d.F), m.params()));
      const Matrix9 written_out = explicit_hessian(d.F, m.params());
      double best_closed = 1e300, best_written = 1e300;
      for (double h : kSteps) {
        Matrix9 fd;
        for (int c = 0; c < 9; ++c) {
          Eigen::Matrix3d plus = d.F, minus = d.F;
          plus(c) += h;
          minus(c) -= h;
          const Eigen::Matrix3d dp = to_eigen(reference::snh_pk1<double>(to_array<double>(plus), m.params())) -
                                     to_eigen(reference::snh_pk1<double>(to_array<double>(minus), m.params()));
          fd.col(c) = Eigen::Map<const Vector9>(dp.data()) / (2.0 * h);
        }
        best_closed = std::min(best_closed, relative((fd - closed_form).norm(), closed_form.norm(), m.material.mu));
        best_written = std::min(best_written, relative((fd - written_out).norm(), written_out.norm(), m.material.mu));
      }
      EXPECT_LT(best_closed, 1e-6);
      EXPECT_LT(best_written, 1e-6);
    }
  }
}

TEST(SnhDerivatives, EnergyAndStressVanishAtRest) {
  for (const TestMaterial& m : test_materials()) {
    SCOPED_TRACE(m.name);
    const auto identity = to_array<double>(Eigen::Matrix3d::Identity());
    EXPECT_EQ(reference::snh_energy<double>(identity, m.params()), 0.0);
    EXPECT_LE(to_eigen(reference::snh_pk1<double>(identity, m.params())).norm(), 1e-15 * m.material.lambda);
  }
}

}  // namespace
}  // namespace snh::test
