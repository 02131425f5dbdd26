// Preconditioned conjugate gradients that keep their scalars on the device
// (kernels/cg.cl): r.z and p.Ap are reduced to per-group partials that the
// next kernel adds itself, so an iteration queues its kernels without a read.
// The device tests convergence in every iteration as ViennaCL's CG does
// (the preconditioned residual, r.z < tolerance^2 r0.z0) and from the
// iteration that met it (or stopped: p.Ap <= 0, a non-finite step or
// residual) leaves x and r as they are, so the solution and the reported
// iterations and relative residual are those of a CG that checks every
// iteration, whatever the check interval. The host reads the status once
// every `check_every` iterations (SolverTuning::cg_check_every): the ring of
// those iterations' r.z and statuses, in one read of 2 k + 2 doubles. Up to
// check_every - 1 iterations run past the one that stopped, their products
// and preconditioner applications spent for nothing (CgResult::past_convergence).
//
// Per iteration: the product, one partial-sum kernel (p.Ap), the update
// (x, r and z = r in one pass), the preconditioner, one partial-sum kernel
// (r.z) and the new direction with the test. Deterministic: fixed reduction
// trees, no atomics. Needs fp64 on the device for its sums
// (DeviceCg::available). Internal.
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
  int iterations = 0;              // up to the one that met the tolerance or stopped (at most max_iterations)
  double relative_residual = 0.0;  // sqrt(r.z / r0.z0) there, as ViennaCL's CG reports it
  bool negative_curvature = false;
  bool breakdown = false;
  // Iterations run after `iterations` before the host saw the stop (at most
  // check_every - 1), x and r unchanged by them.
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
    // kernels/cg.cl: the ring's r.z and statuses, the live status, r0.z0,
    // then r0.z0's partials, which the host does not read.
    check_values_ = 2 * check_every_ + 2;
    check_ = cl.buffer(CL_MEM_READ_WRITE, (check_values_ + groups_) * sizeof(double));
    host_.resize(check_values_);
  }

  int check_every() const { return check_every_; }
  size_t memory_bytes() const { return 4 * n_ * sizeof(Real) + (4 * groups_ + check_values_) * sizeof(double); }

  // x = the CG solution of A x = b from x = 0, to r.z < tolerance^2 r0.z0 or
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
    for (int it = 1; it <= max_iterations; ++it) {
      product(p_, q_);
      cl_.run(device::KernelArgs(dot_.get()).add(mem(p_)).add(mem(q_)).add(n).add(pq_.get()).bind(), groups_ * kGroup);
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
                  .bind(),
              groups_ * kGroup);
      const int slot = (it - 1) % check_every_;
      next_direction(precondition, n, groups, slot, tolerance_squared);
      if (slot != check_every_ - 1 && it != max_iterations) continue;
      // The check: one blocking read of the ring, the live status and r0.z0.
      cl_.read(check_.get(), check_values_ * sizeof(double), host_.data());
      const double r0z0 = host_[2 * check_every_ + 1];
      if (!(r0z0 > 0.0)) {  // b = 0 (or M^-1 not positive on it): x = 0, as ViennaCL returns
        result.iterations = 0;
        result.relative_residual = std::isfinite(r0z0) ? 0.0 : r0z0;
        result.past_convergence = it;
        return result;
      }
      const int first = it - slot;  // the iteration in the ring's slot 0
      for (int s = 0; s <= slot; ++s) {
        const double status = host_[check_every_ + s];
        result.iterations = first + s;
        result.relative_residual = std::sqrt(std::fabs(host_[s] / r0z0));
        if (status == 0.0) continue;
        result.negative_curvature = status == 1.0;
        result.breakdown = status == 2.0;
        result.past_convergence = it - result.iterations;
        return result;
      }
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

  // z = M^-1 r (update left z = r), the partials of the new r.z, the
  // convergence test and p = z + beta p.
  template <typename Precondition>
  void next_direction(Precondition& precondition, int n, int groups, int slot, double tolerance_squared) {
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
                .add(slot)
                .add(tolerance_squared)
                .add(mem(p_))
                .bind(),
            groups_ * kGroup);
    std::swap(rz_, rz_next_);
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
