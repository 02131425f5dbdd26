/* One entry point for every material: energy, PK1 and the principal-stretch
 * eigensystem of its Hessian, for model ids matching snh::MaterialModel.
 * Kernels pass the build-time SNH_MODEL and SNH_BARRIER, so the compiler
 * keeps only that model's code; the host reference and the general kernel
 * pass them at run time.
 * Parameters: mu, lambda (the model's own), c0, c1 (model-specific: Fung
 * gamma, mu1; Arruda-Boyce beta1, beta2; StVK kappa; Neo-Hookean J0).
 *
 * Extensions of Chen and Barbic 2024 (the "general path"): the nonlinearity alpha (Eq. 16)
 * and mixing the lambda_Lame part of one model with the mu_Lame part of
 * another, each with its own alpha (Eqs. 19-20):
 *   psi = lambda_L / a1^2 psi_lambda^A(m(sigma; a1)) + mu_L / a2^2 psi_mu^B(m(sigma; a2)),
 * B = the material's model (its own parameters give lambda_L, mu_L),
 * A = lambda_model with its parameter c2 (Neo-Hookean J0). The parts are
 * separable in the stretch invariants (stretch_invariants.h), the map m is in
 * nonlinearity.h. SNH_NONLINEAR = 0 or 1 fixes the path at build time. */
#ifndef SNH_MATERIAL_H
#define SNH_MATERIAL_H

#include "materials/arruda_boyce.h"
#include "materials/corotational.h"
#include "materials/fixed_corotational.h"
#include "materials/fung.h"
#include "materials/neohookean.h"
#include "materials/nonlinearity.h"
#include "materials/stable_neo_hookean.h"
#include "materials/stvk_kikuuwe.h"

#define SNH_MODEL_SNH 0
#define SNH_MODEL_FUNG 1
#define SNH_MODEL_ARRUDA_BOYCE 2
#define SNH_MODEL_COROTATIONAL 3
#define SNH_MODEL_FIXED_COROTATIONAL 4
#define SNH_MODEL_STVK_KIKUUWE 5
#define SNH_MODEL_NEOHOOKEAN 6

typedef struct {
  scalar_real mu, lambda, c0, c1;
  scalar_real c2;                     /* parameter of the lambda part's model (Neo-Hookean J0) */
  scalar_real alpha_lambda, alpha_mu; /* nonlinearity of each part (Eq. 20); 1: none */
  int lambda_model;                   /* model of the lambda part; -1: the material's own */
} material_params;

SNH_FN material_params material_make_general(scalar_real mu, scalar_real lambda, scalar_real c0, scalar_real c1,
                                             int lambda_model, scalar_real c2, scalar_real alpha_lambda,
                                             scalar_real alpha_mu) {
  material_params m;
  m.mu = mu;
  m.lambda = lambda;
  m.c0 = c0;
  m.c1 = c1;
  m.c2 = c2;
  m.alpha_lambda = alpha_lambda;
  m.alpha_mu = alpha_mu;
  m.lambda_model = lambda_model;
  return m;
}

SNH_FN material_params material_make(scalar_real mu, scalar_real lambda, scalar_real c0, scalar_real c1) {
  return material_make_general(mu, lambda, c0, c1, -1, c0, 1, 1);
}

SNH_FN int material_lambda_model(int model, material_params m) { return m.lambda_model < 0 ? model : m.lambda_model; }

/* Whether the alpha/mixing path is taken (fixed at build time in specialized
 * kernels). */
SNH_FN int material_general(int model, material_params m) {
#if defined(SNH_NONLINEAR) && SNH_NONLINEAR >= 0
  (void)model;
  (void)m;
  return SNH_NONLINEAR;
#else
  return material_lambda_model(model, m) != model || m.alpha_lambda != 1 || m.alpha_mu != 1;
#endif
}

/* Models written in I_C and J; the others in principal stretches. */
SNH_FN int material_is_invariant(int model) {
  return model == SNH_MODEL_SNH || model == SNH_MODEL_FUNG || model == SNH_MODEL_ARRUDA_BOYCE ||
         model == SNH_MODEL_NEOHOOKEAN;
}

