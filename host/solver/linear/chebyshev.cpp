#include "solver/linear/chebyshev.h"

#include <cmath>
#include <string>

#include "snh/error.h"

namespace snh::solver {

namespace {

constexpr double kLower = 0.1, kUpper = 1.1;

// Lottes 2023, the optimized weights beta_i of the fourth-kind smoother for
// degrees 1 to 4 (also PETSc's KSP_CHEBYSHEV_OPT_FOURTH table).
constexpr int kOptimizedDegrees = 4;
constexpr double kOptimizedBeta[kOptimizedDegrees][kOptimizedDegrees] = {
    {1.12500000000000},
    {1.02387287570313, 1.26408905371085},
    {1.00842544782028, 1.08867839208730, 1.33753125909618},
    {1.00391310427285, 1.04035811188593, 1.14863498546254, 1.38268869241000},
};

}  // namespace

ChebyshevSteps chebyshev_steps(ChebyshevKind kind, int degree, double lambda) {
  if (degree < 1) throw Error("chebyshev: degree must be at least 1, got " + std::to_string(degree));
  ChebyshevSteps s;
  s.c_d.assign(degree, 0.0);
  s.c_z.assign(degree, 0.0);
  s.beta.assign(degree, 1.0);
  const double upper = kUpper * lambda;
  if (kind == ChebyshevKind::first) return chebyshev_interval_steps(degree, kLower * lambda, upper);
  if (kind == ChebyshevKind::optimized_fourth && degree > kOptimizedDegrees)
    throw Error("chebyshev: optimized-fourth weights are tabulated for degrees 1 to " +
                std::to_string(kOptimizedDegrees) + ", got " + std::to_string(degree));
  s.c_z[0] = 4.0 / (3.0 * upper);
  for (int i = 1; i < degree; ++i) {
    s.c_d[i] = (2.0 * i - 1.0) / (2.0 * i + 3.0);
    s.c_z[i] = (8.0 * i + 4.0) / ((2.0 * i + 3.0) * upper);
  }
  if (kind == ChebyshevKind::optimized_fourth)
    for (int i = 0; i < degree; ++i) s.beta[i] = kOptimizedBeta[degree - 1][i];
  return s;
}

ChebyshevSteps chebyshev_interval_steps(int degree, double lower, double upper) {
  if (degree < 1) throw Error("chebyshev: degree must be at least 1, got " + std::to_string(degree));
  if (!(lower > 0.0) || !(upper > lower) || !std::isfinite(upper))
    throw Error("chebyshev: an interval needs 0 < lower < upper, got [" + std::to_string(lower) + ", " +
                std::to_string(upper) + "]");
  ChebyshevSteps s;
  s.c_d.assign(degree, 0.0);
  s.c_z.assign(degree, 0.0);
  s.beta.assign(degree, 1.0);
  const double theta = 0.5 * (upper + lower), delta = 0.5 * (upper - lower);
  double rho = delta / theta;
  s.c_z[0] = 1.0 / theta;
  for (int i = 1; i < degree; ++i) {
    const double rho_next = 1.0 / (2.0 * theta / delta - rho);
    s.c_d[i] = rho_next * rho;
    s.c_z[i] = 2.0 * rho_next / delta;
    rho = rho_next;
  }
  return s;
}

double chebyshev_residual_factor(const ChebyshevSteps& steps, double t) {
  // A = t, D = 1, b = 1, x_0 = 0: the error factor is r_degree = 1 - t x.
  const int degree = static_cast<int>(steps.c_z.size());
  double r = 1.0, x = 0.0, d = steps.c_z[0] * r;
  x += steps.beta[0] * d;
  for (int i = 1; i < degree; ++i) {
    r -= t * d;
    d = steps.c_d[i] * d + steps.c_z[i] * r;
    x += steps.beta[i] * d;
  }
  return 1.0 - t * x;
}

}  // namespace snh::solver
