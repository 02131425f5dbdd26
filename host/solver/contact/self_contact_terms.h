// Self-contact's part of the elastic model (ModelTerms::self_contact,
// SNH_SELF_CONTACT): the detector, the frozen active set of springs and its
// device arrays, which the model's gather, mask and block-Jacobi kernels
// read. Internal to the library.
#pragma once

#include <vector>

#include "device/kernel_args.h"
#include "device/opencl_context.h"
#include "device/phase_profile.h"
#include "snh/mesh.h"
#include "solver/contact/self_contact.h"

namespace snh::solver {

template <typename Real>
class SelfContactTerms {
 public:
  // `config`: the model's build (with self_contact); uploads the
  // empty set. Uploads are charged to `profiler`'s transfers.
  SelfContactTerms(device::OpenClContext& cl, const Mesh& mesh, const device::KernelConfig& config,
                   PhaseProfiler* profiler);

  // The springs' stiffness (validated by the caller); uploads the set again
  // when it changes.
  void set_stiffness(double stiffness);
  double stiffness() const { return stiffness_; }
  // The active set detected at x (xyz per vertex). Within a step (new_step
  // false) a sample still in contact keeps the spring it had. Returns
  // whether the set changed.
  bool refresh(const std::vector<double>& x, bool new_step);
  const std::vector<SelfContactPair>& pairs() const { return pairs_; }
  const SelfContactDetector& detector() const { return detector_; }

  // d_c = a_c^T u for the frozen set (before a gather that uses them).
  void differences(cl_mem u) const;
  // The springs' per-vertex arguments of the gather and mask kernels, and
  // their per-vertex k sum a_i^2 for block-Jacobi.
  void add_args(device::KernelArgs& args) const;
  cl_mem diagonal() const { return diagonal_.get(); }

 private:
  void upload();

  device::OpenClContext& cl_;
  PhaseProfiler* profiler_;
  size_t vertex_count_;
  SelfContactDetector detector_;
  std::vector<SelfContactPair> pairs_;
  double stiffness_ = 0.0;
  // Pairs s, j0..j2 and weights per contact; per-vertex CSR of (contact,
  // k a_i); per-vertex k sum a_i^2; the differences d_c.
  device::Buffer pairs_buf_, weights_, offsets_, entries_, coefficients_, differences_, diagonal_;
  device::Kernel differences_k_;
};

}  // namespace snh::solver
