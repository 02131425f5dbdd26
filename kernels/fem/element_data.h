/* Loading an element's data in the kernels: node values, rest gradients and
 * quadrature weights, with the lattice case (SNH_UNIFORM_REST: every element
 * shares element 0's rest data). Layouts: x: xyz per vertex; elements:
 * SNH_NODES ints per element; gradients: [element][q][a][3]; weights:
 * [element][q]. OpenCL only (the host reference reads its own arrays). */
#ifndef SNH_FEM_ELEMENT_DATA_H
#define SNH_FEM_ELEMENT_DATA_H

#include "fem/element.h"

#if SNH_UNIFORM_REST
#define REST_ELEMENT(e) 0
#else
#define REST_ELEMENT(e) (e)
#endif

SNH_FN void load_nodes(SNH_GLOBAL const real* x, SNH_GLOBAL const int* nodes, real* xs) {
  SNH_UNROLL
  for (int a = 0; a < SNH_NODES; ++a)
    for (int i = 0; i < 3; ++i) xs[3 * a + i] = x[3 * nodes[a] + i];
}

SNH_FN void load_gradients(SNH_GLOBAL const real* gradients, size_t e, int q, real* g) {
  SNH_GLOBAL const real* src = gradients + (size_t)3 * SNH_NODES * (SNH_QUADRATURE * REST_ELEMENT(e) + q);
  SNH_UNROLL
  for (int i = 0; i < 3 * SNH_NODES; ++i) g[i] = src[i];
}

SNH_FN real load_weight(SNH_GLOBAL const real* weights, size_t e, int q) {
  return weights[SNH_QUADRATURE * REST_ELEMENT(e) + q];
}

#endif /* SNH_FEM_ELEMENT_DATA_H */
