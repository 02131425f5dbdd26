// Device reductions (solver/device_reduction.h): the Newton loop's energies,
// norms and dot products summed on the device in a fixed order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "device_test_support.h"
#include "solver/device_reduction.h"

namespace snh::test {
namespace {

template <typename Real>
void check_against_host(Precision precision) {
  device::OpenClContext& cl = device_for(precision);
  solver::DeviceReduction reduction(cl, sizeof(Real), nullptr);
  ASSERT_TRUE(reduction.on_device());  // pocl and the GPUs measured have fp64
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // Sizes around the span of 4,096 entries per work-group, and one not a
  // multiple of the group.
  for (size_t n : {size_t(1), size_t(63), size_t(4096), size_t(4097), size_t(100003)}) {
    std::vector<Real> a(n), b(n);
    for (size_t i = 0; i < n; ++i) {
      a[i] = static_cast<Real>(u(rng));
      b[i] = static_cast<Real>(u(rng) + 0.5);
    }
    device::Buffer da = cl.buffer(CL_MEM_READ_WRITE, n * sizeof(Real), a.data());
    device::Buffer db = cl.buffer(CL_MEM_READ_WRITE, n * sizeof(Real), b.data());
    // Reference sums in long double (64-bit mantissa on x86): exact to far
    // below the bound.
    long double sum = 0, squares = 0, dot = 0;
    double absolute = 0.0, absolute_dot = 0.0;
    double least = static_cast<double>(a[0]);
    for (size_t i = 0; i < n; ++i) {
      const double x = a[i], y = b[i];
      sum += x;
      squares += static_cast<long double>(x) * x;
      dot += static_cast<long double>(x) * y;
      absolute += std::abs(x);
      absolute_dot += std::abs(x * y);
      least = std::min(least, x);
    }
    // Each term reaches the total through at most 64 sequential additions in
    // a work-item, a tree of 6 in the work-group and one per work-group on
    // the host: |error| <= (70 + groups) eps sum |terms| (Higham, 2002, 4.2).
    const double groups = std::ceil(static_cast<double>(n) / 4096.0);
    const double bound = (70.0 + groups) * std::numeric_limits<double>::epsilon();
    EXPECT_NEAR(reduction.sum(da.get(), n), static_cast<double>(sum), bound * absolute) << n;
    EXPECT_NEAR(reduction.sum_of_squares(da.get(), n), static_cast<double>(squares),
                bound * static_cast<double>(squares))
        << n;
    EXPECT_NEAR(reduction.dot(da.get(), db.get(), n), static_cast<double>(dot), bound * absolute_dot) << n;
    EXPECT_EQ(reduction.min(da.get(), n), least) << n;
    // Deterministic: the same input gives bitwise the same result.
    EXPECT_EQ(reduction.dot(da.get(), db.get(), n), reduction.dot(da.get(), db.get(), n)) << n;
    // A prefix: entries past n are not read.
    if (n > 1) {
      long double prefix = 0;
      for (size_t i = 0; i + 1 < n; ++i) prefix += static_cast<double>(a[i]);
      EXPECT_NEAR(reduction.sum(da.get(), n - 1), static_cast<double>(prefix), bound * absolute) << n;
    }
  }
  EXPECT_EQ(reduction.sum(nullptr, 0), 0.0);
}

TEST(DeviceReduction, MatchesTheHostSumInDoubleAndFloat) {
  check_against_host<double>(Precision::double_);
  check_against_host<float>(Precision::single);
}

TEST(DeviceReduction, NonFiniteEntriesReachTheSum) {
  device::OpenClContext& cl = device_for(Precision::double_);
  solver::DeviceReduction reduction(cl, sizeof(double), nullptr);
  std::vector<double> a(10000, 1.0);
  a[5000] = std::numeric_limits<double>::quiet_NaN();
  device::Buffer da = cl.buffer(CL_MEM_READ_WRITE, a.size() * sizeof(double), a.data());
  EXPECT_TRUE(std::isnan(reduction.sum_of_squares(da.get(), a.size())));
  a[5000] = std::numeric_limits<double>::infinity();
  cl.write(da.get(), a.size() * sizeof(double), a.data());
  EXPECT_TRUE(std::isinf(reduction.sum(da.get(), a.size())));
}

}  // namespace
}  // namespace snh::test
