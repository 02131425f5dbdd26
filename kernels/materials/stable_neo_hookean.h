/* Stable Neo-Hookean (Smith, de Goes, Kim 2018, "Stable Neo-Hookean Flesh
 * Simulation", ACM TOG 37(2)).
 *
 * With the origin barrier (barrier = 1, Eq. 14):
 *   psi = mu/2 (I_C - 3) + lambda/2 (J - alpha)^2 - mu/2 log(I_C + 1) + c,
 *   alpha = 1 + 3 mu / (4 lambda)            (rest stability, sec. 3.2)
 * Without it (barrier = 0, Eq. 13 with the App. D eigensystem, nu >= 0.4):
 *   psi = mu/2 (I_C - 3) + lambda/2 (J - alpha)^2 + c,  alpha = 1 + mu / lambda.
 * The constant c makes psi(I) = 0; it changes no force or Hessian.
 * I_C = ||F||_F^2, J = det F. mu and lambda here are the energy's own
 * parameters; their relation to the Lame moduli (sec. 3.4) is on the host. */
#ifndef SNH_STABLE_NEO_HOOKEAN_H
#define SNH_STABLE_NEO_HOOKEAN_H

#include "materials/invariant_hessian.h"

/* alpha of Eq. 14 (barrier) or Eq. 13 (no barrier): makes P(I) = 0. */
SNH_FN real snh_alpha(real mu, real lambda, int barrier) {
  return barrier ? SNH_R(1) + SNH_R(0.75) * mu / lambda : SNH_R(1) + mu / lambda;
}

/* The I_C terms, mu/2 (I_C - 3) - mu/2 log((I_C + 1) / 4), zero at rest. */
SNH_FN real snh_ic_energy(real ic, real mu, int barrier) {
  real psi = SNH_R(0.5) * mu * (ic - SNH_R(3));
  if (barrier) psi -= SNH_R(0.5) * mu * log((ic + SNH_R(1)) / SNH_R(4));
  return psi;
}

SNH_FN real snh_energy(mat3 f, real mu, real lambda, int barrier) {
  const real ic = mat3_ddot(f, f);
  const real j = mat3_det(f);
  const real alpha = snh_alpha(mu, lambda, barrier);
  /* (J - alpha)^2 - (1 - alpha)^2 factored so that psi(I) is exactly 0. */
  return snh_ic_energy(ic, mu, barrier) + SNH_R(0.5) * lambda * (j - SNH_R(1)) * (j + SNH_R(1) - SNH_R(2) * alpha);
}

/* The invariant terms of Eq. 52 for this energy (sec. 4.6, App. D):
 * gamma_I = mu_T = mu (1 - 1/(I_C + 1)) (barrier) or mu, gamma_F =
 * 2 mu / (I_C + 1)^2 (barrier) or 0, gamma_G = lambda, gamma_H =
 * lambda (J - alpha). */
SNH_FN invariant_terms snh_invariant_terms(real ic, real j, real mu, real lambda, int barrier) {
  invariant_terms t;
  t.gamma_i = barrier ? mu * (SNH_R(1) - SNH_R(1) / (ic + SNH_R(1))) : mu;
  t.gamma_f = barrier ? SNH_R(2) * mu / ((ic + SNH_R(1)) * (ic + SNH_R(1))) : SNH_R(0);
  t.gamma_g = lambda;
  t.gamma_h = lambda * (j - snh_alpha(mu, lambda, barrier));
  return t;
}

/* PK1, Eq. 18: P = mu (1 - 1/(I_C + 1)) F + lambda (J - alpha) dJ/dF. */
SNH_FN mat3 snh_pk1(mat3 f, real mu, real lambda, int barrier) {
  return invariant_pk1(f, snh_invariant_terms(mat3_ddot(f, f), mat3_det(f), mu, lambda, barrier));
}

/* The Hessian's eigensystem in the SVD frame (sec. 4.6), through the
 * invariant form. The block's characteristic cubic is the rank-two updated
 * cubic of Eqs. 42-43 (App. D: rank-one, Eq. 66) shifted by mu_T and scaled
 * by lambda (J - alpha), Eq. 45. We solve the cubic of the block itself:
 * Eq. 42's coefficients divide by lambda (J - 1) - 3 mu / 4, which is zero
 * at J = alpha, while the block is finite everywhere. Twists and flips,
 * Eqs. 46-48: mu_T +- lambda (J - alpha) sigma_k. Any factorization
 * F = U diag(sigma) V^T with rotations U, V gives the same Hessian
 * (sec. 4.5.1): the sign convention is free. */
SNH_FN principal_hessian snh_principal_hessian_from_svd(mat3 u, vec3 sigma, mat3 v, real mu, real lambda, int barrier) {
  const real s0 = sigma.a[0], s1 = sigma.a[1], s2 = sigma.a[2];
  return invariant_principal_hessian(
      u, sigma, v, snh_invariant_terms(s0 * s0 + s1 * s1 + s2 * s2, s0 * s1 * s2, mu, lambda, barrier));
}

SNH_FN principal_hessian snh_principal_hessian(mat3 f, real mu, real lambda, int barrier) {
  mat3 u, v;
  vec3 sigma;
  svd3_rv(f, &u, &sigma, &v);
  return snh_principal_hessian_from_svd(u, sigma, v, mu, lambda, barrier);
}

#endif /* SNH_STABLE_NEO_HOOKEAN_H */
