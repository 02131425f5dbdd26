// The multigrid's polynomial smoothing: Chebyshev iterations over
// block-Jacobi D for A x = b, written as one recurrence for every kind
// (ChebyshevKind in snh/simulation.h):
//   d_0 = c_z[0] D^-1 r_0,               x_1 = x_0 + beta[0] d_0,
//   r_i = r_{i-1} - A d_{i-1},
//   d_i = c_d[i] d_{i-1} + c_z[i] D^-1 r_i,  x_{i+1} = x_i + beta[i] d_i,
// for i = 1 .. degree - 1, so that the error after `degree` steps is
// p(D^-1 A) e_0 with p(0) = 1 (each d_i is a polynomial in D^-1 A applied to
// D^-1 r_0). The same steps before and after the coarse correction keep the
// V-cycle symmetric for every kind.
//   first: the three-term recurrence of the first-kind Chebyshev polynomial
//     on [lower, upper] (Saad 2003, Algorithm 12.1): d_0 = D^-1 r_0 / theta,
//     rho_0 = delta / theta, rho_i = 1 / (2 theta / delta - rho_{i-1}),
//     c_d = rho_i rho_{i-1}, c_z = 2 rho_i / delta; beta = 1.
//   fourth: Lottes 2023, Algorithm 3 (fourth-kind Chebyshev over
//     [0, upper]): c_z[0] = 4 / (3 upper), c_d[i] = (2i - 1) / (2i + 3),
//     c_z[i] = (8i + 4) / ((2i + 3) upper); beta = 1. Its residual factor
//     p has max over t in (0, upper] of sqrt(t / upper) |p(t)| = 1 /
//     (2 degree + 1), the optimum of that measure.
//   optimized_fourth: the same with Lottes' optimized beta (his Table;
//     tabulated here for degrees 1 to 4).
#pragma once

#include <vector>

#include "snh/simulation.h"

namespace snh::solver {

struct ChebyshevSteps {
  std::vector<double> c_d, c_z, beta;  // degree entries each; c_d[0] unused
  // Some beta is not 1: the recurrence's r is then not b - A x.
  bool weighted() const {
    for (double b : beta)
      if (b != 1.0) return true;
    return false;
  }
};

// The steps for `degree` (>= 1) over the interval the kind uses, given
// lambda, the estimate of lambda_max(D^-1 A): upper = 1.1 lambda, lower
// (first kind) = 0.1 lambda (PETSc's defaults for a Chebyshev smoother;
// Adams et al. 2003). Throws snh::Error for a degree the kind has no
// coefficients for.
ChebyshevSteps chebyshev_steps(ChebyshevKind kind, int degree, double lambda);

// The first kind's steps over [lower, upper] (0 < lower < upper), for
// `degree` >= 1: its residual factor is at most 1 / T_degree((upper +
// lower) / (upper - lower)) there, and falls from 1 to that below lower.
ChebyshevSteps chebyshev_interval_steps(int degree, double lower, double upper);

// p(t) of the steps above (the error factor at eigenvalue t of D^-1 A), from
// the same recurrence on scalars: for tests and documentation.
double chebyshev_residual_factor(const ChebyshevSteps& steps, double t);

}  // namespace snh::solver
