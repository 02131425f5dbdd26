#include "solver/linear/device_reduction.h"

#include <algorithm>

#include "device/kernel_args.h"
#include "snh/error.h"

namespace snh::solver {

namespace {
constexpr size_t kGroup = 64;          // SNH_REDUCE_GROUP, kernels/reduce.cl
constexpr size_t kSpan = kGroup * 64;  // SNH_REDUCE_SPAN
}  // namespace

DeviceReduction::DeviceReduction(device::OpenClContext& cl, size_t real_bytes, PhaseProfiler* profiler)
    : cl_(cl), real_bytes_(real_bytes), profiler_(profiler), on_device_(cl.info().has_fp64) {
  if (real_bytes != 4 && real_bytes != 8) throw Error("solver: a reduction over reals of 4 or 8 bytes");
  if (on_device_) {
    sums_ = cl.kernel("reduce.cl", "", "snh_partial_sums");
    minima_ = cl.kernel("reduce.cl", "", "snh_partial_minima");
    work_ = cl.kernel("reduce.cl", "", "snh_partial_work");
    inertia_ = cl.kernel("reduce.cl", "", "snh_partial_inertia");
    total_ = cl.kernel("reduce.cl", "", "snh_partial_total");
    totals_ = cl.buffer(CL_MEM_READ_WRITE, kSlots * sizeof(double));
  }
}

size_t DeviceReduction::partials_for(size_t n) const {
  const size_t groups = (n + kSpan - 1) / kSpan;
  if (2 * groups > partial_capacity_) {  // two partials per group for queue_work
    partial_ = cl_.buffer(CL_MEM_READ_WRITE, 2 * groups * sizeof(double));
    partial_capacity_ = 2 * groups;
  }
  return groups;
}

void DeviceReduction::queue_total(size_t groups, bool minimum, int slot, size_t offset) const {
  if (slot < 0 || slot >= kSlots) throw Error("solver: a reduction's total slot out of range");
  cl_.run(device::KernelArgs(total_.get())
              .add(partial_.get())
              .add(static_cast<int>(offset))
              .add(static_cast<int>(groups))
              .add(minimum ? 1 : 0)
              .add(totals_.get())
              .add(slot)
              .bind(),
          1);
}

void DeviceReduction::queue(cl_mem a, cl_mem b, size_t n, int mode, int slot) const {
  if (!on_device_) {
    totals_host_[slot] = reduce(a, b, n, mode);
    return;
  }
  const size_t groups = partials_for(n);
  if (groups > 0)
    cl_.run(device::KernelArgs(sums_.get()).add(a).add(b).add(static_cast<int>(n)).add(mode).add(partial_.get()).bind(),
            groups * kGroup);
  queue_total(groups, false, slot);
}

void DeviceReduction::queue_min(cl_mem a, size_t n, int slot) const {
  if (!on_device_) {
    totals_host_[slot] = min(a, n);
    return;
  }
  const size_t groups = partials_for(n);
  if (groups > 0)
    cl_.run(device::KernelArgs(minima_.get()).add(a).add(static_cast<int>(n)).add(partial_.get()).bind(),
            groups * kGroup);
  queue_total(groups, true, slot);
}

void DeviceReduction::queue_work(cl_mem x, cl_mem f, size_t n, int slot) const {
  if (!on_device_) throw Error("solver: the device reduction of a force's work needs fp64 on the device");
  const size_t groups = partials_for(n);
  if (groups > 0)
    cl_.run(device::KernelArgs(work_.get())
                .add(x)
                .add(f)
                .add(static_cast<int>(n))
                .add(static_cast<int>(groups))
                .add(partial_.get())
                .bind(),
            groups * kGroup);
  queue_total(groups, false, slot);
  queue_total(groups, false, slot + 1, groups);
}

void DeviceReduction::queue_inertia(cl_mem x, cl_mem y, cl_mem c, size_t n, int slot) const {
  if (!on_device_) throw Error("solver: the device reduction of the inertia energy needs fp64 on the device");
  const size_t groups = partials_for(n);
  if (groups > 0)
    cl_.run(device::KernelArgs(inertia_.get()).add(x).add(y).add(c).add(static_cast<int>(n)).add(partial_.get()).bind(),
            groups * kGroup);
  queue_total(groups, false, slot);
}

const double* DeviceReduction::read_totals(int count) const {
  if (count < 0 || count > kSlots) throw Error("solver: a reduction's total slot out of range");
  if (on_device_ && count > 0) {
    PhaseScope transfer(profiler_, Phase::transfers);
    cl_.read(totals_.get(), count * sizeof(double), totals_host_);
  }
  return totals_host_;
}

std::vector<double> DeviceReduction::read_all(cl_mem a, size_t n) const {
  std::vector<double> out(n);
  PhaseScope transfer(profiler_, Phase::transfers);
  if (real_bytes_ == 8) {
    cl_.read(a, n * sizeof(double), out.data());
  } else {
    std::vector<float> f(n);
    cl_.read(a, n * sizeof(float), f.data());
    std::copy(f.begin(), f.end(), out.begin());
  }
  return out;
}

double DeviceReduction::reduce(cl_mem a, cl_mem b, size_t n, int mode) const {
  if (n == 0) return 0.0;
  if (!on_device_) {
    const std::vector<double> x = read_all(a, n);
    const std::vector<double> y = mode == 2 ? read_all(b, n) : std::vector<double>();
    double s = 0.0;
    for (size_t i = 0; i < n; ++i) s += mode == 0 ? x[i] : mode == 1 ? x[i] * x[i] : x[i] * y[i];
    return s;
  }
  queue(a, b, n, mode, 0);
  return read_totals(1)[0];
}

double DeviceReduction::min(cl_mem a, size_t n) const {
  if (n == 0) return 0.0;
  if (!on_device_) {
    const std::vector<double> x = read_all(a, n);
    return *std::min_element(x.begin(), x.end());
  }
  queue_min(a, n, 0);
  return read_totals(1)[0];
}

}  // namespace snh::solver
