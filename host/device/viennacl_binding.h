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

}  // namespace snh::device
