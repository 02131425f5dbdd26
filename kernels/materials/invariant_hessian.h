/* Energies of the invariants I_C = ||F||^2 and J = det F only (Smith et al.
 * 2018, sec. 5.3, Eq. 52): the Hessian has the form
 *   gamma_I I + gamma_F f f^T + gamma_G g g^T + gamma_H H_J,
 * gamma_I = 2 dpsi/dI_C, gamma_F = 4 d2psi/dI_C^2, gamma_G = d2psi/dJ^2,
 * gamma_H = dpsi/dJ (no mixed I_C-J term in the models here), and its
 * eigensystem in the SVD frame: the 3x3 block gamma_I I + gamma_F s s^T +
 * gamma_G g g^T + gamma_H H3 (s = sigma, g_i = sigma_j sigma_k, H3 the
 * off-diagonal sigma_k), twists gamma_I + gamma_H sigma_k and flips
 * gamma_I - gamma_H sigma_k (Eqs. 45-48 with mu_T = gamma_I and
 * lambda (J - alpha) = gamma_H). PK1 = gamma_I F + gamma_H dJ/dF. */
#ifndef SNH_INVARIANT_HESSIAN_H
#define SNH_INVARIANT_HESSIAN_H

#include "materials/principal_hessian.h"

typedef struct {
  real gamma_i, gamma_f, gamma_g, gamma_h;
} invariant_terms;

SNH_FN mat3 invariant_pk1(mat3 f, invariant_terms t) {
  const mat3 g = mat3_cofactor(f);
  mat3 p;
  SNH_UNROLL
  for (int i = 0; i < 9; ++i) p.a[i] = t.gamma_i * f.a[i] + t.gamma_h * g.a[i];
  return p;
}

SNH_FN principal_hessian invariant_principal_hessian(mat3 u, vec3 sigma, mat3 v, invariant_terms t) {
  principal_hessian h;
  h.u = u;
  h.sigma = sigma;
  h.v = v;
  const real s0 = sigma.a[0], s1 = sigma.a[1], s2 = sigma.a[2];
  h.block.a[0] = t.gamma_i + t.gamma_f * s0 * s0 + t.gamma_g * (s1 * s2) * (s1 * s2);
  h.block.a[3] = t.gamma_i + t.gamma_f * s1 * s1 + t.gamma_g * (s0 * s2) * (s0 * s2);
  h.block.a[5] = t.gamma_i + t.gamma_f * s2 * s2 + t.gamma_g * (s0 * s1) * (s0 * s1);
  h.block.a[1] = t.gamma_f * s0 * s1 + t.gamma_g * s0 * s1 * s2 * s2 + t.gamma_h * s2;
  h.block.a[2] = t.gamma_f * s0 * s2 + t.gamma_g * s0 * s2 * s1 * s1 + t.gamma_h * s1;
  h.block.a[4] = t.gamma_f * s1 * s2 + t.gamma_g * s1 * s2 * s0 * s0 + t.gamma_h * s0;
  SNH_UNROLL
  for (int k = 0; k < 3; ++k) {
    h.twist.a[k] = t.gamma_i + t.gamma_h * sigma.a[k];
    h.flip.a[k] = t.gamma_i - t.gamma_h * sigma.a[k];
  }
  return h;
}

#endif /* SNH_INVARIANT_HESSIAN_H */
