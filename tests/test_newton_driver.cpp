// The Newton loop (solver/newton/newton_driver.h) on a two-DOF energy with a saddle,
// E(x, y) = x^2 / 2 + y^4 / 4 - eps y^2 / 2, whose linear solve behaves as
// a projected Hessian that, like the per-element projection at a
// bifurcation, keeps positive curvature where the energy has none:
// diag(1, max(E_yy, 0) + 1). Its steps slide off the saddle y = 0 by 1% per
// iteration; started next to it, Newton must reach the minimum at
// y = sqrt(eps) by extending the steps that show negative curvature. On a
// convex start no step is extended.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "snh/simulation.h"
#include "solver/newton/newton_driver.h"

namespace snh::test {
namespace {

constexpr double kEps = 0.01;

class SaddleProblem {
 public:
  using Vector = std::vector<double>;
  size_t dofs() const { return 2; }
  double epsilon() const { return 2.220446049250313e-16; }
  Vector vector() const { return Vector(2, 0.0); }
  double energy(const Vector& v) {
    const double x = v[0], y = v[1];
    return 0.5 * x * x + 0.25 * y * y * y * y - 0.5 * kEps * y * y;
  }
  double last_min_j() const { return 1.0; }
  void residual(const Vector& v, Vector& r) { r = {-v[0], kEps * v[1] - v[1] * v[1] * v[1]}; }
  double norm(const Vector& v) const { return std::sqrt(dot(v, v)); }
  double dot(const Vector& a, const Vector& b) const { return a[0] * b[0] + a[1] * b[1]; }
  // The projection keeps curvature the energy lacks (as per-element
  // projections do at a bifurcation): max(E_yy, 0) + 1; the true Hessian is
  // E_yy, on which the solve reports negative curvature where E_yy <= 0.
  void linearize(const Vector& v, bool projected) {
    const double e_yy = 3.0 * v[1] * v[1] - kEps;
    curvature_ = projected ? std::max(e_yy, 0.0) + 1.0 : e_yy;
  }
  solver::LinearSolve solve(const Vector& r, Vector& p, double, int) {
    solver::LinearSolve s;
    s.iterations = 1;
    s.negative_curvature = !(curvature_ > 0.0);
    p = {r[0], s.negative_curvature ? r[1] : r[1] / curvature_};
    return s;
  }
  void precondition(const Vector& r, Vector& p) { p = r; }
  void step(const Vector& x, double alpha, const Vector& p, Vector& out) {
    out = {x[0] + alpha * p[0], x[1] + alpha * p[1]};
  }
  void swap(Vector& a, Vector& b) { a.swap(b); }
  bool has_true_hessian() const { return true; }

 private:
  double curvature_ = 1.0;
};

struct SaddleRun {
  StepResult result;
  std::vector<NewtonIteration> history;
  std::vector<double> x;
  int extended = 0;  // iterations whose step was extended
};

SaddleRun run_from(double x0, double y0) {
  SaddleProblem problem;
  SolveOptions options;
  options.max_newton_iterations = 400;
  solver::NewtonDriver<SaddleProblem> newton(problem, options);
  SaddleRun run;
  run.x = {x0, y0};
  run.result =
      newton.solve_step(1, run.x, solver::StoppingTest{1e-12, 0.0}, run.history, std::chrono::steady_clock::now());
  for (const NewtonIteration& h : run.history)
    if (contains(h.recovery, RecoveryAction::extended_step)) ++run.extended;
  return run;
}

TEST(NewtonDriver, LeavesASaddleByExtendingStepsAlongNegativeCurvature) {
  // The projected steps grow y by about 1 + eps per iteration: about 1,160
  // iterations from 1e-6 to the minimum at 0.1, past the limit of 400.
  const SaddleRun run = run_from(0.5, 1e-6);
  EXPECT_TRUE(run.result.converged) << run.result.status << " after " << run.result.newton_iterations;
  EXPECT_NEAR(std::abs(run.x[1]), std::sqrt(kEps), 1e-8);
  EXPECT_NEAR(run.x[0], 0.0, 1e-12);
  EXPECT_LT(run.result.newton_iterations, 60);
  EXPECT_GT(run.extended, 0);
  std::printf("saddle: %d Newton iterations, %d extended steps, y = %.10f\n", run.result.newton_iterations,
              run.extended, run.x[1]);
}

TEST(NewtonDriver, ConvexStartTakesNoExtendedStep) {
  const SaddleRun run = run_from(0.5, 0.5);  // 3 y^2 - eps > 0 along the whole path to y = 0.1
  EXPECT_TRUE(run.result.converged) << run.result.status;
  EXPECT_NEAR(run.x[1], std::sqrt(kEps), 1e-8);
  EXPECT_EQ(run.extended, 0);
}

// A problem whose active set (as self-contact's) changes at each of its
// first 12 iterates, each change moving the minimum of E = (x - c)^2 / 2 one
// unit on: every Newton step lands on the last minimum, where the new set
// gives the same residual and energy again. Within a set Newton converges at
// once; comparing residuals and energies across sets would see neither fall
// and call the step stagnated.
class ChangingSetProblem {
 public:
  using Vector = std::vector<double>;
  size_t dofs() const { return 1; }
  double epsilon() const { return 2.220446049250313e-16; }
  Vector vector() const { return Vector(1, 0.0); }
  double energy(const Vector& v) { return 0.5 * (v[0] - center_) * (v[0] - center_); }
  double last_min_j() const { return 1.0; }
  void residual(const Vector& v, Vector& r) { r = {center_ - v[0]}; }
  double norm(const Vector& v) const { return std::abs(v[0]); }
  double dot(const Vector& a, const Vector& b) const { return a[0] * b[0]; }
  void linearize(const Vector&, bool) {}
  solver::LinearSolve solve(const Vector& r, Vector& p, double, int) {
    solver::LinearSolve s;
    s.iterations = 1;
    p = r;
    return s;
  }
  void precondition(const Vector& r, Vector& p) { p = r; }
  void step(const Vector& x, double alpha, const Vector& p, Vector& out) { out = {x[0] + alpha * p[0]}; }
  void swap(Vector& a, Vector& b) { a.swap(b); }
  bool has_true_hessian() const { return true; }
  bool refresh(const Vector&, bool new_step) {
    if (new_step || changes_ == 12) return false;
    ++changes_;
    center_ += 1.0;
    return true;
  }

