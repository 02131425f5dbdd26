// Barrier self-contact's part of the elastic model (ModelTerms::self_barrier,
// SNH_SELF_BARRIER): the host detection (solver/barrier_contact.h) run at
// every x the solver evaluates, and the device arrays the products and
// block-Jacobi read: the projected Hessian in block CSR and its diagonal
// blocks. Internal to the library.
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
  void set_surface(BarrierContact contact) {
    contact_ = std::move(contact);
    excluded_known_ = false;
  }
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

 private:
  device::OpenClContext& cl_;
  PhaseProfiler* profiler_;
  size_t vertex_count_;
  BarrierContact contact_;
  std::vector<double> rest_;  // the mesh's rest positions
  bool excluded_known_ = false;
  size_t excluded_at_rest_ = 0;
  double kappa_ = 0.0;
  BarrierState state_;
  int rows_ = 0;
  device::Buffer offsets_, columns_, blocks_, diagonal_, gradient_;
  device::Kernel product_k_, force_k_;
};

}  // namespace snh::solver
