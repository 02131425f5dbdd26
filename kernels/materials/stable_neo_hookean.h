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

#include "materials/principal_hessian.h"

/* alpha of Eq. 14 (barrier) or Eq. 13 (no barrier): makes P(I) = 0. */
SNH_FN real snh_alpha(real mu, real lambda, int barrier) {
  return barrier ? SNH_R(1) + SNH_R(0.75) * mu / lambda : SNH_R(1) + mu / lambda;
}

SNH_FN real snh_energy(mat3 f, real mu, real lambda, int barrier) {
  const real ic = mat3_ddot(f, f);
  const real j = mat3_det(f);
  const real alpha = snh_alpha(mu, lambda, barrier);
  /* (J - alpha)^2 - (1 - alpha)^2 factored so that psi(I) is exactly 0. */
  real psi =
      SNH_R(0.5) * mu * (ic - SNH_R(3)) + SNH_R(0.5) * lambda * (j - SNH_R(1)) * (j + SNH_R(1) - SNH_R(2) * alpha);
  if (barrier) psi -= SNH_R(0.5) * mu * log((ic + SNH_R(1)) / SNH_R(4));
  return psi;
}

/* PK1, Eq. 18: P = mu (1 - 1/(I_C + 1)) F + lambda (J - alpha) dJ/dF. */
SNH_FN mat3 snh_pk1(mat3 f, real mu, real lambda, int barrier) {
  const real ic = mat3_ddot(f, f);
  const real alpha = snh_alpha(mu, lambda, barrier);
  const mat3 g = mat3_cofactor(f);
  const real j = mat3_det(f);
  const real mu_t = barrier ? mu * (SNH_R(1) - SNH_R(1) / (ic + SNH_R(1))) : mu;
  const real vol = lambda * (j - alpha);
  mat3 p;
  for (int i = 0; i < 9; ++i) p.a[i] = mu_t * f.a[i] + vol * g.a[i];
  return p;
}

/* The Hessian's eigensystem in the SVD frame (sec. 4.6).
 * Block: d2 psi / d sigma_i d sigma_j, whose characteristic cubic is the
 * rank-two updated cubic of Eqs. 42-43 (App. D: rank-one, Eq. 66) shifted by
 * mu_T and scaled by lambda (J - alpha), Eq. 45. We solve the cubic of the
 * block itself: Eq. 42's coefficients divide by lambda (J - 1) - 3 mu / 4,
 * which is zero at J = alpha, while the block is finite everywhere.
 *   A_ii = mu_T + 2 b mu sigma_i^2 / (I_C + 1)^2 + lambda (sigma_j sigma_k)^2
 *   A_ij = 2 b mu sigma_i sigma_j / (I_C + 1)^2 + lambda sigma_i sigma_j sigma_k^2
 *          + lambda (J - alpha) sigma_k
 * Twists and flips, Eqs. 46-48: mu_T +- lambda (J - alpha) sigma_k, with
 * mu_T = mu (1 - 1/(I_C + 1)) (barrier) or mu (App. D).
 * Any factorization F = U diag(sigma) V^T with orthogonal U, V gives the same
 * Hessian (sec. 4.5.1): the convention is free. */
SNH_FN principal_hessian snh_principal_hessian_from_svd(mat3 u, vec3 sigma, mat3 v, real mu, real lambda, int barrier) {
  principal_hessian h;
  h.u = u;
  h.sigma = sigma;
  h.v = v;
  const real s0 = h.sigma.a[0], s1 = h.sigma.a[1], s2 = h.sigma.a[2];
  const real ic = s0 * s0 + s1 * s1 + s2 * s2;
  const real j = s0 * s1 * s2;
  const real alpha = snh_alpha(mu, lambda, barrier);
  const real mu_t = barrier ? mu * (SNH_R(1) - SNH_R(1) / (ic + SNH_R(1))) : mu;
  const real bar = barrier ? SNH_R(2) * mu / ((ic + SNH_R(1)) * (ic + SNH_R(1))) : SNH_R(0);
  const real vol = lambda * (j - alpha);
  h.block.a[0] = mu_t + bar * s0 * s0 + lambda * (s1 * s2) * (s1 * s2);
  h.block.a[3] = mu_t + bar * s1 * s1 + lambda * (s0 * s2) * (s0 * s2);
  h.block.a[5] = mu_t + bar * s2 * s2 + lambda * (s0 * s1) * (s0 * s1);
  h.block.a[1] = bar * s0 * s1 + lambda * s0 * s1 * s2 * s2 + vol * s2;
  h.block.a[2] = bar * s0 * s2 + lambda * s0 * s2 * s1 * s1 + vol * s1;
  h.block.a[4] = bar * s1 * s2 + lambda * s1 * s2 * s0 * s0 + vol * s0;
  for (int k = 0; k < 3; ++k) {
    h.twist.a[k] = mu_t + vol * h.sigma.a[k];
    h.flip.a[k] = mu_t - vol * h.sigma.a[k];
  }
  return h;
}

SNH_FN principal_hessian snh_principal_hessian(mat3 f, real mu, real lambda, int barrier) {
  mat3 u, v;
  vec3 sigma;
  svd3_rv(f, &u, &sigma, &v);
  return snh_principal_hessian_from_svd(u, sigma, v, mu, lambda, barrier);
}

#endif /* SNH_STABLE_NEO_HOOKEAN_H */
