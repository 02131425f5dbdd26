// Implicit Euler time stepping (SolveOptions::dynamics): each substep of
// length h minimizes the incremental potential
//   c/2 (x - y)^T M (x - y) + (1 + b/h) Psi(x) - (f + (b/h) grad Psi(x_n))^T x,
// c = (1 + a h) / h^2, y = (x_n + h v_n + a h x_n) / (1 + a h), with M the
// lumped mass and a, b the Rayleigh damping coefficients (DynamicsOptions);
// then v = (x - x_n) / h.
#pragma once

#include <algorithm>
#include <vector>

#include "device/readback.h"
#include "snh/simulation.h"
#include "solver/model/elastic_model.h"

namespace snh::solver {

// One implicit Euler substep's data: the start x_n, the inertia's per-vertex
// coefficient c m_v and target y, and b / h.
struct EulerStep {
  std::vector<double> start, coefficient, target;
  double stiffness_damping = 0.0;
};

EulerStep euler_step(const DynamicsOptions& dynamics, const std::vector<double>& x, const std::vector<double>& v,
                     const std::vector<double>& mass, double h);

// The load parameter at the end of substep j of time step s of n.
inline double substep_fraction(int s, int j, int substeps, int steps) {
  return (s - 1 + static_cast<double>(j) / substeps) / steps;
}

// Folds a substep's result into its time step's: Newton and CG counts summed,
// the last substep's status, residual and contacts, convergence of all.
void add_substep(const StepResult& sub, StepResult& total);

// Time step s of n: `substeps` minimizations of the incremental potential,
// the constraint targets interpolated linearly within the step. Newton
// starts from x~ = x_n + h v_n when `predict` (from x_n where a material is
// undefined for inverted elements and x~ could invert one), or from
// x_n + alpha h v_n where bound(x_n, h v_n) = alpha < 1: the largest
// fraction of the move that a barrier's continuous collision detection
// clears (infinity without a barrier).
// prepare(euler, t0, t1) places the substep's targets and obstacles for load
// parameters t0 to t1; solve(euler) runs its Newton solve from x.
template <typename Bound, typename Prepare, typename Solve>
StepResult implicit_euler_step(const DynamicsOptions& d, int s, int steps, bool predict, Points& x, Points& v,
                               const std::vector<double>& mass, double& time, Bound&& bound, Prepare&& prepare,
                               Solve&& solve) {
  const double h = d.time_step / d.substeps;
  const size_t dofs = x.xyz().size();
  StepResult total;
  total.step = s;
  total.converged = true;
  for (int j = 1; j <= d.substeps; ++j) {
    const EulerStep euler = euler_step(d, x.xyz(), v.xyz(), mass, h);
    if (predict) {
      // A barrier must not be crossed by the predictor either: it moves the
      // fraction of h v that continuous collision detection clears.
      std::vector<double> dx(dofs);
      const double* pv = v.data();
      for (size_t i = 0; i < dofs; ++i) dx[i] = h * pv[i];
      const double alpha = std::min(1.0, bound(x.xyz(), dx));
      double* px = x.data();
      for (size_t i = 0; i < dofs; ++i) px[i] += alpha * dx[i];
    }
    prepare(euler, substep_fraction(s, j - 1, d.substeps, steps), substep_fraction(s, j, d.substeps, steps));
    const StepResult sub = solve(euler);
    const double* px = x.data();
    double* pv = v.data();
    for (size_t i = 0; i < dofs; ++i) pv[i] = (px[i] - euler.start[i]) / h;
    time += h;
    add_substep(sub, total);
    if (sub.status == StepStatus::cancelled) break;
  }
  return total;
}

// Hands the substep's inertia and forces to the model: the applied force
// plus Rayleigh stiffness damping's linear part (b/h) grad Psi(x_n).
template <typename Real>
void set_incremental_potential(ElasticModel<Real>& model, const EulerStep& euler,
                               const std::vector<double>& force_applied) {
  std::vector<double> force = force_applied;
  if (euler.stiffness_damping > 0.0) {
    const std::vector<Real> xs(euler.start.begin(), euler.start.end());
    viennacl::vector<Real> xn(xs.size()), fe(xs.size());
    device::write_to_device(model.context(), xs, xn);
    model.elastic_forces(xn, fe);
    std::vector<Real> host;
    device::read_back(model.context(), fe, host);
    force.resize(host.size(), 0.0);
    for (size_t i = 0; i < host.size(); ++i) force[i] -= euler.stiffness_damping * static_cast<double>(host[i]);
  }
  model.set_external_force(force);
  model.set_inertia(euler.coefficient, euler.target, 1.0 + euler.stiffness_damping);
}

}  // namespace snh::solver
