// One OpenCL context per precision for the whole test binary (kernels are
// built once per context), each bound to its own ViennaCL context, which the
// call makes current.
#pragma once

#include <memory>

#include "device/opencl_context.h"
#include "device/viennacl_binding.h"

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

}  // namespace snh::test
