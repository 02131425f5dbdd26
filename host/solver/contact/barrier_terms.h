// Barrier self-contact's part of the elastic model (ModelTerms::self_barrier,
// SNH_SELF_BARRIER) at every x the solver evaluates, all on the device from
// the solver's own x (and p): the surface positions W x lifted, the broad
// phase (solver/contact/barrier_broad_phase.h: candidate pairs, the pairs within
// dhat, their index lists), then per pair (kernels/contact/
// barrier_pairs.cl) the distance, the barrier, its gradient and its
// PSD-projected Hessian, summed per vertex through those lists in a fixed
// order (no atomics), and the CCD with its minimum. The Hessian stays on
// the device as 3x3 blocks per surface vertex pair; products apply W^T H W
// in two passes (one for the mesh's own boundary), block-Jacobi gets its
// diagonal blocks. What crosses to the host per evaluation: a few ints
// that size buffers (barrier_broad_phase.h) and the energy's or the step
// bound's few totals. BarrierContact stays the host reference the tests
// compare with. Internal to the library.
#pragma once

#include <utility>
#include <vector>

#include "device/opencl_context.h"
#include "device/phase_profile.h"
#include "snh/mesh.h"
#include "solver/contact/barrier_broad_phase.h"
#include "solver/contact/barrier_contact.h"

namespace snh::solver {

// What the barrier saw at the last x it was evaluated at (energy or
// linearization), and the host time it has taken so far.
struct BarrierState {
  int pairs = 0;              // pairs closer than dhat
  double min_distance = 0.0;  // their smallest distance (dhat when none)
  double seconds = 0.0;       // detection, CCD and assembly since the model was made
};

template <typename Real>
class BarrierTerms {
 public:
  BarrierTerms(device::OpenClContext& cl, const Mesh& mesh, PhaseProfiler* profiler);

  // dhat and kappa (validated by the caller).
  void set_parameters(double dhat, double kappa);
  double distance() const { return contact_.distance(); }
  double stiffness() const { return kappa_; }
  const BarrierContact& contact() const { return contact_; }
  // Acts on `contact`'s surface from now on (an embedded surface over the
  // same mesh's vertices); dhat is kept.
  void set_surface(BarrierContact contact);
  // The surface pairs closer than dhat at rest, left out (BarrierContact::
  // exclude_pairs_near); known once set_parameters has run.
  size_t excluded_at_rest() const { return excluded_at_rest_; }

  // The solver's vectors (x, p, r, y, mask) are device buffers of Real,
  // xyz per vertex.
  // kappa sum b over the pairs within dhat at x.
  double energy(cl_mem x);
  // r -= mask .* kappa d(sum b)/dx at x.
  void add_force(cl_mem x, cl_mem mask, cl_mem r);
  // The projected Hessian at x, kept for add_product and diagonal().
  void linearize(cl_mem x);
  // y += mask .* H (mask .* p) with the Hessian of the last linearize().
  void add_product(cl_mem mask, cl_mem p, cl_mem y) const;
  // The diagonal 3x3 blocks per vertex (9 each, row-major; symmetric).
  cl_mem diagonal() const { return diagonal_.get(); }
  // The largest alpha <= 1 that continuous collision detection clears along
  // x + alpha p.
  double step_bound(cl_mem x, cl_mem p);
  // The device's candidate pairs at x (p null) or along x + t p, and its
  // pairs within dhat at x, read back: what the terms above act on
  // (compared with BarrierContact's in the tests).
  std::vector<BarrierPair> candidate_pairs(cl_mem x, cl_mem p);
  std::vector<BarrierPair> near_pairs(cl_mem x);
  const BarrierState& state() const { return state_; }
  // Candidate pairs from the host's grid (BarrierContact::candidate_pairs,
  // reading x, and p for the CCD) instead of the device's: the same pairs in
  // the same order, so the same results bit for bit.
  void set_candidates_on_host(bool on) {
    host_candidates_ = on;
    x_known_ = false;
  }
  // Whether the pair math runs in double (the device has fp64).
  bool pairs_in_double() const { return pair_bytes_ == sizeof(double); }

 private:
  // W and its transpose on the device, from contact_.
  void upload_surface();
  // Lifts the solver's x to the surface positions `surface` (W x).
  void lift(cl_mem x, device::Buffer& surface);
  // Makes q_ W x. The lists found at the x of the last call are kept when
  // x is the same (compared on the device: one int read), so the energy,
  // force and linearization at one x find them once.
  void at(cl_mem x);
  // The candidate pairs at q_ into candidates_ (kept while x is).
  void find_candidates();
  // The pairs within dhat at x into near_, and with `lists` their index
  // lists into lists_ (kept while x is).
  void find_near(cl_mem x, bool lists);
  // Runs the per-pair kernel over `pairs` at q_: energy and squared
  // distance (derivatives 0), gradient (1), gradient and projected Hessian
  // (2).
  void run_pairs(const DevicePairList& pairs, int derivatives);
  device::Buffer host_to_device(const std::vector<double>& values);
  // A device vector of Real, xyz per vertex, read back in double.
  std::vector<double> to_host(cl_mem v);
  // The candidates at x (p null) or along x + t p into `out`, on the host
  // or the device as set_candidates_on_host says.
  void candidates(cl_mem x, cl_mem p, DevicePairList& out);
  device::Buffer host_to_device(const std::vector<int>& values);
  void reserve(device::Buffer& buffer, size_t bytes);

  device::OpenClContext& cl_;
  PhaseProfiler* profiler_;
  size_t vertex_count_;
  BarrierContact contact_;
  std::vector<double> rest_;  // the mesh's rest positions
  bool excluded_known_ = false;
  size_t excluded_at_rest_ = 0;
  double kappa_ = 0.0;
  BarrierState state_;
  size_t pair_bytes_ = sizeof(double);  // the pair math's real
  BarrierBroadPhase broad_;
  // The surface: its vertex count, carriers per vertex (8 embedded, 1 the
  // mesh's own), W's carriers and weights (pair precision and the build's),
  // and W's transpose per lattice vertex (entries s * carriers + k).
  int surface_count_ = 0, carriers_ = 1;
  device::Buffer carrier_, weight_, weight_store_, transpose_offsets_, transpose_entries_;
  device::Buffer q_, dq_, surface_gradient_, partial_, total_, toi_;
  // The pair lists and, per pair of the list last run: energy, squared
  // distance, gradient (12), projected Hessian (144).
  DevicePairList candidates_, near_, swept_;
  DevicePairLists lists_;
  // The x the lists were found at (a device copy) and what holds for it.
  device::Buffer x_copy_, differs_;
  bool host_candidates_ = false;
  bool x_known_ = false, candidates_known_ = false, near_known_ = false, lists_known_ = false;
  device::Buffer energy_, distance_, gradient_, hessian_;
  // The linearization: surface blocks (block CSR over surface vertices),
  // the lattice diagonal blocks, and the product's surface vectors.
  int blocks_ = 0;
  device::Buffer rows_, columns_, blocks_values_, diagonal_, z_;
  device::Kernel lift_k_, energy_k_, pair_k_, partials_k_, total_k_, surface_gradient_k_, force_k_, surface_blocks_k_,
      diagonal_k_, surface_product_k_, spread_product_k_, ccd_k_, min_partials_k_, min_total_k_, differs_k_;
};

}  // namespace snh::solver
