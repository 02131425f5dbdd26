/* Rotation-variant SVD of a 3x3 matrix: F = U diag(sigma) V^T with U and V
 * proper rotations and any reflection pushed into the last singular value,
 * sigma0 >= sigma1 >= |sigma2| (Irving et al. 2004; Smith et al. 2018, Eq. 2).
 *
 * Method: one-sided (Hestenes) Jacobi on the columns of F builds V, so
 * B = F V has orthogonal columns without ever forming F^T F (which would
 * square the condition number and lose small singular values in float). The
 * columns are sorted by length, then a Givens QR of B gives U = Q and
 * sigma = diag(R); Givens rotations keep R00, R11 >= 0, so the sign of det F
 * lands in sigma2. Robust for repeated, zero and negative singular values.
 *
 * Branch-free, in the spirit of McAdams et al. 2011 ("Computing the Singular
 * Value Decomposition of 3x3 matrices with minimal branching and elementary
 * floating point operations"): a fixed number of cyclic sweeps, a rotation
 * whose pair is already orthogonal becomes the identity by a select instead
 * of a skip, and the sort and the QR's zero guard are selects too, so every
 * work-item runs the same instructions (what pocl's loop vectorizer needs
 * to run across work-items). Sweep counts, measured against the data-dependent loop
 * they replace (stop after a sweep without rotation, at most 12) on 9 x 10^5
 * F per precision (random, nearly rank two, scaled 1e3, repeated, one tiny,
 * reflected with extreme spectra, a zero column, I + 1e-6 X, log-uniform
 * 1e-12..1e2 spectra): the old loop rotated in at most 5 sweeps in double,
 * in float in at most 5 but for a handful (6 to 8), apart from inputs where
 * it cycled at rounding level up to its cap. With 5 sweeps the result equals
 * the old loop's bit for bit on all but 6 of them in double (differences at
 * most 4.4e-16 |F|) and all but 203 in float, those by at most 3e-6 in U, V of nearly
 * repeated tiny singular values, and the worst reconstruction, orthogonality
 * and singular-value errors are the old loop's (tests/test_svd.cpp,
 * FixedSweepsOnExtremeSpectra, keeps them). svd3_jacobi_pair computes each
 * rotation's c and s in closed form (svd3_jacobi_pair) with fewer square
 * roots and divisions: over 10^5 F per family of that test the worst errors
 * moved from reconstruction 1.68e-15, orthogonality 2.51e-15 and singular
 * values 1.04e-15 (double; float 8.5e-7, 1.23e-6, 5.1e-7) to 2.09e-15,
 * 2.71e-15 and 1.2e-15 (float 1.05e-6, 1.37e-6, 5.6e-7), inside the test's
 * bounds; the recompute product measured faster (docs/performance.md, "SVD
 * rotations in closed form"). Where a data-dependent loop costs nothing in
 * vectorization (the host, the lanes programs, GPUs in float), the sweeps
 * stop once converged with the same values (SNH_SVD_EARLY_EXIT below). A
 * non-finite F gives non-finite sigma. */
#ifndef SNH_SVD3_H
#define SNH_SVD3_H

#include "math/mat3.h"

#define SNH_SVD_SWEEPS 5

/* Rotate columns p and q of m by (c, s): [m_p m_q] <- [m_p m_q] [c s; -s c]. */
SNH_FN void svd3_rotate_columns(mat3* m, int p, int q, real c, real s) {
  SNH_UNROLL
  for (int r = 0; r < 3; ++r) {
    const real mp = M3(*m, r, p), mq = M3(*m, r, q);
    M3(*m, r, p) = c * mp - s * mq;
    M3(*m, r, q) = s * mp + c * mq;
  }
}

SNH_FN real svd3_column_norm2(mat3 m, int c) {
  return M3(m, 0, c) * M3(m, 0, c) + M3(m, 1, c) * M3(m, 1, c) + M3(m, 2, c) * M3(m, 2, c);
}

/* When `swap`: swap columns p and q and negate the new column q (keeps det
 * unchanged); else leave them. A blend, not a branch. */
SNH_FN void svd3_swap_columns_if(mat3* m, int p, int q, snh_mask swap) {
  SNH_UNROLL
  for (int r = 0; r < 3; ++r) {
    const real mp = M3(*m, r, p), mq = M3(*m, r, q);
    M3(*m, r, p) = swap ? mq : mp;
    M3(*m, r, q) = swap ? -mp : mq;
  }
}

/* Givens rotation G (acting on rows p, q) that zeroes b = B(q, col) against
 * a = B(p, col); returns c, s with r = c a + s b >= 0 (identity when a = b = 0). */
