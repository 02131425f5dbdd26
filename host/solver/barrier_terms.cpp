#include "solver/barrier_terms.h"

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
    : cl_(cl), profiler_(profiler), vertex_count_(mesh.vertex_count()), contact_(mesh), rest_(mesh.positions) {
  pair_bytes_ = cl_.info().has_fp64 ? sizeof(double) : sizeof(float);
  const char* file = "contact/barrier_pairs.cl";
  const device::KernelConfig config;
  lift_k_ = cl_.kernel(file, config, "snh_barrier_lift");
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
  x_ = cl_.buffer(CL_MEM_READ_ONLY, 3 * vertex_count_ * pair_bytes_);
  p_ = cl_.buffer(CL_MEM_READ_ONLY, 3 * vertex_count_ * pair_bytes_);
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
  }
  kappa_ = kappa;
  near_valid_ = candidates_valid_ = false;
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
  pairs_ = BarrierPairBuffers{};
  near_valid_ = candidates_valid_ = false;
  blocks_ = 0;
}

template <typename Real>
void BarrierTerms<Real>::lift(const std::vector<double>& x, device::Buffer& lattice, device::Buffer& surface) {
  {
    PhaseScope transfer(profiler_, Phase::transfers);
    if (pair_bytes_ == sizeof(double)) {
      cl_.write(lattice.get(), x.size() * sizeof(double), x.data());
    } else {
      const std::vector<float> narrow(x.begin(), x.end());
      cl_.write(lattice.get(), narrow.size() * sizeof(float), narrow.data());
    }
  }
  device::KernelArgs args(lift_k_.get());
  args.add(lattice.get()).add(carrier_.get()).add(weight_.get()).add(carriers_).add(surface_count_).add(surface.get());
  cl_.run(args.bind(), static_cast<size_t>(surface_count_));
}

template <typename Real>
void BarrierTerms<Real>::set_pairs(const std::vector<BarrierPair>& pairs) {
  if (pairs_.count == static_cast<int>(pairs.size()) && pairs_.pairs == pairs) return;
  BarrierPairBuffers& b = pairs_;
  b.pairs = pairs;
  b.count = static_cast<int>(pairs.size());
  b.lists = false;
  const size_t count = pairs.size();
  std::vector<cl_int4> vertex(std::max<size_t>(count, 1));
  std::vector<int> kind(count);
  std::vector<double> ex(count);
  for (size_t i = 0; i < count; ++i) {
    for (int k = 0; k < 4; ++k) vertex[i].s[k] = pairs[i].vertex[k];
    kind[i] = pairs[i].kind;
    ex[i] = pairs[i].ex;
  }
  PhaseScope transfer(profiler_, Phase::transfers);
  b.vertex = cl_.buffer(CL_MEM_READ_ONLY, vertex.size() * sizeof(cl_int4), vertex.data());
  b.kind = host_to_device(kind);
  b.ex = host_to_device(ex);
  const size_t slots = std::max<size_t>(count, 1);
  b.energy = cl_.buffer(CL_MEM_READ_WRITE, slots * pair_bytes_);
  b.distance = cl_.buffer(CL_MEM_READ_WRITE, slots * pair_bytes_);
  b.gradient = device::Buffer();
  b.hessian = device::Buffer();
}

