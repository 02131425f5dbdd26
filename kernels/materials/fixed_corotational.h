/* "Fixed" co-rotational (Stomakhin et al. 2012; Smith et al. 2018, Eq. 49):
 * psi = mu ||F - R||^2 + lambda/2 (J - 1)^2 = mu sum (sigma_i - 1)^2 +
 * lambda/2 (J - 1)^2. Lame parameters (mu, lambda). Principal-stretch
 * eigensystem: block 2 mu I + lambda g g^T + lambda (J - 1) H3 (g_i = sigma_j
 * sigma_k); flip 2 mu - lambda (J - 1) sigma_k; twist 2 mu - 4 mu /
 * (sigma_i + sigma_j) + lambda (J - 1) sigma_k, the sum floored as in
 * corotational.h. */
#ifndef SNH_FIXED_COROTATIONAL_H
#define SNH_FIXED_COROTATIONAL_H

#include "materials/corotational.h"

SNH_FN real fixed_corotational_energy_sigma(vec3 s, real mu, real lambda) {
  const real j = s.a[0] * s.a[1] * s.a[2];
  real e = SNH_R(0);
  for (int i = 0; i < 3; ++i) e += (s.a[i] - SNH_R(1)) * (s.a[i] - SNH_R(1));
  return mu * e + SNH_R(0.5) * lambda * (j - SNH_R(1)) * (j - SNH_R(1));
}

SNH_FN vec3 fixed_corotational_gradient(vec3 s, real mu, real lambda) {
  const real j = s.a[0] * s.a[1] * s.a[2];
  vec3 g;
  g.a[0] = SNH_R(2) * mu * (s.a[0] - SNH_R(1)) + lambda * (j - SNH_R(1)) * s.a[1] * s.a[2];
  g.a[1] = SNH_R(2) * mu * (s.a[1] - SNH_R(1)) + lambda * (j - SNH_R(1)) * s.a[0] * s.a[2];
  g.a[2] = SNH_R(2) * mu * (s.a[2] - SNH_R(1)) + lambda * (j - SNH_R(1)) * s.a[0] * s.a[1];
  return g;
}

SNH_FN principal_hessian fixed_corotational_principal_hessian(mat3 u, vec3 s, mat3 v, real mu, real lambda) {
  principal_hessian h;
  h.u = u;
  h.sigma = s;
  h.v = v;
  const real s0 = s.a[0], s1 = s.a[1], s2 = s.a[2], vol = lambda * (s0 * s1 * s2 - SNH_R(1));
  h.block.a[0] = SNH_R(2) * mu + lambda * (s1 * s2) * (s1 * s2);
  h.block.a[3] = SNH_R(2) * mu + lambda * (s0 * s2) * (s0 * s2);
  h.block.a[5] = SNH_R(2) * mu + lambda * (s0 * s1) * (s0 * s1);
  h.block.a[1] = lambda * s0 * s1 * s2 * s2 + vol * s2;
  h.block.a[2] = lambda * s0 * s2 * s1 * s1 + vol * s1;
  h.block.a[4] = lambda * s1 * s2 * s0 * s0 + vol * s0;
  for (int k = 0; k < 3; ++k) {
    const int i = principal_pair_i(k), j = principal_pair_j(k);
    const real sum = fmax(s.a[i] + s.a[j], SNH_COROTATIONAL_MIN_SUM);
    h.twist.a[k] = SNH_R(2) * mu - SNH_R(4) * mu / sum + vol * s.a[k];
    h.flip.a[k] = SNH_R(2) * mu - vol * s.a[k];
  }
  return h;
}

#endif /* SNH_FIXED_COROTATIONAL_H */
