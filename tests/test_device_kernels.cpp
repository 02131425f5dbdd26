// The OpenCL kernels (pocl in CI) against the host reference compiled from
// the same source: double to ~1e-12 relative, float within the bound below.
#include <gtest/gtest.h>

#include <cfloat>

#include "device/opencl_context.h"
#include "probe/probe_kernel.h"
#include "snh/error.h"
#include "snh/probe.h"
#include "support/snh_test_support.h"

namespace snh::test {
namespace {

// Device against host reference (double), relative to the quantity's norm
// (floored at mu). Double: the same source, rounding alike (no FP
// contraction), so agreement to ~1e-12 is required outright. Float: the
// rounding error of J - alpha and of the SVD is amplified by lambda / mu (the
// volume term dominates as nu -> 0.5), so the documented bound is
//   error <= kFloatUlps * FLT_EPSILON * (1 + lambda / mu)
// over the hard set, measured worst case printed by the test.
constexpr double kDoubleBound = 1e-12;
constexpr double kFloatUlps = 16.0;

double rel(const double* a, const double* b, int n, double floor) {
  double diff = 0.0, norm = 0.0;
  for (int i = 0; i < n; ++i) {
    diff += (a[i] - b[i]) * (a[i] - b[i]);
    norm += b[i] * b[i];
  }
  return std::sqrt(diff) / std::max(std::sqrt(norm), floor);
}

void compare_with_reference(Precision precision) {
  double worst_ulps = 0.0;
  std::string worst_case;
  for (const TestMaterial& m : test_materials()) {
    const std::vector<NamedDeformation> set = deformations_for(m);
    std::vector<Matrix3> fs;
    for (const NamedDeformation& d : set) fs.push_back(to_row_major(d.F));
    MaterialProbe probe(m.material, precision);
    const std::vector<ProbeResult> results = probe.evaluate(fs);
    ASSERT_EQ(results.size(), fs.size());
    const double conditioning = 1.0 + m.material.lambda / m.material.mu;
    const double bound = precision == Precision::double_ ? kDoubleBound : kFloatUlps * FLT_EPSILON * conditioning;
    for (size_t n = 0; n < set.size(); ++n) {
      const std::string name = m.name + " / " + set[n].name + " / " + to_string(precision);
      SCOPED_TRACE(name);
      const ProbeResult& r = results[n];
      const auto f = to_array<double>(set[n].F);
      std::vector<double> errors;
      const double psi = reference::snh_energy<double>(f, m.params());
      errors.push_back(std::abs(r.psi - psi) / std::max(std::abs(psi), m.material.mu));
      const auto p = reference::snh_pk1<double>(f, m.params());
      errors.push_back(rel(r.P.data(), to_row_major(to_eigen(p)).data(), 9, m.material.mu));
      const Matrix9 h = projected_hessian<double>(set[n].F, m.params());
      errors.push_back(rel(r.H.data(), hessian_row_major(h).data(), 81, m.material.mu));
      auto e = reference::snh_hessian_eigensystem<double>(f, m.params()).values;
      std::sort(e.begin(), e.end());
      const double h_scale = std::max(explicit_hessian(set[n].F, m.params()).norm(), m.material.mu);
      for (int k = 0; k < 9; ++k) errors.push_back(std::abs(r.eigenvalues[k] - e[k]) / h_scale);
      const auto svd = reference::svd_rotation_variant<double>(f);
      for (int k = 0; k < 3; ++k)
        errors.push_back(std::abs(r.sigma[k] - svd.sigma[k]) / std::max(1.0, set[n].F.norm()));
      for (size_t k = 0; k < errors.size(); ++k) {
        EXPECT_LE(errors[k], bound) << "quantity " << k << " (0 psi, 1 P, 2 H, 3-11 eigenvalues, 12-14 sigma)";
        const double ulps = errors[k] / ((precision == Precision::double_ ? DBL_EPSILON : FLT_EPSILON) * conditioning);
        if (ulps > worst_ulps) {
          worst_ulps = ulps;
          worst_case = name + ", quantity " + std::to_string(k);
        }
      }
    }
  }
  std::printf("[ measured ] %s: worst error = %.3g eps (1 + lambda/mu), at %s\n", to_string(precision), worst_ulps,
              worst_case.c_str());
}

TEST(DeviceKernels, DoubleMatchesHostReference) { compare_with_reference(Precision::double_); }

TEST(DeviceKernels, FloatWithinDocumentedBound) { compare_with_reference(Precision::single); }

// The GPUs' build of the kernels (-DSNH_GPU=1, OpenClContext::program: in
// float the SVD's sweeps stop early, kernels/math/svd3.h) gives the values
// of the CPUs' build, whose scalar kernels keep the fixed sweeps: both run
// here on pocl, over the hard set of every test material.
void expect_gpu_build_same(Precision precision) {
  device::OpenClContext cl(DeviceOptions{}, precision);
  for (const TestMaterial& m : test_materials()) {
    std::vector<Matrix3> fs;
    for (const NamedDeformation& d : deformations_for(m)) fs.push_back(to_row_major(d.F));
    const std::vector<ProbeResult> cpu = probe::evaluate(cl, m.material, fs);
    const std::vector<ProbeResult> gpu = probe::evaluate(cl, m.material, fs, true);
    ASSERT_EQ(gpu.size(), cpu.size());
    for (size_t n = 0; n < fs.size(); ++n) {
      SCOPED_TRACE(m.name + " / " + std::to_string(n) + " / " + to_string(precision));
      auto same = [](double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); };
      EXPECT_TRUE(same(gpu[n].psi, cpu[n].psi));
      for (int i = 0; i < 9; ++i) EXPECT_TRUE(same(gpu[n].P[i], cpu[n].P[i])) << "P " << i;
      for (int i = 0; i < 81; ++i) EXPECT_TRUE(same(gpu[n].H[i], cpu[n].H[i])) << "H " << i;
      for (int i = 0; i < 9; ++i) EXPECT_TRUE(same(gpu[n].eigenvalues[i], cpu[n].eigenvalues[i])) << "eigenvalue " << i;
      for (int i = 0; i < 3; ++i) EXPECT_TRUE(same(gpu[n].sigma[i], cpu[n].sigma[i])) << "sigma " << i;
    }
  }
}

TEST(DeviceKernels, GpuBuildGivesTheSameValues) {
  expect_gpu_build_same(Precision::single);
  expect_gpu_build_same(Precision::double_);
}

TEST(DeviceKernels, DeterministicAcrossRuns) {
  const StableNeoHookean material = StableNeoHookean::from_youngs_modulus(1.0, 0.45);
  std::vector<Matrix3> fs;
  for (const NamedDeformation& d : hard_deformations()) fs.push_back(to_row_major(d.F));
  for (Precision precision : {Precision::single, Precision::double_}) {
    MaterialProbe probe(material, precision);
    const auto a = probe.evaluate(fs), b = probe.evaluate(fs);
    for (size_t n = 0; n < fs.size(); ++n) {
      EXPECT_EQ(a[n].H, b[n].H);
      EXPECT_EQ(a[n].P, b[n].P);
    }
  }
}

TEST(DeviceKernels, UnknownDeviceGetsClearError) {
  const StableNeoHookean material = StableNeoHookean::from_youngs_modulus(1.0, 0.45);
  try {
    MaterialProbe probe(material, Precision::double_, DeviceOptions{"no-such-device-xyz"});
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no device matches 'no-such-device-xyz'"), std::string::npos) << e.what();
  }
}

TEST(DeviceKernels, EmptyInputGivesEmptyOutput) {
  MaterialProbe probe(StableNeoHookean::from_youngs_modulus(1.0, 0.3), Precision::double_);
  EXPECT_TRUE(probe.evaluate({}).empty());
}

}  // namespace
}  // namespace snh::test

