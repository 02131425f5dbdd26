// Newton's method for one load step, written once over a problem interface
// (as PETSc SNES and Ratel keep one loop for every backend): the device model
// (solver/newton/device_problem.h) and the host Eigen baseline (bench/host_baseline.cpp)
// both implement it, so a comparison between them measures two backends, not
// two algorithms.
//
// The loop: Eisenstat-Walker forcing terms (choice 2 with its safeguards), an
// inexact linear solve of the (projected or true) Hessian, a descent-direction
// check with the preconditioned steepest descent as fallback, and Armijo
// backtracking on the energy that never accepts a non-finite energy or
// residual; a failed line search is retried once along the steepest descent;
// a full step that shows negative curvature along its direction (off a
// saddle) is extended by doubling.
//
// A Problem provides, with `Vector` its vector type:
//   size_t dofs() const;                 double epsilon() const;  // working precision
//   Vector vector() const;                                        // a zero vector of dofs()
//   double energy(const Vector& x);      double last_min_j() const;  // of the last energy()
//   void residual(const Vector& x, Vector& r);                    // -mask * dE/dx
//   double norm(const Vector& v) const;  double dot(const Vector& a, const Vector& b) const;
//   void linearize(const Vector& x, bool projected);              // projected: PSD per element
//   LinearSolve solve(const Vector& r, Vector& p, double eta, int max_iterations);
//   void precondition(const Vector& r, Vector& p);                // p = M^-1 r
//   void step(const Vector& x, double alpha, const Vector& p, Vector& out);  // out = x + alpha p
//   void swap(Vector& a, Vector& b);
//   bool has_true_hessian() const;       // whether linearize(x, false) is available
// and optionally
//   double energy_magnitude() const;     // the size of the terms the last energy() summed
// for the rounding noise of energies that are small sums of large terms, and
//   bool refresh(const Vector& x, bool new_step);  // re-detect an active set (contact) at x
// called at the start of the step and of every Newton iteration, before that
// iteration's energy, residual and convergence test; the set stays frozen for
// the iteration's linearization, linear solve and line search. Returns
// whether the set changed (the energy and residual are then recomputed), and
//   void perturb(Vector& x, uint64_t seed);  // move the free DOFs a little
// for tangled equilibria (below), and
//   double step_bound(const Vector& x, const Vector& p);  // the largest safe alpha
//   bool has_barrier() const;  // whether a barrier is on (tighter solves when crawling, below)
// for barriers that a step must not cross (self-contact's continuous
// collision detection, solver/contact/barrier_contact.h): the line search starts at
// min(1, bound) and a step is never extended past it (infinity: no bound).
//
// Tangled equilibria: where the residual meets the tolerance with an element
// inverted (J <= 0), the iterate may be a saddle that Newton reached by
// symmetry (a cube crushed onto a line: the true Hessian's smallest
// eigenvalue there is -0.038) rather than a minimum. With perturb, the free
// DOFs are then perturbed (RecoveryAction::inverted_equilibrium_perturbed)
// and Newton goes on; if it reaches a lower energy the new state is judged
// the same way (at most kMaxPerturbations times), else (a strict local
// minimum: the scramble of docs/validation.md) the equilibrium is restored
// bit for bit and kept (inverted_equilibrium_kept). converged stays Newton's
// criterion: the inverted elements are reported by the caller.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "snh/simulation.h"
#include "solver/newton/stopping_test.h"

