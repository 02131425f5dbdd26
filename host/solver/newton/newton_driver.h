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
                        Clock::time_point start, const Observer& observe = {});

  // Wall time since `start`, less the time spent in observers since then
  // (a solve's load steps share its start; a new start begins a new count).
  double elapsed(Clock::time_point start) const {
    return std::chrono::duration<double>(Clock::now() - start).count() -
           (start == observer_start_ ? observer_seconds_ : 0.0);
  }

 private:
  Problem& problem_;
  const SolveOptions& options_;
  Clock::time_point observer_start_{};
  double observer_seconds_ = 0.0;  // in observers since observer_start_
};

template <typename Problem>
StepResult NewtonDriver<Problem>::solve_step(int step, Vector& x, const StoppingTest& stop,
                                             std::vector<NewtonIteration>& history, Clock::time_point start,
                                             const Observer& observe) {
  constexpr double kArmijo = 1e-4;
  constexpr size_t kStagnation = 8;
  constexpr int kProjectionCooldown = 3;
  // Full steps in a row that each left more than half the residual: Newton
  // on the projection is crawling (linear convergence).
  constexpr int kCrawling = 4;
  const int max_halvings = options_.line_search_halvings;
  const double eps = problem_.epsilon();
  constexpr int kMaxDoublings = 10;
  Vector r = problem_.vector(), p = problem_.vector(), trial = problem_.vector(), r_trial = problem_.vector();
  Vector far = problem_.vector(), r_far = problem_.vector();  // the extrapolation's trial

  StepResult result;
  result.step = step;
  refresh_of(problem_, x, true);
  problem_.residual(x, r);
  double rn = problem_.norm(r);
  double energy = problem_.energy(x);
  const double tolerance = stop.threshold(rn);
  double eta = options_.forcing_max, previous_rn = rn;
  std::vector<double> residuals, energies;
  int projection_cooldown = 0;
  double last_alpha = 0.0;
  int crawling = 0;
  // Tangled equilibria (above): the converged inverted state while Newton
  // tries a perturbation of it, and its energy.
  constexpr int kMaxPerturbations = 3;
  int perturbations = 0;
  bool perturbed = false;
  std::unique_ptr<Vector> equilibrium;
  double equilibrium_energy = 0.0;
  // Back to the kept equilibrium, its residual and energy recomputed.
  auto restore_equilibrium = [&] {
    problem_.swap(x, *equilibrium);
    refresh_of(problem_, x, false);
    problem_.residual(x, r);
    rn = problem_.norm(r);
    energy = problem_.energy(x);
    perturbed = false;
  };

  for (int it = 0;; ++it) {
    // The active set at this iterate: energy, residual and the convergence
    // test below all see it (so convergence is judged with the set of the
    // final x).
    if (it > 0 && refresh_of(problem_, x, false)) {
      problem_.residual(x, r);
      rn = problem_.norm(r);
      energy = problem_.energy(x);
      // A new active set is a new objective: progress is judged from here.
      residuals.clear();
      energies.clear();
    }
    NewtonIteration rec;
    rec.step = step;
    rec.iteration = it;
    rec.residual_norm = rn;
    rec.energy = energy;
    auto note = [&rec](RecoveryAction action, int factor = 0) {
      Recovery done;
      done.action = action;
      done.factor = factor;
      rec.recovery.push_back(done);
    };
    auto finish = [&](StepStatus status) {
      result.status = status;
      rec.seconds = elapsed(start);
      history.push_back(rec);
    };
    // A failure after a perturbation: the equilibrium it left is kept.
    auto failed_after_perturbation = [&] {
      if (!perturbed) return false;
      restore_equilibrium();
      note(RecoveryAction::inverted_equilibrium_kept);
      rec.residual_norm = rn;
      rec.energy = energy;
      result.converged = rn <= tolerance;
      finish(result.converged ? StepStatus::converged : StepStatus::non_finite_state);
      return true;
    };
    if (!std::isfinite(rn) || !std::isfinite(energy)) {
      if (failed_after_perturbation()) break;
      finish(StepStatus::non_finite_state);
      break;
    }
    if (rn <= tolerance) {
      if constexpr (HasPerturb<Problem>::value) {
        const double noise = 64.0 * eps * std::max(std::abs(energy), energy_magnitude_of(problem_));
        if (perturbed && !(energy < equilibrium_energy - std::max(noise, 1e-6 * std::abs(equilibrium_energy)))) {
          // No lower equilibrium near the inverted one: keep it.
          restore_equilibrium();
          note(RecoveryAction::inverted_equilibrium_kept);
          rec.residual_norm = rn;
          rec.energy = energy;
        } else {
          perturbed = false;
          problem_.energy(x);  // min J at x (the last energy() may have been a rejected trial's)
          if (problem_.last_min_j() <= 0.0 && perturbations < kMaxPerturbations && rn <= tolerance) {
            if (!equilibrium) equilibrium = std::make_unique<Vector>(problem_.vector());
            problem_.step(x, 0.0, r, *equilibrium);  // a copy of x
            equilibrium_energy = energy;
            problem_.perturb(
                x, 0x5eedull + 1000003ull * static_cast<uint64_t>(step) + static_cast<uint64_t>(perturbations));
            ++perturbations;
            perturbed = true;
            note(RecoveryAction::inverted_equilibrium_perturbed);
            rec.seconds = elapsed(start);
            history.push_back(rec);
            refresh_of(problem_, x, false);
            problem_.residual(x, r);
            rn = problem_.norm(r);
            energy = problem_.energy(x);
            // A new start: progress, forcing terms and the Hessian choice
            // are judged from here.
            residuals.clear();
            energies.clear();
            eta = options_.forcing_max;
            previous_rn = rn;
            last_alpha = 0.0;
            crawling = 0;
            projection_cooldown = 0;
            continue;
          }
        }
      }
      result.converged = true;
      finish(StepStatus::converged);
      break;
    }
    // The working precision's floor: in the last kStagnation iterations
    // neither a 1% drop of the residual norm nor an energy decrease above
    // rounding noise. (Far from the solution the residual may plateau while
    // the energy still falls; that is progress.)
    residuals.push_back(rn);
    energies.push_back(energy);
    if (residuals.size() > kStagnation) {
      const size_t old = residuals.size() - 1 - kStagnation;
      const double best = *std::min_element(residuals.begin() + old + 1, residuals.end());
      const double noise = 64.0 * eps * std::max(std::abs(energies[old]), energy_magnitude_of(problem_));
      if (best > 0.99 * residuals[old] && energies[old] - energy <= noise) {
        if (failed_after_perturbation()) break;
        finish(StepStatus::stagnated);
        break;
      }
    }
    if (it >= options_.max_newton_iterations) {
      if (failed_after_perturbation()) break;
      finish(StepStatus::max_newton_iterations);
      break;
    }

    // Eisenstat-Walker choice 2 with its safeguards, floored where the
    // working precision cannot resolve a smaller relative residual.
    if (it > 0) {
      const double candidate = options_.forcing_gamma * (rn / previous_rn) * (rn / previous_rn);
      const double safeguard = options_.forcing_gamma * eta * eta;
      eta = safeguard > 0.1 ? std::max(candidate, safeguard) : candidate;
      eta = std::min(eta, options_.forcing_max);
      eta = std::max(eta, 0.5 * tolerance / rn);
    }
    // With a barrier, full steps that each leave more than half the residual
    // are the inexact solves' doing (the stiff pairs' curvature changes
    // faster than a solve to eta = 0.5 follows; the elbow at 135 degrees
    // crawled 200 iterations at 0.99 per iteration): each further crawling
    // step solves ten times tighter, down to the tolerance's floor.
    if (crawling >= kCrawling && has_barrier_of(problem_))
      eta = std::max(std::min(eta, std::pow(0.1, crawling - kCrawling + 1)), 0.05 * tolerance / rn);
    eta = std::max(eta, 100.0 * eps);

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
    const bool true_hessian = options_.hessian == HessianMode::adaptive && problem_.has_true_hessian() && it > 0 &&
                              last_alpha == 1.0 && rn < previous_rn && projection_cooldown == 0 &&
                              (problem_.last_min_j() > 0.0 || crawling >= kCrawling);
    if (projection_cooldown > 0) --projection_cooldown;
    LinearSolve solve;
    for (bool projected : {!true_hessian, true}) {
      problem_.linearize(x, projected);
      solve = problem_.solve(r, p, eta, options_.max_cg_iterations);
      rec.cg_iterations += solve.iterations;
      rec.cg_relative_residual = solve.relative_residual;
      rec.projected = projected;
      rec.cg_stop = solve.breakdown                  ? CgStop::breakdown
                    : solve.negative_curvature       ? CgStop::negative_curvature
                    : solve.relative_residual <= eta ? CgStop::converged
                                                     : CgStop::max_iterations;
      if (projected || !(solve.negative_curvature || solve.breakdown)) break;
      projection_cooldown = kProjectionCooldown;
    }

    // A usable descent direction: the linear solve's, else the
    // preconditioned residual (else, with a broken preconditioner, the
    // residual itself).
    bool steepest = false;
    double slope = 0.0;
    auto use_steepest_descent = [&] {
      problem_.precondition(r, p);
      slope = problem_.dot(r, p);
      if (!std::isfinite(slope) || !(slope > 0.0)) {
        problem_.step(r, 0.0, r, p);  // p = r
        slope = rn * rn;
      }
      steepest = true;
    };
    slope = problem_.dot(r, p);  // -dE/dalpha at alpha = 0; non-finite when p has a non-finite entry
    if (!std::isfinite(slope) || !(slope > 0.0)) {
      note(rec.cg_stop == CgStop::breakdown ? RecoveryAction::cg_breakdown_steepest_descent
           : !std::isfinite(slope)          ? RecoveryAction::non_finite_direction_steepest_descent
                                            : RecoveryAction::non_descent_steepest_descent);
      rec.steepest_descent = true;
      use_steepest_descent();
    } else if (rec.cg_stop == CgStop::breakdown) {
      note(RecoveryAction::cg_breakdown_partial_direction);
    }

    // Backtracking on the energy; never accept a non-finite energy or a
    // trial whose residual is non-finite. Where the energy change is below
    // its rounding noise (float near the solution), a decrease of the
    // residual norm decides instead. On acceptance r_trial holds the
    // trial's residual.
    double trial_energy = energy, trial_rn = rn;
    bool non_finite_residual = false;
    // step_bound along this p (a barrier's is at most 1; infinity without one)
    double bound = std::numeric_limits<double>::infinity();
    auto line_search = [&]() -> double {
      bound = step_bound_of(problem_, x, p);
      if (!(bound > 0.0)) return 0.0;
      double alpha = std::min(1.0, bound);
      for (int h = 0; h <= max_halvings; ++h, alpha *= 0.5) {
        problem_.step(x, alpha, p, trial);
        trial_energy = problem_.energy(trial);
        if (!std::isfinite(trial_energy)) continue;
        const double noise =
            64.0 * eps * std::max({std::abs(energy), std::abs(trial_energy), energy_magnitude_of(problem_)});
        bool residual_known = false;
        if (!(trial_energy <= energy - kArmijo * alpha * slope)) {
          if (!(std::abs(trial_energy - energy) <= noise)) continue;
          problem_.residual(trial, r_trial);
          trial_rn = problem_.norm(r_trial);
          if (!(trial_rn < rn)) continue;
          residual_known = true;
        }
        if (!residual_known) {
          problem_.residual(trial, r_trial);
          trial_rn = problem_.norm(r_trial);
        }
        if (!std::isfinite(trial_rn)) {
          non_finite_residual = true;
          continue;
        }
        return alpha;
      }
      return 0.0;
    };
    double accepted = line_search();
    if (accepted == 0.0 && !steepest) {
      // Once more along the preconditioned steepest descent before giving up.
      use_steepest_descent();
      accepted = line_search();
      note(accepted == 0.0 ? RecoveryAction::line_search_steepest_descent_failed
                           : RecoveryAction::line_search_steepest_descent);
    }
    if (non_finite_residual) note(RecoveryAction::shorter_step);
    // Negative curvature along p (the energy still falls at alpha = 1 at
    // least as steeply as at 0, as when sliding off a saddle, which the
    // projected Hessian cannot see): extrapolate, doubling alpha while the
    // energy keeps its sufficient decrease from the last point and the
    // descent does not flatten (the bracketing phase of Nocedal & Wright's
    // Algorithm 3.5, which expands before it zooms). Elsewhere (positive
    // curvature along p) nothing changes.
    if (accepted == 1.0) {
      double descent = problem_.dot(r_trial, p);  // -dE/dalpha at the accepted point
      int doublings = 0;
      while (doublings < kMaxDoublings && std::isfinite(descent) && descent >= slope && descent > 0.0) {
        const double next = 2.0 * accepted;
        problem_.step(x, next, p, far);
        // Past the bound along p (a barrier's stops at alpha = 1) the
        // extension from the accepted point is checked on its own.
        if (next > bound) {
          problem_.step(far, -1.0, trial, r_far);  // the move from trial to far
          if (!(step_bound_of(problem_, trial, r_far) >= 1.0)) break;
        }
        const double far_energy = problem_.energy(far);
        if (!std::isfinite(far_energy) || !(far_energy <= trial_energy - kArmijo * (next - accepted) * descent)) break;
        problem_.residual(far, r_far);
        const double far_rn = problem_.norm(r_far);
        if (!std::isfinite(far_rn)) break;
        problem_.swap(trial, far);
        problem_.swap(r_trial, r_far);
        trial_energy = far_energy;
        trial_rn = far_rn;
        accepted = next;
        ++doublings;
        const double next_descent = problem_.dot(r_trial, p);
        if (!(next_descent >= descent)) break;
        descent = next_descent;
      }
      if (doublings > 0) note(RecoveryAction::extended_step, 1 << doublings);
    }
    rec.step_length = accepted;
    if (accepted == 0.0) {
      result.cg_iterations += rec.cg_iterations;
      if (failed_after_perturbation()) break;
      finish(StepStatus::line_search_failed);
      break;
    }
    problem_.swap(x, trial);
    last_alpha = accepted;
    energy = trial_energy;
    previous_rn = rn;
    problem_.swap(r, r_trial);
    rn = trial_rn;
    crawling = accepted == 1.0 && rn > 0.5 * previous_rn ? crawling + 1 : 0;
    result.newton_iterations = it + 1;
    result.cg_iterations += rec.cg_iterations;
    rec.seconds = elapsed(start);
    history.push_back(rec);
    if (observe) {
      const auto paused = Clock::now();
      const bool go_on = observe(rec, x);
      if (observer_start_ != start) {
        observer_start_ = start;
        observer_seconds_ = 0.0;
      }
      observer_seconds_ += std::chrono::duration<double>(Clock::now() - paused).count();
      if (!go_on) {
        result.status = StepStatus::cancelled;
        break;
      }
    }
  }
  result.residual_norm = rn;
  result.seconds = elapsed(start);
  return result;
}

}  // namespace snh::solver
