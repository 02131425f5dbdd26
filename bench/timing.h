// Timing shared by the benchmark's parts.
#pragma once

#include <algorithm>
#include <chrono>

namespace snh::bench {

// Repeats f until min_seconds have passed (at least 3 times, after one
// warm-up call) and returns the best time of one call.
template <typename F>
double best_seconds(F&& f, double min_seconds) {
  using Clock = std::chrono::steady_clock;
  f();
  double best = 1e300, total = 0.0;
  for (int n = 0; n < 3 || total < min_seconds; ++n) {
    const auto t0 = Clock::now();
    f();
    const double dt = std::chrono::duration<double>(Clock::now() - t0).count();
    best = std::min(best, dt);
    total += dt;
    if (n > 10000) break;
  }
  return best;
}

}  // namespace snh::bench
