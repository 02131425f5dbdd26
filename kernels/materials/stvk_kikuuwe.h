/* St. Venant-Kirchhoff (Smith et al. 2018, Eq. 50; Chen and Barbic 2024, Table 1) with
 * the Kikuuwe et al. 2009 compression penalty (Eq. 51):
 *   psi = mu ||E||^2 + lambda/2 tr^2(E) + K(J),  E = (F^T F - I)/2,
 *   K(J) = kappa/12 (1 - J)^3 for J < 1, 0 otherwise.
 * (The extracted Eq. 51 also shows a "6" whose place is unclear: a tet's
 * volume factor in Kikuuwe's edge-based form, we take it to be absorbed in
 * kappa.) In principal stretches: mu/4 sum (sigma_i^2 - 1)^2 +
 * lambda/8 (sum sigma_i^2 - 3)^2 + K(J). Lame parameters (mu, lambda): K is
 * flat to second order at J = 1. Closed-form principal-stretch eigensystem
 * (T2 = sum sigma^2 - 3): flip mu (s_i^2 + s_i s_j + s_j^2 - 1) + lambda T2/2 -
 * K' s_k, twist mu (s_i^2 - s_i s_j + s_j^2 - 1) + lambda T2/2 + K' s_k. */
#ifndef SNH_STVK_KIKUUWE_H
#define SNH_STVK_KIKUUWE_H

#include "materials/stretch_invariants.h"

/* K(J), K'(J), K''(J). */
SNH_FN void kikuuwe_penalty(real j, real kappa, real* k, real* dk, real* ddk) {
  const real c = j < SNH_R(1) ? SNH_R(1) - j : SNH_R(0);
  *k = kappa / SNH_R(12) * c * c * c;
  *dk = -kappa / SNH_R(4) * c * c;
  *ddk = kappa / SNH_R(2) * c;
}

SNH_FN real stvk_kikuuwe_energy_sigma(vec3 s, real mu, real lambda, real kappa) {
  real e = SNH_R(0), t2 = SNH_R(-3);
  for (int i = 0; i < 3; ++i) {
    e += (s.a[i] * s.a[i] - SNH_R(1)) * (s.a[i] * s.a[i] - SNH_R(1));
    t2 += s.a[i] * s.a[i];
  }
  real k, dk, ddk;
  kikuuwe_penalty(s.a[0] * s.a[1] * s.a[2], kappa, &k, &dk, &ddk);
  return SNH_R(0.25) * mu * e + SNH_R(0.125) * lambda * t2 * t2 + k;
}

SNH_FN vec3 stvk_kikuuwe_gradient(vec3 s, real mu, real lambda, real kappa) {
  const real t2 = s.a[0] * s.a[0] + s.a[1] * s.a[1] + s.a[2] * s.a[2] - SNH_R(3);
  real k, dk, ddk;
  kikuuwe_penalty(s.a[0] * s.a[1] * s.a[2], kappa, &k, &dk, &ddk);
  vec3 g;
  for (int i = 0; i < 3; ++i) {
    const int a = (i + 1) % 3, b = (i + 2) % 3;
    g.a[i] = s.a[i] * (mu * (s.a[i] * s.a[i] - SNH_R(1)) + SNH_R(0.5) * lambda * t2) + dk * s.a[a] * s.a[b];
  }
  return g;
}

SNH_FN principal_hessian stvk_kikuuwe_principal_hessian(mat3 u, vec3 s, mat3 v, real mu, real lambda, real kappa) {
  principal_hessian h;
  h.u = u;
  h.sigma = s;
  h.v = v;
  const real s0 = s.a[0], s1 = s.a[1], s2 = s.a[2];
  const real t2 = s0 * s0 + s1 * s1 + s2 * s2 - SNH_R(3);
  real k, dk, ddk;
  kikuuwe_penalty(s0 * s1 * s2, kappa, &k, &dk, &ddk);
  const real lambda_t2 = SNH_R(0.5) * lambda * t2;
  h.block.a[0] = mu * (SNH_R(3) * s0 * s0 - SNH_R(1)) + lambda_t2 + lambda * s0 * s0 + ddk * (s1 * s2) * (s1 * s2);
  h.block.a[3] = mu * (SNH_R(3) * s1 * s1 - SNH_R(1)) + lambda_t2 + lambda * s1 * s1 + ddk * (s0 * s2) * (s0 * s2);
  h.block.a[5] = mu * (SNH_R(3) * s2 * s2 - SNH_R(1)) + lambda_t2 + lambda * s2 * s2 + ddk * (s0 * s1) * (s0 * s1);
  h.block.a[1] = lambda * s0 * s1 + ddk * s0 * s1 * s2 * s2 + dk * s2;
  h.block.a[2] = lambda * s0 * s2 + ddk * s0 * s2 * s1 * s1 + dk * s1;
  h.block.a[4] = lambda * s1 * s2 + ddk * s1 * s2 * s0 * s0 + dk * s0;
  for (int kk = 0; kk < 3; ++kk) {
    const int i = principal_pair_i(kk), j = principal_pair_j(kk);
    const real si = s.a[i], sj = s.a[j];
    h.twist.a[kk] = mu * (si * si - si * sj + sj * sj - SNH_R(1)) + lambda_t2 + dk * s.a[kk];
    h.flip.a[kk] = mu * (si * si + si * sj + sj * sj - SNH_R(1)) + lambda_t2 - dk * s.a[kk];
  }
  return h;
}

/* Chen and Barbic 2024, Eq. 19, parts with unit Lame moduli: lambda part (I2 - 3)^2 / 8;
 * mu part sum (s_i^2 - 1)^2 / 4 = (I4 - 3)/4 - (I2 - 3)/2 plus the Kikuuwe
 * penalty K(J) / mu (kappa is a multiple of mu, see snh::MaterialOptions). */
SNH_FN stretch_terms stvk_kikuuwe_lambda_part(stretch_invariants v) {
  stretch_terms t = stretch_terms_zero();
  const real d = v.i2 - SNH_R(3);
  t.value = SNH_R(0.125) * d * d;
  t.d[1] = SNH_R(0.25) * d;
  t.dd[1] = SNH_R(0.25);
  return t;
}

SNH_FN stretch_terms stvk_kikuuwe_mu_part(stretch_invariants v, real mu, real kappa) {
  stretch_terms t = stretch_terms_zero();
  real k, dk, ddk;
  kikuuwe_penalty(v.i3, kappa / mu, &k, &dk, &ddk);
  t.value = SNH_R(0.25) * (v.i4 - SNH_R(3)) - SNH_R(0.5) * (v.i2 - SNH_R(3)) + k;
  t.d[1] = SNH_R(-0.5);
  t.d[2] = dk;
  t.dd[2] = ddk;
  t.d[3] = SNH_R(0.25);
  return t;
}

#endif /* SNH_STVK_KIKUUWE_H */
