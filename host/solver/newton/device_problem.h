// The device model as a Newton problem (solver/newton/newton_driver.h): energies,
// residuals and the matrix-free Hessian on the OpenCL device, linear solves by
// ViennaCL's CG with the block-Jacobi or multigrid preconditioner. Norms and dot products
// are summed in double in a fixed order (solver/linear/device_reduction.h): deterministic.
// Every call charges its time to a phase of the model's profiler
// (device/phase_profile.h): the CG solve to its vector work, less the
// products and preconditioner applications inside it.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "device/viennacl_binding.h"
#include "snh/error.h"
#include "solver/linear/device_cg.h"
#include "solver/model/elastic_model.h"
#include "solver/newton/matrix_free.h"
#include "solver/newton/newton_driver.h"
#include "viennacl/linalg/cg.hpp"

namespace snh::solver {

template <typename Real>
class DeviceProblem {
 public:
  using Vector = viennacl::vector<Real>;

  // preconditioner: none, block_jacobi or multigrid (then `multigrid` is
  // its V-cycle); automatic is resolved by the caller.
  DeviceProblem(ElasticModel<Real>& model, Preconditioner preconditioner,
                std::unique_ptr<MultigridPreconditioner<Real>> multigrid = nullptr)
      : model_(model),
        op_(model),
        multigrid_(std::move(multigrid)),
        precond_(model, preconditioner, multigrid_.get()),
        preconditioner_(preconditioner),
        rebuild_(multigrid_ ? multigrid_->options() : MultigridOptions{}) {
    if (preconditioner == Preconditioner::multigrid && !multigrid_)
      throw Error("solver: the multigrid preconditioner was not built");
    model_.profiler().count_with(&model_.context().counts());
  }

  // CG on the device checking convergence every `check_every` iterations
  // (SolverTuning::cg_check_every); 0, or a device without fp64: ViennaCL's
  // CG. The line search's steps and copies then run as counted kernels too.
  void use_device_cg(int check_every) {
    device_cg_.reset();
    if (check_every > 0 && DeviceCg<Real>::available(model_.context()))
      device_cg_ = std::make_unique<DeviceCg<Real>>(model_.context(), model_.dofs(), check_every);
  }
  bool device_cg() const { return device_cg_ != nullptr; }

  size_t dofs() const { return model_.dofs(); }
  // The multigrid's options as it resolved them (the smoothing chosen from
  // the mesh and materials); null without multigrid.
  const MultigridOptions* multigrid_options() const { return multigrid_ ? &multigrid_->options() : nullptr; }
  bool multigrid_float_cycle() const { return multigrid_ && multigrid_->float_cycle(); }
  // Device memory at the solve's peak: the model's buffers, the
  // preconditioner's, and the vectors of a Newton iteration (x and the
  // driver's r, p, trial, r_trial, far, r_far) with those of ViennaCL's CG
  // inside it (result, residual, tmp, z, p).
  size_t memory_bytes() const {
    return model_.memory_bytes() + 12 * model_.dofs() * sizeof(Real) + (multigrid_ ? multigrid_->memory_bytes() : 0) +
           (device_cg_ ? device_cg_->memory_bytes() : 0);
  }
  double epsilon() const { return std::numeric_limits<Real>::epsilon(); }
  // A zero vector: zero-filled where it is made (OpenClContext::buffer), no
  // kernel (ViennaCL's own clearing would launch one behind the counts).
  Vector vector() const {
    // Padded as ViennaCL pads its own (fast_swap exchanges buffers, not sizes).
    const size_t padded = viennacl::tools::align_to_multiple<size_t>(model_.dofs(), viennacl::dense_padding_size);
    device::Buffer zeros = model_.context().buffer(CL_MEM_READ_WRITE, padded * sizeof(Real));
    return Vector(zeros.get(), model_.dofs());  // ViennaCL keeps its own reference
  }
  double energy(const Vector& x) { return model_.energy(x); }
  double last_min_j() const { return model_.last_min_j(); }
  double energy_magnitude() const { return model_.last_energy_magnitude(); }
  void residual(const Vector& x, Vector& r) { model_.residual(x, r); }
  // The self-contact set refreshed at x (no-op without self-contact); a new
  // load step also asks for a new multigrid hierarchy.
  bool refresh(const Vector& x, bool new_step) {
    if (new_step) rebuild_.new_step();
    // Friction's normal forces are re-lagged at each step: its Hessian
    // blocks change with them.
    if (new_step && model_.terms().friction) rebuild_.invalidate();
    return model_.contact().refresh_self_contact(x, new_step);
  }
  bool has_true_hessian() const { return true; }
  // Barrier self-contact: the largest step along p that continuous
  // collision detection clears (infinity without it).
  double step_bound(const Vector& x, const Vector& p) { return model_.contact().step_bound(x, p); }
  bool has_barrier() const { return model_.contact().self_barrier() != nullptr; }

