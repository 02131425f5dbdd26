/* One entry point for every material: energy, PK1 and the principal-stretch
 * eigensystem of its Hessian, for model ids matching snh::MaterialModel.
 * Kernels pass the build-time SNH_MODEL and SNH_BARRIER, so the compiler
 * keeps only that model's code; the host reference passes them at run time.
 * Parameters: mu, lambda (the model's own), c0, c1 (model-specific: Fung
 * gamma, mu1; Arruda-Boyce beta1, beta2; StVK kappa; Neo-Hookean J0). */
#ifndef SNH_MATERIAL_H
#define SNH_MATERIAL_H

#include "materials/arruda_boyce.h"
#include "materials/corotational.h"
#include "materials/fixed_corotational.h"
#include "materials/fung.h"
#include "materials/neohookean.h"
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
  real mu, lambda, c0, c1;
} material_params;

SNH_FN material_params material_make(real mu, real lambda, real c0, real c1) {
  material_params m;
  m.mu = mu;
  m.lambda = lambda;
  m.c0 = c0;
  m.c1 = c1;
  return m;
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

SNH_FN real material_energy(int model, int barrier, mat3 f, material_params m) {
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
