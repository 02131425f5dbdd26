// The thresholds of the measured defaults (docs/performance.md, "Why the
// defaults"), written once: the rules that apply them
// (default_preconditioner, resolved_smoothing) and the resolved
// configuration's reasons read them from here.
#pragma once

#include <cstddef>

namespace snh::solver {

// `automatic` is multigrid on hex8 lattices from this many DOFs.
inline constexpr size_t kMultigridFromDofs = 5000;
// The automatic smoothing is degree 1 of the optimized fourth kind on fine
// levels below this many DOFs whose materials' Poisson's ratios are all
// below kDegreeOneBelowPoisson; degree 2 of the first kind otherwise.
inline constexpr size_t kDegreeOneBelowDofs = 600000;
inline constexpr double kDegreeOneBelowPoisson = 0.495;

}  // namespace snh::solver
