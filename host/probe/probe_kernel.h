// The probe kernel (kernels/probe.cl) run on a context: MaterialProbe's
// evaluation, with the GPUs' build open to the tests (SNH_GPU on pocl).
#pragma once

#include <string>
#include <vector>

#include "device/opencl_context.h"
#include "snh/probe.h"

namespace snh::probe {

// psi, P, projected H, eigenvalues and sigma at each F, in the context's
// precision; with `gpu_build`, the GPUs' build (KernelConfig::gpu) on any
// device.
std::vector<ProbeResult> evaluate(device::OpenClContext& cl, const Material& material, const std::vector<Matrix3>& fs,
                                  bool gpu_build = false);

}  // namespace snh::probe
