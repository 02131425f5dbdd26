// Sums, sums of squares, dot products and minima of device vectors, reduced
// on the device (kernels/reduce.cl) to one double per 4,096 entries, which
// one work-item then adds in index order (the host's order before, so the
// same value): deterministic, accumulated in double, and only the totals
// cross to the host, a few bytes whatever the size. Several totals queued
// into slots are read together (queue_* then read_totals): the energy's
// sums and minimum are one read. Reading whole vectors and per-element
// energies back instead took a large share of a solve (docs/performance.md,
// "Device reductions").
// Without fp64 on the device (a float-only device) every entry is read back
// and summed on the host, as before. Internal to the library.
#pragma once

#include <cstddef>
#include <vector>

#include "device/opencl_context.h"
#include "device/phase_profile.h"

namespace snh::solver {

class DeviceReduction {
 public:
  // real_bytes: sizeof the working precision's real (4 or 8).
  DeviceReduction(device::OpenClContext& cl, size_t real_bytes, PhaseProfiler* profiler);

  // Over the first n entries of the buffers.
  double sum(cl_mem a, size_t n) const { return reduce(a, a, n, 0); }
  double sum_of_squares(cl_mem a, size_t n) const { return reduce(a, a, n, 1); }
  double dot(cl_mem a, cl_mem b, size_t n) const { return reduce(a, b, n, 2); }
  // The smallest entry (0 for n = 0).
  double min(cl_mem a, size_t n) const;

  // Queued into total `slot` (< kSlots), read by read_totals(); the
  // totals of one read are queued after the last read_totals().
  void queue_sum(cl_mem a, size_t n, int slot) const { queue(a, a, n, 0, slot); }
  void queue_min(cl_mem a, size_t n, int slot) const;
  // sum f x into `slot` and sum |f x| into slot + 1: the work of forces f
  // (doubles; on_device() only) at x (n reals).
  void queue_work(cl_mem x, cl_mem f, size_t n, int slot) const;
  // sum_i 1/2 c[i / 3] (x_i - y_i)^2 into `slot`: implicit Euler's inertia
  // energy at x (n reals), y (n doubles) and c (n / 3 doubles); on_device()
  // only.
  void queue_inertia(cl_mem x, cl_mem y, cl_mem c, size_t n, int slot) const;
  // Totals [0, count), in one blocking read.
  const double* read_totals(int count) const;
  static constexpr int kSlots = 8;

  // Whether the partials are summed on the device (false: every entry is read).
  bool on_device() const { return on_device_; }

 private:
  double reduce(cl_mem a, cl_mem b, size_t n, int mode) const;
  void queue(cl_mem a, cl_mem b, size_t n, int mode, int slot) const;
  // total[slot] = the partials' sum (minimum) in index order.
  void queue_total(size_t groups, bool minimum, int slot, size_t offset = 0) const;
  // The work-groups for n entries, with a partials buffer large enough.
  size_t partials_for(size_t n) const;
  std::vector<double> read_all(cl_mem a, size_t n) const;

  device::OpenClContext& cl_;
  size_t real_bytes_;
  PhaseProfiler* profiler_;
  bool on_device_;
  device::Kernel sums_, minima_, work_, inertia_, total_;
  mutable device::Buffer partial_, totals_;
  mutable double totals_host_[kSlots] = {};
  mutable size_t partial_capacity_ = 0;
};

}  // namespace snh::solver