#include "device/opencl_context.h"

namespace snh::test {
namespace {

TEST(DeviceKernels, AllocationBeyondTheDeviceIsAClearError) {
  device::OpenClContext cl(DeviceOptions{}, Precision::double_);
  cl_ulong largest = 0;
  clGetDeviceInfo(cl.device(), CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof largest, &largest, nullptr);
  try {
    cl.buffer(CL_MEM_READ_WRITE, static_cast<size_t>(largest) * 4);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("clCreateBuffer failed"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("memory"), std::string::npos) << e.what();
  }
}

TEST(DeviceKernels, KernelBuildFailureCarriesBuildLog) {
  device::OpenClContext cl(DeviceOptions{}, Precision::double_);
  try {
    // fem_lanes.cl refuses any width but 8 and 16 (#error).
    device::KernelConfig config;
    config.element = ElementType::hex8;
    config.lanes = 3;
    cl.program("fem_lanes.cl", config);
    ADD_FAILURE() << "expected a build error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("building kernels/fem_lanes.cl"), std::string::npos) << what;
    EXPECT_NE(what.find("-DSNH_LANES=3"), std::string::npos) << what;
    EXPECT_NE(what.find("build log"), std::string::npos) << what;
    EXPECT_NE(what.find("8 or 16"), std::string::npos) << what;  // the #error's text
  }
}

}  // namespace
}  // namespace snh::test
