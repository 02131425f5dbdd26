#include "solver/contact/barrier_terms.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numeric>

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

// Entries per span of the device's fixed-order sums (SNH_BARRIER_SPAN).
constexpr int kSpan = 256;

int spans(int count) { return (count + kSpan - 1) / kSpan; }

}  // namespace

template <typename Real>
BarrierTerms<Real>::BarrierTerms(device::OpenClContext& cl, const Mesh& mesh, PhaseProfiler* profiler)
    : cl_(cl),
      profiler_(profiler),
      vertex_count_(mesh.vertex_count()),
      contact_(mesh),
      rest_(mesh.positions.xyz()),
      pair_bytes_(cl.info().has_fp64 ? sizeof(double) : sizeof(float)),
      broad_(cl, pair_bytes_, profiler) {
  const char* file = "contact/barrier_pairs.cl";
  const device::KernelConfig config;
  lift_k_ = cl_.kernel(file, config, "snh_barrier_lift_store");
  energy_k_ = cl_.kernel(file, config, "snh_barrier_pair_energy");
  pair_k_ = cl_.kernel(file, config, "snh_barrier_pair_terms");
  partials_k_ = cl_.kernel(file, config, "snh_barrier_partials");
  total_k_ = cl_.kernel(file, config, "snh_barrier_total");
  surface_gradient_k_ = cl_.kernel(file, config, "snh_barrier_surface_gradient");
  force_k_ = cl_.kernel(file, config, "snh_barrier_force");
  surface_blocks_k_ = cl_.kernel(file, config, "snh_barrier_surface_blocks");
  diagonal_k_ = cl_.kernel(file, config, "snh_barrier_diagonal");
  surface_product_k_ = cl_.kernel(file, config, "snh_barrier_surface_product");
  spread_product_k_ = cl_.kernel(file, config, "snh_barrier_spread_product");
  ccd_k_ = cl_.kernel(file, config, "snh_barrier_ccd");
  min_partials_k_ = cl_.kernel(file, config, "snh_barrier_min_partials");
  min_total_k_ = cl_.kernel(file, config, "snh_barrier_min_total");
  differs_k_ = cl_.kernel(file, config, "snh_barrier_differs");
  x_copy_ = cl_.buffer(CL_MEM_READ_WRITE, 3 * vertex_count_ * sizeof(Real));
  differs_ = cl_.buffer(CL_MEM_READ_WRITE, 3 * vertex_count_ * sizeof(int));
  total_ = cl_.buffer(CL_MEM_READ_WRITE, 3 * pair_bytes_);
  diagonal_ = cl_.buffer(CL_MEM_READ_WRITE, 9 * vertex_count_ * sizeof(Real));
  upload_surface();
}

template <typename Real>
void BarrierTerms<Real>::set_parameters(double dhat, double kappa) {
  if (!excluded_known_ || dhat != contact_.distance()) {
    contact_.set_distance(dhat);
    excluded_at_rest_ = contact_.exclude_pairs_near(rest_);
    excluded_known_ = true;
    broad_.set_surface(contact_);
    x_known_ = false;
  }
  kappa_ = kappa;
}

template <typename Real>
void BarrierTerms<Real>::set_surface(BarrierContact contact) {
  contact.set_distance(contact_.distance());
  contact_ = std::move(contact);
  excluded_known_ = false;
  upload_surface();
}

template <typename Real>
device::Buffer BarrierTerms<Real>::host_to_device(const std::vector<double>& values) {
  if (pair_bytes_ == sizeof(double))
    return cl_.buffer(CL_MEM_READ_ONLY, std::max<size_t>(values.size(), 1) * sizeof(double), values.data());
  const std::vector<float> narrow(values.begin(), values.end());
  return cl_.buffer(CL_MEM_READ_ONLY, std::max<size_t>(narrow.size(), 1) * sizeof(float), narrow.data());
}

template <typename Real>
device::Buffer BarrierTerms<Real>::host_to_device(const std::vector<int>& values) {
  return cl_.buffer(CL_MEM_READ_ONLY, std::max<size_t>(values.size(), 1) * sizeof(int), values.data());
}

