// The host CPU baseline: QuasistaticSolver's load stepping and Newton loop
// (host/solver/quasistatic_solver.cpp, host/solver/newton.cpp) on the host in
// double, with the stiffness assembled by Eigen and solved by Eigen's
// diagonally preconditioned ConjugateGradient.
#include "host_baseline.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "fem/rest_state.h"
#include "reference/fem_reference.h"
#include "snh/error.h"

namespace snh::bench {

namespace {

using Clock = std::chrono::steady_clock;
using SparseMatrix = Eigen::SparseMatrix<double>;
using Vector = Eigen::VectorXd;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// L2 norm summed in index order, as the device solver's host-side norm.
double norm(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}

double dot(const Vector& a, const std::vector<double>& b) {
  double s = 0.0;
  for (size_t i = 0; i < b.size(); ++i) s += a[static_cast<Eigen::Index>(i)] * b[i];
  return s;
}

// Throws snh::Error for a bad mesh, as the device solver's constructor does.
fem::RestState validated_rest_state(const Mesh& mesh) {
  validate_mesh(mesh);
  return fem::compute_rest_state(mesh);
}

class HostProblem {
 public:
  HostProblem(const Scene& scene, const SolveOptions& options)
      : mesh_(scene.mesh),
        material_(scene.material),
        constraints_(scene.constraints),
        options_(options),
        rest_(validated_rest_state(scene.mesh)) {
    validate();
    const size_t n = mesh_.vertex_count();
    fixed_.assign(3 * n, 0);
    for (const ConstraintSet& c : constraints_)
      for (int32_t v : c.vertices) fixed_[3 * v] = fixed_[3 * v + 1] = fixed_[3 * v + 2] = 1;
    // Vertices of no element have no stiffness: identity rows, like fixed ones.
    std::vector<char> used(n, 0);
    for (int32_t v : mesh_.elements) used[v] = 1;
    identity_.assign(3 * n, 0);
    for (size_t i = 0; i < 3 * n; ++i) identity_[i] = fixed_[i] || !used[i / 3];
  }

  size_t dofs() const { return 3 * mesh_.vertex_count(); }

  void apply_constraints(double t, std::vector<double>& x) const { snh::apply_constraints(mesh_, constraints_, t, x); }

  // Total potential energy: elastic energy minus external work.
  double energy(const std::vector<double>& x) const {
    double e = reference::assembled_energy(mesh_, rest_, material_, x);
    const std::vector<double>& f = options_.external_force;
    for (size_t i = 0; i < f.size(); ++i) e -= f[i] * x[i];
    return e;
  }

  // r = mask * (elastic forces + external force).
  void residual(const std::vector<double>& x, std::vector<double>& r) const {
    r = reference::assembled_forces(mesh_, rest_, material_, x);
    const std::vector<double>& f = options_.external_force;
    for (size_t i = 0; i < r.size(); ++i) {
      if (!f.empty()) r[i] += f[i];
      if (fixed_[i]) r[i] = 0.0;
    }
  }

  // The projected stiffness with the constrained (and unused) DOFs' rows and
  // columns replaced by those of the identity.
  SparseMatrix stiffness(const std::vector<double>& x) const {
    SparseMatrix k = reference::assembled_projected_stiffness(mesh_, rest_, material_, x);
    k.prune([this](Eigen::Index row, Eigen::Index col, const double&) {
      return row == col || (!identity_[row] && !identity_[col]);
    });
    for (size_t i = 0; i < identity_.size(); ++i) {
      if (!identity_[i]) continue;
      const auto index = static_cast<Eigen::Index>(i);
      k.coeffRef(index, index) = 1.0;
    }
    k.makeCompressed();
    return k;
  }

  bool fixed(size_t i) const { return fixed_[i] != 0; }

 private:
  void validate() const {
    validate_solve_inputs(mesh_, constraints_, options_);
    const size_t n = mesh_.vertex_count();
    if (!options_.external_force.empty() && options_.external_force.size() != 3 * n)
      throw Error("solver: external force has " + std::to_string(options_.external_force.size()) +
                  " entries, expected " + std::to_string(3 * n));
    for (double f : options_.external_force)
      if (!std::isfinite(f)) throw Error("solver: external force has a non-finite entry");
  }