  double norm(const Vector& v) const { return std::sqrt(model_.reduction().sum_of_squares(mem(v), v.size())); }
  double dot(const Vector& u, const Vector& v) const { return model_.reduction().dot(mem(u), mem(v), u.size()); }

  void linearize(const Vector& x, bool projected) {
    model_.linearize(x, projected);
    if (preconditioner_ == Preconditioner::none) return;
    PhaseScope timed(&model_.profiler(), Phase::preconditioner_setup);
    // Obstacle contact: a vertex entering or leaving a layer gains or loses a
    // contact block (k n n^T, 10^4 times the elastic diagonal in a squash)
    // that a reused hierarchy and its fine smoother's blocks lack, and CG
    // with that V-cycle crawled (docs/performance.md, "Multigrid rebuilds on
    // obstacle contact").
    uint64_t contacts = 0;
    if (multigrid_ && model_.terms().obstacles > 0) {
      contacts = model_.contact().contact_set_signature();
      if (contacts != built_contacts_) rebuild_.invalidate();
    }
    if (multigrid_ && !rebuild_.due(projected)) {  // the last hierarchy, its fine bound for this operator
      multigrid_->update_fine_bound();
      rebuild_.reused();
      return;
    }
    // Block-Jacobi, or the multigrid's fine smoother when that follows the
    // model's operator.
    if (!multigrid_ || !multigrid_->fine_level_built()) model_.setup_preconditioner();
    if (multigrid_) {
      multigrid_->setup();
      rebuild_.built(projected);
      built_contacts_ = contacts;
    }
  }
  // The next linearization builds the multigrid hierarchy afresh, its
  // smoothing bounds estimated from the fixed start, as a new problem's first
  // does: what a restored checkpoint needs to continue as the original did.
  void restart_preconditioner() {
    rebuild_.restart();
    if (multigrid_) multigrid_->forget_estimates();
  }
  // Multigrid hierarchies built so far (0 without multigrid).
  int preconditioner_builds() const { return rebuild_.builds(); }
  // CG iterations run past the one that met the tolerance, over all solves
  // (SolveProfile::cg_iterations_past_convergence).
  long long cg_iterations_past_convergence() const { return past_convergence_; }

  LinearSolve solve(const Vector& r, Vector& p, double eta, int max_iterations) {
    PhaseScope timed(&model_.profiler(), Phase::cg_vector_work);
    if (device_cg_) {
      PhaseProfiler* profiler = &model_.profiler();
      // The tolerance ViennaCL's CG would use (its tag holds it in Real).
      const CgResult c = device_cg_->solve(
          r, p, static_cast<double>(static_cast<Real>(eta)), max_iterations,
          [this, profiler](const viennacl::vector_base<Real>& d, viennacl::vector_base<Real>& q) {
            PhaseScope product(profiler, Phase::products);
            model_.product(d, q);
          },
          [this, profiler](viennacl::vector_base<Real>& z) {
            PhaseScope apply(preconditioned() ? profiler : nullptr, Phase::preconditioner_apply);
            precond_.apply(z);
          });
      LinearSolve s;
      s.iterations = c.iterations;
      s.relative_residual = c.relative_residual;
      s.negative_curvature = c.negative_curvature;
      s.breakdown = c.breakdown;
      past_convergence_ += c.past_convergence;
      if (multigrid_) rebuild_.solved(s.iterations, s.relative_residual, s.relative_residual <= eta);
      return s;
    }
    device::tune_viennacl_vector_kernels<Real>(r.size());
    op_.reset();
    viennacl::linalg::cg_tag tag(static_cast<Real>(eta), static_cast<unsigned>(max_iterations));
    viennacl::linalg::cg_solver<Vector> cg(tag);
    cg.set_monitor(&DeviceProblem::stop_cg, this);
    p = cg(op_, r,
           TimedPreconditioner<CgPreconditioner<Real>>{precond_, preconditioned() ? &model_.profiler() : nullptr});
    LinearSolve s;
    s.iterations = static_cast<int>(cg.tag().iters());
    s.relative_residual = cg.tag().error();
    s.negative_curvature = op_.negative_curvature();
    s.breakdown = op_.breakdown();
    if (multigrid_) rebuild_.solved(s.iterations, s.relative_residual, s.relative_residual <= eta);
    return s;
  }

