// Per-phase wall time of a solve (snh::SolveProfile): scopes opened where the
// work happens (solver/model/elastic_model.cpp, solver/newton/device_problem.h, the host
// baseline) charge the time to one phase each. Exclusive timing: a scope
// opened inside another pauses it, so every second lands in exactly one phase
// and the phases add up; time outside every scope is the profile's `other`.
// Inside a preconditioner's setup or apply, nested scopes (its own products,
// vector work) stay charged to the preconditioner; only transfers separate.
//
// OpenCL is asynchronous: ViennaCL's vector operations are queued on the same
// in-order queue as the element kernels. The profiler's `finish` (clFinish on
// that queue) runs at every boundary, so queued work is charged to the phase
// that queued it and not to the next one that waits. Timers read only the
// clock: results stay bit-identical.
//
// With a context's counts attached (count_with), the profiler also charges
// each phase the kernel launches, blocking read-backs and bytes the context
// counted while the phase was open (device/transfer_counts.h). Counts
// outside every scope are left to the caller (the context's total less the
// phases: two engines may share a context). Counted at the call, not
// timed: the same on every device.
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <functional>
#include <utility>
#include <vector>

#include "device/transfer_counts.h"
#include "snh/simulation.h"

namespace snh::solver {

enum class Phase : int {
  linearization,
  products,
  preconditioner_setup,
  preconditioner_apply,
  cg_vector_work,
  line_search_energies,
  transfers,
};
constexpr int kPhaseCount = 7;

using PhaseSeconds = std::array<double, kPhaseCount>;
// Per phase, then `other` (index kPhaseCount).
using PhaseTraffic = std::array<device::TransferCounts, kPhaseCount + 1>;

class PhaseProfiler {
 public:
  using Clock = std::chrono::steady_clock;

  // finish: waits for the device's queued work (empty on the host).
  explicit PhaseProfiler(std::function<void()> finish = {}) : finish_(std::move(finish)) {}

  // Attributes the counts of `counts` (a context's, outliving the profiler's
  // use) to phases from now on.
  void count_with(const device::TransferCounts* counts) {
    counts_ = counts;
    if (counts_) counted_ = *counts_;
  }

  // A scope charged to the phase already charged (nested in a
  // preconditioner's setup or apply) neither waits nor reads the clock: the
  // V-cycle opens one per level product, and each wait costs pocl time
  // (docs/performance.md, "Kernel launches without a wait").
  void enter(Phase requested) {
    Phase phase = requested;
    if (!stack_.empty()) {
      const Phase outer = stack_.back();
      if ((outer == Phase::preconditioner_setup || outer == Phase::preconditioner_apply) &&
          requested != Phase::transfers)
        phase = outer;
      if (phase == outer) {
        stack_.push_back(phase);
        return;
      }
    }
    if (finish_) finish_();
    const auto now = Clock::now();
    if (!stack_.empty()) seconds_[index(stack_.back())] += std::chrono::duration<double>(now - since_).count();
    charge_counts(stack_.empty() ? kPhaseCount : index(stack_.back()));
    stack_.push_back(phase);
    since_ = now;
  }

  void leave() {
    if (stack_.empty()) return;
    const Phase phase = stack_.back();
    stack_.pop_back();
    if (!stack_.empty() && stack_.back() == phase) return;
    if (finish_) finish_();
    const auto now = Clock::now();
    seconds_[index(phase)] += std::chrono::duration<double>(now - since_).count();
    charge_counts(index(phase));
    since_ = now;
  }

  // Seconds per phase so far (an open phase counted up to now).
  PhaseSeconds seconds() const {
    PhaseSeconds out = seconds_;
    if (!stack_.empty()) out[index(stack_.back())] += std::chrono::duration<double>(Clock::now() - since_).count();
    return out;
  }

  // Counts per phase so far (those since the last boundary charged to the
  // open phase); the `other` slot stays 0.
  PhaseTraffic traffic() const {
    PhaseTraffic out = traffic_;
    if (counts_ && !stack_.empty()) out[index(stack_.back())] += *counts_ - counted_;
    return out;
  }

