#include "solver/device_reduction.h"

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
  }
}

size_t DeviceReduction::partials_for(size_t n) const {
  const size_t groups = (n + kSpan - 1) / kSpan;
  if (groups > partial_capacity_) {
    partial_ = cl_.buffer(CL_MEM_READ_WRITE, groups * sizeof(double));
    partial_capacity_ = groups;
  }
  return groups;
}

void DeviceReduction::read_partials(size_t groups) const {
  host_.resize(groups);
  PhaseScope transfer(profiler_, Phase::transfers);
  cl_.read(partial_.get(), groups * sizeof(double), host_.data());
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
  const size_t groups = partials_for(n);
  const int count = static_cast<int>(n);
  cl_.run(device::KernelArgs(sums_.get()).add(a).add(b).add(count).add(mode).add(partial_.get()).bind(),
          groups * kGroup);
  read_partials(groups);
  double s = 0.0;
  for (double p : host_) s += p;
  return s;
}

double DeviceReduction::min(cl_mem a, size_t n) const {
  if (n == 0) return 0.0;
  if (!on_device_) {
    const std::vector<double> x = read_all(a, n);
    return *std::min_element(x.begin(), x.end());
  }
  const size_t groups = partials_for(n);
  const int count = static_cast<int>(n);
  cl_.run(device::KernelArgs(minima_.get()).add(a).add(count).add(partial_.get()).bind(), groups * kGroup);
  read_partials(groups);
  return *std::min_element(host_.begin(), host_.end());
}

}  // namespace snh::solver
