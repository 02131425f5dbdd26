/* Stabilized Arruda-Boyce, three-term expansion (Smith et al. 2018, sec.
 * 5.3, Eqs. 57-61):
 *   psi = mu/2 (I_C - 3) + mu beta1/4 (I_C^2 - 9) + mu beta2/6 (I_C^3 - 27)
 *         + lambda/2 (J - alpha)^2 + c,
 *   alpha = 1 + mu/lambda (1 + 3 beta1 + 9 beta2);
 * gamma_I = mu (1 + beta1 I_C + beta2 I_C^2), gamma_F = 2 mu (beta1 + 2 beta2 I_C)
 * (Eqs. 59-61). c makes psi(I) = 0. */
#ifndef SNH_ARRUDA_BOYCE_H
#define SNH_ARRUDA_BOYCE_H

#include "materials/invariant_hessian.h"

SNH_FN real arruda_boyce_alpha(real mu, real lambda, real beta1, real beta2) {
  return SNH_R(1) + mu / lambda * (SNH_R(1) + SNH_R(3) * beta1 + SNH_R(9) * beta2);
}

SNH_FN invariant_terms arruda_boyce_terms(real ic, real j, real mu, real lambda, real beta1, real beta2) {
  invariant_terms t;
  t.gamma_i = mu * (SNH_R(1) + beta1 * ic + beta2 * ic * ic);
  t.gamma_f = SNH_R(2) * mu * (beta1 + SNH_R(2) * beta2 * ic);
  t.gamma_g = lambda;
  t.gamma_h = lambda * (j - arruda_boyce_alpha(mu, lambda, beta1, beta2));
  return t;
}

/* The I_C terms, zero at rest. */
SNH_FN real arruda_boyce_ic_energy(real ic, real mu, real beta1, real beta2) {
  return SNH_R(0.5) * mu * (ic - SNH_R(3)) + SNH_R(0.25) * mu * beta1 * (ic * ic - SNH_R(9)) +
         mu * beta2 / SNH_R(6) * (ic * ic * ic - SNH_R(27));
}

SNH_FN real arruda_boyce_energy(mat3 f, real mu, real lambda, real beta1, real beta2) {
  const real ic = mat3_ddot(f, f), j = mat3_det(f), alpha = arruda_boyce_alpha(mu, lambda, beta1, beta2);
  return arruda_boyce_ic_energy(ic, mu, beta1, beta2) +
         SNH_R(0.5) * lambda * (j - SNH_R(1)) * (j + SNH_R(1) - SNH_R(2) * alpha);
}

#endif /* SNH_ARRUDA_BOYCE_H */
