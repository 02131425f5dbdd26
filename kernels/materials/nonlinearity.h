/* Adjusting a material's nonlinearity (Chen, Barbic et al., seed 004 sec. 5,
 * Eqs. 16-18): psi_alpha(sigma) = psi(m(sigma_0), m(sigma_1), m(sigma_2)) / alpha^2
 * with m(x) = x^alpha. It keeps the rest Hessian (m(1) = 1, m'(1) = alpha) and
 * softens (alpha < 1) or stiffens (alpha > 1) the material at large strain.
 *
 * The paper's x^alpha is only defined for x > 0, while the rotation-variant
 * SVD puts inversions in a negative sigma_2, and x^alpha has an infinite
 * slope (alpha < 1) or curvature (1 < alpha < 2) at 0. We use the odd
 * extension m(x) = sign(x) |x|^alpha (so J and inversion keep their sign),
 * and for alpha < 2 replace it on |x| < SNH_NONLINEAR_TAU by the odd cubic
 * a x + b x^3 that matches its value and slope at tau:
 *   a = tau^(alpha-1) (3 - alpha) / 2,  b = (alpha - 1) tau^(alpha-3) / 2,
 * monotone (m' >= alpha tau^(alpha-1) > 0 there) and C1. Beyond tau (every
 * stretch of practical interest, and all of seed 004's figures) m is the
 * paper's. The Hessian's twist and flip eigenvalues need the divided
 * differences (m(x) - m(y)) / (x - y) and (m'(x) - m'(y)) / (x - y); they
 * are computed without cancellation (expm1/log1p for two powers of one sign,
 * exactly for two cubics). */
#ifndef SNH_NONLINEARITY_H
#define SNH_NONLINEARITY_H

#include "math/svd3.h"

#define SNH_NONLINEAR_TAU SNH_R(0.1)

SNH_FN int nonlinear_in_cubic(real x, real alpha) { return alpha < SNH_R(2) && fabs(x) < SNH_NONLINEAR_TAU; }

SNH_FN void nonlinear_cubic(real alpha, real* a, real* b) {
  *a = pow(SNH_NONLINEAR_TAU, alpha - SNH_R(1)) * (SNH_R(3) - alpha) * SNH_R(0.5);
  *b = (alpha - SNH_R(1)) * pow(SNH_NONLINEAR_TAU, alpha - SNH_R(3)) * SNH_R(0.5);
}

/* m(x), m'(x), m''(x): one pow per stretch (m' = alpha m / x, m'' =
 * (alpha - 1) m' / x away from 0). */
SNH_FN void nonlinear_map(real x, real alpha, real* m, real* dm, real* ddm) {
  if (alpha == SNH_R(1)) {
    *m = x;
    *dm = SNH_R(1);
    *ddm = SNH_R(0);
    return;
  }
  if (nonlinear_in_cubic(x, alpha)) {
    real a, b;
    nonlinear_cubic(alpha, &a, &b);
    *m = x * (a + b * x * x);
    *dm = a + SNH_R(3) * b * x * x;
    *ddm = SNH_R(6) * b * x;
    return;
  }
  const real ax = fabs(x), sign = x < SNH_R(0) ? SNH_R(-1) : SNH_R(1);
  if (ax == SNH_R(0)) { /* alpha >= 2 here */
    *m = *dm = SNH_R(0);
    *ddm = alpha == SNH_R(2) ? SNH_R(2) * sign : SNH_R(0);
    return;
  }
  const real p = pow(ax, alpha);
  *m = sign * p;
  *dm = alpha * p / ax;
  *ddm = sign * (alpha - SNH_R(1)) * *dm / ax;
}

/* The map at the three stretches, and per pair k = (i, j) the divided
 * differences of m and m' at (sigma_i, sigma_j) (flip) and (sigma_i,
 * -sigma_j) (twist). */
typedef struct {
  real alpha;
  vec3 m, dm, ddm;
  vec3 flip_m, flip_dm, twist_m, twist_dm;
} nonlinear_stretches;

