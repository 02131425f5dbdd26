// The SVD's early stop (kernels/math/svd3.h, SNH_SVD_EARLY_EXIT): stopping
// before a sweep that would change nothing gives the values of the fixed
// SNH_SVD_SWEEPS sweeps. Both builds of the kernels' source in float, where
// the host and the devices' lanes programs stop early, on the hard, random
// and extreme-spectrum matrices of test_svd.cpp and non-finite ones. On the
// device PointLanes.FloatMatchesTheScalarKernels compares the lanes
// programs with pocl's scalar kernels, which do not stop early.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <limits>
#include <random>

#include "hard_deformations.h"

#define SNH_DOUBLE 0
// mat3 in `sweeps`, the two builds of the SVD beside each other in nested
// namespaces (which see mat3, and which argument-dependent lookup of a
// mat3 does not search).
namespace sweeps {
#include "math/mat3.h"
namespace early {
#include "math/svd3.h"
static_assert(SNH_SVD_EARLY_EXIT == 1, "the host stops early in float");
}  // namespace early
namespace fixed {
#undef SNH_SVD3_H
#undef SNH_SVD_EARLY_EXIT
#define SNH_SVD_EARLY_EXIT 0
#include "math/svd3.h"
}  // namespace fixed
}  // namespace sweeps

namespace snh::test {
namespace {

sweeps::mat3 to_mat3(const Eigen::Matrix3d& f) {
  sweeps::mat3 m;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) M3(m, r, c) = static_cast<float>(f(r, c));
  return m;
}

// Same values (== : a zero's sign aside), or NaN in both.
void expect_same(float early, float fixed, const char* what, int i) {
  if (std::isnan(fixed)) {
    EXPECT_TRUE(std::isnan(early)) << what << ' ' << i;
  } else {
    EXPECT_EQ(early, fixed) << what << ' ' << i;
  }
}

void check_same(const Eigen::Matrix3d& f) {
  sweeps::mat3 u0, v0, u1, v1;
  sweeps::vec3 s0, s1;
  sweeps::early::svd3_rv(to_mat3(f), &u0, &s0, &v0);
  sweeps::fixed::svd3_rv(to_mat3(f), &u1, &s1, &v1);
  for (int i = 0; i < 9; ++i) {
    expect_same(u0.a[i], u1.a[i], "U", i);
    expect_same(v0.a[i], v1.a[i], "V", i);
  }
  for (int i = 0; i < 3; ++i) expect_same(s0.a[i], s1.a[i], "sigma", i);
}

TEST(SvdSweeps, EarlyStopGivesTheFixedSweepsValues) {
  for (const NamedDeformation& d : hard_deformations()) {
    SCOPED_TRACE(d.name);
    check_same(d.F);
  }
  // Non-finite entries: every sweep spreads them, so none is left out.
  for (int k = 0; k < 9; ++k) {
    Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
    f(k) = k % 2 ? std::numeric_limits<double>::infinity() : std::numeric_limits<double>::quiet_NaN();
    check_same(f);
  }
  std::mt19937_64 rng(2011);
  std::uniform_real_distribution<double> u(-1.0, 1.0), exponent(-12.0, 2.0);
  for (int n = 0; n < 6000; ++n) {
    SCOPED_TRACE(n);
    Eigen::Matrix3d f;
    if (n % 3 == 0) {  // random, nearly rank two, scaled
      for (int k = 0; k < 9; ++k) f(k) = u(rng);
      if (n % 9 == 0) f.col(2) = 0.5 * f.col(0) - 0.25 * f.col(1) + 1e-9 * f.col(2);
      if (n % 5 == 0) f *= 1e3;
    } else if (n % 3 == 1) {  // log-uniform spectra, either sign of det
      const Eigen::Vector3d s(std::pow(10.0, exponent(rng)), std::pow(10.0, exponent(rng)),
                              (u(rng) < 0 ? -1.0 : 1.0) * std::pow(10.0, exponent(rng)));
      f = random_rotation(rng) * s.asDiagonal() * random_rotation(rng).transpose();
    } else {  // near the identity and repeated singular values
      const double a = 1.5 + u(rng);
      f = random_rotation(rng) * Eigen::Vector3d(a, a, n % 2 ? a : -a).asDiagonal() * random_rotation(rng).transpose();
      if (n % 4 == 2) {
        for (int k = 0; k < 9; ++k) f(k) = 1e-6 * u(rng);
        f += Eigen::Matrix3d::Identity();
      }
    }
    check_same(f);
  }
}

}  // namespace
}  // namespace snh::test
