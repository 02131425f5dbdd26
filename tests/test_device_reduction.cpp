// Device reductions (solver/linear/device_reduction.h): the Newton loop's energies,
// norms and dot products summed on the device in a fixed order. And
// ViennaCL's element-wise vector kernels (CG's updates) at the work-group
// sizes device/viennacl_binding.h sets on CPU devices: the same values as
// at ViennaCL's own.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "solver/linear/device_reduction.h"
#include "solver/model/vertex_terms.h"
#include "support/device_test_support.h"
#include "viennacl/linalg/opencl/kernels/vector.hpp"

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

// Implicit Euler's inertia energy 1/2 sum_v c_v |x_v - y_v|^2 reduced on the
// device (VertexTerms::queue_inertia_energy) is the host's sum
// (add_inertia_energy) within the reordering's rounding, bitwise repeatable,
// in double and float models alike (c and y in double on both sides).
template <typename Real>
void check_inertia_against_host(Precision precision) {
  device::OpenClContext& cl = device_for(precision);
  solver::DeviceReduction reduction(cl, sizeof(Real), nullptr);
  ASSERT_TRUE(reduction.on_device());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // Vertex counts whose 3 n DOFs fall below, on and above one span of 4,096.
  for (size_t vertices : {size_t(5), size_t(1365), size_t(1366), size_t(20011)}) {
    const size_t n = 3 * vertices;
    std::vector<double> c(vertices), y(n);
    std::vector<Real> x(n);
    for (double& v : c) v = 1e3 * (u(rng) + 1.5);
    for (size_t i = 0; i < n; ++i) {
      y[i] = u(rng);
      x[i] = static_cast<Real>(y[i] + 1e-3 * u(rng));
    }
    solver::VertexTerms<Real> terms(cl, vertices, true, 0, false, device::KernelConfig{}, nullptr);
    terms.set_inertia(c, y);
    device::Buffer dx = cl.buffer(CL_MEM_READ_WRITE, n * sizeof(Real), x.data());
    double host = 0.0;
    terms.add_inertia_energy(x, host);
    long double exact = 0;
    for (size_t i = 0; i < n; ++i) {
      const long double d = static_cast<long double>(x[i]) - y[i];
      exact += 0.5L * c[i / 3] * d * d;
    }
    terms.queue_inertia_energy(reduction, dx.get(), 0);
    const double device = reduction.read_totals(1)[0];
    terms.queue_inertia_energy(reduction, dx.get(), 1);
    EXPECT_EQ(reduction.read_totals(2)[1], device) << vertices;
    // Positive terms: each within (70 + groups) eps of the sum after the
    // per-term rounding (a few eps), as in check_against_host.
    const double groups = std::ceil(static_cast<double>(n) / 4096.0);
    const double bound = (75.0 + groups) * std::numeric_limits<double>::epsilon() * static_cast<double>(exact);
    EXPECT_NEAR(device, static_cast<double>(exact), bound) << vertices;
    EXPECT_NEAR(host, static_cast<double>(exact), 1.0 * n * std::numeric_limits<double>::epsilon() * exact) << vertices;
    EXPECT_GT(device, 0.0);
  }
}

TEST(DeviceReduction, InertiaEnergyMatchesTheHostSum) {
  check_inertia_against_host<double>(Precision::double_);
  check_inertia_against_host<float>(Precision::single);
}

// CG's updates (x += a p, r -= a q, p = z + b p) and a copy, in ViennaCL's
// own kernels.
std::vector<double> cg_updates(const viennacl::vector<double>& p, const viennacl::vector<double>& q,
                               const viennacl::vector<double>& z) {
  viennacl::vector<double> x = z, r = q, w = p;
  x += 0.37 * w;
  r -= 1.3 * q;
  w = z + 0.61 * w;
  x = x + 0.5 * r;
  x -= w;
  const std::vector<double> hx = download(x), hr = download(r), hw = download(w);
  std::vector<double> out(hx);
  out.insert(out.end(), hr.begin(), hr.end());
  out.insert(out.end(), hw.begin(), hw.end());
  return out;
}

TEST(ViennaclVectorKernels, WorkGroupsFollowTheSizeAndKeepTheValues) {
  const device::OpenClContext& cl = device_for(Precision::double_);
  const bool gpu = cl.info().is_gpu;
  using Kernels = viennacl::linalg::opencl::kernels::vector<double>;
  viennacl::ocl::context& ctx = viennacl::ocl::current_context();
  // Below 16 x 512 entries ViennaCL's own size (1 on CPUs), then the
  // largest power of two up to size / 512 (GPUs: ViennaCL's, untouched).
  const std::vector<std::pair<size_t, size_t>> expected = {{2154, 1},   {8191, 1},     {8192, 16},
                                                           {20000, 32}, {107811, 128}, {300000, 512}};
  for (const auto& [size, local] : expected) {
    const size_t set = device::tune_viennacl_vector_kernels<double>(size);
    EXPECT_EQ(set, gpu ? 0u : local) << size;
    if (!gpu) {
      EXPECT_EQ(ctx.get_program(Kernels::program_name()).get_kernel("avbv_v_cpu_cpu").local_work_size(), local) << size;
    }
  }
  EXPECT_LE(device::tune_viennacl_vector_kernels<double>(size_t(1) << 26), gpu ? 0u : 4096u);
  // The same values at ViennaCL's sizes and at the tuned ones, at a size
  // that is no multiple of the group and spans many groups.
  const size_t n = 300007;
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> hp(n), hq(n), hz(n);
  for (size_t i = 0; i < n; ++i) {
    hp[i] = u(rng);
    hq[i] = u(rng);
    hz[i] = u(rng);
  }
  const viennacl::vector<double> p = upload<double>(hp), q = upload<double>(hq), z = upload<double>(hz);
  device::tune_viennacl_vector_kernels<double>(1);
  const std::vector<double> reference = cg_updates(p, q, z);
  EXPECT_EQ(device::tune_viennacl_vector_kernels<double>(n), gpu ? 0u : 512u);
  const std::vector<double> tuned = cg_updates(p, q, z);
  ASSERT_EQ(tuned.size(), reference.size());
  size_t differ = 0;
  for (size_t i = 0; i < tuned.size(); ++i) differ += tuned[i] != reference[i];
  EXPECT_EQ(differ, 0u);
  // And what those updates are: x = (z + 0.37 p) + 0.5 (q - 1.3 q) - (z + 0.61 p), entry 0 and the last.
  for (size_t i : {size_t(0), n - 1}) {
    const double w = hz[i] + 0.61 * hp[i], r = hq[i] - 1.3 * hq[i];
    EXPECT_NEAR(tuned[i], (hz[i] + 0.37 * hp[i]) + 0.5 * r - w, 1e-14);
    EXPECT_NEAR(tuned[n + i], r, 1e-15);
    EXPECT_NEAR(tuned[2 * n + i], w, 1e-15);
  }
  device::tune_viennacl_vector_kernels<double>(1);
}

}  // namespace
}  // namespace snh::test
