/* The 9x9 Hessian of an isotropic energy psi(F) = psi(sigma) in the frame of
 * the rotation-variant SVD F = U diag(sigma) V^T (Smith et al. 2018, sec. 4.5
 * and 4.6; the structure Teran et al. 2005 describe): one 3x3 block acting on
 * the diagonal of U^T dF V (eigenvectors Q_k = U diag(v_k) V^T, Eqs. 39/44)
 * and, for each pair (i, j) with k the third axis, a twist and a flip
 * eigenvector (Eqs. 35-38 and App. A),
 *   twist_k = (e_i e_j^T - e_j e_i^T) / sqrt(2),  flip_k = (e_i e_j^T + e_j e_i^T) / sqrt(2),
 * mapped by U (.) V^T. A material fills the block and the six scalars; this
 * file projects them to PSD and applies the result to dF without forming a
 * 9x9 matrix: dP = sum_k max(eps_k, 0) <Q_k, dF> Q_k. */
#ifndef SNH_PRINCIPAL_HESSIAN_H
#define SNH_PRINCIPAL_HESSIAN_H

#include "math/eigen_sym3.h"
#include "math/svd3.h"

typedef struct {
  mat3 u;     /* left rotation of the SVD */
  mat3 v;     /* right rotation of the SVD */
  vec3 sigma; /* signed singular values, sigma0 >= sigma1 >= |sigma2| */
  sym3 block; /* d2 psi / d sigma_i d sigma_j (or its PSD projection) */
  vec3 twist; /* twist eigenvalue of pair k: (1,2), (0,2), (0,1) */
  vec3 flip;  /* flip eigenvalue of pair k */
} principal_hessian;

/* Indices (i, j) of pair k: the two axes other than k. */
SNH_FN int principal_pair_i(int k) { return k == 0 ? 1 : 0; }
SNH_FN int principal_pair_j(int k) { return k == 2 ? 1 : 2; }

/* The same system with every eigenvalue clamped at zero: the block is
 * rebuilt as V max(Lambda, 0) V^T from its closed-form eigensystem. */
SNH_FN principal_hessian principal_hessian_project(principal_hessian h) {
  vec3 values;
  mat3 vectors;
  eigen_sym3(h.block, &values, &vectors);
  sym3 b;
  SNH_UNROLL
  for (int i = 0; i < 6; ++i) b.a[i] = SNH_R(0);
  SNH_UNROLL
  for (int e = 0; e < 3; ++e) {
    const real w = fmax(values.a[e], SNH_R(0));
    const real x = M3(vectors, 0, e), y = M3(vectors, 1, e), z = M3(vectors, 2, e);
    b.a[0] += w * x * x;
    b.a[1] += w * x * y;
    b.a[2] += w * x * z;
    b.a[3] += w * y * y;
    b.a[4] += w * y * z;
    b.a[5] += w * z * z;
  }
  h.block = b;
  SNH_UNROLL
  for (int k = 0; k < 3; ++k) {
    h.twist.a[k] = fmax(h.twist.a[k], SNH_R(0));
    h.flip.a[k] = fmax(h.flip.a[k], SNH_R(0));
  }
  return h;
}

/* The action in the SVD's frame: with R = U^T dF V, returns U^T (H : dF) V
 * (the block on R's diagonal, each twist/flip pair on its off-diagonal
 * pair). */
SNH_FN mat3 principal_hessian_rotated_action(const principal_hessian* h, mat3 r) {
  mat3 out = mat3_zero();
  const vec3 d = vec3_make(M3(r, 0, 0), M3(r, 1, 1), M3(r, 2, 2));
  const vec3 bd = sym3_apply(h->block, d);
  M3(out, 0, 0) = bd.a[0];
  M3(out, 1, 1) = bd.a[1];
  M3(out, 2, 2) = bd.a[2];
  SNH_UNROLL
  for (int k = 0; k < 3; ++k) {
    const int i = principal_pair_i(k), j = principal_pair_j(k);
    const real anti = SNH_R(0.5) * h->twist.a[k] * (M3(r, i, j) - M3(r, j, i));
    const real sym = SNH_R(0.5) * h->flip.a[k] * (M3(r, i, j) + M3(r, j, i));
    M3(out, i, j) = sym + anti;
    M3(out, j, i) = sym - anti;
  }
  return out;
}

/* dP = H : dF for the (possibly projected) system h. */
SNH_FN mat3 principal_hessian_action(const principal_hessian* h, mat3 df) {
  const mat3 r = mat3_mul(mat3_tmul(h->u, df), h->v);                             /* U^T dF V */
  return mat3_mult(mat3_mul(h->u, principal_hessian_rotated_action(h, r)), h->v); /* U out V^T */
}

/* All nine eigenpairs of h: values[0..2] from the block (ascending),
 * values[3..5] the twists and values[6..8] the flips of pairs k = 0, 1, 2,
 * as in Eqs. 45-48; vectors[n] is the unit 3x3 eigenvector Q_n. */
SNH_FN void principal_hessian_eigensystem(const principal_hessian* h, real* values, mat3* vectors) {
  vec3 bv;
  mat3 bq;
  eigen_sym3(h->block, &bv, &bq);
  SNH_UNROLL
  for (int e = 0; e < 3; ++e) {
    values[e] = bv.a[e];
    vectors[e] = mat3_udvt(h->u, vec3_make(M3(bq, 0, e), M3(bq, 1, e), M3(bq, 2, e)), h->v);
  }
  const real inv_sqrt2 = SNH_R(0.70710678118654752440084436210484904);
  SNH_UNROLL
  for (int k = 0; k < 3; ++k) {
    const int i = principal_pair_i(k), j = principal_pair_j(k);
    mat3 t = mat3_zero(), f = mat3_zero();
    M3(t, i, j) = inv_sqrt2;
    M3(t, j, i) = -inv_sqrt2;
    M3(f, i, j) = inv_sqrt2;
    M3(f, j, i) = inv_sqrt2;
    values[3 + k] = h->twist.a[k];
    values[6 + k] = h->flip.a[k];
    vectors[3 + k] = mat3_mult(mat3_mul(h->u, t), h->v);
    vectors[6 + k] = mat3_mult(mat3_mul(h->u, f), h->v);
  }
}

#endif /* SNH_PRINCIPAL_HESSIAN_H */