template <typename Real>
void BarrierTerms<Real>::upload_surface() {
  const size_t n = vertex_count_;
  std::vector<int> carrier = contact_.carriers();
  std::vector<double> weight = contact_.weights();
  if (carrier.empty()) {  // the mesh's own boundary: W = I
    carriers_ = 1;
    carrier.resize(n);
    std::iota(carrier.begin(), carrier.end(), 0);
    weight.assign(n, 1.0);
  } else {
    carriers_ = 8;
  }
  surface_count_ = static_cast<int>(carrier.size() / carriers_);
  // W^T: per lattice vertex, its entries s * carriers + k in ascending order.
  std::vector<int> offsets(n + 1, 0), entries(carrier.size());
  for (int c : carrier) ++offsets[c + 1];
  for (size_t v = 0; v < n; ++v) offsets[v + 1] += offsets[v];
  std::vector<int> fill(offsets.begin(), offsets.end() - 1);
  for (size_t e = 0; e < carrier.size(); ++e) entries[fill[carrier[e]]++] = static_cast<int>(e);
  PhaseScope transfer(profiler_, Phase::transfers);
  carrier_ = host_to_device(carrier);
  weight_ = host_to_device(weight);
  const std::vector<Real> weight_store(weight.begin(), weight.end());
  weight_store_ = cl_.buffer(CL_MEM_READ_ONLY, weight_store.size() * sizeof(Real), weight_store.data());
  transpose_offsets_ = host_to_device(offsets);
  transpose_entries_ = host_to_device(entries);
  const size_t s3 = 3 * static_cast<size_t>(surface_count_);
  q_ = cl_.buffer(CL_MEM_READ_WRITE, s3 * pair_bytes_);
  dq_ = cl_.buffer(CL_MEM_READ_WRITE, s3 * pair_bytes_);
  surface_gradient_ = cl_.buffer(CL_MEM_READ_WRITE, s3 * pair_bytes_);
  z_ = cl_.buffer(CL_MEM_READ_WRITE, s3 * sizeof(Real));
  broad_.set_surface(contact_);
  x_known_ = false;
  blocks_ = 0;
}

template <typename Real>
void BarrierTerms<Real>::reserve(device::Buffer& buffer, size_t bytes) {
  bytes = std::max<size_t>(bytes, 1);
  if (buffer && device::OpenClContext::bytes(buffer.get()) >= bytes) return;
  buffer = cl_.buffer(CL_MEM_READ_WRITE, bytes + bytes / 2);  // room to grow
}

template <typename Real>
void BarrierTerms<Real>::lift(cl_mem x, device::Buffer& surface) {
  device::KernelArgs args(lift_k_.get());
  args.add(x).add(carrier_.get()).add(weight_.get()).add(carriers_).add(surface_count_).add(surface.get());
  cl_.run(args.bind(), static_cast<size_t>(surface_count_));
}

template <typename Real>
void BarrierTerms<Real>::at(cl_mem x) {
  const int n = static_cast<int>(3 * vertex_count_);
  if (x_known_) {
    device::KernelArgs args(differs_k_.get());
    args.add(x).add(x_copy_.get()).add(n).add(differs_.get());
    cl_.run(args.bind(), static_cast<size_t>(n));
    if (broad_.count_set(differs_.get(), n) == 0) return;
  }
  cl_.copy(x, x_copy_.get(), static_cast<size_t>(n) * sizeof(Real));
  lift(x, q_);
  x_known_ = true;
  candidates_known_ = near_known_ = lists_known_ = false;
}

template <typename Real>
void BarrierTerms<Real>::find_candidates() {
  if (candidates_known_) return;
  candidates(x_copy_.get(), nullptr, candidates_);
  candidates_known_ = true;
}

template <typename Real>
std::vector<double> BarrierTerms<Real>::to_host(cl_mem v) {
  std::vector<Real> values(3 * vertex_count_);
  PhaseScope transfer(profiler_, Phase::transfers);
  cl_.read(v, values.size() * sizeof(Real), values.data());
  return {values.begin(), values.end()};
}

template <typename Real>
void BarrierTerms<Real>::candidates(cl_mem x, cl_mem p, DevicePairList& out) {
  if (!host_candidates_) {
    broad_.candidates(q_.get(), p ? dq_.get() : nullptr, contact_.distance(), out);
    return;
  }
  const std::vector<double> xh = to_host(x);
  if (!p) {
    broad_.upload(contact_.candidate_pairs(xh, nullptr), out);
    return;
  }
  const std::vector<double> ph = to_host(p);
  broad_.upload(contact_.candidate_pairs(xh, &ph), out);
}

template <typename Real>
void BarrierTerms<Real>::find_near(cl_mem x, bool lists) {
  at(x);
  if (!near_known_) {
    find_candidates();
    run_pairs(candidates_, 0);
    broad_.near(candidates_, distance_.get(), contact_.distance() * contact_.distance(), near_);
    near_known_ = true;
  }
  if (lists && !lists_known_) {
    broad_.lists(near_, surface_count_, lists_);
    lists_known_ = true;
  }
}