template <typename Real>
void BarrierTerms<Real>::build_lists() {
  BarrierPairBuffers& b = pairs_;
  if (b.lists) return;
  const std::vector<BarrierPair>& pairs = b.pairs;
  const size_t count = pairs.size();
  // Incidences per surface vertex, in pair order (a counting sort).
  std::vector<int> offsets(surface_count_ + 1, 0), incidence(4 * count);
  for (const BarrierPair& p : pairs)
    for (int v : p.vertex) ++offsets[v + 1];
  for (int s = 0; s < surface_count_; ++s) offsets[s + 1] += offsets[s];
  std::vector<int> fill(offsets.begin(), offsets.end() - 1);
  for (size_t i = 0; i < count; ++i)
    for (int v = 0; v < 4; ++v) incidence[fill[pairs[i].vertex[v]]++] = static_cast<int>(4 * i + v);
  // The pairs' blocks by (row, column), contributions in pair order.
  std::vector<std::array<int, 3>> keys;
  keys.reserve(16 * count);
  for (size_t i = 0; i < count; ++i)
    for (int v = 0; v < 4; ++v)
      for (int w = 0; w < 4; ++w)
        keys.push_back({pairs[i].vertex[v], pairs[i].vertex[w], static_cast<int>(16 * i + 4 * v + w)});
  std::sort(keys.begin(), keys.end());
  b.rows.assign(surface_count_ + 1, 0);
  b.columns.clear();
  std::vector<int> contribution_offsets{0}, contributions;
  contributions.reserve(keys.size());
  for (size_t k = 0; k < keys.size(); ++k) {
    if (k == 0 || keys[k][0] != keys[k - 1][0] || keys[k][1] != keys[k - 1][1]) {
      if (k > 0) contribution_offsets.push_back(static_cast<int>(k));
      ++b.rows[keys[k][0] + 1];
      b.columns.push_back(keys[k][1]);
    }
    contributions.push_back(keys[k][2]);
  }
  contribution_offsets.push_back(static_cast<int>(keys.size()));
  if (keys.empty()) contribution_offsets.assign(1, 0);
  for (int s = 0; s < surface_count_; ++s) b.rows[s + 1] += b.rows[s];
  b.blocks = static_cast<int>(b.columns.size());
  PhaseScope transfer(profiler_, Phase::transfers);
  b.incidence_offsets = host_to_device(offsets);
  b.incidence = host_to_device(incidence);
  b.contribution_offsets = host_to_device(contribution_offsets);
  b.contributions = host_to_device(contributions);
  b.lists = true;
}

template <typename Real>
const std::vector<BarrierPair>& BarrierTerms<Real>::candidates(const std::vector<double>& x) {
  if (!(candidates_valid_ && x == candidates_x_)) {
    candidates_ = contact_.candidate_pairs(x, nullptr);
    candidates_x_ = x;
    candidates_valid_ = true;
  }
  return candidates_;
}

template <typename Real>
void BarrierTerms<Real>::run_pairs(int derivatives) {
  BarrierPairBuffers& b = pairs_;
  if (b.count == 0) return;
  const double sh = contact_.distance() * contact_.distance();
  auto add_real = [&](device::KernelArgs& args, double value) {
    if (pair_bytes_ == sizeof(double))
      args.add(value);
    else
      args.add(static_cast<float>(value));
  };
  const size_t count = static_cast<size_t>(b.count);
  if (derivatives == 0) {
    device::KernelArgs args(energy_k_.get());
    args.add(q_.get()).add(b.vertex.get()).add(b.kind.get()).add(b.ex.get()).add(b.count);
    add_real(args, sh);
    args.add(b.energy.get()).add(b.distance.get());
    cl_.run(args.bind(), count);
    return;
  }
  if (!b.gradient) b.gradient = cl_.buffer(CL_MEM_READ_WRITE, 12 * count * pair_bytes_);
  const int hessian = derivatives > 1 ? 1 : 0;
  if (hessian && !b.hessian) b.hessian = cl_.buffer(CL_MEM_READ_WRITE, 144 * count * pair_bytes_);
  device::KernelArgs args(pair_k_.get());
  args.add(q_.get()).add(b.vertex.get()).add(b.kind.get()).add(b.ex.get()).add(b.count);
  add_real(args, sh);
  args.add(hessian).add(b.gradient.get()).add(hessian ? b.hessian.get() : b.gradient.get());
  cl_.run(args.bind(), count);
}

template <typename Real>
const std::vector<BarrierPair>& BarrierTerms<Real>::near_pairs(const std::vector<double>& x) {
  if (near_valid_ && x == near_x_) return near_;
  const std::vector<BarrierPair>& candidates = this->candidates(x);
  near_.clear();
  if (!candidates.empty()) {
    lift(x, x_, q_);
    set_pairs(candidates);
    run_pairs(0);
    std::vector<double> distance(candidates.size());
    {
      PhaseScope transfer(profiler_, Phase::transfers);
      if (pair_bytes_ == sizeof(double)) {
        cl_.read(pairs_.distance.get(), distance.size() * sizeof(double), distance.data());
      } else {
        std::vector<float> narrow(distance.size());
        cl_.read(pairs_.distance.get(), narrow.size() * sizeof(float), narrow.data());
        distance.assign(narrow.begin(), narrow.end());
      }
    }
    const double sh = contact_.distance() * contact_.distance();
    for (size_t i = 0; i < candidates.size(); ++i)
      if (distance[i] < sh) near_.push_back(candidates[i]);
  }
  near_x_ = x;
  near_valid_ = true;
  return near_;
}