namespace snh::solver {

// What a problem's linear solve reports.
struct LinearSolve {
  int iterations = 0;  // operator applications
  double relative_residual = 0.0;
  bool negative_curvature = false;  // the operator showed p^T K p <= 0 (true Hessian, or rounding)
  bool breakdown = false;           // non-finite curvature
};

// The problem's energy_magnitude(), or 0 when it has none.
template <typename P, typename = void>
struct HasEnergyMagnitude : std::false_type {};
template <typename P>
struct HasEnergyMagnitude<P, std::void_t<decltype(std::declval<const P&>().energy_magnitude())>> : std::true_type {};
template <typename P>
double energy_magnitude_of(const P& problem) {
  if constexpr (HasEnergyMagnitude<P>::value)
    return problem.energy_magnitude();
  else
    return 0.0;
}

// The problem's refresh(x), or false (no active set) when it has none.
template <typename P, typename = void>
struct HasRefresh : std::false_type {};
template <typename P>
struct HasRefresh<P, std::void_t<decltype(std::declval<P&>().refresh(std::declval<const typename P::Vector&>(), true))>>
    : std::true_type {};
template <typename P>
bool refresh_of(P& problem, const typename P::Vector& x, bool new_step) {
  if constexpr (HasRefresh<P>::value)
    return problem.refresh(x, new_step);
  else
    return false;
}

// The problem's perturb(x, seed), or false (no perturbation) when it has none.
template <typename P, typename = void>
struct HasPerturb : std::false_type {};
template <typename P>
struct HasPerturb<P, std::void_t<decltype(std::declval<P&>().perturb(std::declval<typename P::Vector&>(), 1u))>>
    : std::true_type {};

// The problem's step_bound(x, p), or infinity (no bound) when it has none.
template <typename P, typename = void>
struct HasStepBound : std::false_type {};
template <typename P>
struct HasStepBound<P, std::void_t<decltype(std::declval<P&>().step_bound(std::declval<const typename P::Vector&>(),
                                                                          std::declval<const typename P::Vector&>()))>>
    : std::true_type {};
template <typename P>
double step_bound_of(P& problem, const typename P::Vector& x, const typename P::Vector& p) {
  if constexpr (HasStepBound<P>::value)
    return problem.step_bound(x, p);
  else
    return std::numeric_limits<double>::infinity();
}

// Whether the problem carries a barrier (problem.has_barrier()), false when
// it cannot say.
template <typename P, typename = void>
struct HasBarrierQuery : std::false_type {};
template <typename P>
struct HasBarrierQuery<P, std::void_t<decltype(std::declval<const P&>().has_barrier())>> : std::true_type {};
template <typename P>
bool has_barrier_of(const P& problem) {
  if constexpr (HasBarrierQuery<P>::value)
    return problem.has_barrier();
  else
    return false;
}

template <typename Problem>
class NewtonDriver {
 public:
  using Vector = typename Problem::Vector;
  using Clock = std::chrono::steady_clock;
  // Called after every accepted Newton update with its record and the new x;
  // returning false ends the step with status cancelled. Its time is not
  // counted in the records' seconds.
  using Observer = std::function<bool(const NewtonIteration&, const Vector& x)>;

  NewtonDriver(Problem& problem, const SolveOptions& options) : problem_(problem), options_(options) {}

  // Solves from x (constrained entries already at their targets, kept fixed)
  // until `stop` holds (solver/newton/stopping_test.h), appending one record
  // per iteration to `history`.
  StepResult solve_step(int step, Vector& x, const StoppingTest& stop, std::vector<NewtonIteration>& history,
                        Clock::time_point start, const Observer& observe = {}) {
    return Step(*this, step, x, stop, history, start, observe).run();
  }

  // Wall time since `start`, less the time spent in observers since then
  // (a solve's load steps share its start; a new start begins a new count).
  double elapsed(Clock::time_point start) const {
    return std::chrono::duration<double>(Clock::now() - start).count() -
           (start == observer_start_ ? observer_seconds_ : 0.0);
  }

 private:
  class Step;

  Problem& problem_;
  const SolveOptions& options_;
  Clock::time_point observer_start_{};
  double observer_seconds_ = 0.0;  // in observers since observer_start_
};

// One step's Newton solve: its state across iterations, and each iteration
// as named phases, run in order by run(): the active set, the stopping
// tests (with the tangled equilibria's perturbation), the forcing term, the
// linear solve, the descent direction, the line search with its
// extension, and the update.
template <typename Problem>
class NewtonDriver<Problem>::Step {
 public:
  Step(NewtonDriver& driver, int step, Vector& x, const StoppingTest& stop, std::vector<NewtonIteration>& history,
       Clock::time_point start, const Observer& observe)
      : driver_(driver),
        problem_(driver.problem_),
        options_(driver.options_),
        x_(x),
        history_(history),
        start_(start),
        observe_(observe),
        eps_(problem_.epsilon()),
        r_(problem_.vector()),
        p_(problem_.vector()),
        trial_(problem_.vector()),
        r_trial_(problem_.vector()),
        far_(problem_.vector()),
        r_far_(problem_.vector()) {
    result_.step = step;
    refresh_of(problem_, x_, true);
    problem_.residual(x_, r_);
    rn_ = problem_.norm(r_);
    energy_ = problem_.energy(x_);
    tolerance_ = stop.threshold(rn_);
    eta_ = options_.forcing_max;
    previous_rn_ = rn_;
  }

