/* A symmetric operator stored as 3x3 blocks per vertex pair (a block
 * stencil, kernels/stencil.cl): per vertex v, `width` neighbours (v itself
 * first, the vertices sharing an element with it in increasing order, then v
 * again as padding with zero blocks) at neighbours[width v + s], and the
 * blocks A(v, n) column-major at stencil[9 (width v + s) + 3 j + i]. The
 * storage of the assembled product variant (host/solver/elastic_model.h) and
 * of the multigrid's assembled levels (host/solver/multigrid.h). OpenCL only. */
#ifndef SNH_FEM_BLOCK_STENCIL_H
#define SNH_FEM_BLOCK_STENCIL_H

#include "fem/element.h"

/* (A p) at vertex v: its row of blocks in order (deterministic sums), the
 * padding's zero blocks too (stopping at the padding, a compare per block,
 * measured 20-45% slower on pocl on box lattices and tet boxes at 48^3). */
SNH_FN void stencil_row(__global const real* p, __global const int* neighbours, __global const matrix_real* stencil,
                        const int width, const int v, real* out) {
  real s0 = SNH_R(0), s1 = SNH_R(0), s2 = SNH_R(0);
  __global const int* around = neighbours + (size_t)width * v;
  __global const matrix_real* a = stencil + (size_t)9 * width * v;
  for (int s = 0; s < width; ++s) {
    const int n = around[s];
    const real p0 = p[3 * n], p1 = p[3 * n + 1], p2 = p[3 * n + 2];
    s0 += (real)a[9 * s] * p0 + (real)a[9 * s + 3] * p1 + (real)a[9 * s + 6] * p2;
    s1 += (real)a[9 * s + 1] * p0 + (real)a[9 * s + 4] * p1 + (real)a[9 * s + 7] * p2;
    s2 += (real)a[9 * s + 2] * p0 + (real)a[9 * s + 5] * p1 + (real)a[9 * s + 8] * p2;
  }
  out[0] = s0;
  out[1] = s1;
  out[2] = s2;
}

#endif
