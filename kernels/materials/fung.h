/* Stabilized Fung hardening (Smith et al. 2018, sec. 5.3, Eqs. 53-56):
 *   psi = mu0/2 (I_C - 3) + lambda/2 (J - alpha)^2 + gamma/2 (exp(mu1 (I_C - 3)) - 1) + c,
 *   alpha = 1 + (mu0 + gamma mu1) / lambda.
 * The extracted text leaves the exponent's factor unclear; this form is the
 * one consistent with the paper's alpha, its PK1 (Eq. 54:
 * (mu0 + gamma mu1 e) F + lambda (J - alpha) dJ/dF) and its
 * eta = 2 gamma mu1^2 e / (lambda (J - alpha)) (Eq. 56). c makes psi(I) = 0.
 * Beyond x = mu1 (I_C - 3) = SNH_FUNG_MAX_EXPONENT the exponential continues
 * as its second-order Taylor polynomial (C2), so that stretches far past any
 * tissue's range stay finite in float and double instead of overflowing. */
#ifndef SNH_FUNG_H
#define SNH_FUNG_H

#include "materials/invariant_hessian.h"

#define SNH_FUNG_MAX_EXPONENT SNH_R(30)

/* exp(x) capped as above, with its first and second derivatives. */
SNH_FN void fung_exp(real x, real* e, real* de, real* dde) {
  /* Both sides computed and selected (lanes, snh_portable.h); exp of the
   * capped exponent is exp(x) below the cap and the cap's value above. */
  const snh_mask below = x <= SNH_FUNG_MAX_EXPONENT;
  const real ex = exp(below ? x : SNH_FUNG_MAX_EXPONENT), d = x - SNH_FUNG_MAX_EXPONENT;
  *e = below ? ex : ex * (SNH_R(1) + d + SNH_R(0.5) * d * d);
  *de = below ? ex : ex * (SNH_R(1) + d);
  *dde = ex;
}

SNH_FN real fung_alpha(real mu0, real lambda, real gamma, real mu1) { return SNH_R(1) + (mu0 + gamma * mu1) / lambda; }

SNH_FN invariant_terms fung_terms(real ic, real j, real mu0, real lambda, real gamma, real mu1) {
  real e, de, dde;
  fung_exp(mu1 * (ic - SNH_R(3)), &e, &de, &dde);
  invariant_terms t;
  t.gamma_i = mu0 + gamma * mu1 * de;
  t.gamma_f = SNH_R(2) * gamma * mu1 * mu1 * dde;
  t.gamma_g = lambda;
  t.gamma_h = lambda * (j - fung_alpha(mu0, lambda, gamma, mu1));
  return t;
}

SNH_FN real fung_energy_exp(real x) {
  real e, de, dde;
  fung_exp(x, &e, &de, &dde);
  return e;
}

/* The I_C terms, zero at rest. */
SNH_FN real fung_ic_energy(real ic, real mu0, real gamma, real mu1) {
  return SNH_R(0.5) * mu0 * (ic - SNH_R(3)) + SNH_R(0.5) * gamma * (fung_energy_exp(mu1 * (ic - SNH_R(3))) - SNH_R(1));
}

SNH_FN real fung_energy(mat3 f, real mu0, real lambda, real gamma, real mu1) {
  const real ic = mat3_ddot(f, f), j = mat3_det(f), alpha = fung_alpha(mu0, lambda, gamma, mu1);
  return fung_ic_energy(ic, mu0, gamma, mu1) + SNH_R(0.5) * lambda * (j - SNH_R(1)) * (j + SNH_R(1) - SNH_R(2) * alpha);
}

#endif /* SNH_FUNG_H */
