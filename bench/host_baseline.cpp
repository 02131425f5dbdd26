// The host CPU baseline: the engine's Newton driver (solver/newton/newton_driver.h,
// the very loop the device solver runs) over a host problem in double, with
// the stiffness assembled by Eigen and solved by Eigen's diagonally
// preconditioned ConjugateGradient.
#include "host_baseline.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "device/phase_profile.h"
#include "fem/rest_state.h"
#include "reference/fem_reference.h"
#include "snh/error.h"
#include "snh/loads.h"
#include "snh/regions.h"
#include "solver/newton/newton_driver.h"
#include "solver/newton/stopping_test.h"
#include "solver/simulation/constraint_checks.h"
#include "solver/simulation/load_stepping.h"
#include "solver/simulation/solve_input_validation.h"

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
    fixed_ = solver::prescribed_dofs(mesh_, constraints_);
    full_force_.assign(3 * n, 0.0);
    const std::vector<double>& external = options_.external_force.xyz();
    for (size_t i = 0; i < external.size(); ++i) full_force_[i] += external[i];
    const auto& b = options_.body_force;
    if (b[0] != 0.0 || b[1] != 0.0 || b[2] != 0.0) {
      const std::vector<double> lumped = lump_body_force(mesh_, b).release();
      for (size_t i = 0; i < lumped.size(); ++i) full_force_[i] += lumped[i];
    }
    force_ = full_force_;
    // Vertices of no element have no stiffness: identity rows, like fixed ones.
    std::vector<char> used(n, 0);
    for (int32_t v : mesh_.elements) used[v] = 1;
    identity_.assign(3 * n, 0);
    for (size_t i = 0; i < 3 * n; ++i) identity_[i] = fixed_[i] || !used[i / 3];
  }

  size_t dofs() const { return 3 * mesh_.vertex_count(); }

  // Constraint targets and, with SolveOptions::ramp_loads, forces at load parameter t.
  void apply_load(double t, std::vector<double>& x) {
    snh::apply_constraints(mesh_, constraints_, t, x);
    if (options_.ramp_loads)
      solver::ramp_force(std::vector<double>(full_force_.size(), 0.0), full_force_, t, force_);
    else
      force_ = full_force_;
  }

  // Total potential energy: elastic energy minus external work.
  double energy(const std::vector<double>& x) const {
    double e = reference::assembled_energy(mesh_, rest_, material_, x);
    for (size_t i = 0; i < force_.size(); ++i) e -= force_[i] * x[i];
    return e;
  }

  // r = mask * (elastic forces + external force).
  void residual(const std::vector<double>& x, std::vector<double>& r) const {
    r = reference::assembled_forces(mesh_, rest_, material_, x);
    for (size_t i = 0; i < r.size(); ++i) {
      r[i] += force_[i];
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
  void validate() const { validate_solve_inputs(mesh_, constraints_, options_); }

  const Mesh& mesh_;
  const StableNeoHookean& material_;
  const std::vector<ConstraintSet>& constraints_;
  const SolveOptions& options_;
  fem::RestState rest_;
  std::vector<double> full_force_, force_;  // lumped external and body force; at the current load
  std::vector<char> fixed_;                 // per DOF: constrained
  std::vector<char> identity_;              // per DOF: identity row and column in the stiffness
};

using IterationCallback = std::function<void(const NewtonIteration&, const std::vector<double>&)>;

// The host problem behind solver::NewtonDriver: the same Newton loop as the
// device solver's, over Eigen's assembled stiffness and diagonally
// preconditioned ConjugateGradient.
class HostNewtonProblem {
 public:
  using Vector = std::vector<double>;

  HostNewtonProblem(const HostProblem& problem, HostBaselineResult& out, solver::PhaseProfiler& profiler)
      : problem_(problem), out_(out), profiler_(profiler) {}

  size_t dofs() const { return problem_.dofs(); }
  double epsilon() const { return std::numeric_limits<double>::epsilon(); }
  Vector vector() const { return Vector(problem_.dofs(), 0.0); }
  double energy(const Vector& x) {
    solver::PhaseScope timed(&profiler_, solver::Phase::line_search_energies);
    return problem_.energy(x);
  }
  double last_min_j() const { return 1.0; }  // only asked for with a true Hessian
  void residual(const Vector& x, Vector& r) {
    solver::PhaseScope timed(&profiler_, solver::Phase::line_search_energies);
    problem_.residual(x, r);
  }
  double norm(const Vector& v) const { return bench::norm(v); }
  double dot(const Vector& a, const Vector& b) const {
    double s = 0.0;
    for (size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
    return s;
  }
  // The host reference assembles the projected stiffness only: adaptive
  // Hessians fall back to the projection here.
  bool has_true_hessian() const { return false; }

  void linearize(const Vector& x, bool) {
    solver::PhaseScope timed(&profiler_, solver::Phase::linearization);
    const Clock::time_point start = Clock::now();
    k_ = problem_.stiffness(x);
    out_.assembly_seconds += seconds_since(start);
  }

  solver::LinearSolve solve(const Vector& r, Vector& p, double eta, int max_iterations) {
    const Clock::time_point start = Clock::now();
    Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper> cg;
    cg.setTolerance(eta);
    cg.setMaxIterations(max_iterations);
    {
      solver::PhaseScope setup(&profiler_, solver::Phase::preconditioner_setup);
      cg.compute(k_);
    }
    const Eigen::Map<const Eigen::VectorXd> rhs(r.data(), static_cast<Eigen::Index>(r.size()));
    const Eigen::VectorXd solution = cg.solve(rhs);
    out_.cg_seconds += seconds_since(start);
    solver::LinearSolve s;
    s.relative_residual = cg.error();
    const bool converged = cg.info() == Eigen::Success;
    // Matrix-vector products, as ViennaCL counts: Eigen's count leaves out
    // the iteration in which the residual fell below the tolerance (unless
    // it returned at once, with p = 0, for eta >= 1).
    s.iterations = static_cast<int>(cg.iterations()) + (converged && !solution.isZero(0.0) ? 1 : 0);
    p.assign(solution.data(), solution.data() + solution.size());
    for (size_t i = 0; i < p.size(); ++i)
      if (problem_.fixed(i)) p[i] = 0.0;
    return s;
  }

  // The diagonal (Jacobi) preconditioner Eigen's CG uses.
  void precondition(const Vector& r, Vector& p) {
    solver::PhaseScope timed(&profiler_, solver::Phase::preconditioner_apply);
    const Eigen::VectorXd diagonal = k_.diagonal();
    p.resize(r.size());
    for (size_t i = 0; i < r.size(); ++i) {
      const double d = diagonal[static_cast<Eigen::Index>(i)];
      p[i] = d != 0.0 && std::isfinite(d) ? r[i] / d : r[i];
    }
  }
  void step(const Vector& x, double alpha, const Vector& p, Vector& out) {
    solver::PhaseScope timed(&profiler_, solver::Phase::line_search_energies);
    out.resize(x.size());
    for (size_t i = 0; i < x.size(); ++i) out[i] = x[i] + alpha * p[i];
  }
  void swap(Vector& a, Vector& b) { a.swap(b); }

 private:
  const HostProblem& problem_;
  HostBaselineResult& out_;
  solver::PhaseProfiler& profiler_;
  SparseMatrix k_;
};

}  // namespace

HostBaselineResult solve_on_host(const Scene& scene, const SolveOptions& options,
                                 const IterationCallback& on_iteration) {
  const Clock::time_point start = Clock::now();
  HostProblem problem(scene, options);
  HostBaselineResult result;
  solver::PhaseProfiler profiler;
  HostNewtonProblem newton_problem(problem, result, profiler);
  solver::NewtonDriver<HostNewtonProblem> newton(newton_problem, options);
  solver::NewtonDriver<HostNewtonProblem>::Observer observe;
  if (on_iteration)
    observe = [&on_iteration](const NewtonIteration& rec, const std::vector<double>& x) {
      on_iteration(rec, x);
      return true;
    };
  else if (options.on_iteration)
    observe = [&options](const NewtonIteration& rec, const std::vector<double>& x) {
      options.on_iteration(rec, Points::from_xyz(x));  // a copy, in the callback's (excluded) time
      return true;
    };
  const solver::StoppingTest stop =
      solver::stopping_test(scene.mesh, uniform_material(scene.mesh, scene.material), options);

  std::vector<double> x = (options.initial_positions.empty() ? scene.mesh.positions : options.initial_positions).xyz();
  result.converged = true;
  for (int s = 1; s <= options.load_steps; ++s) {
    problem.apply_load(solver::load_fraction(s, options.load_steps), x);
    const StepResult step = newton.solve_step(s, x, stop, result.history, start, observe);
    result.converged = result.converged && step.converged;
    result.steps.push_back(step);
  }
  result.positions = std::move(x);
  result.seconds = newton.elapsed(start);
  result.profile = solver::make_profile(profiler.seconds(), result.seconds);
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
