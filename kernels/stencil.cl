/* Block stencils (kernels/fem/block_stencil.h): assembled on the device from
 * element matrices, and their products. Built with the same switches as
 * fem.cl; the element matrices are SNH_DOFS x SNH_DOFS, column-major,
 * [element][(3 b + d) SNH_DOFS + 3 a + i] (snh_element_matrices, and the
 * multigrid's Galerkin cell matrices). */
#include "fem/block_jacobi.h"
#include "fem/block_stencil.h"
#include "fem/element_data.h"

/* Block (v, s) is the sum of the element blocks (a, b) with node a at v and b
 * at n, each read as the transpose of block (b, a) in node a's columns (the
 * same values: element matrices and the multigrid's Galerkin cell matrices
 * are stored exactly symmetric, their lower triangles mirrored; a vertex's
 * blocks then come from its own nodes' contiguous columns), listed (as the
 * offset of that block's first entry, SNH_DOFS^2 e + 3 SNH_DOFS a + 3 b: no
 * decoding in the kernel) between
 * parts[width v + s] and the next offset in increasing element order, so
 * that blocks (v, n) and (n, v) add the same elements' mutually transposed
 * blocks in the same order and, from exactly symmetric element matrices,
 * come out exactly transposed (host/solver/model/block_stencil.h). */
__kernel void snh_stencil_assemble(__global const matrix_real* matrices, __global const int* part_offsets,
                                   __global const int* parts, const int blocks, const int width,
                                   __global matrix_real* stencil /* null: the float copy only */,
                                   __global float* stencil_float /* null, or the blocks' float copy */) {
  const int item = get_global_id(0);
  if (item >= blocks) return;
  /* Block s of vertex v, where the layout puts it (fem/block_stencil.h). */
  const size_t at = SNH_STENCIL_BLOCKS_AT(width, item / width) + (size_t)9 * SNH_STENCIL_TILE * (item % width);
  real block[9];
  for (int i = 0; i < 9; ++i) block[i] = SNH_R(0);
  for (int k = part_offsets[item]; k < part_offsets[item + 1]; ++k) {
    __global const matrix_real* ke = matrices + parts[k];
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) block[3 * j + i] += (real)ke[SNH_DOFS * i + j];
  }
  if (stencil)
    for (int i = 0; i < 9; ++i) stencil[at + SNH_STENCIL_TILE * i] = (matrix_real)block[i];
  /* A double model's float products (ProductVariants::set_float_products): the
   * same values narrowed, as snh_narrow would from the stored blocks. */
  if (stencil_float)
    for (int i = 0; i < 9; ++i) stencil_float[at + SNH_STENCIL_TILE * i] = (float)(matrix_real)block[i];
}

/* y = mask * (A p). */
__kernel void snh_stencil_product(__global const real* p, __global const int* neighbours,
                                  __global const matrix_real* stencil, __global const real* mask, const int count,
                                  const int width, __global real* y) {
  const int v = get_global_id(0);
  if (v >= count) return;
  real ap[3];
  stencil_row(p, neighbours, stencil, width, v, ap);
  for (int i = 0; i < 3; ++i) y[3 * v + i] = mask[3 * v + i] * ap[i];
}

/* r = base - mask * (A p) (base may be r: r -= A p). */
__kernel void snh_stencil_residual(__global const real* p, __global const int* neighbours,
                                   __global const matrix_real* stencil, __global const real* mask, const int count,
                                   const int width, __global const real* base, __global real* r) {
  const int v = get_global_id(0);
  if (v >= count) return;
  real ap[3];
  stencil_row(p, neighbours, stencil, width, v, ap);
  for (int i = 0; i < 3; ++i) r[3 * v + i] = base[3 * v + i] - mask[3 * v + i] * ap[i];
}

/* One step of the multigrid's Chebyshev smoothing on an assembled level
 * (kernels/multigrid.cl, snh_chebyshev_start): r = base - mask * (A d),
 * d_next = c_d d + c_z Dinv r, x += beta d_next. */
__kernel void snh_chebyshev_step(__global const real* d, __global const int* neighbours,
                                 __global const matrix_real* stencil, __global const real* mask,
                                 __global const real* inverse, const int count, const int width, const real c_d,
                                 const real c_z, const real beta, __global const real* base, __global real* r,
                                 __global real* x, __global real* d_next) {
  const int v = get_global_id(0);
  if (v >= count) return;
  real ap[3], rv[3], z[3];
  stencil_row(d, neighbours, stencil, width, v, ap);
  for (int i = 0; i < 3; ++i) {
    rv[i] = base[3 * v + i] - mask[3 * v + i] * ap[i];
    r[3 * v + i] = rv[i];
  }
  block_inverse_apply(inverse, v, rv, z);
  for (int i = 0; i < 3; ++i) {
    const real dv = c_d * d[3 * v + i] + c_z * z[i];
    d_next[3 * v + i] = dv;
    x[3 * v + i] += beta * dv;
  }
}