template <typename Real>
void BarrierTerms<Real>::run_pairs(const DevicePairList& pairs, int derivatives) {
  if (pairs.count == 0) return;
  const double sh = contact_.distance() * contact_.distance();
  auto add_real = [&](device::KernelArgs& args, double value) {
    if (pair_bytes_ == sizeof(double))
      args.add(value);
    else
      args.add(static_cast<float>(value));
  };
  const size_t count = static_cast<size_t>(pairs.count);
  if (derivatives == 0) {
    reserve(energy_, count * pair_bytes_);
    reserve(distance_, count * pair_bytes_);
    device::KernelArgs args(energy_k_.get());
    args.add(q_.get()).add(pairs.vertex.get()).add(pairs.kind.get()).add(pairs.ex.get()).add(pairs.count);
    add_real(args, sh);
    args.add(energy_.get()).add(distance_.get());
    cl_.run(args.bind(), count);
    return;
  }
  reserve(gradient_, 12 * count * pair_bytes_);
  const int hessian = derivatives > 1 ? 1 : 0;
  if (hessian) reserve(hessian_, 144 * count * pair_bytes_);
  device::KernelArgs args(pair_k_.get());
  args.add(q_.get()).add(pairs.vertex.get()).add(pairs.kind.get()).add(pairs.ex.get()).add(pairs.count);
  add_real(args, sh);
  args.add(hessian).add(gradient_.get()).add(hessian ? hessian_.get() : gradient_.get());
  cl_.run(args.bind(), count);
}

template <typename Real>
std::vector<BarrierPair> BarrierTerms<Real>::candidate_pairs(cl_mem x, cl_mem p) {
  at(x);
  if (p) {
    lift(p, dq_);
    candidates(x, p, swept_);
    return broad_.download(swept_);
  }
  find_candidates();
  return broad_.download(candidates_);
}

template <typename Real>
std::vector<BarrierPair> BarrierTerms<Real>::near_pairs(cl_mem x) {
  find_near(x, false);
  return broad_.download(near_);
}

template <typename Real>
double BarrierTerms<Real>::energy(cl_mem x) {
  Stopwatch watch{state_.seconds};
  const double dhat = contact_.distance(), sh = dhat * dhat;
  state_.pairs = 0;
  state_.min_distance = dhat;
  at(x);
  find_candidates();
  if (candidates_.count == 0) return 0.0;
  run_pairs(candidates_, 0);
  const int count = candidates_.count, groups = spans(count);
  reserve(partial_, 3 * static_cast<size_t>(groups) * pair_bytes_);
  double totals[3];
  {
    device::KernelArgs args(partials_k_.get());
    args.add(energy_.get()).add(distance_.get()).add(count);
    if (pair_bytes_ == sizeof(double))
      args.add(sh);
    else
      args.add(static_cast<float>(sh));
    args.add(partial_.get());
    cl_.run(args.bind(), static_cast<size_t>(groups));
    device::KernelArgs total(total_k_.get());
    total.add(partial_.get()).add(groups);
    if (pair_bytes_ == sizeof(double))
      total.add(sh);
    else
      total.add(static_cast<float>(sh));
    total.add(total_.get());
    cl_.run(total.bind(), 1);
    PhaseScope transfer(profiler_, Phase::transfers);
    if (pair_bytes_ == sizeof(double)) {
      cl_.read(total_.get(), sizeof totals, totals);
    } else {
      float narrow[3];
      cl_.read(total_.get(), sizeof narrow, narrow);
      std::copy(narrow, narrow + 3, totals);
    }
  }
  state_.pairs = static_cast<int>(totals[2]);
  state_.min_distance = std::sqrt(totals[1]);
  return kappa_ * totals[0];
}

template <typename Real>
void BarrierTerms<Real>::add_force(cl_mem x, cl_mem mask, cl_mem r) {
  Stopwatch watch{state_.seconds};
  find_near(x, true);
  if (near_.count == 0) return;
  run_pairs(near_, 1);
  device::KernelArgs gather(surface_gradient_k_.get());
  gather.add(gradient_.get()).add(lists_.incidence_offsets.get()).add(lists_.incidence.get());
  gather.add(surface_count_);
  if (pair_bytes_ == sizeof(double))
    gather.add(kappa_);
  else
    gather.add(static_cast<float>(kappa_));
  gather.add(surface_gradient_.get());
  cl_.run(gather.bind(), static_cast<size_t>(surface_count_));
  const int n = static_cast<int>(vertex_count_);
  device::KernelArgs force(force_k_.get());
  force.add(surface_gradient_.get()).add(transpose_offsets_.get()).add(transpose_entries_.get()).add(weight_.get());
  force.add(carriers_).add(n).add(mask).add(r);
  cl_.run(force.bind(), vertex_count_);
  cl_.finish();  // the device's part counted in state().seconds
}

