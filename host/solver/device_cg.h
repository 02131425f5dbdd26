// Preconditioned conjugate gradients that keep their scalars on the device
// (kernels/cg.cl): r.z and p.Ap are reduced to per-group partials that the
// next kernel adds itself, so an iteration queues its kernels without a read
// and the host reads only the convergence check, once every `check_every`
// iterations (SolverTuning::cg_check_every): the residual norms of those
// iterations and the status, in one read. CG may so run up to check_every - 1
// iterations past the one that met the tolerance; the solve reports how many
// (CgResult::past_convergence) and returns the last iterate, which is at
// least as good. Negative curvature (p.Ap <= 0) or a non-finite step stops
// the iteration on the device (alpha 0 from then on: x and r stay as they
// were, as ViennaCL's CG left them when its curvature monitor stopped it).
//
// Per iteration: the product, one partial-sum kernel (p.Ap), the update
// (x, r, z = r and the partials of r.r in one pass), the preconditioner, one
// partial-sum kernel (r.z) and the new direction. The relative residual is
// |r| / |b|, as in ViennaCL's CG. Deterministic: fixed reduction trees, no
// atomics. Needs fp64 on the device for its sums (DeviceCg::available).
// Internal.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "device/kernel_args.h"
#include "device/opencl_context.h"
#include "snh/error.h"
#include "viennacl/vector.hpp"

namespace snh::solver {

struct CgResult {
  int iterations = 0;  // iterations run (at most max_iterations), past_convergence included
  double relative_residual = 0.0;
  bool negative_curvature = false;
  bool breakdown = false;
  // Of those, the iterations run after the one that met the tolerance or
  // stopped (between it and the next check; at most check_every - 1).
  int past_convergence = 0;
};

template <typename Real>
class DeviceCg {
 public:
  using VectorBase = viennacl::vector_base<Real>;

  static bool available(const device::OpenClContext& cl) { return cl.info().has_fp64; }

  DeviceCg(device::OpenClContext& cl, size_t n, int check_every)
      : cl_(cl), n_(n), check_every_(std::max(1, check_every)) {
    if (!available(cl)) throw Error("solver: the device CG needs fp64 on the device for its sums");
    const size_t span = cl.info().is_gpu ? 512 : 4096;  // SNH_CG_SPAN
    groups_ = std::max<size_t>(1, (n + span - 1) / span);
    device::KernelConfig defines;
    defines.cg_check = check_every_;
    defines.cg_span = static_cast<int>(span);
    defines.float_cycle = sizeof(Real) == 4 && cl.precision() == Precision::double_;
    dot_ = cl.kernel("cg.cl", defines, "snh_cg_dot");
    start_ = cl.kernel("cg.cl", defines, "snh_cg_start");
    first_ = cl.kernel("cg.cl", defines, "snh_cg_first_direction");
    update_ = cl.kernel("cg.cl", defines, "snh_cg_update");
    direction_ = cl.kernel("cg.cl", defines, "snh_cg_direction");
    axpy_ = cl.kernel("cg.cl", defines, "snh_cg_axpy");
    copy_ = cl.kernel("cg.cl", defines, "snh_cg_copy");
    r_ = viennacl::vector<Real>(n);
    z_ = viennacl::vector<Real>(n);
    p_ = viennacl::vector<Real>(n);
    q_ = viennacl::vector<Real>(n);
    pq_ = cl.buffer(CL_MEM_READ_WRITE, groups_ * sizeof(double));
    rz_ = cl.buffer(CL_MEM_READ_WRITE, groups_ * sizeof(double));
    rz_next_ = cl.buffer(CL_MEM_READ_WRITE, groups_ * sizeof(double));
    check_values_ = (check_every_ + 1) * groups_ + check_every_ + 1;
    check_ = cl.buffer(CL_MEM_READ_WRITE, check_values_ * sizeof(double));
    host_.resize(check_values_);
  }

  int check_every() const { return check_every_; }
  size_t memory_bytes() const { return 4 * n_ * sizeof(Real) + (3 * groups_ + check_values_) * sizeof(double); }

