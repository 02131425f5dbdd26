/* Adjusting a material's nonlinearity (Chen and Barbic 2024, sec. 5,
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
 * stretch of practical interest, and all of the figures of Chen and Barbic 2024) m is the
 * paper's. The Hessian's twist and flip eigenvalues need the divided
 * differences (m(x) - m(y)) / (x - y) and (m'(x) - m'(y)) / (x - y); they
 * are computed without cancellation (expm1/log1p for two powers of one sign,
 * exactly for two cubics). */
#ifndef SNH_NONLINEARITY_H
#define SNH_NONLINEARITY_H

#include "math/svd3.h"

#define SNH_NONLINEAR_TAU SNH_R(0.1)

SNH_FN snh_mask nonlinear_in_cubic(real x, scalar_real alpha) {
  return alpha < SNH_R(2) && fabs(x) < SNH_NONLINEAR_TAU;
}

SNH_FN void nonlinear_cubic(scalar_real alpha, real* a, real* b) {
  const real tau = SNH_NONLINEAR_TAU, al = SNH_R(alpha);
  *a = pow(tau, al - SNH_R(1)) * (SNH_R(3) - al) * SNH_R(0.5);
  *b = (al - SNH_R(1)) * pow(tau, al - SNH_R(3)) * SNH_R(0.5);
}

/* m(x), m'(x), m''(x): one pow per stretch (m' = alpha m / x, m'' =
 * (alpha - 1) m' / x away from 0). The cases are computed and selected, not
 * branched on (lanes, snh_portable.h); alpha is a parameter, so alpha = 1
 * may branch. */
SNH_FN void nonlinear_map(real x, scalar_real alpha, real* m, real* dm, real* ddm) {
  if (alpha == 1) {
    *m = x;
    *dm = SNH_R(1);
    *ddm = SNH_R(0);
    return;
  }
  const snh_mask cubic = nonlinear_in_cubic(x, alpha);
  real a, b;
  nonlinear_cubic(alpha, &a, &b);
  const real ax = fabs(x), sign = x < SNH_R(0) ? SNH_R(-1) : SNH_R(1);
  /* x = 0 outside the cubic: alpha >= 2 there */
  const snh_mask zero = ax == SNH_R(0);
  const real safe = zero ? SNH_R(1) : ax, al = SNH_R(alpha);
  const real p = pow(safe, al);
  const real pdm = al * p / safe;
  const real zero_ddm = alpha == 2 ? SNH_R(2) * sign : SNH_R(0);
  *m = cubic ? x * (a + b * x * x) : (zero ? SNH_R(0) : sign * p);
  *dm = cubic ? a + SNH_R(3) * b * x * x : (zero ? SNH_R(0) : pdm);
  *ddm = cubic ? SNH_R(6) * b * x : (zero ? zero_ddm : sign * (al - SNH_R(1)) * pdm / safe);
}

/* The map at the three stretches, and per pair k = (i, j) the divided
 * differences of m and m' at (sigma_i, sigma_j) (flip) and (sigma_i,
 * -sigma_j) (twist). */
typedef struct {
  scalar_real alpha;
  vec3 m, dm, ddm;
  vec3 flip_m, flip_dm, twist_m, twist_dm;
} nonlinear_stretches;

/* Divided differences of m (*d0) and m' (*d1) at x, y with their map values.
 * Every case is computed and the first that applies selected, in this order
 * (lanes, snh_portable.h): */
SNH_FN void nonlinear_divided(real x, real mx, real dmx, real ddmx, real y, real my, real dmy, real ddmy,
                              scalar_real alpha, real* d0, real* d1) {
  /* x = y: the derivatives. */
  const snh_mask same = x == y;
  /* Both in the cubic: exact. */
  const snh_mask cx = nonlinear_in_cubic(x, alpha), cy = nonlinear_in_cubic(y, alpha);
  const snh_mask cubics = cx && cy;
  real a, b;
  nonlinear_cubic(alpha, &a, &b);
  const real cubic_d0 = a + b * (x * x + x * y + y * y), cubic_d1 = SNH_R(3) * b * (x + y);
  /* Both powers, one sign: with big >= small > 0, r = small / big,
   * (big^p - small^p) / (big - small) = big^(p-1) expm1(p log r) / expm1(log r),
   * p = alpha for m and alpha - 1 for m' / alpha; big^(alpha-1) = m'(big) / alpha. */
  const snh_mask powers = !cx && !cy && x * y > SNH_R(0);
  const snh_mask x_big = fabs(x) >= fabs(y);
  const real big = x_big ? fabs(x) : fabs(y), small = x_big ? fabs(y) : fabs(x);
  const real big_dm = x_big ? dmx : dmy, al = SNH_R(alpha);
  const real log_r = log1p((small - big) / big), e = expm1(log_r);
  const real power_d0 = big_dm / al * expm1(al * log_r) / e;
  /* m is odd (same value for x, y < 0); m' is even (sign flips). */
  const real sign = x < SNH_R(0) ? SNH_R(-1) : SNH_R(1);
  const real power_d1 = sign * big_dm / big * expm1((al - SNH_R(1)) * log_r) / e;
  /* Opposite signs (|x - y| = |x| + |y|: m(x) - m(y) adds two terms of one
   * sign) or the two sides of tau, where x and y closer than sqrt(eps) tau
   * take the mean derivative (error below sqrt(eps) relative). */
  const snh_mask close = x * y > SNH_R(0) && fabs(x - y) <= sqrt(SNH_EPS) * SNH_NONLINEAR_TAU;
  const real plain_d0 = close ? SNH_R(0.5) * (dmx + dmy) : (mx - my) / (x - y);
  const real plain_d1 = close ? SNH_R(0.5) * (ddmx + ddmy) : (dmx - dmy) / (x - y);
  *d0 = same ? dmx : (cubics ? cubic_d0 : (powers ? power_d0 : plain_d0));
  *d1 = same ? ddmx : (cubics ? cubic_d1 : (powers ? power_d1 : plain_d1));
}

SNH_FN nonlinear_stretches nonlinear_stretches_of(vec3 sigma, scalar_real alpha) {
  nonlinear_stretches n;
  n.alpha = alpha;
  for (int i = 0; i < 3; ++i) nonlinear_map(sigma.a[i], alpha, &n.m.a[i], &n.dm.a[i], &n.ddm.a[i]);
  for (int k = 0; k < 3; ++k) {
    const int i = k == 0 ? 1 : 0, j = k == 2 ? 1 : 2; /* principal_pair_i, _j */
    if (alpha == 1) {
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
