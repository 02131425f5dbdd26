/* Closed-form eigensystem of a symmetric 3x3 matrix.
 *
 * Eigenvalues: the roots of the characteristic cubic det(A - e I) = 0 in
 * trigonometric form after shifting by tr(A)/3 and scaling to unit spread,
 * so a repeated root never divides by zero (cos(3 theta) is clamped); the
 * most separated root by Newton's method on that normalized cubic.
 * Eigenvectors: the most separated eigenvalue's vector from the largest cross
 * product of two rows of A - e I, as in the robust non-iterative scheme of
 * D. Eberly ("A Robust Eigensolver for 3x3 Symmetric Matrices", Geometric
 * Tools, 2014); the other two from one exact Jacobi rotation of A restricted
 * to the orthogonal complement. Eigenvalues come out ascending; eigenvectors are orthonormal
 * columns of `vectors` even when eigenvalues coincide. */
#ifndef SNH_EIGEN_SYM3_H
#define SNH_EIGEN_SYM3_H

#include "math/mat3.h"

/* Newton steps for the isolated root of the characteristic cubic (see
 * eigen_sym3): converged to rounding from the fixed start after 6 (double)
 * or 5 (float). */
#if SNH_DOUBLE
#define SNH_EIGEN_NEWTON_STEPS 6
#else
#define SNH_EIGEN_NEWTON_STEPS 5
#endif

/* Symmetric 3x3 packed as (a00, a01, a02, a11, a12, a22). */
typedef struct {
  real a[6];
} sym3;

SNH_FN vec3 vec3_make(real x, real y, real z) {
  vec3 v;
  v.a[0] = x;
  v.a[1] = y;
  v.a[2] = z;
  return v;
}

SNH_FN vec3 vec3_cross(vec3 x, vec3 y) {
  return vec3_make(x.a[1] * y.a[2] - x.a[2] * y.a[1], x.a[2] * y.a[0] - x.a[0] * y.a[2],
                   x.a[0] * y.a[1] - x.a[1] * y.a[0]);
}

SNH_FN real vec3_dot(vec3 x, vec3 y) { return x.a[0] * y.a[0] + x.a[1] * y.a[1] + x.a[2] * y.a[2]; }

SNH_FN vec3 vec3_scale(vec3 x, real s) { return vec3_make(s * x.a[0], s * x.a[1], s * x.a[2]); }

SNH_FN vec3 sym3_apply(sym3 m, vec3 x) {
  return vec3_make(m.a[0] * x.a[0] + m.a[1] * x.a[1] + m.a[2] * x.a[2],
                   m.a[1] * x.a[0] + m.a[3] * x.a[1] + m.a[4] * x.a[2],
                   m.a[2] * x.a[0] + m.a[4] * x.a[1] + m.a[5] * x.a[2]);
}

/* Unit eigenvector for eigenvalue e, assumed simple and the most separated:
 * the largest of the three row cross products, normalized; (1, 0, 0) when all
 * vanish. Chosen by selects, not branches (see eigen_sym3). */
SNH_FN vec3 eigen_sym3_vector_isolated(sym3 m, real e) {
  const vec3 r0 = vec3_make(m.a[0] - e, m.a[1], m.a[2]);
  const vec3 r1 = vec3_make(m.a[1], m.a[3] - e, m.a[4]);
  const vec3 r2 = vec3_make(m.a[2], m.a[4], m.a[5] - e);
  const vec3 c01 = vec3_cross(r0, r1), c02 = vec3_cross(r0, r2), c12 = vec3_cross(r1, r2);
  const real d01 = vec3_dot(c01, c01), d02 = vec3_dot(c02, c02), d12 = vec3_dot(c12, c12);
  const snh_mask use01 = d01 >= d02 && d01 >= d12 && d01 > SNH_R(0);
  const snh_mask use02 = !use01 && d02 >= d12 && d02 > SNH_R(0);
  const snh_mask use12 = !use01 && !use02 && d12 > SNH_R(0);
  const real d = use01 ? d01 : (use02 ? d02 : (use12 ? d12 : SNH_R(1)));
  const real inv = SNH_R(1) / sqrt(d);
  vec3 out;
  SNH_UNROLL
  for (int i = 0; i < 3; ++i)
    out.a[i] =
        use01 ? c01.a[i] * inv : (use02 ? c02.a[i] * inv : (use12 ? c12.a[i] * inv : (i == 0 ? SNH_R(1) : SNH_R(0))));
  return out;
}

