/* Closed-form eigensystem of a symmetric 3x3 matrix.
 *
 * Eigenvalues: the roots of the characteristic cubic det(A - e I) = 0 in
 * trigonometric form after shifting by tr(A)/3 and scaling to unit spread,
 * so a repeated root never divides by zero (the argument of acos is clamped).
 * Eigenvectors: the most separated eigenvalue's vector from the largest cross
 * product of two rows of A - e I, as in the robust non-iterative scheme of
 * D. Eberly ("A Robust Eigensolver for 3x3 Symmetric Matrices", Geometric
 * Tools, 2014); the other two from one exact Jacobi rotation of A restricted
 * to the orthogonal complement. Eigenvalues come out ascending; eigenvectors are orthonormal
 * columns of `vectors` even when eigenvalues coincide. */
#ifndef SNH_EIGEN_SYM3_H
#define SNH_EIGEN_SYM3_H

#include "math/mat3.h"

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

/* Unit eigenvector for eigenvalue e, assumed simple and the most separated. */
SNH_FN vec3 eigen_sym3_vector_isolated(sym3 m, real e) {
  const vec3 r0 = vec3_make(m.a[0] - e, m.a[1], m.a[2]);
  const vec3 r1 = vec3_make(m.a[1], m.a[3] - e, m.a[4]);
  const vec3 r2 = vec3_make(m.a[2], m.a[4], m.a[5] - e);
  const vec3 c01 = vec3_cross(r0, r1), c02 = vec3_cross(r0, r2), c12 = vec3_cross(r1, r2);
  const real d01 = vec3_dot(c01, c01), d02 = vec3_dot(c02, c02), d12 = vec3_dot(c12, c12);
  if (d01 >= d02 && d01 >= d12 && d01 > SNH_R(0)) return vec3_scale(c01, SNH_R(1) / sqrt(d01));
  if (d02 >= d12 && d02 > SNH_R(0)) return vec3_scale(c02, SNH_R(1) / sqrt(d02));
  if (d12 > SNH_R(0)) return vec3_scale(c12, SNH_R(1) / sqrt(d12));
  return vec3_make(SNH_R(1), SNH_R(0), SNH_R(0));
}

/* Completes the unit eigenvector w to an eigenbasis: the restriction of A to
 * the plane orthogonal to w is a symmetric 2x2 matrix, diagonalized by one
 * exact Jacobi rotation. Its eigenvalues come from that rotation, not from
 * the cubic, whose trigonometric roots lose half the digits when two roots
 * nearly coincide. */
