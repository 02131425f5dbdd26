// Hands an OpenClContext's context and queue to ViennaCL, so that ViennaCL's
// vectors, reductions and CG run on the same device queue as our kernels.
#pragma once

#include "device/opencl_context.h"

namespace snh::device {

// Registers cl under a fresh ViennaCL context id (never reused within the
// process: ViennaCL ignores a second set-up of an id) and switches to it.
long bind_viennacl(const OpenClContext& cl);

// Makes `id` ViennaCL's current context again (before a solve).
void use_viennacl(long id);

// Work-group sizes of ViennaCL's element-wise vector kernels (x = a y + b z
// and the like: CG's updates, the line search's steps) in the current
// context, for vectors of `size` entries of Real, on CPU devices; GPUs keep
// ViennaCL's defaults. ViennaCL's CPU default is one work-item per group and
// 128 work-items in all, each looping over a strided share of the vector,
// which pocl runs as scalar code, far below the triad bandwidth; larger
// groups let pocl vectorize across work-items (docs/performance.md,
// "ViennaCL work-group sizes"). Values and their order are the
// same at any size: the kernels are element-wise. Inner products keep
// ViennaCL's sizes. Returns the local size set (1: ViennaCL's default).
template <typename Real>
size_t tune_viennacl_vector_kernels(size_t size);

}  // namespace snh::device