/* Completes the unit eigenvector w to an eigenbasis: the restriction of A to
 * the plane orthogonal to w is a symmetric 2x2 matrix, diagonalized by one
 * exact Jacobi rotation. Its eigenvalues come from that rotation, not from
 * the cubic, whose trigonometric roots lose half the digits when two roots
 * nearly coincide. */
SNH_FN void eigen_sym3_complement(sym3 m, vec3 w, vec3* x, real* ex, vec3* y, real* ey) {
  const snh_mask big0 = fabs(w.a[0]) > fabs(w.a[1]);
  const real inv = SNH_R(1) / sqrt(big0 ? w.a[0] * w.a[0] + w.a[2] * w.a[2] : w.a[1] * w.a[1] + w.a[2] * w.a[2]);
  const vec3 u =
      vec3_make(big0 ? -w.a[2] * inv : SNH_R(0), big0 ? SNH_R(0) : w.a[2] * inv, big0 ? w.a[0] * inv : -w.a[1] * inv);
  const vec3 v = vec3_cross(w, u);
  const vec3 au = sym3_apply(m, u), av = sym3_apply(m, v);
  const real b00 = vec3_dot(u, au), b01 = SNH_R(0.5) * (vec3_dot(u, av) + vec3_dot(v, au)), b11 = vec3_dot(v, av);
  /* The exact Jacobi rotation, or the identity when b01 = 0 (a select). */
  const snh_mask rotate = b01 != SNH_R(0);
  const real tau = (b11 - b00) / (SNH_R(2) * (rotate ? b01 : SNH_R(1)));
  const real tr = (tau >= SNH_R(0) ? SNH_R(1) : SNH_R(-1)) / (fabs(tau) + sqrt(SNH_R(1) + tau * tau));
  const real cr = SNH_R(1) / sqrt(SNH_R(1) + tr * tr);
  const real t = rotate ? tr : SNH_R(0), c = rotate ? cr : SNH_R(1), s = rotate ? tr * cr : SNH_R(0);
  *ex = b00 - t * b01;
  *ey = b11 + t * b01;
  *x = vec3_make(c * u.a[0] - s * v.a[0], c * u.a[1] - s * v.a[1], c * u.a[2] - s * v.a[2]);
  *y = vec3_make(s * u.a[0] + c * v.a[0], s * u.a[1] + c * v.a[1], s * u.a[2] + c * v.a[2]);
}

SNH_FN void eigen_sym3_set_column(mat3* m, int c, vec3 x) {
  M3(*m, 0, c) = x.a[0];
  M3(*m, 1, c) = x.a[1];
  M3(*m, 2, c) = x.a[2];
}

/* Both cases (general and diagonal) and the zero / NaN guard are computed and
 * blended by selects, without branches, so that kernels calling this for
 * every quadrature point vectorize across work-items (the result is the same
 * as branching would give). */
