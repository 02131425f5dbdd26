// The material's part of a kernel build and launch, in the order of
// kernels/materials/kernel_args.h (MATERIAL_ARGS): its build switches and its
// ten kernel arguments. Shared by the engine's and the probe's kernels.
#pragma once

#include <CL/cl.h>

#include <string>

#include "snh/material.h"

namespace snh::device {

// Build switches for a kernel specialized to `material`, or, with `general`,
// for the one kernel that takes model, barrier and the seed 004 path at run
// time (the baseline of the specialization benchmark).
std::string material_defines(const Material& material, bool general = false);

constexpr cl_uint kMaterialArgCount = 10;

// Sets MATERIAL_ARGS from index `first`; returns the index after them.
template <typename Real>
cl_uint set_material_args(cl_kernel kernel, cl_uint first, const Material& material);

}  // namespace snh::device