SNH_FN void svd3_givens(real a, real b, real* c, real* s) {
  const real r = sqrt(a * a + b * b);
  const snh_mask nonzero = r > SNH_R(0);
  const real d = nonzero ? r : SNH_R(1);
  *c = nonzero ? a / d : SNH_R(1);
  *s = nonzero ? b / d : SNH_R(0);
}

/* Apply the Givens rotation to rows p, q of B and accumulate it into Q so
 * that Q R stays equal to the original matrix. */
SNH_FN void svd3_apply_givens(mat3* b, mat3* q, int p, int qq, real c, real s) {
  SNH_UNROLL
  for (int k = 0; k < 3; ++k) {
    const real bp = M3(*b, p, k), bq = M3(*b, qq, k);
    M3(*b, p, k) = c * bp + s * bq;
    M3(*b, qq, k) = -s * bp + c * bq;
    const real qp = M3(*q, k, p), qq_ = M3(*q, k, qq);
    M3(*q, k, p) = c * qp + s * qq_;
    M3(*q, k, qq) = -s * qp + c * qq_;
  }
}

/* Whether the Jacobi rotation of columns p, q of B rotates: |gamma| > eps
 * sqrt(alpha beta) for the pair's [alpha gamma; gamma beta] of B^T B, without
 * the square root: squared, on alpha, beta and gamma scaled by the power of
 * two that brings max(alpha, beta) into [1, 2), so that gamma^2 and alpha
 * beta neither under- nor overflow where it matters (unscaled, float's
 * reconstruction error reached 0.7 on the extreme spectra). */
SNH_FN snh_mask svd3_pair_rotates(real alpha, real beta, real gamma) {
  const real kn = snh_pow2_inverse(fmax(alpha, beta));
  const real an = alpha * kn, bn = beta * kn, gn = gamma * kn;
  return gn * gn > (SNH_EPS * SNH_EPS) * (an * bn) && fabs(gamma) > SNH_REAL_MIN;
}

SNH_FN real svd3_column_dot(mat3 m, int p, int q) {
  return M3(m, 0, p) * M3(m, 0, q) + M3(m, 1, p) * M3(m, 1, q) + M3(m, 2, p) * M3(m, 2, q);
}

/* One Jacobi rotation of columns p, q of B (and V) that zeroes the (p, q)
 * entry of B^T B, [alpha gamma; gamma beta]; the identity when that entry is
 * already negligible. The angle is Rutishauser's, t = sign(zeta) / (|zeta| +
 * sqrt(1 + zeta^2)) with zeta = (beta - alpha) / (2 gamma), taken in closed
 * form: with d = beta - alpha and g = 2 gamma scaled by the power of two k
 * that brings m = max(|d|, |g|) into [1, 2) (d' = k |d|, g' = k |g|: exact,
 * and nothing under- or overflows, as d^2 + g^2 would for singular values
 * below 1e-9.5 in float), r = sqrt(d'^2 + g'^2)
 * and u = d' + r give t = sign(zeta) g' / u and 1 + t^2 = 2 r / u, so
 * c = u / h and s = sign(zeta) g' / h with h = sqrt(2 r u). Two square roots
 * and one division per rotation, all on its chain of dependent operations,
 * where zeta, t, c and the negligibility test took three square roots and
 * three divisions (that chain is what bounds the SVD: docs/performance.md). */
SNH_FN void svd3_jacobi_pair(mat3* b, mat3* v, int p, int q) {
  const real alpha = svd3_column_norm2(*b, p);
  const real beta = svd3_column_norm2(*b, q);
  const real gamma = svd3_column_dot(*b, p, q);
  const snh_mask rotate = svd3_pair_rotates(alpha, beta, gamma);
  const real d = beta - alpha, g = SNH_R(2) * gamma;
  /* Scaled by a power of two (exact): m >= 2 SNH_REAL_MIN is normal where
   * rotating. */
  const real k = snh_pow2_inverse(rotate ? fmax(fabs(d), fabs(g)) : SNH_R(1));
  const real dm = fabs(d) * k, gm = fabs(g) * k;
  const real r = sqrt(dm * dm + gm * gm);
  const real u = dm + r;
  const real inv_h = SNH_R(1) / sqrt(SNH_R(2) * r * u);
  /* sign(zeta), zeta = +-0 counting as positive. */
  const snh_mask positive = d == SNH_R(0) || (d > SNH_R(0)) == (g > SNH_R(0));
  const real c = u * inv_h, s = positive ? gm * inv_h : -(gm * inv_h);
  svd3_rotate_columns(b, p, q, rotate ? c : SNH_R(1), rotate ? s : SNH_R(0));
  svd3_rotate_columns(v, p, q, rotate ? c : SNH_R(1), rotate ? s : SNH_R(0));
}

/* Whether a sweep over B would change it: rotate a pair (as it rotates
 * none, it sees the same B at each pair), or spread a non-finite entry
 * (0 times it is NaN), which the sweeps do for a non-finite F. */
