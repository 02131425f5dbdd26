// The probe kernel (kernels/probe.cl) run on a context: MaterialProbe's
// evaluation, with the kernel's build options open to the tests (e.g. a
// GPU's -DSNH_GPU=1 on pocl).
#pragma once

#include <string>
#include <vector>

#include "device/opencl_context.h"
#include "snh/probe.h"

namespace snh::probe {

// psi, P, projected H, eigenvalues and sigma at each F, in the context's
// precision; `extra_defines` is added to the material's build options.
std::vector<ProbeResult> evaluate(device::OpenClContext& cl, const Material& material, const std::vector<Matrix3>& fs,
                                  const std::string& extra_defines = "");

}  // namespace snh::probe