 private:
  static int index(Phase p) { return static_cast<int>(p); }
  // Charges the counts since the last boundary to `slot` (kPhaseCount:
  // outside every scope, left to the caller).
  void charge_counts(int slot) {
    if (!counts_) return;
    if (slot < kPhaseCount) traffic_[slot] += *counts_ - counted_;
    counted_ = *counts_;
  }

  std::function<void()> finish_;
  PhaseSeconds seconds_{};
  const device::TransferCounts* counts_ = nullptr;
  device::TransferCounts counted_;  // *counts_ at the last boundary
  PhaseTraffic traffic_{};
  std::vector<Phase> stack_;
  Clock::time_point since_;
};

// Charges its lifetime to `phase` (nothing with a null profiler).
class PhaseScope {
 public:
  PhaseScope(PhaseProfiler* profiler, Phase phase) : profiler_(profiler) {
    if (profiler_) profiler_->enter(phase);
  }
  ~PhaseScope() {
    if (profiler_) profiler_->leave();
  }
  PhaseScope(const PhaseScope&) = delete;
  PhaseScope& operator=(const PhaseScope&) = delete;

 private:
  PhaseProfiler* profiler_;
};

// Per phase, a - b and a + b.
inline PhaseSeconds difference(const PhaseSeconds& a, const PhaseSeconds& b) {
  PhaseSeconds out;
  for (int k = 0; k < kPhaseCount; ++k) out[k] = a[k] - b[k];
  return out;
}

inline PhaseSeconds sum(const PhaseSeconds& a, const PhaseSeconds& b) {
  PhaseSeconds out;
  for (int k = 0; k < kPhaseCount; ++k) out[k] = a[k] + b[k];
  return out;
}

inline PhaseTraffic difference(const PhaseTraffic& a, const PhaseTraffic& b) {
  PhaseTraffic out;
  for (int k = 0; k <= kPhaseCount; ++k) out[k] = a[k] - b[k];
  return out;
}

inline PhaseTraffic sum(const PhaseTraffic& a, const PhaseTraffic& b) {
  PhaseTraffic out;
  for (int k = 0; k <= kPhaseCount; ++k) out[k] = a[k] + b[k];
  return out;
}

// The phases' names as SolveProfile and the reports spell them, `other` last.
inline const char* phase_name(int k) {
  static const char* const names[kPhaseCount + 1] = {"linearization",
                                                     "products",
                                                     "preconditioner_setup",
                                                     "preconditioner_apply",
                                                     "cg_vector_work",
                                                     "line_search_energies",
                                                     "transfers",
                                                     "other"};
  return names[k];
}

// The public counts of `traffic` into `p`: totals and per phase.
inline void add_traffic(const PhaseTraffic& traffic, SolveProfile& p) {
  for (int k = 0; k <= kPhaseCount; ++k) {
    const device::TransferCounts& c = traffic[k];
    DeviceTraffic t;
    t.kernel_launches = c.kernel_launches;
    t.blocking_readbacks = c.blocking_readbacks;
    t.bytes_to_host = c.bytes_to_host;
    t.bytes_to_device = c.bytes_to_device;
    p.traffic[phase_name(k)] = t;
    p.kernel_launches += t.kernel_launches;
    p.blocking_readbacks += t.blocking_readbacks;
    p.bytes_to_host += t.bytes_to_host;
    p.bytes_to_device += t.bytes_to_device;
  }
}

// The public profile of `spent` within a wall time `total`; `other` is what
// no phase claimed (never below 0: clock reads of the phases and of the
// caller's total may differ by a few microseconds).
inline SolveProfile make_profile(const PhaseSeconds& spent, double total) {
  SolveProfile p;
  p.linearization = spent[static_cast<int>(Phase::linearization)];
  p.products = spent[static_cast<int>(Phase::products)];
  p.preconditioner_setup = spent[static_cast<int>(Phase::preconditioner_setup)];
  p.preconditioner_apply = spent[static_cast<int>(Phase::preconditioner_apply)];
  p.cg_vector_work = spent[static_cast<int>(Phase::cg_vector_work)];
  p.line_search_energies = spent[static_cast<int>(Phase::line_search_energies)];
  p.transfers = spent[static_cast<int>(Phase::transfers)];
  double phases = 0.0;
  for (double s : spent) phases += s;
  p.total = std::max(total, phases);
  p.other = p.total - phases;
  return p;
}

}  // namespace snh::solver
