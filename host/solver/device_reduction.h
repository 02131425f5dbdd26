// Sums, sums of squares, dot products and minima of device vectors, reduced
// on the device (kernels/reduce.cl) to one double per 4,096 entries which
// the host then adds in index order: deterministic, accumulated in double as
// before, and only the partials cross to the host. Measured on an H100 at
// 969,111 DOF: reading whole vectors and per-element energies back for the
// Newton loop's norms, dots and energies was 3.8 of 16.4 s (docs/performance.md).
// Without fp64 on the device (a float-only device) every entry is read back
// and summed on the host, as before. Internal to the library.
#pragma once

#include <cstddef>
#include <vector>

#include "device/opencl_context.h"
#include "solver/phase_profile.h"

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

  // Whether the partials are summed on the device (false: every entry is read).
  bool on_device() const { return on_device_; }

 private:
  double reduce(cl_mem a, cl_mem b, size_t n, int mode) const;
  // The work-groups for n entries, with a partials buffer large enough.
  size_t partials_for(size_t n) const;
  void read_partials(size_t groups) const;
  std::vector<double> read_all(cl_mem a, size_t n) const;

  device::OpenClContext& cl_;
  size_t real_bytes_;
  PhaseProfiler* profiler_;
  bool on_device_;
  device::Kernel sums_, minima_;
  mutable device::Buffer partial_;
  mutable size_t partial_capacity_ = 0;
  mutable std::vector<double> host_;
};

}  // namespace snh::solver