SNH_FN snh_mask svd3_sweep_changes(mat3 b) {
  const real n0 = svd3_column_norm2(b, 0), n1 = svd3_column_norm2(b, 1), n2 = svd3_column_norm2(b, 2);
  return !isfinite(n0 + n1 + n2) || svd3_pair_rotates(n0, n1, svd3_column_dot(b, 0, 1)) ||
         svd3_pair_rotates(n0, n2, svd3_column_dot(b, 0, 2)) || svd3_pair_rotates(n1, n2, svd3_column_dot(b, 1, 2));
}

/* SNH_SVD_EARLY_EXIT = 1: before each sweep from SNH_SVD_EARLY_EXIT_FROM
 * on, stop if it would change nothing (in any lane): it and every later
 * one would see the same B and leave B and V as they are, an identity
 * rotation (c = 1, s = 0) keeping each value (only a zero's sign may
 * differ: -0 - (-0) is +0), so U, sigma and V are the values of the
 * SNH_SVD_SWEEPS sweeps (tests/svd_sweeps_test.inc). On the host, in the
 * lanes programs (one work-item's 8 or 16 points stop together) and, in
 * float, on GPUs (a warp's, likewise; SNH_GPU); not in pocl's scalar
 * kernels, which it vectorizes across work-items only without
 * data-dependent loops. A test costs less than a sweep but not nothing:
 * the first is before the second sweep in float and before the fourth in
 * double; tests before earlier sweeps measured no faster than no test
 * (docs/performance.md, "SVD early exit"). Double on GPUs is not yet
 * measured. */
#ifndef SNH_SVD_EARLY_EXIT
#if SNH_LANES > 1 || !SNH_IS_OPENCL || (SNH_GPU && !SNH_DOUBLE)
#define SNH_SVD_EARLY_EXIT 1
#else
#define SNH_SVD_EARLY_EXIT 0
#endif
#endif
#ifndef SNH_SVD_EARLY_EXIT_FROM
#define SNH_SVD_EARLY_EXIT_FROM (SNH_DOUBLE ? 3 : 1)
#endif
#if SNH_LANES > 1
#define svd3_any(mask) any(mask)
#else
#define svd3_any(mask) ((mask) != 0)
#endif

SNH_FN_LARGE void svd3_rv(mat3 f, mat3* u, vec3* sigma, mat3* v) {
  mat3 b = f;
  *v = mat3_identity();

  /* One-sided Jacobi: orthogonalize the column pairs of B = F V. */
  SNH_UNROLL
  for (int sweep = 0; sweep < SNH_SVD_SWEEPS; ++sweep) {
#if SNH_SVD_EARLY_EXIT
    if (sweep >= SNH_SVD_EARLY_EXIT_FROM && !svd3_any(svd3_sweep_changes(b))) break;
#endif
    svd3_jacobi_pair(&b, v, 0, 1);
    svd3_jacobi_pair(&b, v, 0, 2);
    svd3_jacobi_pair(&b, v, 1, 2);
  }

  /* Sort columns by decreasing length; each swap negates one column of both
   * B and V, so V stays a rotation and B = F V still holds. */
  real n0 = svd3_column_norm2(b, 0), n1 = svd3_column_norm2(b, 1), n2 = svd3_column_norm2(b, 2);
  const snh_mask swap01 = n0 < n1;
  svd3_swap_columns_if(&b, 0, 1, swap01);
  svd3_swap_columns_if(v, 0, 1, swap01);
  {
    const real t = n0;
    n0 = swap01 ? n1 : n0;
    n1 = swap01 ? t : n1;
  }
  const snh_mask swap02 = n0 < n2;
  svd3_swap_columns_if(&b, 0, 2, swap02);
  svd3_swap_columns_if(v, 0, 2, swap02);
  n2 = swap02 ? n0 : n2;
  const snh_mask swap12 = n1 < n2;
  svd3_swap_columns_if(&b, 1, 2, swap12);
  svd3_swap_columns_if(v, 1, 2, swap12);

  /* Givens QR of B: zero (1,0), (2,0), (2,1). */
  *u = mat3_identity();
  real c, s;
  svd3_givens(M3(b, 0, 0), M3(b, 1, 0), &c, &s);
  svd3_apply_givens(&b, u, 0, 1, c, s);
  svd3_givens(M3(b, 0, 0), M3(b, 2, 0), &c, &s);
  svd3_apply_givens(&b, u, 0, 2, c, s);
  svd3_givens(M3(b, 1, 1), M3(b, 2, 1), &c, &s);
  svd3_apply_givens(&b, u, 1, 2, c, s);

  sigma->a[0] = M3(b, 0, 0);
  sigma->a[1] = M3(b, 1, 1);
  sigma->a[2] = M3(b, 2, 2);
}

#endif /* SNH_SVD3_H */
