// Newton's method with a backtracking (Armijo) line search on the energy for
// one load step; the linear systems go to ViennaCL's CG with the
// matrix-free operator, tolerances from Eisenstat-Walker forcing terms.
#pragma once

#include <chrono>
#include <vector>

#include "snh/simulation.h"
#include "solver/elastic_model.h"

namespace snh::solver {

template <typename Real>
class NewtonSolver {
 public:
  using Clock = std::chrono::steady_clock;
  NewtonSolver(ElasticModel<Real>& model, const SolveOptions& options) : model_(model), options_(options) {}

  // Solves from x (constrained entries already at their targets, kept fixed)
  // and appends one record per iteration to `history`.
  StepResult solve_step(int step, viennacl::vector<Real>& x, std::vector<NewtonIteration>& history,
                        Clock::time_point start);

 private:
  // Wall time since `start`, less the time spent in on_iteration callbacks.
  double elapsed(Clock::time_point start) const {
    return std::chrono::duration<double>(Clock::now() - start).count() - callback_seconds_;
  }

  double callback_seconds_ = 0.0;
  ElasticModel<Real>& model_;
  const SolveOptions& options_;
};

}  // namespace snh::solver
