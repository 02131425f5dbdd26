// Barrier self-contact's part of the elastic model (ModelTerms::self_barrier,
// SNH_SELF_BARRIER) at every x the solver evaluates. The host finds the
// candidate pairs (solver/barrier_contact.h's broad phase) and builds the
// index lists of each pair list; the device (kernels/contact/
// barrier_pairs.cl) computes per pair the distance, the barrier, its
// gradient and its PSD-projected Hessian, sums them per vertex through
// those lists in a fixed order (no atomics), and runs the CCD with its
// minimum. The Hessian stays on the device as 3x3 blocks per surface vertex
// pair; products apply W^T H W in two passes (one for the mesh's own
// boundary), block-Jacobi gets its diagonal blocks. What crosses to the
// host per evaluation: the candidate pairs up, their squared distances
// down (to keep those within dhat), and the energy's or the step bound's
// few totals. Internal to the library.
#pragma once

#include <utility>
#include <vector>

#include "device/opencl_context.h"
#include "snh/mesh.h"
#include "solver/barrier_contact.h"
#include "solver/phase_profile.h"

namespace snh::solver {

// What the barrier saw at the last x it was evaluated at (energy or
// linearization), and the host time it has taken so far.
struct BarrierState {
  int pairs = 0;              // pairs closer than dhat
  double min_distance = 0.0;  // their smallest distance (dhat when none)
  double seconds = 0.0;       // detection, CCD and assembly since the model was made
};

// A pair list on the device with the index lists its sums run through.
struct BarrierPairBuffers {
  std::vector<BarrierPair> pairs;  // as uploaded (the comparison for reuse)
  device::Buffer vertex, kind, ex;
  // Per surface vertex, its incidences (pair * 4 + corner), in pair order.
  device::Buffer incidence_offsets, incidence;
  // The pairs' 3x3 blocks per surface vertex pair (rows, then columns,
  // ascending) and per block its contributions (pair * 16 + 4 row corner +
  // column corner), in pair order.
  std::vector<int> rows, columns;
  device::Buffer contribution_offsets, contributions;
  // Per pair: energy, squared distance, gradient (12), projected Hessian (144).
  device::Buffer energy, distance, gradient, hessian;
  int count = 0, blocks = 0;
  bool lists = false;  // the index lists built for `pairs`
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

  // kappa sum b over the pairs within dhat at x (xyz per vertex, double).
  double energy(const std::vector<double>& x);
  // r -= mask .* kappa d(sum b)/dx at x.
  void add_force(const std::vector<double>& x, cl_mem mask, cl_mem r);
  // The projected Hessian at x, uploaded for add_product and diagonal().
  void linearize(const std::vector<double>& x);
  // y += mask .* H (mask .* p) with the Hessian of the last linearize().
  void add_product(cl_mem mask, cl_mem p, cl_mem y) const;
  // The diagonal 3x3 blocks per vertex (9 each, row-major; symmetric).
  cl_mem diagonal() const { return diagonal_.get(); }
  // The largest alpha <= 1 that continuous collision detection clears along
  // x + alpha p.
  double step_bound(const std::vector<double>& x, const std::vector<double>& p);
  const BarrierState& state() const { return state_; }
  // Whether the pair math runs in double (the device has fp64).
  bool pairs_in_double() const { return pair_bytes_ == sizeof(double); }

 private:
  // W and its transpose on the device, from contact_.
  void upload_surface();
  // Uploads x and lifts it to the surface positions q_.
  void lift(const std::vector<double>& x, device::Buffer& lattice, device::Buffer& surface);
  // Makes `pairs` the device's pair list (nothing when it is already).
  void set_pairs(const std::vector<BarrierPair>& pairs);
  // The current pair list's index lists (once per list).
  void build_lists();
  // The candidate pairs at x (cached for the last x).
  const std::vector<BarrierPair>& candidates(const std::vector<double>& x);
  // Runs the per-pair kernel over the current pair list at q_: energy and
  // squared distance (derivatives 0), gradient (1), gradient and projected
  // Hessian (2).
  void run_pairs(int derivatives);
  // The pairs within dhat at x (cached for the last x), on the device.
  const std::vector<BarrierPair>& near_pairs(const std::vector<double>& x);
  device::Buffer host_to_device(const std::vector<double>& values);
  device::Buffer host_to_device(const std::vector<int>& values);

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
  // The surface: its vertex count, carriers per vertex (8 embedded, 1 the
  // mesh's own), W's carriers and weights (pair precision and the build's),
  // and W's transpose per lattice vertex (entries s * carriers + k).
  int surface_count_ = 0, carriers_ = 1;
  device::Buffer carrier_, weight_, weight_store_, transpose_offsets_, transpose_entries_;
  device::Buffer x_, q_, p_, dq_, surface_gradient_, partial_, total_, toi_;
  BarrierPairBuffers pairs_;
  std::vector<double> near_x_, candidates_x_;
  std::vector<BarrierPair> near_, candidates_;
  bool near_valid_ = false, candidates_valid_ = false;
  // The linearization: surface blocks (block CSR over surface vertices), the
  // lattice diagonal blocks, and the product's surface vectors.
  int blocks_ = 0;
  device::Buffer rows_, columns_, blocks_values_, diagonal_, z_;
  device::Kernel lift_k_, energy_k_, pair_k_, partials_k_, total_k_, surface_gradient_k_, force_k_, surface_blocks_k_,
      diagonal_k_, surface_product_k_, spread_product_k_, ccd_k_, min_partials_k_, min_total_k_;
};

}  // namespace snh::solver
