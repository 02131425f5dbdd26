/* Barrier self-contact's device part (solver/barrier_terms.h): the
 * projected Hessian of kappa sum b as 3x3 blocks per vertex row (block CSR,
 * assembled on the host in a fixed order, solver/barrier_contact.h) applied
 * to a vector, and the barrier's force added to a residual. One work-item
 * per vertex (per entry for the force), each summing its own row in column
 * order: no atomics, the same bits on every run. */
#include "snh_portable.h"

/* y += mask .* H (mask .* p); blocks row-major. */
__kernel void snh_barrier_product(__global const int* offsets, __global const int* columns, __global const real* blocks,
                                  __global const real* mask, __global const real* p, const int vertex_count,
                                  __global real* y) {
  const int v = get_global_id(0);
  if (v >= vertex_count) return;
  real s0 = SNH_R(0), s1 = SNH_R(0), s2 = SNH_R(0);
  for (int k = offsets[v]; k < offsets[v + 1]; ++k) {
    const int c = columns[k];
    const real q0 = mask[3 * c] * p[3 * c], q1 = mask[3 * c + 1] * p[3 * c + 1], q2 = mask[3 * c + 2] * p[3 * c + 2];
    __global const real* b = blocks + 9 * k;
    s0 += b[0] * q0 + b[1] * q1 + b[2] * q2;
    s1 += b[3] * q0 + b[4] * q1 + b[5] * q2;
    s2 += b[6] * q0 + b[7] * q1 + b[8] * q2;
  }
  y[3 * v] += mask[3 * v] * s0;
  y[3 * v + 1] += mask[3 * v + 1] * s1;
  y[3 * v + 2] += mask[3 * v + 2] * s2;
}

/* r -= mask .* g, g = kappa d(sum b)/dx. */
__kernel void snh_barrier_force(__global const real* mask, __global const real* gradient, const int size,
                                __global real* r) {
  const int i = get_global_id(0);
  if (i >= size) return;
  r[i] -= mask[i] * gradient[i];
}