  // x = the CG solution of A x = b from x = 0, to |r| <= tolerance |b| or
  // max_iterations; product(p, q): q = A p; precondition(z): z = M^-1 z in
  // place. Both queue device work only.
  template <typename Product, typename Precondition>
  CgResult solve(const VectorBase& b, VectorBase& x, double tolerance, int max_iterations, Product&& product,
                 Precondition&& precondition) {
    const int n = static_cast<int>(n_), groups = static_cast<int>(groups_);
    cl_.run(device::KernelArgs(start_.get()).add(mem(b)).add(n).add(mem(x)).add(mem(r_)).add(mem(z_)).bind(), n_);
    precondition(z_);
    cl_.run(device::KernelArgs(first_.get())
                .add(mem(r_))
                .add(mem(z_))
                .add(n)
                .add(mem(p_))
                .add(rz_.get())
                .add(check_.get())
                .add(groups)
                .bind(),
            groups_ * kGroup);
    CgResult result;
    const double tolerance_squared = tolerance * tolerance;
    double rr0 = -1.0;  // read at the first check
    for (int it = 1; it <= max_iterations; ++it) {
      product(p_, q_);
      cl_.run(device::KernelArgs(dot_.get()).add(mem(p_)).add(mem(q_)).add(n).add(pq_.get()).bind(), groups_ * kGroup);
      const int slot = (it - 1) % check_every_;
      cl_.run(device::KernelArgs(update_.get())
                  .add(mem(p_))
                  .add(mem(q_))
                  .add(n)
                  .add(rz_.get())
                  .add(pq_.get())
                  .add(mem(x))
                  .add(mem(r_))
                  .add(mem(z_))
                  .add(check_.get())
                  .add(groups)
                  .add(slot)
                  .bind(),
              groups_ * kGroup);
      const bool check = slot == check_every_ - 1 || it == max_iterations;
      if (!check) next_direction(precondition, n, groups);
      if (!check) continue;
      // The check: one blocking read of the ring, r0's partials and statuses.
      cl_.read(check_.get(), check_values_ * sizeof(double), host_.data());
      if (rr0 < 0.0) rr0 = sum(check_every_ * groups_);
      const int first = it - slot;  // the iteration in the ring's slot 0
      const double* status = host_.data() + (check_every_ + 1) * groups_;
      for (int s = 0; s <= slot; ++s) {
        const double rr = sum(static_cast<size_t>(s) * groups_);
        const int at = first + s;
        result.iterations = it;
        result.relative_residual = rr0 > 0.0 ? std::sqrt(std::fabs(rr / rr0)) : 0.0;
        result.past_convergence = it - at;
        if (status[s] != 0.0) {  // stopped in this iteration (where ViennaCL's monitor stopped); x and r stayed
          result.negative_curvature = status[s] == 1.0;
          result.breakdown = status[s] == 2.0;
          return result;
        }
        if (!(rr0 > 0.0)) {  // b = 0: x = 0
          result.past_convergence = it;
          return result;
        }
        if (!std::isfinite(result.relative_residual)) return result;
        if (rr < tolerance_squared * rr0) {
          // Met at `at`; x holds iteration it, no worse: its residual.
          const double last = sum(static_cast<size_t>(slot) * groups_);
          result.relative_residual = std::sqrt(std::fabs(last / rr0));
          return result;
        }
      }
      if (it < max_iterations) next_direction(precondition, n, groups);
    }
    return result;
  }

  // y = x + alpha p; y = x.
  void axpy(const VectorBase& x, double alpha, const VectorBase& p, VectorBase& y) {
    const int n = static_cast<int>(x.size());
    cl_.run(device::KernelArgs(axpy_.get()).add(mem(x)).add(alpha).add(mem(p)).add(n).add(mem(y)).bind(), x.size());
  }
  void copy(const VectorBase& x, VectorBase& y) {
    const int n = static_cast<int>(x.size());
    cl_.run(device::KernelArgs(copy_.get()).add(mem(x)).add(n).add(mem(y)).bind(), x.size());
  }

 private:
  static constexpr size_t kGroup = 64;  // SNH_CG_GROUP
  static cl_mem mem(const VectorBase& v) { return v.handle().opencl_handle().get(); }

  // z = M^-1 r (update left z = r), the partials of the new r.z, p = z + beta p.
  template <typename Precondition>
  void next_direction(Precondition& precondition, int n, int groups) {
    precondition(z_);
    cl_.run(device::KernelArgs(dot_.get()).add(mem(r_)).add(mem(z_)).add(n).add(rz_next_.get()).bind(),
            groups_ * kGroup);
    cl_.run(device::KernelArgs(direction_.get())
                .add(mem(z_))
                .add(n)
                .add(rz_next_.get())
                .add(rz_.get())
                .add(check_.get())
                .add(groups)
                .add(mem(p_))
                .bind(),
            groups_ * kGroup);
    std::swap(rz_, rz_next_);
  }
  // The sum of host_[from, from + groups) in index order.
  double sum(size_t from) const {
    double s = 0.0;
    for (size_t g = 0; g < groups_; ++g) s += host_[from + g];
    return s;
  }

  device::OpenClContext& cl_;
  size_t n_;
  int check_every_;
  size_t groups_ = 1;
  device::Kernel dot_, start_, first_, update_, direction_, axpy_, copy_;
  viennacl::vector<Real> r_, z_, p_, q_;
  device::Buffer pq_, rz_, rz_next_, check_;
  size_t check_values_ = 0;
  std::vector<double> host_;
};

}  // namespace snh::solver
