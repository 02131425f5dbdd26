// Kernel launches and blocking read-backs per iteration, from a solve's
// counted device traffic (SolveProfile::traffic): per CG iteration, the
// linear solves' share (the phases products, preconditioner_apply and
// cg_vector_work) divided by the CG iterations; per Newton iteration, the
// whole solve's counts divided by the Newton iterations. 0 where the
// divisor is 0 (no CG or no Newton iteration ran) and for a solve without
// device traffic (the host baseline). `scale` and `errtime` report them
// under the names of the fields below.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "snh/simulation.h"

namespace snh::bench {

struct IterationTraffic {
  double launches_per_cg_iteration = 0.0;
  double readbacks_per_cg_iteration = 0.0;
  double launches_per_newton_iteration = 0.0;
  double readbacks_per_newton_iteration = 0.0;
};

// The phases of SolveProfile::traffic that make up a linear solve.
inline const std::vector<std::string>& linear_solve_phases() {
  static const std::vector<std::string> phases{"products", "preconditioner_apply", "cg_vector_work"};
  return phases;
}

inline IterationTraffic iteration_traffic(const SolveProfile& p, long long cg_iterations, long long newton_iterations) {
  DeviceTraffic linear;
  for (const std::string& phase : linear_solve_phases()) {
    const auto it = p.traffic.find(phase);
    if (it != p.traffic.end()) linear += it->second;
  }
  const auto per = [](long long count, long long iterations) {
    return iterations > 0 ? static_cast<double>(count) / static_cast<double>(iterations) : 0.0;
  };
  IterationTraffic t;
  t.launches_per_cg_iteration = per(linear.kernel_launches, cg_iterations);
  t.readbacks_per_cg_iteration = per(linear.blocking_readbacks, cg_iterations);
  t.launches_per_newton_iteration = per(p.kernel_launches, newton_iterations);
  t.readbacks_per_newton_iteration = per(p.blocking_readbacks, newton_iterations);
  return t;
}

// (JSON key and CSV column, value), in the order the reports write them.
inline std::vector<std::pair<std::string, double>> iteration_traffic_parts(const IterationTraffic& t) {
  return {{"launches_per_cg_iteration", t.launches_per_cg_iteration},
          {"readbacks_per_cg_iteration", t.readbacks_per_cg_iteration},
          {"launches_per_newton_iteration", t.launches_per_newton_iteration},
          {"readbacks_per_newton_iteration", t.readbacks_per_newton_iteration}};
}

// Their headings in the Markdown and printed tables, in the same order.
inline const std::vector<std::string>& iteration_traffic_headings() {
  static const std::vector<std::string> headings{"launches per CG iteration", "reads per CG iteration",
                                                 "launches per Newton iteration", "reads per Newton iteration"};
  return headings;
}

}  // namespace snh::bench