/* Divided differences of m (*d0) and m' (*d1) at x, y with their map values. */
SNH_FN void nonlinear_divided(real x, real mx, real dmx, real ddmx, real y, real my, real dmy, real ddmy, real alpha,
                              real* d0, real* d1) {
  if (x == y) {
    *d0 = dmx;
    *d1 = ddmx;
    return;
  }
  const int cx = nonlinear_in_cubic(x, alpha), cy = nonlinear_in_cubic(y, alpha);
  if (cx && cy) {
    real a, b;
    nonlinear_cubic(alpha, &a, &b);
    *d0 = a + b * (x * x + x * y + y * y);
    *d1 = SNH_R(3) * b * (x + y);
    return;
  }
  if (!cx && !cy && x * y > SNH_R(0)) {
    /* Both powers, one sign: with big >= small > 0, r = small / big,
     * (big^p - small^p) / (big - small) = big^(p-1) expm1(p log r) / expm1(log r),
     * p = alpha for m and alpha - 1 for m' / alpha; big^(alpha-1) = m'(big) / alpha. */
    const int x_big = fabs(x) >= fabs(y);
    const real big = x_big ? fabs(x) : fabs(y), small = x_big ? fabs(y) : fabs(x);
    const real big_dm = x_big ? dmx : dmy;
    const real log_r = log1p((small - big) / big), e = expm1(log_r);
    *d0 = big_dm / alpha * expm1(alpha * log_r) / e;
    /* m is odd (same value for x, y < 0); m' is even (sign flips). */
    const real sign = x < SNH_R(0) ? SNH_R(-1) : SNH_R(1);
    *d1 = sign * big_dm / big * expm1((alpha - SNH_R(1)) * log_r) / e;
    return;
  }
  /* Opposite signs (|x - y| = |x| + |y|: m(x) - m(y) adds two terms of one
   * sign) or the two sides of tau, where x and y closer than sqrt(eps) tau
   * take the mean derivative (error below sqrt(eps) relative). */
  if (x * y > SNH_R(0) && fabs(x - y) <= sqrt(SNH_EPS) * SNH_NONLINEAR_TAU) {
    *d0 = SNH_R(0.5) * (dmx + dmy);
    *d1 = SNH_R(0.5) * (ddmx + ddmy);
    return;
  }
  *d0 = (mx - my) / (x - y);
  *d1 = (dmx - dmy) / (x - y);
}

SNH_FN nonlinear_stretches nonlinear_stretches_of(vec3 sigma, real alpha) {
  nonlinear_stretches n;
  n.alpha = alpha;
  for (int i = 0; i < 3; ++i) nonlinear_map(sigma.a[i], alpha, &n.m.a[i], &n.dm.a[i], &n.ddm.a[i]);
  for (int k = 0; k < 3; ++k) {
    const int i = k == 0 ? 1 : 0, j = k == 2 ? 1 : 2; /* principal_pair_i, _j */
    if (alpha == SNH_R(1)) {
      n.flip_m.a[k] = n.twist_m.a[k] = SNH_R(1);
      n.flip_dm.a[k] = n.twist_dm.a[k] = SNH_R(0);
      continue;
    }
    nonlinear_divided(sigma.a[i], n.m.a[i], n.dm.a[i], n.ddm.a[i], sigma.a[j], n.m.a[j], n.dm.a[j], n.ddm.a[j], alpha,
                      &n.flip_m.a[k], &n.flip_dm.a[k]);
    /* m(-x) = -m(x), m'(-x) = m'(x), m''(-x) = -m''(x) */
    nonlinear_divided(sigma.a[i], n.m.a[i], n.dm.a[i], n.ddm.a[i], -sigma.a[j], -n.m.a[j], n.dm.a[j], -n.ddm.a[j],
                      alpha, &n.twist_m.a[k], &n.twist_dm.a[k]);
  }
  return n;
}

#endif /* SNH_NONLINEARITY_H */
