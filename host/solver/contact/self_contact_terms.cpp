#include "solver/contact/self_contact_terms.h"

#include <algorithm>

namespace snh::solver {

template <typename Real>
SelfContactTerms<Real>::SelfContactTerms(device::OpenClContext& cl, const Mesh& mesh,
                                         const device::KernelConfig& config, PhaseProfiler* profiler)
    : cl_(cl), profiler_(profiler), vertex_count_(mesh.vertex_count()), detector_(mesh) {
  differences_k_ = cl_.kernel("fem.cl", config, "snh_self_contact_differences");
  upload();  // the empty set
}

template <typename Real>
void SelfContactTerms<Real>::set_stiffness(double stiffness) {
  if (stiffness == stiffness_) return;
  stiffness_ = stiffness;
  upload();
}

template <typename Real>
bool SelfContactTerms<Real>::refresh(const std::vector<double>& x, bool new_step) {
  std::vector<SelfContactPair> pairs = detector_.detect(x);
  // Within a step a sample still in contact with the same triangle keeps its
  // spring (weights) from when it was found; new samples, and samples whose
  // closest triangle changed, get new ones, samples no longer inside an
  // element lose theirs. Measured on the elbow (res 3, step
  // 25 of 28): re-weighting every Newton iteration made Newton a fixed-point
  // iteration in w (the residual fell from 7e-3 to 3e-3 in 30 iterations, the
  // step stopped at 200) while the set of samples no longer changed.
  if (!new_step) {
    size_t k = 0;
    for (SelfContactPair& p : pairs) {
      while (k < pairs_.size() && pairs_[k].sample < p.sample) ++k;
      if (k < pairs_.size() && pairs_[k].sample == p.sample && pairs_[k].vertex == p.vertex) p = pairs_[k];
    }
  }
  if (pairs == pairs_) return false;
  pairs_ = std::move(pairs);
  upload();
  return true;
}

template <typename Real>
void SelfContactTerms<Real>::upload() {
  // Per contact (s, j0, j1, j2) and w; per vertex, in contact order, the
  // entries (contact, k a_i) and k sum a_i^2: deterministic gathers.
  const size_t n = pairs_.size();
  std::vector<int> pairs(4 * std::max<size_t>(n, 1), 0);
  std::vector<Real> weights(3 * std::max<size_t>(n, 1), Real(0));
  std::vector<int> offsets(vertex_count_ + 1, 0);
  std::vector<double> diagonal(vertex_count_, 0.0);
  for (size_t c = 0; c < n; ++c) {
    const SelfContactPair& p = pairs_[c];
    pairs[4 * c] = p.sample;
    ++offsets[p.sample + 1];
    diagonal[p.sample] += stiffness_;
    for (int j = 0; j < 3; ++j) {
      pairs[4 * c + 1 + j] = p.vertex[j];
      weights[3 * c + j] = static_cast<Real>(p.weight[j]);
      ++offsets[p.vertex[j] + 1];
      diagonal[p.vertex[j]] += stiffness_ * p.weight[j] * p.weight[j];
    }
  }
  for (size_t v = 0; v < vertex_count_; ++v) offsets[v + 1] += offsets[v];
  const size_t entries = std::max<size_t>(offsets[vertex_count_], 1);
  std::vector<int> entry(entries, 0);
  std::vector<Real> coefficient(entries, Real(0));
  std::vector<int> fill(offsets.begin(), offsets.end() - 1);
  for (size_t c = 0; c < n; ++c) {
    const SelfContactPair& p = pairs_[c];
    entry[fill[p.sample]] = static_cast<int>(c);
    coefficient[fill[p.sample]++] = static_cast<Real>(stiffness_);
    for (int j = 0; j < 3; ++j) {
      entry[fill[p.vertex[j]]] = static_cast<int>(c);
      coefficient[fill[p.vertex[j]]++] = static_cast<Real>(-stiffness_ * p.weight[j]);
    }
  }
  const std::vector<Real> diag(diagonal.begin(), diagonal.end());
  PhaseScope transfer(profiler_, Phase::transfers);
  pairs_buf_ = cl_.buffer(CL_MEM_READ_ONLY, pairs.size() * sizeof(int), pairs.data());
  weights_ = cl_.buffer(CL_MEM_READ_ONLY, weights.size() * sizeof(Real), weights.data());
  offsets_ = cl_.buffer(CL_MEM_READ_ONLY, offsets.size() * sizeof(int), offsets.data());
  entries_ = cl_.buffer(CL_MEM_READ_ONLY, entry.size() * sizeof(int), entry.data());
  coefficients_ = cl_.buffer(CL_MEM_READ_ONLY, coefficient.size() * sizeof(Real), coefficient.data());
  diagonal_ = cl_.buffer(CL_MEM_READ_ONLY, diag.size() * sizeof(Real), diag.data());
  const std::vector<Real> zeros(3 * std::max<size_t>(n, 1), Real(0));
  differences_ = cl_.buffer(CL_MEM_READ_WRITE, zeros.size() * sizeof(Real), zeros.data());
}

template <typename Real>
void SelfContactTerms<Real>::differences(cl_mem u) const {
  if (pairs_.empty()) return;
  const int count = static_cast<int>(pairs_.size());
  device::KernelArgs args(differences_k_.get());
  args.add(u).add(pairs_buf_.get()).add(weights_.get()).add(count).add(differences_.get());
  cl_.run(args.bind(), pairs_.size());
}

template <typename Real>
void SelfContactTerms<Real>::add_args(device::KernelArgs& args) const {
  args.add(offsets_.get()).add(entries_.get()).add(coefficients_.get()).add(differences_.get());
}

template class SelfContactTerms<float>;
template class SelfContactTerms<double>;

}  // namespace snh::solver