SNH_FN invariant_terms material_invariant_terms(int model, int barrier, real ic, real j, material_params m) {
  if (model == SNH_MODEL_FUNG) return fung_terms(ic, j, m.mu, m.lambda, m.c0, m.c1);
  if (model == SNH_MODEL_ARRUDA_BOYCE) return arruda_boyce_terms(ic, j, m.mu, m.lambda, m.c0, m.c1);
  if (model == SNH_MODEL_NEOHOOKEAN) return neohookean_terms(j, m.mu, m.lambda, m.c0);
  return snh_invariant_terms(ic, j, m.mu, m.lambda, barrier);
}

SNH_FN vec3 material_stretch_gradient(int model, vec3 s, material_params m) {
  if (model == SNH_MODEL_COROTATIONAL) return corotational_gradient(s, m.mu, m.lambda);
  if (model == SNH_MODEL_FIXED_COROTATIONAL) return fixed_corotational_gradient(s, m.mu, m.lambda);
  return stvk_kikuuwe_gradient(s, m.mu, m.lambda, m.c0);
}

/* I_C terms of the I_C-J models (zero at rest). */
SNH_FN real material_ic_energy(int model, int barrier, real ic, material_params m) {
  if (model == SNH_MODEL_FUNG) return fung_ic_energy(ic, m.mu, m.c0, m.c1);
  if (model == SNH_MODEL_ARRUDA_BOYCE) return arruda_boyce_ic_energy(ic, m.mu, m.c0, m.c1);
  return snh_ic_energy(ic, m.mu, barrier);
}

/* Small-strain Lame moduli of a model from its own parameters (Chen and Barbic 2024
 * Eqs. 3-4): for psi = f(I_C) + lambda/2 (J - alpha)^2 with P(I) = 0,
 * mu_L = gamma_I(rest) = 2 f'(3) and lambda_L = lambda + gamma_F(rest) - mu_L;
 * the principal-stretch models carry them directly. */
SNH_FN void material_lame(int model, int barrier, material_params m, real* mu_l, real* lambda_l) {
  if (material_is_invariant(model) && model != SNH_MODEL_NEOHOOKEAN) {
    const invariant_terms rest = material_invariant_terms(model, barrier, SNH_R(3), SNH_R(1), m);
    *mu_l = rest.gamma_i;
    *lambda_l = m.lambda + rest.gamma_f - rest.gamma_i;
    return;
  }
  *mu_l = m.mu;
  *lambda_l = m.lambda;
}

/* Chen and Barbic 2024, Eq. 19: the part of unit lambda_Lame of model `model` (c: its
 * Neo-Hookean J0). */
SNH_FN stretch_terms material_lambda_part(int model, stretch_invariants v, real c) {
  if (model == SNH_MODEL_COROTATIONAL) return corotational_lambda_part(v);
  if (model == SNH_MODEL_STVK_KIKUUWE) return stvk_kikuuwe_lambda_part(v);
  if (model == SNH_MODEL_NEOHOOKEAN) return neohookean_lambda_part(v, c);
  return stretch_j_quadratic_part(v);
}

/* The part of unit mu_Lame: (psi - lambda_L psi_lambda) / mu_L. For the I_C-J
 * models, with lambda (alpha - 1) = mu_L:
 *   f(I_C) / mu_L + (1 - gamma_F(rest) / mu_L) (J - 1)^2 / 2 - (J - 1). */
SNH_FN stretch_terms material_mu_part(int model, int barrier, stretch_invariants v, material_params m) {
  if (model == SNH_MODEL_COROTATIONAL || model == SNH_MODEL_FIXED_COROTATIONAL) return corotational_mu_part(v);
  if (model == SNH_MODEL_STVK_KIKUUWE) return stvk_kikuuwe_mu_part(v, m.mu, m.c0);
  if (model == SNH_MODEL_NEOHOOKEAN) return neohookean_mu_part(v, m.c0);
  const invariant_terms rest = material_invariant_terms(model, barrier, SNH_R(3), SNH_R(1), m);
  const invariant_terms here = material_invariant_terms(model, barrier, v.i2, v.i3, m);
  const real inv_mu = SNH_R(1) / rest.gamma_i, q = SNH_R(1) - rest.gamma_f * inv_mu, dj = v.i3 - SNH_R(1);
  stretch_terms t = stretch_terms_zero();
  t.value = material_ic_energy(model, barrier, v.i2, m) * inv_mu + SNH_R(0.5) * q * dj * dj - dj;
  t.d[1] = SNH_R(0.5) * here.gamma_i * inv_mu;
  t.dd[1] = SNH_R(0.25) * here.gamma_f * inv_mu;
  t.d[2] = q * dj - SNH_R(1);
  t.dd[2] = q;
  return t;
}