SNH_FN_LARGE void eigen_sym3(sym3 a, vec3* values, mat3* vectors) {
  real scale = SNH_R(0);
  SNH_UNROLL
  for (int i = 0; i < 6; ++i) scale = fmax(scale, fabs(a.a[i]));
  /* Zero matrix, or NaN entries: reported as they are, identity vectors. */
  const snh_mask nonzero = scale > SNH_R(0);
  const real divisor = nonzero ? scale : SNH_R(1);
  sym3 m;
  SNH_UNROLL
  for (int i = 0; i < 6; ++i) m.a[i] = a.a[i] / divisor;

  /* General case. */
  const real off = m.a[1] * m.a[1] + m.a[2] * m.a[2] + m.a[4] * m.a[4];
  const snh_mask general = off > SNH_R(0);
  const real q = (m.a[0] + m.a[3] + m.a[5]) / SNH_R(3);
  const real b00 = m.a[0] - q, b11 = m.a[3] - q, b22 = m.a[5] - q;
  const real p = sqrt((b00 * b00 + b11 * b11 + b22 * b22 + SNH_R(2) * off) / SNH_R(6));
  const real p_safe = general ? p : SNH_R(1);
  /* det((A - qI) / p) / 2 = cos(3 theta): the cubic in trigonometric form. */
  const real c00 = b11 * b22 - m.a[4] * m.a[4];
  const real c01 = m.a[1] * b22 - m.a[4] * m.a[2];
  const real c02 = m.a[1] * m.a[4] - b11 * m.a[2];
  const real det = (b00 * c00 - m.a[1] * c01 + m.a[2] * c02) / (p_safe * p_safe * p_safe);
  const real half_det = fmin(fmax(det / SNH_R(2), SNH_R(-1)), SNH_R(1));
  /* The most separated root is the largest when cos(3 theta) >= 0, else the
   * smallest; it is accurate even when the other two nearly coincide. With
   * beta = (root - q) / p = 2 cos(theta), beta^3 - 3 beta = 2 cos(3 theta): the
   * largest root of beta^3 - 3 beta - 2 |half_det| lies in [sqrt(3), 2], where
   * the cubic is convex with slope >= 6, so Newton's method from beta = 2
   * decreases monotonically onto it (worst error over |half_det| in [0, 1]:
   * 0.27, 0.046, 1.7e-3, 2.5e-6, 5.5e-12, then rounding, after 0..5 steps);
   * the smallest root of the original is its negative when
   * half_det < 0. No acos / cos: those have no vector version on pocl and
   * would keep the kernels from vectorizing across work-items. */
  const snh_mask top = half_det >= SNH_R(0);
  const real target = SNH_R(2) * fabs(half_det);
  real beta = SNH_R(2);
  SNH_UNROLL
  for (int it = 0; it < SNH_EIGEN_NEWTON_STEPS; ++it)
    beta -= (beta * beta * beta - SNH_R(3) * beta - target) / (SNH_R(3) * beta * beta - SNH_R(3));
  const real isolated = q + p * (top ? beta : -beta);
  const vec3 w = eigen_sym3_vector_isolated(m, isolated);
  vec3 x0, y0;
  real ex0, ey0;
  eigen_sym3_complement(m, w, &x0, &ex0, &y0, &ey0);
  const snh_mask order = ex0 > ey0;
  const vec3 x = vec3_make(order ? y0.a[0] : x0.a[0], order ? y0.a[1] : x0.a[1], order ? y0.a[2] : x0.a[2]);
  const vec3 y = vec3_make(order ? x0.a[0] : y0.a[0], order ? x0.a[1] : y0.a[1], order ? x0.a[2] : y0.a[2]);
  const real ex = order ? ey0 : ex0, ey = order ? ex0 : ey0;
  const real ew = vec3_dot(w, sym3_apply(m, w)); /* Rayleigh quotient */
  vec3 gv;
  mat3 gq;
  gv.a[0] = top ? ex : fmin(ew, ex);
  gv.a[1] = top ? ey : ex;
  gv.a[2] = top ? fmax(ew, ey) : ey;
  SNH_UNROLL
  for (int r = 0; r < 3; ++r) {
    M3(gq, r, 0) = top ? x.a[r] : w.a[r];
    M3(gq, r, 1) = top ? y.a[r] : x.a[r];
    M3(gq, r, 2) = top ? w.a[r] : y.a[r];
  }

  /* Diagonal case: sort the entries ascending, permuting the unit vectors
   * (compare-exchange (0,1), (1,2), (0,1): insertion sort of three). */
  vec3 dv = vec3_make(m.a[0], m.a[3], m.a[5]);
  mat3 dq = mat3_identity();
  SNH_UNROLL
  for (int k = 0; k < 3; ++k) {
    const int i = k == 1 ? 1 : 0, j = i + 1;
    const snh_mask swap = dv.a[i] > dv.a[j];
    const real vi = dv.a[i], vj = dv.a[j];
    dv.a[i] = swap ? vj : vi;
    dv.a[j] = swap ? vi : vj;
    SNH_UNROLL
    for (int r = 0; r < 3; ++r) {
      const real qi = M3(dq, r, i), qj = M3(dq, r, j);
      M3(dq, r, i) = swap ? qj : qi;
      M3(dq, r, j) = swap ? qi : qj;
    }
  }

  SNH_UNROLL
  for (int i = 0; i < 3; ++i) {
    const real raw = a.a[i == 0 ? 0 : (i == 1 ? 3 : 5)];
    values->a[i] = nonzero ? (general ? gv.a[i] : dv.a[i]) * scale : raw;
  }
  SNH_UNROLL
  for (int i = 0; i < 9; ++i)
    vectors->a[i] = nonzero ? (general ? gq.a[i] : dq.a[i]) : (i % 4 == 0 ? SNH_R(1) : SNH_R(0));
}

#endif /* SNH_EIGEN_SYM3_H */