 private:
  double center_ = 1.0;
  int changes_ = 0;
};

TEST(NewtonDriver, ProgressIsJudgedWithinOneActiveSet) {
  ChangingSetProblem problem;
  SolveOptions options;
  options.max_newton_iterations = 100;
  solver::NewtonDriver<ChangingSetProblem> newton(problem, options);
  std::vector<double> x = {0.0};
  std::vector<NewtonIteration> history;
  const StepResult r =
      newton.solve_step(1, x, solver::StoppingTest{1e-12, 0.0}, history, std::chrono::steady_clock::now());
  EXPECT_TRUE(r.converged) << r.status << " after " << r.newton_iterations;
  EXPECT_NEAR(x[0], 13.0, 1e-12);
  EXPECT_EQ(r.newton_iterations, 13);
}

// An equilibrium with an inverted element, as at a squeezed elbow: E =
// k (x - 1)^2 / 2, positive definite, but the projection (clamping the
// inverted element's negative eigenvalues) overestimates the curvature ten
// times, so projected Newton converges linearly, at 0.9 per iteration:
// about 260 iterations from a residual of 1 to 1e-12. Once it crawls, the
// adaptive mode must try the true Hessian even though an element is
// inverted, and converge at once.
class InvertedEquilibriumProblem {
 public:
  using Vector = std::vector<double>;
  size_t dofs() const { return 1; }
  double epsilon() const { return 2.220446049250313e-16; }
  Vector vector() const { return Vector(1, 0.0); }
  double energy(const Vector& v) { return 0.5 * (v[0] - 1.0) * (v[0] - 1.0); }
  double last_min_j() const { return -0.01; }
  void residual(const Vector& v, Vector& r) { r = {1.0 - v[0]}; }
  double norm(const Vector& v) const { return std::abs(v[0]); }
  double dot(const Vector& a, const Vector& b) const { return a[0] * b[0]; }
  void linearize(const Vector&, bool projected) { curvature_ = projected ? 10.0 : 1.0; }
  solver::LinearSolve solve(const Vector& r, Vector& p, double, int) {
    p = {r[0] / curvature_};
    solver::LinearSolve s;
    s.iterations = 1;
    return s;
  }
  void precondition(const Vector& r, Vector& p) { p = r; }
  void step(const Vector& x, double alpha, const Vector& p, Vector& out) { out = {x[0] + alpha * p[0]}; }
  void swap(Vector& a, Vector& b) { a.swap(b); }
  bool has_true_hessian() const { return true; }

 private:
  double curvature_ = 10.0;
};

TEST(NewtonDriver, CrawlingProjectionTriesTheTrueHessianDespiteInversion) {
  InvertedEquilibriumProblem problem;
  SolveOptions options;
  options.max_newton_iterations = 100;
  solver::NewtonDriver<InvertedEquilibriumProblem> newton(problem, options);
  std::vector<NewtonIteration> history;
  std::vector<double> x = {0.0};
  const StepResult result =
      newton.solve_step(1, x, solver::StoppingTest{1e-12, 0.0}, history, std::chrono::steady_clock::now());
  EXPECT_TRUE(result.converged) << result.status << " after " << result.newton_iterations;
  EXPECT_NEAR(x[0], 1.0, 1e-12);
  EXPECT_LT(result.newton_iterations, 10);
  int first_true = -1;
  for (const NewtonIteration& h : history)
    if (!h.projected && h.cg_stop != CgStop::none) {
      first_true = h.iteration;
      break;
    }
  EXPECT_GE(first_true, 4) << "only after the projection crawled";
  std::printf("inverted equilibrium: %d Newton iterations, first true Hessian at iteration %d\n",
              result.newton_iterations, first_true);
}

}  // namespace
}  // namespace snh::test