/* The general path's per-point state: each part's map of the stretches
 * (computed once when the alphas agree) and its scale L / alpha^2 (the Lame
 * moduli computed once). */
typedef struct {
  nonlinear_stretches part[2];
  real scale[2];
} material_stretches;

SNH_FN material_stretches material_stretches_of(int model, int barrier, vec3 sigma, material_params m) {
  material_stretches s;
  s.part[0] = nonlinear_stretches_of(sigma, m.alpha_lambda);
  s.part[1] = m.alpha_mu == m.alpha_lambda ? s.part[0] : nonlinear_stretches_of(sigma, m.alpha_mu);
  real mu_l, lambda_l;
  material_lame(model, barrier, m, &mu_l, &lambda_l);
  s.scale[0] = lambda_l / (m.alpha_lambda * m.alpha_lambda);
  s.scale[1] = mu_l / (m.alpha_mu * m.alpha_mu);
  return s;
}

/* The invariant terms of one part at its mapped stretches s = m(sigma). */
SNH_FN stretch_terms material_part_at(int part, int model, int barrier, const nonlinear_stretches* n,
                                      material_params m) {
  const stretch_invariants v = stretch_invariants_of(n->m);
  return part ? material_mu_part(model, barrier, v, m) : material_lambda_part(material_lambda_model(model, m), v, m.c2);
}

SNH_FN real material_general_energy(int model, int barrier, vec3 sigma, material_params m) {
  const material_stretches ms = material_stretches_of(model, barrier, sigma, m);
  real psi = SNH_R(0);
  for (int part = 0; part < 2; ++part) {
    psi += ms.scale[part] * material_part_at(part, model, barrier, &ms.part[part], m).value;
  }
  return psi;
}

/* Eq. 17: dpsi/dsigma_i = sum over parts of scale g_i(s) m'(sigma_i). */
SNH_FN vec3 material_general_gradient(int model, int barrier, vec3 sigma, material_params m) {
  const material_stretches ms = material_stretches_of(model, barrier, sigma, m);
  vec3 out = vec3_make(SNH_R(0), SNH_R(0), SNH_R(0));
  for (int part = 0; part < 2; ++part) {
    const nonlinear_stretches* n = &ms.part[part];
    const stretch_terms t = material_part_at(part, model, barrier, n, m);
    const vec3 g = stretch_gradient(&t, n->m);
    for (int i = 0; i < 3; ++i) out.a[i] += ms.scale[part] * g.a[i] * n->dm.a[i];
  }
  return out;
}

/* Eq. 18 for the block, H_ij m'_i m'_j + delta_ij g_i m''_i; twists and flips
 * by the chain rule on (g_i +- g_j) / (sigma_i +- sigma_j):
 *   flip  = scale [flip(s) m'_i D[m](sigma_i, sigma_j) + g_j D[m'](sigma_i, sigma_j)]
 *   twist = scale [twist(s) m'_i D[m](sigma_i, -sigma_j) - g_j D[m'](sigma_i, -sigma_j)]
 * (m odd, m' even; D the divided differences of nonlinearity.h). */
