/* Co-rotational elasticity (Smith et al. 2018, Eq. 3; Chen and Barbic 2024, Table 1,
 * "Linear Corotational"): psi = mu ||F - R||^2 + lambda/2 tr^2(S - I), in
 * principal stretches mu sum (sigma_i - 1)^2 + lambda/2 (sum sigma_i - 3)^2
 * with the rotation-variant SVD (R = U V^T). Lame parameters (mu, lambda).
 * Hessian in the principal-stretch eigensystem (sec. 4.5, Teran et al. 2005):
 * block 2 mu I + lambda 1 1^T; flip 2 mu; twist (psi_i + psi_j) / (sigma_i +
 * sigma_j) = 2 mu + (2 lambda T - 4 mu) / (sigma_i + sigma_j), T = sum sigma - 3,
 * singular where sigma_i + sigma_j -> 0 (the model's known degeneracy): the
 * sum is floored at SNH_COROTATIONAL_MIN_SUM. */
#ifndef SNH_COROTATIONAL_H
#define SNH_COROTATIONAL_H

#include "materials/stretch_invariants.h"

SNH_FN real corotational_energy_sigma(vec3 s, real mu, real lambda) {
  const real t = s.a[0] + s.a[1] + s.a[2] - SNH_R(3);
  real e = SNH_R(0);
  for (int i = 0; i < 3; ++i) e += (s.a[i] - SNH_R(1)) * (s.a[i] - SNH_R(1));
  return mu * e + SNH_R(0.5) * lambda * t * t;
}

SNH_FN vec3 corotational_gradient(vec3 s, real mu, real lambda) {
  const real t = s.a[0] + s.a[1] + s.a[2] - SNH_R(3);
  vec3 g;
  for (int i = 0; i < 3; ++i) g.a[i] = SNH_R(2) * mu * (s.a[i] - SNH_R(1)) + lambda * t;
  return g;
}

SNH_FN principal_hessian corotational_principal_hessian(mat3 u, vec3 s, mat3 v, real mu, real lambda) {
  principal_hessian h;
  h.u = u;
  h.sigma = s;
  h.v = v;
  const real t = s.a[0] + s.a[1] + s.a[2] - SNH_R(3);
  h.block.a[0] = h.block.a[3] = h.block.a[5] = SNH_R(2) * mu + lambda;
  h.block.a[1] = h.block.a[2] = h.block.a[4] = lambda;
  for (int k = 0; k < 3; ++k) {
    const int i = principal_pair_i(k), j = principal_pair_j(k);
    const real sum = fmax(s.a[i] + s.a[j], SNH_COROTATIONAL_MIN_SUM);
    h.twist.a[k] = SNH_R(2) * mu + (SNH_R(2) * lambda * t - SNH_R(4) * mu) / sum;
    h.flip.a[k] = SNH_R(2) * mu;
  }
  return h;
}

/* Chen and Barbic 2024, Eq. 19, parts with unit Lame moduli: lambda part (I1 - 3)^2 / 2;
 * mu part sum (s_i - 1)^2 = (I2 - 3) - 2 (I1 - 3) (shared by the fixed
 * co-rotational model). */
SNH_FN stretch_terms corotational_lambda_part(stretch_invariants v) { return stretch_half_square(0, v.i1 - SNH_R(3)); }

SNH_FN stretch_terms corotational_mu_part(stretch_invariants v) {
  stretch_terms t = stretch_terms_zero();
  t.value = (v.i2 - SNH_R(3)) - SNH_R(2) * (v.i1 - SNH_R(3));
  t.d[0] = SNH_R(-2);
  t.d[1] = SNH_R(1);
  return t;
}

#endif /* SNH_COROTATIONAL_H */