  StepResult run() {
    for (int it = 0;; ++it) {
      refresh_active_set(it);
      begin_record(it);
      const Next next = test_stop(it);
      if (next == Next::stop) break;
      if (next == Next::next_iteration) continue;
      choose_forcing(it);
      solve_linear(it);
      choose_direction();
      if (!search_line()) break;
      if (!update(it)) break;
    }
    result_.residual_norm = rn_;
    result_.seconds = driver_.elapsed(start_);
    return result_;
  }

 private:
  enum class Next { proceed, next_iteration, stop };

  static constexpr double kArmijo = 1e-4;
  static constexpr size_t kStagnation = 8;
  static constexpr int kProjectionCooldown = 3;
  // Full steps in a row that each left more than half the residual: Newton
  // on the projection is crawling (linear convergence).
  static constexpr int kCrawling = 4;
  static constexpr int kMaxDoublings = 10;
  // Tangled equilibria (above): perturbations of a converged inverted state.
  static constexpr int kMaxPerturbations = 3;

  NewtonDriver& driver_;
  Problem& problem_;
  const SolveOptions& options_;
  Vector& x_;
  std::vector<NewtonIteration>& history_;
  const Clock::time_point start_;
  const Observer& observe_;
  const double eps_;
  Vector r_, p_, trial_, r_trial_;
  Vector far_, r_far_;  // the extrapolation's trial

  StepResult result_;
  NewtonIteration rec_;
  double rn_ = 0.0, energy_ = 0.0, tolerance_ = 0.0, eta_ = 0.0, previous_rn_ = 0.0;
  std::vector<double> residuals_, energies_;
  int projection_cooldown_ = 0;
  double last_alpha_ = 0.0;
  int crawling_ = 0;
  // The converged inverted state while Newton tries a perturbation of it,
  // and its energy.
  int perturbations_ = 0;
  bool perturbed_ = false;
  std::unique_ptr<Vector> equilibrium_;
  double equilibrium_energy_ = 0.0;
  // This iteration's direction and line search.
  bool steepest_ = false;
  double slope_ = 0.0;
  double trial_energy_ = 0.0, trial_rn_ = 0.0;
  bool non_finite_residual_ = false;
  double bound_ = 0.0;  // step_bound along p (a barrier's is at most 1; infinity without one)
  double accepted_ = 0.0;

  // The residual and energy at x recomputed.
  void evaluate() {
    problem_.residual(x_, r_);
    rn_ = problem_.norm(r_);
    energy_ = problem_.energy(x_);
  }

  // Back to the kept equilibrium, its residual and energy recomputed.
  void restore_equilibrium() {
    problem_.swap(x_, *equilibrium_);
    refresh_of(problem_, x_, false);
    evaluate();
    perturbed_ = false;
  }

  void note(RecoveryAction action, int factor = 0) {
    Recovery done;
    done.action = action;
    done.factor = factor;
    rec_.recovery.push_back(done);
  }

  void finish(StepStatus status) {
    result_.status = status;
    rec_.seconds = driver_.elapsed(start_);
    history_.push_back(rec_);
  }

  // A failure after a perturbation: the equilibrium it left is kept.
  bool failed_after_perturbation() {
    if (!perturbed_) return false;
    restore_equilibrium();
    note(RecoveryAction::inverted_equilibrium_kept);
    rec_.residual_norm = rn_;
    rec_.energy = energy_;
    result_.converged = rn_ <= tolerance_;
    finish(result_.converged ? StepStatus::converged : StepStatus::non_finite_state);
    return true;
  }

  // Ends the step as `status` unless a perturbation's equilibrium is kept.
  Next fail(StepStatus status) {
    if (!failed_after_perturbation()) finish(status);
    return Next::stop;
  }

  // The active set at this iterate: energy, residual and the convergence
  // test all see it (so convergence is judged with the set of the final x).
  void refresh_active_set(int it) {
    if (it > 0 && refresh_of(problem_, x_, false)) {
      evaluate();
      // A new active set is a new objective: progress is judged from here.
      residuals_.clear();
      energies_.clear();
    }
  }

  void begin_record(int it) {
    rec_ = NewtonIteration();
    rec_.step = result_.step;
    rec_.iteration = it;
    rec_.residual_norm = rn_;
    rec_.energy = energy_;
  }

