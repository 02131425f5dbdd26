// One OpenCL context per precision for the whole test binary (kernels are
// built once per context), each bound to its own ViennaCL context, which the
// call makes current.
#pragma once

#include <memory>
#include <vector>

#include "device/opencl_context.h"
#include "device/viennacl_binding.h"
#include "solver/elastic_model.h"
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

}  // namespace snh::test
