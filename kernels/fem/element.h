/* Element kinematics shared by the OpenCL kernels and the host reference:
 * the deformation gradient at a quadrature point and the scatter of a stress
 * back to the element's nodes. The element type is fixed at build time:
 * SNH_HEX8 = 1 (trilinear hexahedron, 2x2x2 Gauss points) or 0 (linear
 * tetrahedron, one point). Gradients g are dN_a/dX at one point, [a][3]. */
#ifndef SNH_FEM_ELEMENT_H
#define SNH_FEM_ELEMENT_H

#include "materials/principal_hessian.h"

#ifndef SNH_HEX8
#error "define SNH_HEX8 as 1 (hex8) or 0 (tet4)"
#endif

#if SNH_HEX8
#define SNH_NODES 8
#define SNH_QUADRATURE 8
#else
#define SNH_NODES 4
#define SNH_QUADRATURE 1
#endif
#define SNH_DOFS (3 * SNH_NODES) /* an element's: the size of its matrices */

/* Per quadrature point, the cached linearization: U, V, the PSD-projected
 * 3x3 block and the clamped twist and flip eigenvalues. Three layouts
 * (solver::PointDataLayout), fixed at build time:
 * - value-major (hex8 on CPU devices): stored per element, value k of point
 *   q of element e at 240 e + 8 k + q, so that the lanes kernels
 *   (fem_lanes.cl, a lane per point) move each value of the element's 8
 *   points as one vector;
 * - point-major (tet4 on CPU devices; hex8 with SNH_POINT_MAJOR): value k of
 *   point P = SNH_QUADRATURE e + q at 30 P + k (grouping 8 tet4 elements
 *   value-major measured slower in double, docs/performance.md);
 * - tiled (GPUs, SNH_CACHE_TILE = T > 1, with SNH_POINT_MAJOR for hex8):
 *   elements in tiles of T, value k of point q of element e at
 *   30 SNH_QUADRATURE T (e / T) + T (30 q + k) + e % T, so that the
 *   consecutive work-items of the scalar kernels (a work-item per element)
 *   read each value from consecutive words: with point-major, the layout
 *   used before, they read words 30 SNH_QUADRATURE apart (docs/performance.md,
 *   NVIDIA H200). The lanes program reads the first two only.
 * SNH_CACHE_AT(cache, e, q) is point q of element e, its values
 * SNH_CACHE_STRIDE apart; an element's 30 SNH_QUADRATURE values, in the
 * order (q, k), are SNH_CACHE_TILE apart from SNH_CACHE_AT(cache, e, 0) in
 * the point-major and tiled layouts and consecutive in the value-major one.
 * SNH_CACHE_POINT(P) (lanes) is point P's first value in the first two:
 * value k of point P at 30 G (P / G) + G k + P % G, G = SNH_CACHE_GROUP. */
#define SNH_LINEARIZATION_SIZE 30
#if SNH_HEX8 && !SNH_POINT_MAJOR
#define SNH_CACHE_GROUP 8
#define SNH_CACHE_TILE 1
#define SNH_CACHE_STRIDE SNH_CACHE_GROUP
#else
#define SNH_CACHE_GROUP 1
#ifndef SNH_CACHE_TILE
#define SNH_CACHE_TILE 1
#endif
#define SNH_CACHE_STRIDE SNH_CACHE_TILE
#endif
#define SNH_CACHE_POINT(point) \
  ((size_t)SNH_LINEARIZATION_SIZE * SNH_CACHE_GROUP * ((point) / SNH_CACHE_GROUP) + (point) % SNH_CACHE_GROUP)
/* Point q of element e in the cache. */
#if SNH_CACHE_GROUP > 1
#define SNH_CACHE_AT(cache, e, q) ((cache) + SNH_CACHE_POINT((size_t)SNH_QUADRATURE * (e) + (q)))
#else
#define SNH_CACHE_AT(cache, e, q)                                                                        \
  ((cache) + (size_t)SNH_LINEARIZATION_SIZE * SNH_QUADRATURE * SNH_CACHE_TILE * ((e) / SNH_CACHE_TILE) + \
   (size_t)SNH_LINEARIZATION_SIZE * SNH_CACHE_TILE * (q) + (e) % SNH_CACHE_TILE)