  const Mesh& mesh_;
  const StableNeoHookean& material_;
  const std::vector<ConstraintSet>& constraints_;
  const SolveOptions& options_;
  fem::RestState rest_;
  std::vector<char> fixed_;     // per DOF: constrained
  std::vector<char> identity_;  // per DOF: identity row and column in the stiffness
};

using IterationCallback = std::function<void(const NewtonIteration&, const std::vector<double>&)>;

class HostNewton {
 public:
  HostNewton(const HostProblem& problem, const SolveOptions& options, const IterationCallback& on_iteration,
             HostBaselineResult& out)
      : problem_(problem), options_(options), on_iteration_(on_iteration), out_(out) {}

  // Wall time since `start`, less the time spent in on_iteration callbacks.
  double elapsed(Clock::time_point start) const { return seconds_since(start) - callback_seconds_; }

  // Mirrors solver::NewtonSolver::solve_step with Real = double.
  StepResult solve_step(int step, std::vector<double>& x, Clock::time_point start) {
    constexpr double kArmijo = 1e-4;
    constexpr int kMaxHalvings = 40;
    const double eps = std::numeric_limits<double>::epsilon();
    const size_t n = problem_.dofs();
    std::vector<double> r(n), trial(n), r_trial(n);
    std::vector<NewtonIteration>& history = out_.history;

    StepResult result;
    result.step = step;
    problem_.residual(x, r);
    double rn = norm(r);
    double energy = problem_.energy(x);
    const double tolerance = std::max(options_.absolute_tolerance, options_.relative_tolerance * rn);
    double eta = options_.forcing_max, previous_rn = rn;
    constexpr size_t kStagnation = 8;
    std::vector<double> residuals, energies;

    for (int it = 0;; ++it) {
      NewtonIteration rec;
      rec.step = step;
      rec.iteration = it;
      rec.residual_norm = rn;
      rec.energy = energy;
      rec.projected = true;
      if (!std::isfinite(rn) || !std::isfinite(energy)) {
        result.status = "non_finite_state";
        rec.seconds = elapsed(start);
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
      // The precision floor: in the last kStagnation iterations neither a 1%
      // drop of the residual norm nor an energy decrease above rounding noise.
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

      // Eisenstat-Walker choice 2 with its safeguards and floors.
      if (it > 0) {
        const double candidate = options_.forcing_gamma * (rn / previous_rn) * (rn / previous_rn);
        const double safeguard = options_.forcing_gamma * eta * eta;
        eta = safeguard > 0.1 ? std::max(candidate, safeguard) : candidate;
        eta = std::min(eta, options_.forcing_max);
        eta = std::max(eta, 0.5 * tolerance / rn);
      }
      eta = std::max(eta, 100.0 * eps);

      const Clock::time_point assembly_start = Clock::now();
      const SparseMatrix k = problem_.stiffness(x);
      out_.assembly_seconds += seconds_since(assembly_start);

      const Clock::time_point cg_start = Clock::now();
      Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper> cg;
      cg.setTolerance(eta);
      cg.setMaxIterations(options_.max_cg_iterations);
      cg.compute(k);
      const Eigen::Map<const Vector> rhs(r.data(), static_cast<Eigen::Index>(n));
      Vector p = cg.solve(rhs);
      out_.cg_seconds += seconds_since(cg_start);
      rec.cg_relative_residual = cg.error();
      const bool cg_converged = cg.info() == Eigen::Success;
      rec.cg_stop = cg_converged ? "converged" : "max_iterations";
      // Matrix-vector products, as ViennaCL counts: Eigen's count leaves out
      // the iteration in which the residual fell below the tolerance (unless
      // it returned at once, with p = 0, for eta >= 1).
      rec.cg_iterations = static_cast<int>(cg.iterations()) + (cg_converged && !p.isZero(0.0) ? 1 : 0);
      for (size_t i = 0; i < n; ++i)
        if (problem_.fixed(i)) p[static_cast<Eigen::Index>(i)] = 0.0;

      // A usable descent direction: CG's, else the (diagonally) preconditioned residual.
      double slope = dot(p, r);  // -dE/dalpha at alpha = 0
      if (!std::isfinite(slope) || !(slope > 0.0)) {
        rec.cg_stop += "+steepest_descent";
        const Vector diagonal = k.diagonal();
        for (size_t i = 0; i < n; ++i) {
          const auto index = static_cast<Eigen::Index>(i);
          const double d = diagonal[index];
          p[index] = d != 0.0 && std::isfinite(d) ? r[i] / d : r[i];
        }
        slope = dot(p, r);
      }

      // Backtracking on the energy; never accept a non-finite energy. Where
      // the energy change is below its rounding noise, a decrease of the
      // residual norm decides instead.
      double alpha = 1.0, accepted = 0.0, trial_energy = energy;
      for (int h = 0; h < kMaxHalvings; ++h, alpha *= 0.5) {
        for (size_t i = 0; i < n; ++i) trial[i] = x[i] + alpha * p[static_cast<Eigen::Index>(i)];
        trial_energy = problem_.energy(trial);
        if (!std::isfinite(trial_energy)) continue;
        const double noise = 64.0 * eps * std::max(std::abs(energy), std::abs(trial_energy));
        if (trial_energy <= energy - kArmijo * alpha * slope) {
          accepted = alpha;
          break;
        }
        if (std::abs(trial_energy - energy) <= noise) {
          problem_.residual(trial, r_trial);
          if (norm(r_trial) < rn) {
            accepted = alpha;
            break;
          }
        }
      }
      rec.step_length = accepted;
      if (accepted == 0.0) {
        result.status = "line_search_failed";
        rec.seconds = elapsed(start);
        history.push_back(rec);
        result.cg_iterations += rec.cg_iterations;
        break;
      }
      x = trial;
      energy = trial_energy;
      previous_rn = rn;
      problem_.residual(x, r);
      rn = norm(r);
      result.newton_iterations = it + 1;
      result.cg_iterations += rec.cg_iterations;
      rec.seconds = elapsed(start);
      history.push_back(rec);
      if (on_iteration_) {
        const Clock::time_point paused = Clock::now();
        on_iteration_(rec, x);
        callback_seconds_ += seconds_since(paused);
      }
    }
    result.residual_norm = rn;
    result.seconds = elapsed(start);
    return result;
  }

 private:
  const HostProblem& problem_;
  const SolveOptions& options_;
  const IterationCallback& on_iteration_;
  HostBaselineResult& out_;
  double callback_seconds_ = 0.0;
};

}  // namespace

HostBaselineResult solve_on_host(const Scene& scene, const SolveOptions& options,
                                 const IterationCallback& on_iteration) {
  const Clock::time_point start = Clock::now();
  const HostProblem problem(scene, options);
  HostBaselineResult result;
  const IterationCallback& callback = on_iteration ? on_iteration : options.on_iteration;
  HostNewton newton(problem, options, callback, result);

  std::vector<double> x = options.initial_positions.empty() ? scene.mesh.positions : options.initial_positions;
  result.converged = true;
  for (int s = 1; s <= options.load_steps; ++s) {
    problem.apply_constraints(static_cast<double>(s) / options.load_steps, x);
    const StepResult step = newton.solve_step(s, x, start);
    result.converged = result.converged && step.converged;
    result.steps.push_back(step);
  }
  result.positions = std::move(x);
  result.seconds = newton.elapsed(start);
  return result;
}

HostProductTiming time_host_product(const Mesh& mesh, const StableNeoHookean& material, const std::vector<double>& x,
                                    int repetitions) {
  if (repetitions < 1) throw Error("time_host_product: repetitions must be >= 1");
  const fem::RestState rest = fem::compute_rest_state(mesh);
  HostProductTiming timing;
  const Clock::time_point assembly_start = Clock::now();
  const SparseMatrix k = reference::assembled_projected_stiffness(mesh, rest, material, x);
  timing.assembly_seconds = seconds_since(assembly_start);
  timing.nonzeros = static_cast<size_t>(k.nonZeros());

  // A fixed, non-trivial direction.
  std::vector<double> p_storage(x.size()), y_storage(x.size());
  for (size_t i = 0; i < p_storage.size(); ++i) p_storage[i] = std::sin(0.37 * static_cast<double>(i) + 0.1);
  // Maps: the product writes into fixed storage (no resize inside the loop).
  const Eigen::Map<const Vector> p(p_storage.data(), k.cols());
  Eigen::Map<Vector> y(y_storage.data(), k.rows());
  double checksum = 0.0;
  const Clock::time_point product_start = Clock::now();
  for (int rep = 0; rep < repetitions; ++rep) {
    y.noalias() = k * p;
    if (y.size() > 0) checksum += y[rep % y.size()];
  }
  timing.product_seconds = seconds_since(product_start) / repetitions;
  // Keeps the products from being optimized away.
  volatile double sink = checksum;
  (void)sink;
  return timing;
}

}  // namespace snh::bench