SNH_FN principal_hessian material_general_principal_hessian(int model, int barrier, mat3 u, vec3 sigma, mat3 v,
                                                            material_params m) {
  const material_stretches ms = material_stretches_of(model, barrier, sigma, m);
  principal_hessian h;
  h.u = u;
  h.sigma = sigma;
  h.v = v;
  for (int k = 0; k < 6; ++k) h.block.a[k] = SNH_R(0);
  h.twist = h.flip = vec3_make(SNH_R(0), SNH_R(0), SNH_R(0));
  for (int part = 0; part < 2; ++part) {
    const nonlinear_stretches* n = &ms.part[part];
    const stretch_terms t = material_part_at(part, model, barrier, n, m);
    const real scale = ms.scale[part];
    const vec3 g = stretch_gradient(&t, n->m);
    const sym3 b = stretch_block(&t, n->m);
    int idx = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = i; j < 3; ++j, ++idx)
        h.block.a[idx] += scale * (b.a[idx] * n->dm.a[i] * n->dm.a[j] + (i == j ? g.a[i] * n->ddm.a[i] : SNH_R(0)));
    for (int k = 0; k < 3; ++k) {
      const int i = principal_pair_i(k), j = principal_pair_j(k);
      h.flip.a[k] += scale * (stretch_flip(&t, n->m, k) * n->dm.a[i] * n->flip_m.a[k] + g.a[j] * n->flip_dm.a[k]);
      h.twist.a[k] += scale * (stretch_twist(&t, n->m, k) * n->dm.a[i] * n->twist_m.a[k] - g.a[j] * n->twist_dm.a[k]);
    }
  }
  return h;
}

SNH_FN real material_energy(int model, int barrier, mat3 f, material_params m) {
  if (material_general(model, m)) {
    mat3 u, v;
    vec3 s;
    svd3_rv(f, &u, &s, &v);
    return material_general_energy(model, barrier, s, m);
  }
  if (model == SNH_MODEL_SNH) return snh_energy(f, m.mu, m.lambda, barrier);
  if (model == SNH_MODEL_FUNG) return fung_energy(f, m.mu, m.lambda, m.c0, m.c1);
  if (model == SNH_MODEL_ARRUDA_BOYCE) return arruda_boyce_energy(f, m.mu, m.lambda, m.c0, m.c1);
  if (model == SNH_MODEL_NEOHOOKEAN) return neohookean_energy(f, m.mu, m.lambda, m.c0);
  mat3 u, v;
  vec3 s;
  svd3_rv(f, &u, &s, &v);
  if (model == SNH_MODEL_COROTATIONAL) return corotational_energy_sigma(s, m.mu, m.lambda);
  if (model == SNH_MODEL_FIXED_COROTATIONAL) return fixed_corotational_energy_sigma(s, m.mu, m.lambda);
  return stvk_kikuuwe_energy_sigma(s, m.mu, m.lambda, m.c0);
}

SNH_FN mat3 material_pk1(int model, int barrier, mat3 f, material_params m) {
  if (material_general(model, m)) {
    mat3 u, v;
    vec3 s;
    svd3_rv(f, &u, &s, &v);
    return mat3_udvt(u, material_general_gradient(model, barrier, s, m), v);
  }
  if (material_is_invariant(model))
    return invariant_pk1(f, material_invariant_terms(model, barrier, mat3_ddot(f, f), mat3_det(f), m));
  /* P = U diag(dpsi/dsigma) V^T */
  mat3 u, v;
  vec3 s;
  svd3_rv(f, &u, &s, &v);
  return mat3_udvt(u, material_stretch_gradient(model, s, m), v);
}

SNH_FN principal_hessian material_principal_hessian_from_svd(int model, int barrier, mat3 u, vec3 s, mat3 v,
                                                             material_params m) {
  if (material_general(model, m)) return material_general_principal_hessian(model, barrier, u, s, v, m);
  if (material_is_invariant(model)) {
    const real s0 = s.a[0], s1 = s.a[1], s2 = s.a[2];
    return invariant_principal_hessian(
        u, s, v, material_invariant_terms(model, barrier, s0 * s0 + s1 * s1 + s2 * s2, s0 * s1 * s2, m));
  }
  if (model == SNH_MODEL_COROTATIONAL) return corotational_principal_hessian(u, s, v, m.mu, m.lambda);
  if (model == SNH_MODEL_FIXED_COROTATIONAL) return fixed_corotational_principal_hessian(u, s, v, m.mu, m.lambda);
  return stvk_kikuuwe_principal_hessian(u, s, v, m.mu, m.lambda, m.c0);
}

SNH_FN principal_hessian material_principal_hessian(int model, int barrier, mat3 f, material_params m) {
  mat3 u, v;
  vec3 s;
  svd3_rv(f, &u, &s, &v);
  return material_principal_hessian_from_svd(model, barrier, u, s, v, m);
}

#endif /* SNH_MATERIAL_H */
