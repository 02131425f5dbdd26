/* Block-Jacobi's inverse blocks per vertex (snh_block_jacobi_setup in
 * kernels/fem.cl): 3x3, column-major, at inverse[9 v]. Applied by fem.cl's
 * snh_block_jacobi_apply and by the multigrid's smoother (kernels/multigrid.cl,
 * kernels/stencil.cl). OpenCL only. */
#ifndef SNH_FEM_BLOCK_JACOBI_H
#define SNH_FEM_BLOCK_JACOBI_H

#include "fem/element.h"

/* z = Dinv r at vertex v, r and z private. */
SNH_FN void block_inverse_apply(__global const real* inverse, const int v, const real* r, real* z) {
  for (int i = 0; i < 3; ++i)
    z[i] = inverse[9 * v + i] * r[0] + inverse[9 * v + 3 + i] * r[1] + inverse[9 * v + 6 + i] * r[2];
}

#endif