  // Non-finite state, convergence, stagnation and the iteration limit.
  Next test_stop(int it) {
    if (!std::isfinite(rn_) || !std::isfinite(energy_)) return fail(StepStatus::non_finite_state);
    if (rn_ <= tolerance_) return at_tolerance();
    // The working precision's floor: in the last kStagnation iterations
    // neither a 1% drop of the residual norm nor an energy decrease above
    // rounding noise. (Far from the solution the residual may plateau while
    // the energy still falls; that is progress.)
    residuals_.push_back(rn_);
    energies_.push_back(energy_);
    if (residuals_.size() > kStagnation) {
      const size_t old = residuals_.size() - 1 - kStagnation;
      const double best = *std::min_element(residuals_.begin() + old + 1, residuals_.end());
      const double noise = 64.0 * eps_ * std::max(std::abs(energies_[old]), energy_magnitude_of(problem_));
      if (best > 0.99 * residuals_[old] && energies_[old] - energy_ <= noise) return fail(StepStatus::stagnated);
    }
    if (it >= options_.max_newton_iterations) return fail(StepStatus::max_newton_iterations);
    return Next::proceed;
  }

  // The residual meets the tolerance: converged, unless an inverted
  // equilibrium is to be perturbed (tangled equilibria, above).
  Next at_tolerance() {
    if constexpr (HasPerturb<Problem>::value) {
      const double noise = 64.0 * eps_ * std::max(std::abs(energy_), energy_magnitude_of(problem_));
      if (perturbed_ && !(energy_ < equilibrium_energy_ - std::max(noise, 1e-6 * std::abs(equilibrium_energy_)))) {
        // No lower equilibrium near the inverted one: keep it.
        restore_equilibrium();
        note(RecoveryAction::inverted_equilibrium_kept);
        rec_.residual_norm = rn_;
        rec_.energy = energy_;
      } else {
        perturbed_ = false;
        problem_.energy(x_);  // min J at x (the last energy() may have been a rejected trial's)
        if (problem_.last_min_j() <= 0.0 && perturbations_ < kMaxPerturbations && rn_ <= tolerance_) {
          perturb();
          return Next::next_iteration;
        }
      }
    }
    result_.converged = true;
    finish(StepStatus::converged);
    return Next::stop;
  }

  // Keeps the inverted equilibrium and moves the free DOFs a little.
  void perturb() {
    if (!equilibrium_) equilibrium_ = std::make_unique<Vector>(problem_.vector());
    problem_.step(x_, 0.0, r_, *equilibrium_);  // a copy of x
    equilibrium_energy_ = energy_;
    problem_.perturb(
        x_, 0x5eedull + 1000003ull * static_cast<uint64_t>(result_.step) + static_cast<uint64_t>(perturbations_));
    ++perturbations_;
    perturbed_ = true;
    note(RecoveryAction::inverted_equilibrium_perturbed);
    rec_.seconds = driver_.elapsed(start_);
    history_.push_back(rec_);
    refresh_of(problem_, x_, false);
    evaluate();
    // A new start: progress, forcing terms and the Hessian choice are
    // judged from here.
    residuals_.clear();
    energies_.clear();
    eta_ = options_.forcing_max;
    previous_rn_ = rn_;
    last_alpha_ = 0.0;
    crawling_ = 0;
    projection_cooldown_ = 0;
  }

  // Eisenstat-Walker choice 2 with its safeguards, floored where the
  // working precision cannot resolve a smaller relative residual.
  void choose_forcing(int it) {
    if (it > 0) {
      const double candidate = options_.forcing_gamma * (rn_ / previous_rn_) * (rn_ / previous_rn_);
      const double safeguard = options_.forcing_gamma * eta_ * eta_;
      eta_ = safeguard > 0.1 ? std::max(candidate, safeguard) : candidate;
      eta_ = std::min(eta_, options_.forcing_max);
      eta_ = std::max(eta_, 0.5 * tolerance_ / rn_);
    }
    // With a barrier, full steps that each leave more than half the residual
    // are the inexact solves' doing (the stiff pairs' curvature changes
    // faster than a solve to eta = 0.5 follows; the elbow at 135 degrees
    // crawled 200 iterations at 0.99 per iteration): each further crawling
    // step solves ten times tighter, down to the tolerance's floor.
    if (crawling_ >= kCrawling && has_barrier_of(problem_))
      eta_ = std::max(std::min(eta_, std::pow(0.1, crawling_ - kCrawling + 1)), 0.05 * tolerance_ / rn_);
    eta_ = std::max(eta_, 100.0 * eps_);
  }

