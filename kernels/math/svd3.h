/* Rotation-variant SVD of a 3x3 matrix: F = U diag(sigma) V^T with U and V
 * proper rotations and any reflection pushed into the last singular value,
 * sigma0 >= sigma1 >= |sigma2| (Irving et al. 2004; Smith et al. 2018, Eq. 2).
 *
 * Method: one-sided (Hestenes) Jacobi on the columns of F builds V, so
 * B = F V has orthogonal columns without ever forming F^T F (which would
 * square the condition number and lose small singular values in float). The
 * columns are sorted by length, then a Givens QR of B gives U = Q and
 * sigma = diag(R); Givens rotations keep R00, R11 >= 0, so the sign of det F
 * lands in sigma2. Robust for repeated, zero and negative singular values;
 * a non-finite F terminates after the fixed sweep budget. */
#ifndef SNH_SVD3_H
#define SNH_SVD3_H

#include "math/mat3.h"

#define SNH_SVD_MAX_SWEEPS 12

/* Rotate columns p and q of m by (c, s): [m_p m_q] <- [m_p m_q] [c s; -s c]. */
SNH_FN void svd3_rotate_columns(mat3* m, int p, int q, real c, real s) {
  for (int r = 0; r < 3; ++r) {
    const real mp = M3(*m, r, p), mq = M3(*m, r, q);
    M3(*m, r, p) = c * mp - s * mq;
    M3(*m, r, q) = s * mp + c * mq;
  }
}

SNH_FN real svd3_column_norm2(mat3 m, int c) {
  return M3(m, 0, c) * M3(m, 0, c) + M3(m, 1, c) * M3(m, 1, c) + M3(m, 2, c) * M3(m, 2, c);
}

/* Swap columns p and q and negate the new column q: keeps det unchanged. */
SNH_FN void svd3_swap_columns(mat3* m, int p, int q) {
  for (int r = 0; r < 3; ++r) {
    const real t = M3(*m, r, p);
    M3(*m, r, p) = M3(*m, r, q);
    M3(*m, r, q) = -t;
  }
}

/* Givens rotation G (acting on rows p, q) that zeroes b = B(q, col) against
 * a = B(p, col); returns c, s with r = c a + s b >= 0. */
SNH_FN void svd3_givens(real a, real b, real* c, real* s) {
  const real r = sqrt(a * a + b * b);
  if (r > SNH_R(0)) {
    *c = a / r;
    *s = b / r;
  } else {
    *c = SNH_R(1);
    *s = SNH_R(0);
  }
}

/* Apply the Givens rotation to rows p, q of B and accumulate it into Q so
 * that Q R stays equal to the original matrix. */
SNH_FN void svd3_apply_givens(mat3* b, mat3* q, int p, int qq, real c, real s) {
  for (int k = 0; k < 3; ++k) {
    const real bp = M3(*b, p, k), bq = M3(*b, qq, k);
    M3(*b, p, k) = c * bp + s * bq;
    M3(*b, qq, k) = -s * bp + c * bq;
    const real qp = M3(*q, k, p), qq_ = M3(*q, k, qq);
    M3(*q, k, p) = c * qp + s * qq_;
    M3(*q, k, qq) = -s * qp + c * qq_;
  }
}

SNH_FN void svd3_rv(mat3 f, mat3* u, vec3* sigma, mat3* v) {
  mat3 b = f;
  *v = mat3_identity();

  /* One-sided Jacobi: orthogonalize the column pairs of B = F V. */
  for (int sweep = 0; sweep < SNH_SVD_MAX_SWEEPS; ++sweep) {
    int rotated = 0;
    for (int pair = 0; pair < 3; ++pair) {
      const int p = pair == 2 ? 1 : 0;
      const int q = pair == 0 ? 1 : 2;
      const real alpha = svd3_column_norm2(b, p);
      const real beta = svd3_column_norm2(b, q);
      const real gamma = M3(b, 0, p) * M3(b, 0, q) + M3(b, 1, p) * M3(b, 1, q) + M3(b, 2, p) * M3(b, 2, q);
      if (!(fabs(gamma) > SNH_EPS * sqrt(alpha * beta)) || !(fabs(gamma) > SNH_REAL_MIN)) continue;
      /* Rotation angle that zeroes the (p, q) entry of B^T B. */
      const real zeta = (beta - alpha) / (SNH_R(2) * gamma);
      const real t = (zeta >= SNH_R(0) ? SNH_R(1) : SNH_R(-1)) / (fabs(zeta) + sqrt(SNH_R(1) + zeta * zeta));
      const real c = SNH_R(1) / sqrt(SNH_R(1) + t * t);
      const real s = c * t;
      svd3_rotate_columns(&b, p, q, c, s);
      svd3_rotate_columns(v, p, q, c, s);
      rotated = 1;
    }
    if (!rotated) break;
  }

  /* Sort columns by decreasing length; each swap negates one column of both
   * B and V, so V stays a rotation and B = F V still holds. */
  real n0 = svd3_column_norm2(b, 0), n1 = svd3_column_norm2(b, 1), n2 = svd3_column_norm2(b, 2);
  if (n0 < n1) {
    svd3_swap_columns(&b, 0, 1);
    svd3_swap_columns(v, 0, 1);
    const real t = n0;
    n0 = n1;
    n1 = t;
  }
  if (n0 < n2) {
    svd3_swap_columns(&b, 0, 2);
    svd3_swap_columns(v, 0, 2);
    const real t = n0;
    n0 = n2;
    n2 = t;
  }
  if (n1 < n2) {
    svd3_swap_columns(&b, 1, 2);
    svd3_swap_columns(v, 1, 2);
  }

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