template <typename Real>
void BarrierTerms<Real>::linearize(cl_mem x) {
  Stopwatch watch{state_.seconds};
  find_near(x, true);
  blocks_ = 0;
  if (near_.count == 0) {
    const std::vector<Real> zeros(9 * vertex_count_, Real(0));
    PhaseScope transfer(profiler_, Phase::transfers);
    cl_.write(diagonal_.get(), zeros.size() * sizeof(Real), zeros.data());
    return;
  }
  run_pairs(near_, 2);
  const int count = lists_.blocks;
  reserve(blocks_values_, 9 * static_cast<size_t>(count) * sizeof(Real));
  device::KernelArgs blocks(surface_blocks_k_.get());
  blocks.add(hessian_.get()).add(lists_.contribution_offsets.get()).add(lists_.contributions.get()).add(count);
  if (pair_bytes_ == sizeof(double))
    blocks.add(kappa_);
  else
    blocks.add(static_cast<float>(kappa_));
  blocks.add(blocks_values_.get());
  cl_.run(blocks.bind(), static_cast<size_t>(count));
  const int n = static_cast<int>(vertex_count_);
  device::KernelArgs diagonal(diagonal_k_.get());
  // The linearization's own block rows and columns: a force at another x
  // rebuilds lists_ before the products that use these.
  const size_t row_bytes = (static_cast<size_t>(surface_count_) + 1) * sizeof(int);
  reserve(rows_, row_bytes);
  reserve(columns_, static_cast<size_t>(count) * sizeof(int));
  cl_.copy(lists_.rows.get(), rows_.get(), row_bytes);
  if (count > 0) cl_.copy(lists_.columns.get(), columns_.get(), static_cast<size_t>(count) * sizeof(int));
  diagonal.add(rows_.get()).add(columns_.get()).add(blocks_values_.get());
  diagonal.add(transpose_offsets_.get()).add(transpose_entries_.get()).add(carrier_.get()).add(weight_.get());
  diagonal.add(carriers_).add(n).add(diagonal_.get());
  cl_.run(diagonal.bind(), vertex_count_);
  blocks_ = count;
  cl_.finish();  // the device's part counted in state().seconds
}

template <typename Real>
void BarrierTerms<Real>::add_product(cl_mem mask, cl_mem p, cl_mem y) const {
  if (blocks_ == 0) return;
  device::KernelArgs surface(surface_product_k_.get());
  surface.add(rows_.get()).add(columns_.get()).add(blocks_values_.get()).add(carrier_.get());
  surface.add(weight_store_.get()).add(carriers_).add(surface_count_).add(mask).add(p).add(z_.get()).add(y);
  cl_.run(surface.bind(), static_cast<size_t>(surface_count_));
  if (carriers_ == 1) return;  // W = I: the first pass added to y
  const int n = static_cast<int>(vertex_count_);
  device::KernelArgs spread(spread_product_k_.get());
  spread.add(z_.get()).add(transpose_offsets_.get()).add(transpose_entries_.get()).add(weight_store_.get());
  spread.add(carriers_).add(n).add(mask).add(y);
  cl_.run(spread.bind(), vertex_count_);
}

template <typename Real>
double BarrierTerms<Real>::step_bound(cl_mem x, cl_mem p) {
  Stopwatch watch{state_.seconds};
  at(x);
  lift(p, dq_);
  candidates(x, p, swept_);
  const int count = swept_.count, groups = spans(count);
  if (count == 0) return 1.0;
  reserve(toi_, static_cast<size_t>(count) * pair_bytes_);
  reserve(partial_, 3 * static_cast<size_t>(groups) * pair_bytes_);
  device::KernelArgs ccd(ccd_k_.get());
  ccd.add(q_.get()).add(dq_.get()).add(swept_.vertex.get()).add(swept_.kind.get()).add(count);
  ccd.add(toi_.get());
  cl_.run(ccd.bind(), static_cast<size_t>(count));
  device::KernelArgs partials(min_partials_k_.get());
  partials.add(toi_.get()).add(count).add(partial_.get());
  cl_.run(partials.bind(), static_cast<size_t>(groups));
  device::KernelArgs total(min_total_k_.get());
  total.add(partial_.get()).add(groups).add(total_.get());
  cl_.run(total.bind(), 1);
  PhaseScope transfer(profiler_, Phase::transfers);
  if (pair_bytes_ == sizeof(double)) {
    double bound = 1.0;
    cl_.read(total_.get(), sizeof bound, &bound);
    return bound;
  }
  float bound = 1.0f;
  cl_.read(total_.get(), sizeof bound, &bound);
  return bound;
}

template class BarrierTerms<float>;
template class BarrierTerms<double>;

}  // namespace snh::solver
