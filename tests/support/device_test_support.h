// One OpenCL context per precision for the whole test binary (kernels are
// built once per context), each bound to its own ViennaCL context, which the
// call makes current.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "device/opencl_context.h"
#include "device/viennacl_binding.h"
#include "solver/model/elastic_model.h"
#include "support/lattices.h"
#include "viennacl/vector.hpp"

namespace snh::test {

inline device::OpenClContext& device_for(Precision precision) {
  static std::unique_ptr<device::OpenClContext> contexts[2];
  static long ids[2];
  const int k = precision == Precision::double_ ? 1 : 0;
  if (!contexts[k]) {
    contexts[k] = std::make_unique<device::OpenClContext>(DeviceOptions{}, precision);
    ids[k] = device::bind_viennacl(*contexts[k]);
  }
  device::use_viennacl(ids[k]);
  return *contexts[k];
}

// Values as the device of precision Real sees them, back in double.
template <typename Real>
std::vector<double> rounded(const std::vector<double>& v) {
  std::vector<double> out(v.size());
  for (size_t i = 0; i < v.size(); ++i) out[i] = static_cast<double>(static_cast<Real>(v[i]));
  return out;
}

template <typename Real>
viennacl::vector<Real> upload(const std::vector<double>& v) {
  const std::vector<Real> r(v.begin(), v.end());
  viennacl::vector<Real> d(r.size());
  viennacl::copy(r.begin(), r.end(), d.begin());
  return d;
}

template <typename Real>
std::vector<Real> download_raw(const viennacl::vector_base<Real>& d) {
  std::vector<Real> r(d.size());
  viennacl::copy(d.begin(), d.end(), r.begin());
  return r;
}

template <typename Real>
std::vector<double> download(const viennacl::vector_base<Real>& d) {
  const std::vector<Real> r = download_raw(d);
  return {r.begin(), r.end()};
}

// What run(model, out) writes for a model with some term less what it writes
// for the same model without it, downloaded: that term's own contribution to
// a residual or product.
template <typename Run>
std::vector<double> model_difference(solver::ElasticModel<double>& with, solver::ElasticModel<double>& without,
                                     Run run) {
  viennacl::vector<double> a(with.dofs()), b(without.dofs());
  run(with, a);
  run(without, b);
  std::vector<double> ha(a.size()), hb(b.size());
  viennacl::copy(a.begin(), a.end(), ha.begin());
  viennacl::copy(b.begin(), b.end(), hb.begin());
  for (size_t i = 0; i < ha.size(); ++i) ha[i] -= hb[i];
  return ha;
}

// A term beyond elasticity (obstacle contact, friction, self-contact springs)
// seen through the model:
// the model with it less the model without it gains exactly the host
// reference's energy, force (residual) and Hessian times p (products of the
// cached and assembled variants, linearized at x, with another residual
// evaluation in between that must not change the linearization's blocks).
inline void expect_vertex_term_matches(solver::ElasticModel<double>& with, solver::ElasticModel<double>& without,
                                       const viennacl::vector<double>& xd, const viennacl::vector<double>& pd,
                                       double energy, const std::vector<double>& force,
                                       const std::vector<double>& product) {
  EXPECT_NEAR(with.energy(xd) - without.energy(xd), energy, 1e-12 * (1 + energy));
  auto difference = [&](auto run) { return model_difference(with, without, run); };
  const std::vector<double> dr =
      difference([&](solver::ElasticModel<double>& m, viennacl::vector<double>& out) { m.residual(xd, out); });
  for (size_t i = 0; i < force.size(); ++i) EXPECT_NEAR(dr[i], force[i], 1e-12) << i;
  for (ProductVariant variant : {ProductVariant::cached, ProductVariant::assembled}) {
    with.products().set_variant(variant);
    without.products().set_variant(variant);
    const std::vector<double> dp = difference([&](solver::ElasticModel<double>& m, viennacl::vector<double>& out) {
      m.linearize(xd, true);
      const viennacl::vector<double> elsewhere = xd + pd;
      m.residual(elsewhere, out);  // another evaluation must not change the linearization's terms
      m.product(pd, out);
    });
    for (size_t i = 0; i < product.size(); ++i) EXPECT_NEAR(dp[i], product[i], 1e-12) << to_string(variant) << " " << i;
  }
}

// Two vectors of uniform values in [-1, 1), drawn in turn from a generator
// seeded with `seed`, each times `mask` (0 on the constrained DOFs).
inline std::pair<std::vector<double>, std::vector<double>> masked_random_pair(const std::vector<double>& mask,
                                                                              uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> a(mask.size()), b(mask.size());
  for (size_t i = 0; i < mask.size(); ++i) {
    a[i] = mask[i] * u(rng);
    b[i] = mask[i] * u(rng);
  }
  return {a, b};
}

// za = M a and zb = M b for a preconditioner M: a.(M b) = b.(M a) within
// bound * sum_i |a_i (M b)_i|, a.(M a) > 0, and both exactly 0 on the
// constrained DOFs (mask 0).
inline void expect_symmetric_positive(const std::vector<double>& mask, const std::vector<double>& a,
                                      const std::vector<double>& b, const std::vector<double>& za,
                                      const std::vector<double>& zb, double bound) {
  double ab = 0.0, ba = 0.0, aa = 0.0, scale = 0.0;
  for (size_t i = 0; i < mask.size(); ++i) {
    ab += a[i] * zb[i];
    ba += b[i] * za[i];
    aa += a[i] * za[i];
    scale += std::abs(a[i] * zb[i]);
    if (mask[i] == 0.0) {
      EXPECT_EQ(za[i], 0.0) << "constrained DOF " << i;
      EXPECT_EQ(zb[i], 0.0) << "constrained DOF " << i;
    }
  }
  EXPECT_LT(std::abs(ab - ba), bound * scale) << "a.Mb " << ab << " b.Ma " << ba;
  EXPECT_GT(aa, 0.0);
}

}  // namespace snh::test
