// The kernel programs a scene's simulation builds (`snh programs`).
#pragma once

#include <ostream>
#include <vector>

#include "device/kernel_config.h"
#include "snh/scene.h"

namespace snh::cli {

// Builds the scene's simulation with `options`, runs its first Newton
// iteration (then cancels the solve) and returns the programs that
// compiled, in build order.
std::vector<device::BuiltProgram> scene_programs(const SceneFile& file, const SolveOptions& options);
// One line a program: "<file>  <switches with -DSNH_DOUBLE>".
void print_programs(std::ostream& out, const std::vector<device::BuiltProgram>& programs);

}  // namespace snh::cli