#endif
/* The distance between an element's consecutive cache values in the order
 * (q, k) (linearization_copy_float). */
#define SNH_CACHE_ELEMENT_STRIDE SNH_CACHE_TILE

/* Element matrices' storage: the working precision, or float with
 * SNH_MATRIX_FLOAT = 1 (a double build's multigrid fine level, whose
 * smoother reads them at every V-cycle: half the memory traffic). A float
 * matrix is stored exactly symmetric: column c writes its rows r >= c, each
 * at (r, c) and (c, r). Products read either type in the working
 * precision. */
#if SNH_MATRIX_FLOAT
typedef float matrix_real;
#else
typedef scalar_real matrix_real;
#endif

/* Entry (r, c) of column c of an n x n column-major element matrix, for
 * r >= c, stored at (r, c) and (c, r): the matrix is symmetric by
 * construction and only its lower triangle is computed (calls with r < c
 * store nothing). */
SNH_FN void element_matrix_store(SNH_GLOBAL matrix_real* k, int n, int c, int r, scalar_real value) {
  if (r >= c) {
    k[n * c + r] = (matrix_real)value;
    k[n * r + c] = (matrix_real)value;
  }
}

/* F = sum_a x_a (dN_a/dX)^T for node values xs[a][3]. */
SNH_FN mat3 element_deformation_gradient(const real* xs, const real* g) {
  mat3 f = mat3_zero();
  SNH_UNROLL
  for (int a = 0; a < SNH_NODES; ++a) {
    SNH_UNROLL
    for (int i = 0; i < 9; ++i) M3(f, i % 3, i / 3) += xs[3 * a + i % 3] * g[3 * a + i / 3];
  }
  return f;
}

/* out[a][i] += w sum_j P_ij dN_a/dX_j: the stress's work-conjugate nodal
 * vector (the internal force is its negative). */
SNH_FN void element_scatter(mat3 p, const real* g, real w, real* out) {
  SNH_UNROLL
  for (int a = 0; a < SNH_NODES; ++a) {
    SNH_UNROLL
    for (int i = 0; i < 3; ++i)
      out[3 * a + i] += w * (M3(p, i, 0) * g[3 * a] + M3(p, i, 1) * g[3 * a + 1] + M3(p, i, 2) * g[3 * a + 2]);
  }
}

/* Stiffness columns from rank-one dF. Column (b, d) of one point's
 * w B^T H B is the response to dF = e_d g_b^T; in the SVD's frame that dF is
 * R = U^T dF V = (U^T e_d)(V^T g_b)^T, and the scatter sum_j dP_ij g_aj of
 * dP = U (H R) V^T is (U (H R) vg_a)_i with vg_a = V^T g_a. So with the
 * rotated gradients vg (element_rotated_gradients, once per point) a column
 * costs one rotated action, one 3x3 product and a 3x3 matrix-vector product
 * per node, instead of two rotations of dF and a full scatter. */
SNH_FN void element_rotated_gradients(const principal_hessian* h, const real* g, real* vg) {
  for (int a = 0; a < SNH_NODES; ++a)
    for (int j = 0; j < 3; ++j)
      vg[3 * a + j] = M3(h->v, 0, j) * g[3 * a] + M3(h->v, 1, j) * g[3 * a + 1] + M3(h->v, 2, j) * g[3 * a + 2];
}

/* U (H R) for the column (b, d): its product with vg_a is node a's rows. */
SNH_FN mat3 element_column_frame(const principal_hessian* h, const real* vg, int b, int d) {
  mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) M3(r, i, j) = M3(h->u, d, i) * vg[3 * b + j];
  return mat3_mul(h->u, principal_hessian_rotated_action(h, r));
}

