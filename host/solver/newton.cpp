#include "solver/newton.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/matrix_free.h"
#include "viennacl/linalg/cg.hpp"
#include "viennacl/linalg/norm_2.hpp"

namespace snh::solver {

namespace {

// L2 norm on the host in double, summed in index order: deterministic.
template <typename Real>
double norm(const viennacl::vector<Real>& v, std::vector<Real>& scratch) {
  scratch.resize(v.size());
  viennacl::copy(v.begin(), v.end(), scratch.begin());
  double s = 0.0;
  for (Real x : scratch) s += static_cast<double>(x) * static_cast<double>(x);
  return std::sqrt(s);
}

template <typename Real>
double dot(const viennacl::vector<Real>& a, const viennacl::vector<Real>& b) {
  std::vector<Real> ha(a.size()), hb(b.size());
  viennacl::copy(a.begin(), a.end(), ha.begin());
  viennacl::copy(b.begin(), b.end(), hb.begin());
  double s = 0.0;
  for (size_t i = 0; i < ha.size(); ++i) s += static_cast<double>(ha[i]) * static_cast<double>(hb[i]);
  return s;
}

template <typename Real>
struct CgMonitor {
  const HessianOperator<Real>* op;
  static bool stop(const viennacl::vector<Real>&, Real relative_residual, void* self) {
    const CgMonitor* m = static_cast<CgMonitor*>(self);
    return m->op->negative_curvature() || m->op->breakdown() || !std::isfinite(static_cast<double>(relative_residual));
  }
};

}  // namespace

template <typename Real>
StepResult NewtonSolver<Real>::solve_step(int step, viennacl::vector<Real>& x, std::vector<NewtonIteration>& history,
                                          Clock::time_point start) {
  constexpr double kArmijo = 1e-4;
  const int max_halvings = options_.line_search_halvings;
  const double eps = std::numeric_limits<Real>::epsilon();
  const size_t n = model_.dofs();
  viennacl::vector<Real> r(n), p(n), trial(n), r_trial(n);
  std::vector<Real> scratch;
  HessianOperator<Real> op(model_);
  BlockJacobiPreconditioner<Real> precond(model_, options_.block_jacobi);

  StepResult result;
  result.step = step;
  model_.residual(x, r);
  double rn = norm(r, scratch);
  double energy = model_.energy(x);
  const double tolerance = std::max(options_.absolute_tolerance, options_.relative_tolerance * rn);
  double eta = options_.forcing_max, previous_rn = rn;
  constexpr size_t kStagnation = 8;
  std::vector<double> residuals, energies;
  constexpr int kProjectionCooldown = 3;
  int projection_cooldown = 0;
  double last_alpha = 0.0;

  for (int it = 0;; ++it) {
    NewtonIteration rec;
    rec.step = step;
    rec.iteration = it;
    rec.residual_norm = rn;
    rec.energy = energy;
    if (!std::isfinite(rn) || !std::isfinite(energy)) {
      result.status = "non_finite_state";
      history.push_back(rec);
      break;
    }
    if (rn <= tolerance) {
      result.converged = true;
      result.status = "converged";
      rec.seconds = elapsed(start);
      history.push_back(rec);
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
      const double noise = 64.0 * eps * std::abs(energies[old]);
      if (best > 0.99 * residuals[old] && energies[old] - energy <= noise) {
        result.status = "stagnated";
        rec.seconds = elapsed(start);
        history.push_back(rec);
        break;
      }
    }
    if (it >= options_.max_newton_iterations) {
      result.status = "max_newton_iterations";
      rec.seconds = elapsed(start);
      history.push_back(rec);
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
    eta = std::max(eta, 100.0 * eps);

    // The true Hessian only where Newton is converging (full steps, falling
    // residual), no element is inverted and it has not just shown negative
    // curvature; CG on it stops at negative curvature, and the iteration is
    // then redone with the projection. (An inverted element is where the
    // projection's robustness matters: Newton on the true Hessian could be
    // drawn to a tangled stationary point.)
    const bool true_hessian = options_.hessian == HessianMode::adaptive && it > 0 && last_alpha == 1.0 &&
                              rn < previous_rn && projection_cooldown == 0 && model_.last_min_j() > 0.0;
    if (projection_cooldown > 0) --projection_cooldown;
    for (bool projected : {!true_hessian, true}) {
      model_.linearize(x, projected);
      if (options_.block_jacobi) model_.setup_preconditioner();
      op.reset();
      viennacl::linalg::cg_tag tag(static_cast<Real>(eta), static_cast<unsigned>(options_.max_cg_iterations));
      viennacl::linalg::cg_solver<viennacl::vector<Real>> cg(tag);
      CgMonitor<Real> monitor{&op};
      cg.set_monitor(&CgMonitor<Real>::stop, &monitor);
      p = cg(op, r, precond);
      rec.cg_iterations += static_cast<int>(cg.tag().iters());
      rec.cg_relative_residual = cg.tag().error();
      rec.projected = projected;
      rec.cg_stop = op.breakdown()            ? "breakdown"
                    : op.negative_curvature() ? "negative_curvature"
                                              : (rec.cg_relative_residual <= eta ? "converged" : "max_iterations");
      if (projected || !(op.negative_curvature() || op.breakdown())) break;
      projection_cooldown = kProjectionCooldown;
    }

    // A usable descent direction: CG's, else the preconditioned residual
    // (else, with a broken preconditioner, the residual itself).
    bool steepest = false;
    double slope = 0.0;
    auto use_steepest_descent = [&] {
      p = r;
      precond.apply(p);
      slope = dot(r, p);
      if (!std::isfinite(slope) || !(slope > 0.0)) {
        p = r;
        slope = rn * rn;
      }
      steepest = true;
    };
    slope = dot(r, p);  // -dE/dalpha at alpha = 0; non-finite when p has a non-finite entry
    if (!std::isfinite(slope) || !(slope > 0.0)) {
      rec.recovery = std::string(rec.cg_stop == "breakdown" ? "cg_breakdown"
                                 : !std::isfinite(slope)    ? "non_finite_direction"
                                                            : "non_descent") +
                     " -> steepest_descent";
      rec.cg_stop += "+steepest_descent";
      use_steepest_descent();
    } else if (rec.cg_stop == "breakdown") {
      rec.recovery = "cg_breakdown -> partial_cg_direction";
    }

    // Backtracking on the energy; never accept a non-finite energy or a
    // trial whose residual is non-finite. Where the energy change is below
    // its rounding noise (float near the solution), a decrease of the
    // residual norm decides instead. On acceptance r_trial holds the
    // trial's residual.
    double trial_energy = energy, trial_rn = rn;
    bool non_finite_residual = false;
    auto line_search = [&]() -> double {
      double alpha = 1.0;
      for (int h = 0; h <= max_halvings; ++h, alpha *= 0.5) {
        trial = x + static_cast<Real>(alpha) * p;
        trial_energy = model_.energy(trial);
        if (!std::isfinite(trial_energy)) continue;
        const double noise = 64.0 * eps * std::max(std::abs(energy), std::abs(trial_energy));
        bool residual_known = false;
        if (!(trial_energy <= energy - kArmijo * alpha * slope)) {
          if (!(std::abs(trial_energy - energy) <= noise)) continue;
          model_.residual(trial, r_trial);
          trial_rn = norm(r_trial, scratch);
          if (!(trial_rn < rn)) continue;
          residual_known = true;
        }
        if (!residual_known) {
          model_.residual(trial, r_trial);
          trial_rn = norm(r_trial, scratch);
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
      const std::string before = rec.recovery;
      use_steepest_descent();
      accepted = line_search();
      rec.recovery = (before.empty() ? "" : before + "; ") + "line_search_failed -> steepest_descent" +
                     (accepted == 0.0 ? " failed" : "");
    }
    if (non_finite_residual)
      rec.recovery += std::string(rec.recovery.empty() ? "" : "; ") + "non_finite_residual -> shorter_step";
    rec.step_length = accepted;
    if (accepted == 0.0) {
      result.status = "line_search_failed";
      rec.seconds = elapsed(start);
      history.push_back(rec);
      result.cg_iterations += rec.cg_iterations;
      break;
    }
    x = trial;
    last_alpha = accepted;
    energy = trial_energy;
    previous_rn = rn;
    r.fast_swap(r_trial);
    rn = trial_rn;
    result.newton_iterations = it + 1;
    result.cg_iterations += rec.cg_iterations;
    rec.seconds = elapsed(start);
    history.push_back(rec);
    if (options_.on_iteration) {
      // The download and the caller's work are not the solver's time.
      const auto paused = Clock::now();
      std::vector<Real> xr(n);
      viennacl::copy(x.begin(), x.end(), xr.begin());
      options_.on_iteration(rec, std::vector<double>(xr.begin(), xr.end()));
      callback_seconds_ += std::chrono::duration<double>(Clock::now() - paused).count();
    }
  }
  result.residual_norm = rn;
  result.seconds = elapsed(start);
  return result;
}

template class NewtonSolver<float>;
template class NewtonSolver<double>;

}  // namespace snh::solver
