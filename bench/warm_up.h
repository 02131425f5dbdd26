// Before a timed solve: one Newton iteration of one load step on a small
// copy of the scene (the same kernel specialization) compiles the element
// kernels and ViennaCL's into pocl's cache, so that the timed solve loads
// them instead of compiling them. (Each solver has its own OpenCL context;
// loading its programs stays in the timings, as in any solve.) errtime and
// scale share it.
#pragma once

#include "snh/scenes.h"
#include "snh/simulation.h"

namespace snh::bench {

// Solves `tiny` with `options` cut to one load step and one Newton update.
inline void warm_up_kernels(const Scene& tiny, SolveOptions options) {
  options.max_newton_iterations = 1;
  options.load_steps = 1;
  QuasistaticSolver(tiny.mesh, tiny.material, tiny.constraints, options).solve();
}

}  // namespace snh::bench