  void precondition(const Vector& r, Vector& p) {
    PhaseScope timed(preconditioned() ? &model_.profiler() : nullptr, Phase::preconditioner_apply);
    if (device_cg_)
      device_cg_->copy(r, p);
    else
      p = r;
    precond_.apply(p);
  }
  void step(const Vector& x, double alpha, const Vector& p, Vector& out) {
    PhaseScope timed(&model_.profiler(), Phase::line_search_energies);
    if (device_cg_)
      device_cg_->axpy(x, alpha, p, out);
    else
      out = x + static_cast<Real>(alpha) * p;
  }
  void swap(Vector& u, Vector& v) { u.fast_swap(v); }
  // Tangled equilibria (solver/newton/newton_driver.h): each free DOF of x moved by
  // `size` (set_perturbation) times a number in [-1, 1) drawn from `seed`
  // (splitmix64: the same on every platform).
  void set_perturbation(std::vector<Real> free, double size) {
    free_ = std::move(free);
    perturbation_ = size;
  }
  void perturb(Vector& x, uint64_t seed) {
    PhaseScope timed(&model_.profiler(), Phase::transfers);
    std::vector<Real> host(x.size());
    viennacl::copy(x.begin(), x.end(), host.begin());
    std::vector<double> move(host.size(), 0.0);
    for (size_t i = 0; i < host.size(); ++i) {
      uint64_t z = (seed += 0x9e3779b97f4a7c15ull);
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
      z ^= z >> 31;
      const double unit = static_cast<double>(z >> 11) * 0x1.0p-52 - 1.0;  // [-1, 1)
      if (i < free_.size() && free_[i] != Real(0)) move[i] = perturbation_ * unit;
    }
    // With barrier self-contact the move is cut to what continuous collision
    // detection clears: a perturbation never passes the surface through itself.
    double alpha = 1.0;
    if (model_.contact().self_barrier()) {  // the device's CCD from x as it is there
      const std::vector<Real> narrow(move.begin(), move.end());
      viennacl::vector<Real> step(narrow.size());
      viennacl::copy(narrow.begin(), narrow.end(), step.begin());
      alpha = std::min(1.0, model_.contact().step_bound(x, step));
    }
    for (size_t i = 0; i < host.size(); ++i) host[i] += static_cast<Real>(alpha * move[i]);
    viennacl::copy(host.begin(), host.end(), x.begin());
  }

 private:
  bool preconditioned() const { return preconditioner_ != Preconditioner::none; }
  static bool stop_cg(const Vector&, Real relative_residual, void* self) {
    const DeviceProblem* problem = static_cast<DeviceProblem*>(self);
    return problem->op_.negative_curvature() || problem->op_.breakdown() ||
           !std::isfinite(static_cast<double>(relative_residual));
  }
  // What CG applies: the preconditioner, its time charged to
  // preconditioner_apply (none with a null profiler: no preconditioner).
  template <typename Inner>
  struct TimedPreconditioner {
    const Inner& inner;
    PhaseProfiler* profiler;
    void apply(viennacl::vector_base<Real>& z) const {
      PhaseScope timed(profiler, Phase::preconditioner_apply);
      inner.apply(z);
    }
  };

  ElasticModel<Real>& model_;
  HessianOperator<Real> op_;
  std::unique_ptr<MultigridPreconditioner<Real>> multigrid_;
  CgPreconditioner<Real> precond_;
  Preconditioner preconditioner_;
  MultigridRebuild rebuild_;
  uint64_t built_contacts_ = 0;  // contact_set_signature() at the last multigrid build
  std::vector<Real> free_;       // 1 per free DOF, 0 per prescribed (perturb)
  double perturbation_ = 0.0;
  long long past_convergence_ = 0;
  std::unique_ptr<DeviceCg<Real>> device_cg_;
};

}  // namespace snh::solver
