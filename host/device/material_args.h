// The material's part of a kernel build and launch, in the order of
// kernels/materials/kernel_args.h (MATERIAL_ARGS): its build switches and its
// ten kernel arguments. Shared by the engine's and the probe's kernels.
#pragma once

#include <CL/cl.h>

#include <string>

#include "snh/material.h"

namespace snh::device {

// How much of the material a kernel build fixes:
//   specialized   model, barrier, seed 004 path and lambda model at build time
//                 (the engine's default: only what the scene uses is compiled);
//   runtime       one kernel for every material, all of it read at run time;
//   all_terms     specialized to the model, but always through the seed 004
//                 parts (as a kernel that carries every term would compute).
// The last two are the baselines of `snh-gpu-bench specialization`.
enum class MaterialKernel { specialized, runtime, all_terms };

std::string material_defines(const Material& material, MaterialKernel build = MaterialKernel::specialized);

// Sets MATERIAL_ARGS from index `first`; returns the index after them.
template <typename Real>
cl_uint set_material_args(cl_kernel kernel, cl_uint first, const Material& material);

}  // namespace snh::device
