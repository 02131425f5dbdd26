/* Energies written as separable functions of the principal-stretch
 * invariants (Smith, de Goes, Kim 2019 use the same I1..I3):
 *   I1 = sum s_i,  I2 = sum s_i^2 (= I_C),  I3 = s0 s1 s2 (= J),  I4 = sum s_i^4,
 *   phi(s) = sum_a phi_a(I_a).
 * A material part (Chen and Barbic 2024, Eq. 19: the lambda_Lame or mu_Lame part of a
 * model) fills phi_a', phi_a'' per invariant, and this file gives its
 * gradient, its 3x3 Hessian block in s and the twist and flip eigenvalues of
 * each pair (i, j), k the third axis, in closed form:
 *   g_i   = phi1' + 2 phi2' s_i + phi3' s_j s_k + 4 phi4' s_i^3,
 *   twist = (g_i + g_j) / (s_i + s_j)
 *         = 2 phi1' / (s_i + s_j) + 2 phi2' + phi3' s_k + 4 phi4' (s_i^2 - s_i s_j + s_j^2),
 *   flip  = (g_i - g_j) / (s_i - s_j)
 *         = 2 phi2' - phi3' s_k + 4 phi4' (s_i^2 + s_i s_j + s_j^2).
 * The only singular term is I1's twist (the co-rotational degeneracy at
 * s_i + s_j = 0), floored as in corotational.h. */
#ifndef SNH_STRETCH_INVARIANTS_H
#define SNH_STRETCH_INVARIANTS_H

#include "materials/principal_hessian.h"

/* Floor of s_i + s_j in twists with an I1 term (co-rotational models). */
#define SNH_COROTATIONAL_MIN_SUM SNH_R(1e-6)

typedef struct {
  real value; /* sum_a phi_a(I_a) */
  real d[4];  /* phi_a'(I_a), a = I1..I4 */
  real dd[4]; /* phi_a''(I_a) */
} stretch_terms;

typedef struct {
  real i1, i2, i3, i4;
} stretch_invariants;

SNH_FN stretch_invariants stretch_invariants_of(vec3 s) {
  stretch_invariants v;
  v.i1 = s.a[0] + s.a[1] + s.a[2];
  v.i2 = s.a[0] * s.a[0] + s.a[1] * s.a[1] + s.a[2] * s.a[2];
  v.i3 = s.a[0] * s.a[1] * s.a[2];
  v.i4 = s.a[0] * s.a[0] * s.a[0] * s.a[0] + s.a[1] * s.a[1] * s.a[1] * s.a[1] + s.a[2] * s.a[2] * s.a[2] * s.a[2];
  return v;
}

SNH_FN stretch_terms stretch_terms_zero(void) {
  stretch_terms t;
  t.value = SNH_R(0);
  for (int a = 0; a < 4; ++a) t.d[a] = t.dd[a] = SNH_R(0);
  return t;
}

SNH_FN vec3 stretch_gradient(const stretch_terms* t, vec3 s) {
  vec3 g;
  for (int i = 0; i < 3; ++i) {
    const real si = s.a[i], others = s.a[(i + 1) % 3] * s.a[(i + 2) % 3];
    g.a[i] = t->d[0] + SNH_R(2) * t->d[1] * si + t->d[2] * others + SNH_R(4) * t->d[3] * si * si * si;
  }
  return g;
}

/* d2 phi / d s_i d s_j, packed as sym3 (00, 01, 02, 11, 12, 22). */
SNH_FN sym3 stretch_block(const stretch_terms* t, vec3 s) {
  real di[3][4]; /* dI_a / ds_i */
  for (int i = 0; i < 3; ++i) {
    di[i][0] = SNH_R(1);
    di[i][1] = SNH_R(2) * s.a[i];
    di[i][2] = s.a[(i + 1) % 3] * s.a[(i + 2) % 3];
    di[i][3] = SNH_R(4) * s.a[i] * s.a[i] * s.a[i];
  }
  sym3 b;
  int n = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      real h = SNH_R(0);
      for (int a = 0; a < 4; ++a) h += t->dd[a] * di[i][a] * di[j][a];
      if (i == j)
        h += SNH_R(2) * t->d[1] + SNH_R(12) * t->d[3] * s.a[i] * s.a[i];
      else
        h += t->d[2] * s.a[3 - i - j];
      b.a[n++] = h;
    }
  return b;
}

SNH_FN real stretch_twist(const stretch_terms* t, vec3 s, int k) {
  const int i = principal_pair_i(k), j = principal_pair_j(k);
  const real si = s.a[i], sj = s.a[j];
  return SNH_R(2) * t->d[0] / fmax(si + sj, SNH_COROTATIONAL_MIN_SUM) + SNH_R(2) * t->d[1] + t->d[2] * s.a[k] +
         SNH_R(4) * t->d[3] * (si * si - si * sj + sj * sj);
}

SNH_FN real stretch_flip(const stretch_terms* t, vec3 s, int k) {
  const int i = principal_pair_i(k), j = principal_pair_j(k);
  const real si = s.a[i], sj = s.a[j];
  return SNH_R(2) * t->d[1] - t->d[2] * s.a[k] + SNH_R(4) * t->d[3] * (si * si + si * sj + sj * sj);
}

/* d^2 / 2 with d = I_a - c: a volume term quadratic in one invariant. */
SNH_FN stretch_terms stretch_half_square(int a, real d) {
  stretch_terms t = stretch_terms_zero();
  t.value = SNH_R(0.5) * d * d;
  t.d[a] = d;
  t.dd[a] = SNH_R(1);
  return t;
}

/* (J - 1)^2 / 2: the lambda part (unit lambda_Lame) of every model whose
 * volume term is quadratic in J (Stable Neo-Hookean and its Fung and
 * Arruda-Boyce extensions, fixed co-rotational). */
SNH_FN stretch_terms stretch_j_quadratic_part(stretch_invariants v) { return stretch_half_square(2, v.i3 - SNH_R(1)); }

#endif /* SNH_STRETCH_INVARIANTS_H */