SNH_FN void eigen_sym3_complement(sym3 m, vec3 w, vec3* x, real* ex, vec3* y, real* ey) {
  vec3 u;
  if (fabs(w.a[0]) > fabs(w.a[1])) {
    const real inv = SNH_R(1) / sqrt(w.a[0] * w.a[0] + w.a[2] * w.a[2]);
    u = vec3_make(-w.a[2] * inv, SNH_R(0), w.a[0] * inv);
  } else {
    const real inv = SNH_R(1) / sqrt(w.a[1] * w.a[1] + w.a[2] * w.a[2]);
    u = vec3_make(SNH_R(0), w.a[2] * inv, -w.a[1] * inv);
  }
  const vec3 v = vec3_cross(w, u);
  const vec3 au = sym3_apply(m, u), av = sym3_apply(m, v);
  const real b00 = vec3_dot(u, au), b01 = SNH_R(0.5) * (vec3_dot(u, av) + vec3_dot(v, au)), b11 = vec3_dot(v, av);
  real c = SNH_R(1), s = SNH_R(0), t = SNH_R(0);
  if (b01 != SNH_R(0)) {
    const real tau = (b11 - b00) / (SNH_R(2) * b01);
    t = (tau >= SNH_R(0) ? SNH_R(1) : SNH_R(-1)) / (fabs(tau) + sqrt(SNH_R(1) + tau * tau));
    c = SNH_R(1) / sqrt(SNH_R(1) + t * t);
    s = t * c;
  }
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

SNH_FN void eigen_sym3(sym3 a, vec3* values, mat3* vectors) {
  real scale = SNH_R(0);
  for (int i = 0; i < 6; ++i) scale = fmax(scale, fabs(a.a[i]));
  *vectors = mat3_identity();
  if (!(scale > SNH_R(0))) {
    /* Zero matrix, or NaN entries: report them as they are. */
    for (int i = 0; i < 3; ++i) values->a[i] = a.a[i == 0 ? 0 : (i == 1 ? 3 : 5)];
    return;
  }
  sym3 m;
  for (int i = 0; i < 6; ++i) m.a[i] = a.a[i] / scale;

  const real off = m.a[1] * m.a[1] + m.a[2] * m.a[2] + m.a[4] * m.a[4];
  if (off > SNH_R(0)) {
    const real q = (m.a[0] + m.a[3] + m.a[5]) / SNH_R(3);
    const real b00 = m.a[0] - q, b11 = m.a[3] - q, b22 = m.a[5] - q;
    const real p = sqrt((b00 * b00 + b11 * b11 + b22 * b22 + SNH_R(2) * off) / SNH_R(6));
    /* det((A - qI) / p) / 2 = cos(3 theta): the cubic in trigonometric form. */
    const real c00 = b11 * b22 - m.a[4] * m.a[4];
    const real c01 = m.a[1] * b22 - m.a[4] * m.a[2];
    const real c02 = m.a[1] * m.a[4] - b11 * m.a[2];
    const real det = (b00 * c00 - m.a[1] * c01 + m.a[2] * c02) / (p * p * p);
    const real half_det = fmin(fmax(det / SNH_R(2), SNH_R(-1)), SNH_R(1));
    const real angle = acos(half_det) / SNH_R(3);
    const real two_thirds_pi = SNH_R(2.09439510239319549230842892218633526);
    const real beta2 = SNH_R(2) * cos(angle);
    const real beta0 = SNH_R(2) * cos(angle + two_thirds_pi);
    /* The most separated root is the largest when cos(3 theta) >= 0, else the
     * smallest; it is accurate even when the other two nearly coincide. */
    const int top = half_det >= SNH_R(0);
    const real isolated = q + p * (top ? beta2 : beta0);
    const vec3 w = eigen_sym3_vector_isolated(m, isolated);
    vec3 x, y;
    real ex, ey;
    eigen_sym3_complement(m, w, &x, &ex, &y, &ey);
    if (ex > ey) {
      const vec3 tv = x;
      x = y;
      y = tv;
      const real te = ex;
      ex = ey;
      ey = te;
    }
    const real ew = vec3_dot(w, sym3_apply(m, w)); /* Rayleigh quotient */
    if (top) {
      values->a[0] = ex;
      values->a[1] = ey;
      values->a[2] = fmax(ew, ey);
      eigen_sym3_set_column(vectors, 0, x);
      eigen_sym3_set_column(vectors, 1, y);
      eigen_sym3_set_column(vectors, 2, w);
    } else {
      values->a[0] = fmin(ew, ex);
      values->a[1] = ex;
      values->a[2] = ey;
      eigen_sym3_set_column(vectors, 0, w);
      eigen_sym3_set_column(vectors, 1, x);
      eigen_sym3_set_column(vectors, 2, y);
    }
  } else {
    /* Diagonal: sort the entries ascending, permuting the unit vectors. */
    values->a[0] = m.a[0];
    values->a[1] = m.a[3];
    values->a[2] = m.a[5];
    for (int i = 1; i < 3; ++i)
      for (int j = i; j > 0 && values->a[j - 1] > values->a[j]; --j) {
        const real t = values->a[j];
        values->a[j] = values->a[j - 1];
        values->a[j - 1] = t;
        for (int r = 0; r < 3; ++r) {
          const real s = M3(*vectors, r, j);
          M3(*vectors, r, j) = M3(*vectors, r, j - 1);
          M3(*vectors, r, j - 1) = s;
        }
      }
  }
  for (int i = 0; i < 3; ++i) values->a[i] *= scale;
}

#endif /* SNH_EIGEN_SYM3_H */