  // The true Hessian only where Newton is converging (full steps, falling
  // residual), no element is inverted and it has not just shown negative
  // curvature; the linear solve on it stops at negative curvature, and the
  // iteration is then redone with the projection. (An inverted element is
  // where the projection's robustness matters: Newton on the true Hessian
  // could be drawn to a tangled stationary point.) With an inverted
  // element it waits until Newton on the projection crawls (kCrawling full
  // steps each leaving more than half the residual): the iterate is then
  // at the equilibrium the projection was converging to, linearly, at the
  // rate the projected eigenvalues set (a 100-degree elbow with inverted
  // elements: 0.94 per iteration, 200 iterations short of tolerance).
  void solve_linear(int it) {
    const bool true_hessian = options_.hessian == HessianMode::adaptive && problem_.has_true_hessian() && it > 0 &&
                              last_alpha_ == 1.0 && rn_ < previous_rn_ && projection_cooldown_ == 0 &&
                              (problem_.last_min_j() > 0.0 || crawling_ >= kCrawling);
    if (projection_cooldown_ > 0) --projection_cooldown_;
    for (bool projected : {!true_hessian, true}) {
      problem_.linearize(x_, projected);
      const LinearSolve solve = problem_.solve(r_, p_, eta_, options_.max_cg_iterations);
      rec_.cg_iterations += solve.iterations;
      rec_.cg_relative_residual = solve.relative_residual;
      rec_.projected = projected;
      rec_.cg_stop = solve.breakdown                   ? CgStop::breakdown
                     : solve.negative_curvature        ? CgStop::negative_curvature
                     : solve.relative_residual <= eta_ ? CgStop::converged
                                                       : CgStop::max_iterations;
      if (projected || !(solve.negative_curvature || solve.breakdown)) break;
      projection_cooldown_ = kProjectionCooldown;
    }
  }

  // p: the preconditioned residual (else, with a broken preconditioner, the
  // residual itself).
  void use_steepest_descent() {
    problem_.precondition(r_, p_);
    slope_ = problem_.dot(r_, p_);
    if (!std::isfinite(slope_) || !(slope_ > 0.0)) {
      problem_.step(r_, 0.0, r_, p_);  // p = r
      slope_ = rn_ * rn_;
    }
    steepest_ = true;
  }

  // A usable descent direction: the linear solve's, else the steepest
  // descent above.
  void choose_direction() {
    steepest_ = false;
    slope_ = problem_.dot(r_, p_);  // -dE/dalpha at alpha = 0; non-finite when p has a non-finite entry
    if (!std::isfinite(slope_) || !(slope_ > 0.0)) {
      note(rec_.cg_stop == CgStop::breakdown ? RecoveryAction::cg_breakdown_steepest_descent
           : !std::isfinite(slope_)          ? RecoveryAction::non_finite_direction_steepest_descent
                                             : RecoveryAction::non_descent_steepest_descent);
      rec_.steepest_descent = true;
      use_steepest_descent();
    } else if (rec_.cg_stop == CgStop::breakdown) {
      note(RecoveryAction::cg_breakdown_partial_direction);
    }
  }

  // Backtracking on the energy; never accept a non-finite energy or a
  // trial whose residual is non-finite. Where the energy change is below
  // its rounding noise (float near the solution), a decrease of the
  // residual norm decides instead. On acceptance r_trial holds the
  // trial's residual. Returns the step length, 0 for none.
  double backtrack() {
    bound_ = step_bound_of(problem_, x_, p_);
    if (!(bound_ > 0.0)) return 0.0;
    double alpha = std::min(1.0, bound_);
    for (int h = 0; h <= options_.line_search_halvings; ++h, alpha *= 0.5) {
      problem_.step(x_, alpha, p_, trial_);
      trial_energy_ = problem_.energy(trial_);
      if (!std::isfinite(trial_energy_)) continue;
      const double noise =
          64.0 * eps_ * std::max({std::abs(energy_), std::abs(trial_energy_), energy_magnitude_of(problem_)});
      bool residual_known = false;
      if (!(trial_energy_ <= energy_ - kArmijo * alpha * slope_)) {
        if (!(std::abs(trial_energy_ - energy_) <= noise)) continue;
        problem_.residual(trial_, r_trial_);
        trial_rn_ = problem_.norm(r_trial_);
        if (!(trial_rn_ < rn_)) continue;
        residual_known = true;
      }
      if (!residual_known) {
        problem_.residual(trial_, r_trial_);
        trial_rn_ = problem_.norm(r_trial_);
      }
      if (!std::isfinite(trial_rn_)) {
        non_finite_residual_ = true;
        continue;
      }
      return alpha;
    }
    return 0.0;
  }

