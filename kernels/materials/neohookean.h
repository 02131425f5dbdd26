/* The standard Neo-Hookean energy (Smith et al. 2018, Eq. 5; Chen and Barbic 2024, Table 1):
 *   psi = mu/2 (I_C - 3) - mu log J + lambda/2 (log J)^2,
 * undefined for J <= 0. Inversion handling, as its literature extends it:
 * below J0 > 0, log J is replaced by its second-order Taylor expansion at J0,
 *   l(J) = log J0 + (J - J0)/J0 - (J - J0)^2 / (2 J0^2),
 * which is C2 at J0, defined for every J and keeps pushing inverted elements
 * back (psi grows as J falls). With J0 = 0 there is no handling: J <= 0 gives
 * a non-finite value, which the host reports as an error. */
#ifndef SNH_NEOHOOKEAN_H
#define SNH_NEOHOOKEAN_H

#include "materials/invariant_hessian.h"
#include "materials/stretch_invariants.h"

/* l(J) and its first two derivatives. */
SNH_FN void neohookean_log(real j, real j0, real* l, real* dl, real* ddl) {
  /* Both sides computed and selected (lanes, snh_portable.h). */
  const snh_mask extend = j0 > SNH_R(0) && j < j0;
  const real d = j - j0;
  *l = extend ? log(j0) + d / j0 - d * d / (SNH_R(2) * j0 * j0) : log(j);
  *dl = extend ? SNH_R(1) / j0 - d / (j0 * j0) : SNH_R(1) / j;
  *ddl = extend ? SNH_R(-1) / (j0 * j0) : SNH_R(-1) / (j * j);
}

SNH_FN invariant_terms neohookean_terms(real j, real mu, real lambda, real j0) {
  real l, dl, ddl;
  neohookean_log(j, j0, &l, &dl, &ddl);
  invariant_terms t;
  t.gamma_i = mu;
  t.gamma_f = SNH_R(0);
  t.gamma_g = lambda * dl * dl + (lambda * l - mu) * ddl;
  t.gamma_h = (lambda * l - mu) * dl;
  return t;
}

SNH_FN real neohookean_energy(mat3 f, real mu, real lambda, real j0) {
  real l, dl, ddl;
  neohookean_log(mat3_det(f), j0, &l, &dl, &ddl);
  return SNH_R(0.5) * mu * (mat3_ddot(f, f) - SNH_R(3)) - mu * l + SNH_R(0.5) * lambda * l * l;
}

/* Chen and Barbic 2024, Eq. 19, parts with unit Lame moduli: lambda part l(J)^2 / 2;
 * mu part (I_C - 3)/2 - l(J). */
SNH_FN stretch_terms neohookean_lambda_part(stretch_invariants v, real j0) {
  stretch_terms t = stretch_terms_zero();
  real l, dl, ddl;
  neohookean_log(v.i3, j0, &l, &dl, &ddl);
  t.value = SNH_R(0.5) * l * l;
  t.d[2] = l * dl;
  t.dd[2] = dl * dl + l * ddl;
  return t;
}

SNH_FN stretch_terms neohookean_mu_part(stretch_invariants v, real j0) {
  stretch_terms t = stretch_terms_zero();
  real l, dl, ddl;
  neohookean_log(v.i3, j0, &l, &dl, &ddl);
  t.value = SNH_R(0.5) * (v.i2 - SNH_R(3)) - l;
  t.d[1] = SNH_R(0.5);
  t.d[2] = -dl;
  t.dd[2] = -ddl;
  return t;
}

#endif /* SNH_NEOHOOKEAN_H */
