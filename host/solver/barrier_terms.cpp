#include "solver/barrier_terms.h"

#include <chrono>

#include "device/kernel_args.h"

namespace snh::solver {

namespace {

using Clock = std::chrono::steady_clock;

// Adds the seconds since it was made to `total` when it goes.
struct Stopwatch {
  double& total;
  Clock::time_point start = Clock::now();
  ~Stopwatch() { total += std::chrono::duration<double>(Clock::now() - start).count(); }
};

}  // namespace

template <typename Real>
BarrierTerms<Real>::BarrierTerms(device::OpenClContext& cl, const Mesh& mesh, PhaseProfiler* profiler)
    : cl_(cl), profiler_(profiler), vertex_count_(mesh.vertex_count()), contact_(mesh), rest_(mesh.positions) {
  product_k_ = cl_.kernel("contact/barrier.cl", device::KernelConfig{}, "snh_barrier_product");
  force_k_ = cl_.kernel("contact/barrier.cl", device::KernelConfig{}, "snh_barrier_force");
  const std::vector<int> offsets(vertex_count_ + 1, 0);
  offsets_ = cl_.buffer(CL_MEM_READ_ONLY, offsets.size() * sizeof(int), offsets.data());
  columns_ = cl_.buffer(CL_MEM_READ_ONLY, sizeof(int));
  blocks_ = cl_.buffer(CL_MEM_READ_ONLY, 9 * sizeof(Real));
  diagonal_ = cl_.buffer(CL_MEM_READ_ONLY, 9 * vertex_count_ * sizeof(Real));
  gradient_ = cl_.buffer(CL_MEM_READ_WRITE, 3 * vertex_count_ * sizeof(Real));
}

template <typename Real>
void BarrierTerms<Real>::set_parameters(double dhat, double kappa) {
  if (!excluded_known_ || dhat != contact_.distance()) {
    contact_.set_distance(dhat);
    excluded_at_rest_ = contact_.exclude_pairs_near(rest_);
    excluded_known_ = true;
  }
  kappa_ = kappa;
}

template <typename Real>
double BarrierTerms<Real>::energy(const std::vector<double>& x) {
  Stopwatch watch{state_.seconds};
  const std::vector<BarrierPair> pairs = contact_.near_pairs(x);
  double smallest = 0.0;
  const double sum = contact_.energy(x, pairs, &smallest);
  state_.pairs = static_cast<int>(pairs.size());
  state_.min_distance = smallest;
  return kappa_ * sum;
}

template <typename Real>
void BarrierTerms<Real>::add_force(const std::vector<double>& x, cl_mem mask, cl_mem r) {
  std::vector<Real> gradient(3 * vertex_count_);
  {
    Stopwatch watch{state_.seconds};
    const std::vector<BarrierPair> pairs = contact_.near_pairs(x);
    if (pairs.empty()) return;
    std::vector<double> g(x.size(), 0.0);
    contact_.add_gradient(x, pairs, kappa_, g);
    gradient.assign(g.begin(), g.end());
  }
  {
    PhaseScope transfer(profiler_, Phase::transfers);
    cl_.write(gradient_.get(), gradient.size() * sizeof(Real), gradient.data());
  }
  const int size = static_cast<int>(gradient.size());
  device::KernelArgs args(force_k_.get());
  args.add(mask).add(gradient_.get()).add(size).add(r);
  cl_.run(args.bind(), gradient.size());
}

template <typename Real>
void BarrierTerms<Real>::linearize(const std::vector<double>& x) {
  BarrierHessian h;
  std::vector<Real> diagonal(9 * vertex_count_, Real(0));
  {
    Stopwatch watch{state_.seconds};
    const std::vector<BarrierPair> pairs = contact_.near_pairs(x);
    h = contact_.hessian(x, pairs, kappa_);
    for (size_t v = 0; v < vertex_count_; ++v)
      for (int k = h.offsets[v]; k < h.offsets[v + 1]; ++k)
        if (h.columns[k] == static_cast<int>(v))
          for (int i = 0; i < 9; ++i) diagonal[9 * v + i] = static_cast<Real>(h.blocks[9 * k + i]);
  }
  rows_ = h.columns.empty() ? 0 : static_cast<int>(vertex_count_);
  const std::vector<Real> blocks(h.blocks.begin(), h.blocks.end());
  PhaseScope transfer(profiler_, Phase::transfers);
  cl_.write(diagonal_.get(), diagonal.size() * sizeof(Real), diagonal.data());
  if (rows_ == 0) return;
  offsets_ = cl_.buffer(CL_MEM_READ_ONLY, h.offsets.size() * sizeof(int), h.offsets.data());
  columns_ = cl_.buffer(CL_MEM_READ_ONLY, h.columns.size() * sizeof(int), h.columns.data());
  blocks_ = cl_.buffer(CL_MEM_READ_ONLY, blocks.size() * sizeof(Real), blocks.data());
}

template <typename Real>
void BarrierTerms<Real>::add_product(cl_mem mask, cl_mem p, cl_mem y) const {
  if (rows_ == 0) return;
  device::KernelArgs args(product_k_.get());
  args.add(offsets_.get()).add(columns_.get()).add(blocks_.get()).add(mask).add(p).add(rows_).add(y);
  cl_.run(args.bind(), static_cast<size_t>(rows_));
}

template <typename Real>
double BarrierTerms<Real>::step_bound(const std::vector<double>& x, const std::vector<double>& p) {
  Stopwatch watch{state_.seconds};
  return contact_.step_bound(x, p);
}

template class BarrierTerms<float>;
template class BarrierTerms<double>;

}  // namespace snh::solver