/* column[3 a + i] += w (m vg_a)_i for the nodes a >= first (first = b:
 * the column's rows from its own node's block on, all that its lower
 * triangle needs). */
SNH_FN void element_column_scatter_from(mat3 m, const real* vg, real w, int first, real* column) {
  for (int a = first; a < SNH_NODES; ++a)
    for (int i = 0; i < 3; ++i)
      column[3 * a + i] += w * (M3(m, i, 0) * vg[3 * a] + M3(m, i, 1) * vg[3 * a + 1] + M3(m, i, 2) * vg[3 * a + 2]);
}

/* column[3 a + i] += w (m vg_a)_i for every node a. */
SNH_FN void element_column_scatter(mat3 m, const real* vg, real w, real* column) {
  element_column_scatter_from(m, vg, w, 0, column);
}

/* y_a += w (H : dF) dN_a/dX with dF = sum_b p_b (dN_b/dX)^T: one point's
 * share of the Hessian product. */
SNH_FN void element_product(const principal_hessian* h, const real* ps, const real* g, real w, real* y) {
  const mat3 dp = principal_hessian_action(h, element_deformation_gradient(ps, g));
  element_scatter(dp, g, w, y);
}

#if SNH_IS_OPENCL && SNH_DOUBLE
/* The float copy of n cache values `stride` apart, for a double solve's
 * products in float (SNH_MIXED; ProductVariants::set_float_products): an
 * element's values (SNH_CACHE_ELEMENT_STRIDE apart), or a tet4 lanes
 * work-item's (consecutive). */
SNH_FN void linearization_copy_float(__global const double* in, int n, int stride, __global float* out) {
  int i = 0;
  if (stride == 1)
    for (; i + 8 <= n; i += 8) vstore8(convert_float8(vload8(0, in + i)), 0, out + i);
  for (; i < n; ++i) out[(size_t)stride * i] = (float)in[(size_t)stride * i];
}
#endif

#if SNH_LANES == 1
/* out: SNH_CACHE_AT(cache, e, q); its values SNH_CACHE_STRIDE apart. */
SNH_FN void linearization_store(const principal_hessian* h, SNH_GLOBAL real* out) {
  SNH_UNROLL
  for (int i = 0; i < 9; ++i) out[SNH_CACHE_STRIDE * i] = h->u.a[i];
  SNH_UNROLL
  for (int i = 0; i < 9; ++i) out[SNH_CACHE_STRIDE * (9 + i)] = h->v.a[i];
  SNH_UNROLL
  for (int i = 0; i < 6; ++i) out[SNH_CACHE_STRIDE * (18 + i)] = h->block.a[i];
  SNH_UNROLL
  for (int i = 0; i < 3; ++i) out[SNH_CACHE_STRIDE * (24 + i)] = h->twist.a[i];
  SNH_UNROLL
  for (int i = 0; i < 3; ++i) out[SNH_CACHE_STRIDE * (27 + i)] = h->flip.a[i];
}

SNH_FN principal_hessian linearization_load(SNH_GLOBAL const real* in) {
  principal_hessian h;
  SNH_UNROLL
  for (int i = 0; i < 9; ++i) h.u.a[i] = in[SNH_CACHE_STRIDE * i];
  SNH_UNROLL
  for (int i = 0; i < 9; ++i) h.v.a[i] = in[SNH_CACHE_STRIDE * (9 + i)];
  SNH_UNROLL
  for (int i = 0; i < 6; ++i) h.block.a[i] = in[SNH_CACHE_STRIDE * (18 + i)];
  SNH_UNROLL
  for (int i = 0; i < 3; ++i) h.twist.a[i] = in[SNH_CACHE_STRIDE * (24 + i)];
  SNH_UNROLL
  for (int i = 0; i < 3; ++i) h.flip.a[i] = in[SNH_CACHE_STRIDE * (27 + i)];
  SNH_UNROLL
  for (int i = 0; i < 3; ++i) h.sigma.a[i] = SNH_R(0);
  return h;
}
#endif

#endif /* SNH_FEM_ELEMENT_H */
