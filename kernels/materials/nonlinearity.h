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

#define SNH_NONLINEAR_TAU SNH_R(0.1)

SNH_FN int nonlinear_in_cubic(real x, real alpha) { return alpha < SNH_R(2) && fabs(x) < SNH_NONLINEAR_TAU; }

SNH_FN void nonlinear_cubic(real alpha, real* a, real* b) {
  *a = pow(SNH_NONLINEAR_TAU, alpha - SNH_R(1)) * (SNH_R(3) - alpha) * SNH_R(0.5);
  *b = (alpha - SNH_R(1)) * pow(SNH_NONLINEAR_TAU, alpha - SNH_R(3)) * SNH_R(0.5);
}

/* m(x), m'(x), m''(x). */
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
  *m = sign * pow(ax, alpha);
  *dm = alpha * pow(ax, alpha - SNH_R(1));
  *ddm = sign * alpha * (alpha - SNH_R(1)) * pow(ax, alpha - SNH_R(2));
}

/* Divided difference of m (order 0) or m' (order 1) at x, y. */
SNH_FN real nonlinear_divided(real x, real y, real alpha, int order) {
  if (alpha == SNH_R(1)) return order == 0 ? SNH_R(1) : SNH_R(0);
  real mx, dmx, ddmx, my, dmy, ddmy;
  nonlinear_map(x, alpha, &mx, &dmx, &ddmx);
  if (x == y) return order == 0 ? dmx : ddmx;
  const int cx = nonlinear_in_cubic(x, alpha), cy = nonlinear_in_cubic(y, alpha);
  if (cx && cy) {
    real a, b;
    nonlinear_cubic(alpha, &a, &b);
    return order == 0 ? a + b * (x * x + x * y + y * y) : SNH_R(3) * b * (x + y);
  }
  if (!cx && !cy && x * y > SNH_R(0)) {
    /* Both powers, one sign: with big >= small > 0, r = small / big,
     * (big^p - small^p) / (big - small) = big^(p-1) expm1(p log r) / expm1(log r). */
    const real ax = fabs(x), ay = fabs(y);
    const real big = fmax(ax, ay), small = fmin(ax, ay);
    const real log_r = log1p((small - big) / big);
    const real p = order == 0 ? alpha : alpha - SNH_R(1);
    const real ratio = expm1(p * log_r) / expm1(log_r);
    /* m is odd (same value for x, y < 0); m' is even (sign flips). */
    const real sign = (order == 1 && x < SNH_R(0)) ? SNH_R(-1) : SNH_R(1);
    return order == 0 ? pow(big, alpha - SNH_R(1)) * ratio : sign * alpha * pow(big, alpha - SNH_R(2)) * ratio;
  }
  /* Opposite signs (|x - y| = |x| + |y|: m(x) - m(y) adds two terms of one
   * sign) or the two sides of tau, where x and y closer than sqrt(eps) tau
   * take the mean derivative (error below sqrt(eps) relative). */
  nonlinear_map(y, alpha, &my, &dmy, &ddmy);
  if (x * y > SNH_R(0) && fabs(x - y) <= sqrt(SNH_EPS) * SNH_NONLINEAR_TAU)
    return order == 0 ? SNH_R(0.5) * (dmx + dmy) : SNH_R(0.5) * (ddmx + ddmy);
  return order == 0 ? (mx - my) / (x - y) : (dmx - dmy) / (x - y);
}

#endif /* SNH_NONLINEARITY_H */
