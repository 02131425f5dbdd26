/* A symmetric operator stored as 3x3 blocks per vertex pair (a block
 * stencil, kernels/stencil.cl): per vertex v, `width` neighbours (v itself
 * first, the vertices sharing an element with it in increasing order, then v
 * again as padding with zero blocks) at neighbours[width v + s], and the
 * blocks A(v, n) column-major at stencil[9 (width v + s) + 3 j + i]. The
 * storage of the assembled product variant (host/solver/model/elastic_model.h) and
 * of the multigrid's assembled levels (host/solver/multigrid/multigrid.h). OpenCL only.
 *
 * Tiled (SNH_STENCIL_TILE = T > 1, the GPUs' layout with the tiled cache,
 * solver::PointDataLayout::tiled): vertices in tiles of T, entry m of block
 * s of vertex v at 9 width T (v / T) + T (9 s + m) + v % T and its neighbour
 * at width T (v / T) + T s + v % T, so that consecutive work-items read
 * consecutive words; T = 1 is the layout above. The buffers hold whole
 * tiles (host/solver/model/block_stencil.h).
 *
 * Upper (SNH_STENCIL_LOWER = L > 0, with SNH_STENCIL_WIDTH = W; per vertex,
 * tile 1: the CPUs' assembled variant and multigrid levels): vertex v stores its W blocks against
 * itself and the neighbours after it, and reads its L blocks against the
 * neighbours before it as the transposes of theirs: neighbours[(W + 2 L) v
 * + W + s] is such a neighbour n and [(W + 2 L) v + W + L + s] the index of
 * block (n, v) among the stored blocks (padding: a zero block). Half the
 * bytes: the mirrored blocks were streamed with their own rows just before
 * and come from the caches. */
#ifndef SNH_FEM_BLOCK_STENCIL_H
#define SNH_FEM_BLOCK_STENCIL_H

#include "fem/element.h"

#ifndef SNH_STENCIL_TILE
#define SNH_STENCIL_TILE 1
#endif
#if defined(SNH_STENCIL_LOWER) && (SNH_STENCIL_TILE != 1 || !defined(SNH_STENCIL_WIDTH))
#error "the upper layout is per vertex, its width a constant"
#endif
/* Where vertex v's first block (its first neighbour) starts: its entries
 * (neighbours) follow SNH_STENCIL_TILE apart. */
#define SNH_STENCIL_BLOCKS_AT(width, v) \
  ((size_t)9 * (width)*SNH_STENCIL_TILE * ((v) / SNH_STENCIL_TILE) + (v) % SNH_STENCIL_TILE)
#define SNH_STENCIL_NEIGHBOURS_AT(width, v) \
  ((size_t)(width)*SNH_STENCIL_TILE * ((v) / SNH_STENCIL_TILE) + (v) % SNH_STENCIL_TILE)

/* (A p) at vertex v: its row of blocks in order (deterministic sums), the
 * padding's zero blocks too (stopping at the padding, a compare per block,
 * measured slower on pocl). With SNH_STENCIL_WIDTH (the host's
 * stencil_width_define: the width argument's value, known when the kernel
 * is built) the loop's count is a constant and unrolled, measured faster on
 * pocl (docs/performance.md, "Block stencil rows"). */
/* s += B p for a block whose entry (i, j) is at b[i r + j c]: stored
 * column-major (r = tile, c = 3 tile), or read transposed (r = 3, c = 1). */
SNH_FN void stencil_block_add(__global const matrix_real* b, const int r, const int c, const real p0, const real p1,
                              const real p2, real* s0, real* s1, real* s2) {
  *s0 += (real)b[0] * p0 + (real)b[c] * p1 + (real)b[2 * c] * p2;
  *s1 += (real)b[r] * p0 + (real)b[r + c] * p1 + (real)b[r + 2 * c] * p2;
  *s2 += (real)b[2 * r] * p0 + (real)b[2 * r + c] * p1 + (real)b[2 * r + 2 * c] * p2;
}

SNH_FN void stencil_row(__global const real* p, __global const int* neighbours, __global const matrix_real* stencil,
                        const int width, const int v, real* out) {
  real s0 = SNH_R(0), s1 = SNH_R(0), s2 = SNH_R(0);
#ifdef SNH_STENCIL_LOWER
  /* The upper layout, in the full layout's order: v itself, the neighbours
   * before it (block (n, v) read transposed: the same values as the full
   * layout's block (v, n)), then those after it; padding adds zeros. So the
   * same sums in the same order, bit for bit. */
  __global const int* around = neighbours + (size_t)(SNH_STENCIL_WIDTH + 2 * SNH_STENCIL_LOWER) * v;
  __global const matrix_real* a = stencil + (size_t)9 * SNH_STENCIL_WIDTH * v;
  stencil_block_add(a, 1, 3, p[3 * v], p[3 * v + 1], p[3 * v + 2], &s0, &s1, &s2);
  SNH_UNROLL
  for (int s = 0; s < SNH_STENCIL_LOWER; ++s) {
    const int n = around[SNH_STENCIL_WIDTH + s];
    __global const matrix_real* b = stencil + (size_t)9 * around[SNH_STENCIL_WIDTH + SNH_STENCIL_LOWER + s];
    stencil_block_add(b, 3, 1, p[3 * n], p[3 * n + 1], p[3 * n + 2], &s0, &s1, &s2);
  }
  SNH_UNROLL
  for (int s = 1; s < SNH_STENCIL_WIDTH; ++s) {
    const int n = around[s];
    stencil_block_add(a + 9 * s, 1, 3, p[3 * n], p[3 * n + 1], p[3 * n + 2], &s0, &s1, &s2);
  }
#else
  __global const int* around = neighbours + SNH_STENCIL_NEIGHBOURS_AT(width, v);
  __global const matrix_real* a = stencil + SNH_STENCIL_BLOCKS_AT(width, v);
  const int t = SNH_STENCIL_TILE;
#ifdef SNH_STENCIL_WIDTH
  SNH_UNROLL
  for (int s = 0; s < SNH_STENCIL_WIDTH; ++s) {
#else
  for (int s = 0; s < width; ++s) {
#endif
    const int n = around[t * s];
    stencil_block_add(a + 9 * t * s, t, 3 * t, p[3 * n], p[3 * n + 1], p[3 * n + 2], &s0, &s1, &s2);
  }
#endif
  out[0] = s0;
  out[1] = s1;
  out[2] = s2;
}

#endif