  // The line search along p, once more along the steepest descent when it
  // fails, and the extension of a full step. false: no step was accepted
  // (the step has ended).
  bool search_line() {
    trial_energy_ = energy_;
    trial_rn_ = rn_;
    non_finite_residual_ = false;
    bound_ = std::numeric_limits<double>::infinity();
    double accepted = backtrack();
    if (accepted == 0.0 && !steepest_) {
      // Once more along the preconditioned steepest descent before giving up.
      use_steepest_descent();
      accepted = backtrack();
      note(accepted == 0.0 ? RecoveryAction::line_search_steepest_descent_failed
                           : RecoveryAction::line_search_steepest_descent);
    }
    if (non_finite_residual_) note(RecoveryAction::shorter_step);
    if (accepted == 1.0) accepted = extend(accepted);
    rec_.step_length = accepted;
    if (accepted == 0.0) {
      result_.cg_iterations += rec_.cg_iterations;
      fail(StepStatus::line_search_failed);
      return false;
    }
    accepted_ = accepted;
    return true;
  }

  // Negative curvature along p (the energy still falls at alpha = 1 at
  // least as steeply as at 0, as when sliding off a saddle, which the
  // projected Hessian cannot see): extrapolate, doubling alpha while the
  // energy keeps its sufficient decrease from the last point and the
  // descent does not flatten (the bracketing phase of Nocedal & Wright's
  // Algorithm 3.5, which expands before it zooms). Elsewhere (positive
  // curvature along p) nothing changes. Returns the step length.
  double extend(double accepted) {
    double descent = problem_.dot(r_trial_, p_);  // -dE/dalpha at the accepted point
    int doublings = 0;
    while (doublings < kMaxDoublings && std::isfinite(descent) && descent >= slope_ && descent > 0.0) {
      const double next = 2.0 * accepted;
      problem_.step(x_, next, p_, far_);
      // Past the bound along p (a barrier's stops at alpha = 1) the
      // extension from the accepted point is checked on its own.
      if (next > bound_) {
        problem_.step(far_, -1.0, trial_, r_far_);  // the move from trial to far
        if (!(step_bound_of(problem_, trial_, r_far_) >= 1.0)) break;
      }
      const double far_energy = problem_.energy(far_);
      if (!std::isfinite(far_energy) || !(far_energy <= trial_energy_ - kArmijo * (next - accepted) * descent)) break;
      problem_.residual(far_, r_far_);
      const double far_rn = problem_.norm(r_far_);
      if (!std::isfinite(far_rn)) break;
      problem_.swap(trial_, far_);
      problem_.swap(r_trial_, r_far_);
      trial_energy_ = far_energy;
      trial_rn_ = far_rn;
      accepted = next;
      ++doublings;
      const double next_descent = problem_.dot(r_trial_, p_);
      if (!(next_descent >= descent)) break;
      descent = next_descent;
    }
    if (doublings > 0) note(RecoveryAction::extended_step, 1 << doublings);
    return accepted;
  }

  // x moves to the accepted trial; the record is kept and observed. false:
  // the observer cancelled the step.
  bool update(int it) {
    problem_.swap(x_, trial_);
    last_alpha_ = accepted_;
    energy_ = trial_energy_;
    previous_rn_ = rn_;
    problem_.swap(r_, r_trial_);
    rn_ = trial_rn_;
    crawling_ = accepted_ == 1.0 && rn_ > 0.5 * previous_rn_ ? crawling_ + 1 : 0;
    result_.newton_iterations = it + 1;
    result_.cg_iterations += rec_.cg_iterations;
    rec_.seconds = driver_.elapsed(start_);
    history_.push_back(rec_);
    if (!observe_) return true;
    const auto paused = Clock::now();
    const bool go_on = observe_(rec_, x_);
    if (driver_.observer_start_ != start_) {
      driver_.observer_start_ = start_;
      driver_.observer_seconds_ = 0.0;
    }
    driver_.observer_seconds_ += std::chrono::duration<double>(Clock::now() - paused).count();
    if (!go_on) {
      result_.status = StepStatus::cancelled;
      return false;
    }
    return true;
  }
};

}  // namespace snh::solver
