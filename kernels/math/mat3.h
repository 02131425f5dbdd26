/* 3x3 matrices stored column-major, a[3*column + row]: the storage order is
 * the paper's vec(F) (Smith et al. 2018, Eq. 1), so a 9-vector index of the
 * Hessian is the same index into this array. */
#ifndef SNH_MAT3_H
#define SNH_MAT3_H

#include "snh_portable.h"

typedef struct {
  real a[9];
} mat3;

typedef struct {
  real a[3];
} vec3;

#define M3(m, r, c) ((m).a[3 * (c) + (r)])

SNH_FN mat3 mat3_zero(void) {
  mat3 m;
  SNH_UNROLL
  for (int i = 0; i < 9; ++i) m.a[i] = SNH_R(0);
  return m;
}

SNH_FN mat3 mat3_identity(void) {
  mat3 m = mat3_zero();
  m.a[0] = m.a[4] = m.a[8] = SNH_R(1);
  return m;
}

SNH_FN mat3 mat3_mul(mat3 x, mat3 y) {
  mat3 m;
  SNH_UNROLL
  for (int i = 0; i < 9; ++i) {
    const int r = i % 3, c = i / 3;
    M3(m, r, c) = M3(x, r, 0) * M3(y, 0, c) + M3(x, r, 1) * M3(y, 1, c) + M3(x, r, 2) * M3(y, 2, c);
  }
  return m;
}

/* x^T y */
SNH_FN mat3 mat3_tmul(mat3 x, mat3 y) {
  mat3 m;
  SNH_UNROLL
  for (int i = 0; i < 9; ++i) {
    const int r = i % 3, c = i / 3;
    M3(m, r, c) = M3(x, 0, r) * M3(y, 0, c) + M3(x, 1, r) * M3(y, 1, c) + M3(x, 2, r) * M3(y, 2, c);
  }
  return m;
}

/* x y^T */
SNH_FN mat3 mat3_mult(mat3 x, mat3 y) {
  mat3 m;
  SNH_UNROLL
  for (int i = 0; i < 9; ++i) {
    const int r = i % 3, c = i / 3;
    M3(m, r, c) = M3(x, r, 0) * M3(y, c, 0) + M3(x, r, 1) * M3(y, c, 1) + M3(x, r, 2) * M3(y, c, 2);
  }
  return m;
}

/* U diag(s) V^T */
SNH_FN mat3 mat3_udvt(mat3 u, vec3 s, mat3 v) {
  mat3 m;
  SNH_UNROLL
  for (int i = 0; i < 9; ++i) {
    const int r = i % 3, c = i / 3;
    M3(m, r, c) =
        M3(u, r, 0) * s.a[0] * M3(v, c, 0) + M3(u, r, 1) * s.a[1] * M3(v, c, 1) + M3(u, r, 2) * s.a[2] * M3(v, c, 2);
  }
  return m;
}

SNH_FN real mat3_det(mat3 m) {
  return M3(m, 0, 0) * (M3(m, 1, 1) * M3(m, 2, 2) - M3(m, 2, 1) * M3(m, 1, 2)) -
         M3(m, 0, 1) * (M3(m, 1, 0) * M3(m, 2, 2) - M3(m, 2, 0) * M3(m, 1, 2)) +
         M3(m, 0, 2) * (M3(m, 1, 0) * M3(m, 2, 1) - M3(m, 2, 0) * M3(m, 1, 1));
}

/* dJ/dF, the cofactor matrix, written column by column as cross products of
 * the columns of F (Smith et al. 2018, Eq. 19). */
SNH_FN mat3 mat3_cofactor(mat3 f) {
  mat3 g;
  SNH_UNROLL
  for (int c = 0; c < 3; ++c) {
    const int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
    SNH_UNROLL
    for (int r = 0; r < 3; ++r) {
      const int r1 = (r + 1) % 3, r2 = (r + 2) % 3;
      M3(g, r, c) = M3(f, r1, c1) * M3(f, r2, c2) - M3(f, r2, c1) * M3(f, r1, c2);
    }
  }
  return g;
}

SNH_FN real mat3_ddot(mat3 x, mat3 y) {
  real s = SNH_R(0);
  SNH_UNROLL
  for (int i = 0; i < 9; ++i) s += x.a[i] * y.a[i];
  return s;
}

#endif /* SNH_MAT3_H */
