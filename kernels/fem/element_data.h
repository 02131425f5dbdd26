/* Loading an element's data in the kernels: node values, rest gradients and
 * quadrature weights, with the lattice case (SNH_UNIFORM_REST: every element
 * shares element 0's rest data). Layouts: x: xyz per vertex; elements:
 * SNH_NODES ints per element; gradients: [element][3 a + j][q] (dN_a/dX_j at
 * point q: value-major, ElasticModel permutes the host's RestState); weights:
 * [element][q]. OpenCL only (the host reference reads its own arrays). */
#ifndef SNH_FEM_ELEMENT_DATA_H
#define SNH_FEM_ELEMENT_DATA_H

#include "fem/element.h"

#if SNH_UNIFORM_REST
#define REST_ELEMENT(e) 0
#else
#define REST_ELEMENT(e) (e)
#endif

SNH_FN void load_nodes(SNH_GLOBAL const vector_real* x, SNH_GLOBAL const int* nodes, real* xs) {
  SNH_UNROLL
  for (int a = 0; a < SNH_NODES; ++a)
    for (int i = 0; i < 3; ++i) xs[3 * a + i] = (real)x[3 * nodes[a] + i];
}

SNH_FN void load_gradients(SNH_GLOBAL const real* gradients, size_t e, int q, real* g) {
#if SNH_POINT_MAJOR
  SNH_GLOBAL const real* src = gradients + (size_t)3 * SNH_NODES * (SNH_QUADRATURE * REST_ELEMENT(e) + q);
  SNH_UNROLL
  for (int i = 0; i < 3 * SNH_NODES; ++i) g[i] = src[i];
#else
  SNH_GLOBAL const real* src = gradients + (size_t)3 * SNH_NODES * SNH_QUADRATURE * REST_ELEMENT(e) + q;
  SNH_UNROLL
  for (int i = 0; i < 3 * SNH_NODES; ++i) g[i] = src[SNH_QUADRATURE * i];
#endif
}

SNH_FN real load_weight(SNH_GLOBAL const real* weights, size_t e, int q) {
  return weights[SNH_QUADRATURE * REST_ELEMENT(e) + q];
}

/* What a stiffness column of element e reads at each of its points: the
 * rotated gradients (element_rotated_gradients), the weight and the cached
 * linearization. */
typedef struct {
  real vg[SNH_QUADRATURE][3 * SNH_NODES];
  real qw[SNH_QUADRATURE];
  principal_hessian h[SNH_QUADRATURE];
} element_linearization;

SNH_FN void element_linearization_load(SNH_GLOBAL const real* gradients, SNH_GLOBAL const real* weights,
                                       SNH_GLOBAL const real* cache, size_t e, element_linearization* out) {
  for (int q = 0; q < SNH_QUADRATURE; ++q) {
    real g[3 * SNH_NODES];
    load_gradients(gradients, e, q, g);
    out->qw[q] = load_weight(weights, e, q);
    out->h[q] = linearization_load(SNH_CACHE_AT(cache, e, q));
    element_rotated_gradients(&out->h[q], g, out->vg[q]);
  }
}

/* Rows 3 a + i, a >= first, of column (b, d) of the element's stiffness
 * sum_q w_q B_q^T H_q B_q (element.h's rank-one columns), into column[3 N]
 * (the rows of nodes a < first are left 0). */
SNH_FN void element_stiffness_column_from(const element_linearization* l, int b, int d, int first, real* column) {
  for (int i = 0; i < 3 * SNH_NODES; ++i) column[i] = SNH_R(0);
  for (int q = 0; q < SNH_QUADRATURE; ++q)
    element_column_scatter_from(element_column_frame(&l->h[q], l->vg[q], b, d), l->vg[q], l->qw[q], first, column);
}

/* The whole column (b, d). */
SNH_FN void element_stiffness_column(const element_linearization* l, int b, int d, real* column) {
  element_stiffness_column_from(l, b, d, 0, column);
}

#endif /* SNH_FEM_ELEMENT_DATA_H */