template <typename Real>
double BarrierTerms<Real>::energy(const std::vector<double>& x) {
  Stopwatch watch{state_.seconds};
  const double dhat = contact_.distance(), sh = dhat * dhat;
  const std::vector<BarrierPair>& candidates = this->candidates(x);
  state_.pairs = 0;
  state_.min_distance = dhat;
  if (candidates.empty()) return 0.0;
  lift(x, x_, q_);
  set_pairs(candidates);
  run_pairs(0);
  const int count = pairs_.count, groups = spans(count);
  if (!partial_ || device::OpenClContext::bytes(partial_.get()) < 3 * static_cast<size_t>(groups) * pair_bytes_)
    partial_ = cl_.buffer(CL_MEM_READ_WRITE, 3 * static_cast<size_t>(groups) * pair_bytes_);
  double totals[3];
  {
    device::KernelArgs args(partials_k_.get());
    args.add(pairs_.energy.get()).add(pairs_.distance.get()).add(count);
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
void BarrierTerms<Real>::add_force(const std::vector<double>& x, cl_mem mask, cl_mem r) {
  Stopwatch watch{state_.seconds};
  const std::vector<BarrierPair> near = near_pairs(x);
  if (near.empty()) return;
  lift(x, x_, q_);
  set_pairs(near);
  build_lists();
  run_pairs(1);
  device::KernelArgs gather(surface_gradient_k_.get());
  gather.add(pairs_.gradient.get()).add(pairs_.incidence_offsets.get()).add(pairs_.incidence.get());
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
void BarrierTerms<Real>::linearize(const std::vector<double>& x) {
  Stopwatch watch{state_.seconds};
  const std::vector<BarrierPair> near = near_pairs(x);
  blocks_ = 0;
  if (near.empty()) {
    const std::vector<Real> zeros(9 * vertex_count_, Real(0));
    PhaseScope transfer(profiler_, Phase::transfers);
    cl_.write(diagonal_.get(), zeros.size() * sizeof(Real), zeros.data());
    return;
  }
  lift(x, x_, q_);
  set_pairs(near);
  build_lists();
  run_pairs(2);
  const BarrierPairBuffers& b = pairs_;
  {
    PhaseScope transfer(profiler_, Phase::transfers);
    rows_ = host_to_device(b.rows);
    columns_ = host_to_device(b.columns);
  }
  blocks_values_ = cl_.buffer(CL_MEM_READ_WRITE, 9 * static_cast<size_t>(b.blocks) * sizeof(Real));
  device::KernelArgs blocks(surface_blocks_k_.get());
  blocks.add(b.hessian.get()).add(b.contribution_offsets.get()).add(b.contributions.get()).add(b.blocks);
  if (pair_bytes_ == sizeof(double))
    blocks.add(kappa_);
  else
    blocks.add(static_cast<float>(kappa_));
  blocks.add(blocks_values_.get());
  cl_.run(blocks.bind(), static_cast<size_t>(b.blocks));
  const int n = static_cast<int>(vertex_count_);
  device::KernelArgs diagonal(diagonal_k_.get());
  diagonal.add(rows_.get()).add(columns_.get()).add(blocks_values_.get());
  diagonal.add(transpose_offsets_.get()).add(transpose_entries_.get()).add(carrier_.get()).add(weight_.get());
  diagonal.add(carriers_).add(n).add(diagonal_.get());
  cl_.run(diagonal.bind(), vertex_count_);
  blocks_ = b.blocks;
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
double BarrierTerms<Real>::step_bound(const std::vector<double>& x, const std::vector<double>& p) {
  Stopwatch watch{state_.seconds};
  const std::vector<BarrierPair> candidates = contact_.candidate_pairs(x, &p);
  if (candidates.empty()) return 1.0;
  lift(x, x_, q_);
  lift(p, p_, dq_);
  set_pairs(candidates);
  const int count = pairs_.count, groups = spans(count);
  if (!toi_ || device::OpenClContext::bytes(toi_.get()) < static_cast<size_t>(count) * pair_bytes_)
    toi_ = cl_.buffer(CL_MEM_READ_WRITE, static_cast<size_t>(count) * pair_bytes_);
  if (!partial_ || device::OpenClContext::bytes(partial_.get()) < 3 * static_cast<size_t>(groups) * pair_bytes_)
    partial_ = cl_.buffer(CL_MEM_READ_WRITE, 3 * static_cast<size_t>(groups) * pair_bytes_);
  device::KernelArgs ccd(ccd_k_.get());
  ccd.add(q_.get()).add(dq_.get()).add(pairs_.vertex.get()).add(pairs_.kind.get()).add(count).add(toi_.get());
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
