/* Geometric multigrid on hex8 lattices (host/solver/multigrid/multigrid.h): Galerkin
 * coarse operators built cell by cell, transfers, and the smoother's block
 * diagonal. Built with the same switches as fem.cl (SNH_HEX8 must be 1).
 *
 * Nested lattices coarsened 2x per axis with trilinear prolongation P: each
 * fine cell lies in one coarse cell, at octant o (bits x, y, z), and its node
 * a (VTK order) interpolates the coarse cell's corners A with the weights
 * W_o[a][A] = prod_d (1 - |p_d - c_d| / 2), p = octant + node offset in
 * {0,1,2}^3 and c = 2 * corner offset, in units of the fine spacing (the
 * host's child_weight, solver/multigrid/lattice_hierarchy.h, passed as the table
 * octant_weights[64 o + 8 a + A]). The
 * Galerkin operator A_c = P^T D A_f D P (D: the fine level's mask, 0 on
 * constrained DOFs) is then a sum over coarse cells of
 *   K_C = sum_children W_o^T (D K_child D) W_o    (kron I3),
 * one 24x24 matrix per coarse cell: the hierarchy stays element-wise, with
 * the fine level's Dirichlet masks and projected Hessians carried in exactly
 * (the design of the shared notes, after Dick, Georgii and Westermann 2011).
 * Element matrices are column-major, [cell][(3 b + d) * 24 + 3 a + i]; both
 * Galerkin kernels also write each cell's 3x3 diagonal blocks,
 * [cell][9 b + 3 d + i] (the smoother's block-Jacobi blocks). */
#include "fem/block_jacobi.h"
#include "fem/element_data.h"
#include "fem/vertex_terms.h"

#if !SNH_HEX8
#error "multigrid.cl is for hex8 lattices"
#endif

#define MG_DOFS 24

/* k += W_o^T diag(m) col e_(b,d)^T ... : adds the masked column (b, d) of a
 * child's matrix, `column`, to the coarse matrix k through W_o on both sides. */
SNH_FN void galerkin_add_column(const real* w, const real* m, int b, int d, const real* column, real* k) {
  real t[MG_DOFS];
  for (int i = 0; i < MG_DOFS; ++i) t[i] = SNH_R(0);
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i) {
      const real v = m[3 * a + i] * column[3 * a + i];
      for (int corner = 0; corner < 8; ++corner)
        if (w[8 * a + corner] != SNH_R(0)) t[3 * corner + i] += w[8 * a + corner] * v;
    }
  const real scale = m[3 * b + d];
  for (int corner = 0; corner < 8; ++corner) {
    const real wb = scale * w[8 * b + corner];
    if (wb == SNH_R(0)) continue;
    real* out = k + MG_DOFS * (3 * corner + d);
    for (int i = 0; i < MG_DOFS; ++i) out[i] += wb * t[i];
  }
}

SNH_FN void child_weights_and_mask(SNH_GLOBAL const real* octant_weights, int o, SNH_GLOBAL const int* nodes,
                                   SNH_GLOBAL const real* mask, real* w, real* m) {
  for (int i = 0; i < 64; ++i) w[i] = octant_weights[64 * o + i];
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i) m[3 * a + i] = mask[3 * nodes[a] + i];
}

/* First coarse level from the fine linearization cache (the product
 * variants that keep no element matrices): each child's stiffness
 * K = sum_q w_q B_q^T H_q B_q column by column, H as the cache holds it
 * (projected or true), so that the coarse operator is the Galerkin product of
 * the very operator CG solves with. */
__kernel void snh_galerkin_from_cache(__global const real* octant_weights, __global const int* children,
                                      __global const int* fine_elements, __global const real* gradients,
                                      __global const real* weights, __global const real* cache,
                                      __global const real* fine_mask, const int count, __global real* out,
                                      __global real* blocks) {
  const int c = get_global_id(0);
  if (c >= count) return;
  real k[MG_DOFS * MG_DOFS];
  for (int i = 0; i < MG_DOFS * MG_DOFS; ++i) k[i] = SNH_R(0);
  for (int o = 0; o < 8; ++o) {
    const int e = children[8 * c + o];
    if (e < 0) continue;
    real w[64], m[MG_DOFS];
    element_linearization l;
    child_weights_and_mask(octant_weights, o, fine_elements + 8 * e, fine_mask, w, m);
    element_linearization_load(gradients, weights, cache, e, &l);
    for (int b = 0; b < 8; ++b)
      for (int d = 0; d < 3; ++d) {
        if (m[3 * b + d] == SNH_R(0)) continue;
        real column[MG_DOFS];
        element_stiffness_column(&l, b, d, column);
        galerkin_add_column(w, m, b, d, column, k);
      }
  }
  /* Its lower triangle, mirrored: exactly symmetric (as in
   * snh_galerkin_from_matrices below). */
  __global real* dst = out + (size_t)MG_DOFS * MG_DOFS * c;
  for (int col = 0; col < MG_DOFS; ++col)
    for (int row = 0; row < MG_DOFS; ++row)
      dst[MG_DOFS * col + row] = row >= col ? k[MG_DOFS * col + row] : k[MG_DOFS * row + col];
  for (int b = 0; b < 8; ++b)
    for (int d = 0; d < 3; ++d)
      for (int i = 0; i < 3; ++i)
        blocks[(size_t)72 * c + 9 * b + 3 * d + i] =
            i >= d ? k[MG_DOFS * (3 * b + d) + 3 * b + i] : k[MG_DOFS * (3 * b + i) + 3 * b + d];
}

#if SNH_DOUBLE
typedef double8 corners8;
#else
typedef float8 corners8;
#endif

/* Next coarser level from a level's element matrices (also the first, from
 * the fine element matrices when the product variant keeps them). One
 * work-item per coarse cell, its 8 corners B in the lanes of one vector:
 * K_C = sum_children W_o^T D K_child D W_o column by column (B, d), the
 * weights W_o[b][B] of a fine node b one contiguous row of the table. The
 * second product skips W_o's zero weights (37 of each child's 64
 * node-corner pairs), the same in every lane; missing children and
 * constrained DOFs multiply by 0. Per fine node a the first product's three
 * rows are formed, in three named vectors, and at once spread by the second
 * (the same sums in the same order as forming a column's 24
 * rows first into an indexed array, which pocl kept in memory with a load
 * and a store per term). Measured faster on pocl than that array and than
 * one scalar work-item per coarse column skipping zeros in both products,
 * which pocl ran one by one (docs/performance.md, "Galerkin products on the
 * device"). */
__kernel void snh_galerkin_from_matrices(__global const real* octant_weights, __global const int* children,
                                         __global const int* fine_elements, __global const matrix_real* fine_matrices,
                                         __global const real* fine_mask, const int count, __global real* out,
                                         __global real* blocks) {
  const int c = get_global_id(0);
  if (c >= count) return;
  corners8 k[3 * MG_DOFS]; /* [MG_DOFS d + row]: entry (row, (B, d)) in lane B */
  for (int i = 0; i < 3 * MG_DOFS; ++i) k[i] = (corners8)(SNH_R(0));
  for (int o = 0; o < 8; ++o) {
    const int child = children[8 * c + o];
    const real alive = child < 0 ? SNH_R(0) : SNH_R(1);
    const int e = child < 0 ? 0 : child;
    SNH_GLOBAL const int* nodes = fine_elements + 8 * e;
    __global const matrix_real* ke = fine_matrices + (size_t)MG_DOFS * MG_DOFS * e;
    __global const real* w = octant_weights + 64 * o;
    real m[MG_DOFS];
    for (int a = 0; a < 8; ++a)
      for (int i = 0; i < 3; ++i) m[3 * a + i] = alive * fine_mask[3 * nodes[a] + i];
    for (int d = 0; d < 3; ++d) {
      corners8 wb[8]; /* D W_o[b][.] for column component d */
      for (int b = 0; b < 8; ++b) wb[b] = vload8(b, w) * m[3 * b + d];
      corners8* column = k + MG_DOFS * d;
      for (int a = 0; a < 8; ++a) {
        /* rows (a, .) of D K_child D W_o e_(B,d) for every B: the child's
         * columns (b, d) times the weight rows, summed over b */
        corners8 right0 = (corners8)(SNH_R(0)), right1 = right0, right2 = right0;
        SNH_UNROLL
        for (int b = 0; b < 8; ++b) {
          __global const matrix_real* kb = ke + MG_DOFS * (3 * b + d) + 3 * a;
          right0 += wb[b] * (real)kb[0];
          right1 += wb[b] * (real)kb[1];
          right2 += wb[b] * (real)kb[2];
        }
        /* columns (., d) += W_o^T D right */
        const corners8 v0 = m[3 * a] * right0, v1 = m[3 * a + 1] * right1, v2 = m[3 * a + 2] * right2;
        for (int corner = 0; corner < 8; ++corner) {
          const real wa = w[8 * a + corner];
          if (wa != SNH_R(0)) {
            column[3 * corner] += wa * v0;
            column[3 * corner + 1] += wa * v1;
            column[3 * corner + 2] += wa * v2;
          }
        }
      }
    }
  }
  /* entry (row, (B, d)) at 8 (MG_DOFS d + row) + B; written from the lower
   * triangle (row >= 3 B + d), each entry above it as its mirror: K_C is
   * symmetric, and so stored exactly (the rounding of the two triangles'
   * sums differs), so that the coarse stencils, their smoothers and the
   * coarsest factor see one symmetric operator. */
  const real* flat = (const real*)k;
  __global real* dst = out + (size_t)MG_DOFS * MG_DOFS * c;
  for (int corner_b = 0; corner_b < 8; ++corner_b)
    for (int d = 0; d < 3; ++d) {
      const int col = 3 * corner_b + d;
      for (int row = 0; row < MG_DOFS; ++row)
        dst[MG_DOFS * col + row] =
            row >= col ? flat[8 * (MG_DOFS * d + row) + corner_b] : flat[8 * (MG_DOFS * (row % 3) + col) + row / 3];
      for (int i = 0; i < 3; ++i)
        blocks[(size_t)72 * c + 9 * corner_b + 3 * d + i] =
            i >= d ? flat[8 * (MG_DOFS * d + 3 * corner_b + i) + corner_b] : flat[8 * (MG_DOFS * i + col) + corner_b];
    }
}

#if SNH_INERTIA || SNH_OBSTACLES || SNH_SELF_BARRIER
/* The fine operator's per-vertex terms on the first coarse level. The fine
 * Hessian is s K + sum_v B_v (s: implicit Euler's elastic scale; B_v the
 * vertex's 3x3 block, c_v I for inertia plus its obstacle contact and
 * friction blocks). Each B_v is shared out equally to the fine cells around
 * v (share[v] = 1 / their count), so that P^T D (sum_v B_v) D P is a sum over
 * coarse cells of W_o^T (D B_a share D) W_o over children and their nodes a,
 * like the elastic part. This kernel scales a cell's elastic Galerkin matrix
 * (from either kernel above) by s, adds those terms, and rewrites the cell's
 * diagonal blocks. Barrier self-contact adds W^T H W to the fine Hessian:
 * its diagonal blocks join B_v; its couplings, between vertices of cells far
 * apart that no coarse cell holds, are left out (the coarse operators stay
 * PSD: the diagonal blocks of a PSD matrix are). */
__kernel void snh_galerkin_vertex_terms(__global const real* octant_weights, __global const int* children,
                                        __global const int* fine_elements, __global const real* share,
                                        __global const real* fine_mask, const int count, const real elastic_scale,
#if SNH_INERTIA
                                        __global const real* inertia,
#endif
#if SNH_OBSTACLES
                                        __global const real* contact_blocks,
#endif
#if SNH_SELF_BARRIER
                                        __global const real* barrier_diagonal,
#endif
                                        __global real* out, __global real* blocks) {
  const int c = get_global_id(0);
  if (c >= count) return;
  __global real* k = out + (size_t)MG_DOFS * MG_DOFS * c;
  for (int i = 0; i < MG_DOFS * MG_DOFS; ++i) k[i] *= elastic_scale;
  for (int o = 0; o < 8; ++o) {
    const int e = children[8 * c + o];
    if (e < 0) continue;
    real w[64], m[MG_DOFS];
    child_weights_and_mask(octant_weights, o, fine_elements + 8 * e, fine_mask, w, m);
    for (int a = 0; a < 8; ++a) {
      const int v = fine_elements[8 * e + a];
      real b[9];
      for (int i = 0; i < 9; ++i) b[i] = SNH_R(0);
#if SNH_INERTIA
      for (int d = 0; d < 3; ++d) b[4 * d] += inertia[v];
#endif
#if SNH_OBSTACLES
      for (int i = 0; i < 9; ++i) b[i] += contact_blocks[9 * v + i];
#endif
#if SNH_SELF_BARRIER
      /* row-major and symmetric (solver/contact/barrier_terms.h): either order */
      for (int i = 0; i < 9; ++i) b[i] += barrier_diagonal[9 * v + i];
#endif
      /* b(i, j) column-major (as the model's 3x3 blocks), masked on both sides */
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) b[3 * j + i] *= share[v] * m[3 * a + i] * m[3 * a + j];
      for (int cj = 0; cj < 8; ++cj) {
        const real wj = w[8 * a + cj];
        for (int ci = 0; ci < 8; ++ci) {
          const real wij = w[8 * a + ci] * wj;
          for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) k[MG_DOFS * (3 * cj + j) + 3 * ci + i] += wij * b[3 * j + i];
        }
      }
    }
  }
  /* The contact and friction blocks are symmetric to rounding: the lower
   * triangle mirrored again, as the Galerkin kernels store it. */
  for (int col = 0; col < MG_DOFS; ++col)
    for (int row = col + 1; row < MG_DOFS; ++row) k[MG_DOFS * row + col] = k[MG_DOFS * col + row];
  for (int b = 0; b < 8; ++b)
    for (int d = 0; d < 3; ++d)
      for (int i = 0; i < 3; ++i) blocks[(size_t)72 * c + 9 * b + 3 * d + i] = k[MG_DOFS * (3 * b + d) + 3 * b + i];
}
#endif

/* A level's operator assembled per vertex: its 3x3 blocks against each
 * vertex that shares a cell with it (27 on a box; more where a slit leaves
 * two vertices at one lattice point), `width` per vertex: block s of vertex v
 * couples it to n = neighbours[width v + s] (s = 0: v itself; padding: v
 * again, with a zero block) and holds A(3 v + i, 3 n + j) at
 * stencil[9 (width v + s) + 3 j + i]. The same operator as the level's cell
 * matrices and gather, read as about a third of the bytes (27 blocks a
 * vertex against 8 cells' 64 blocks of which each vertex owns 8) and without
 * the per-cell scratch. (Vertex-minor blocks, [(9 s + 3 j + i) count + v],
 * measured slower on pocl: 243 streams at once; docs/performance.md, "Block
 * stencil layout".) On CPUs the blocks
 * are in the upper layout (kernels/fem/block_stencil.h): 14 stored a
 * vertex on a box, the other 13 read as their mirrors' transposes. */

/* Chebyshev smoothing over block-Jacobi (Levels::chebyshev in host/solver/multigrid/multigrid.cpp,
 * the recurrence of solver/linear/chebyshev.h) in one pass per degree on the
 * assembled levels. Start: d = c Dinv r, x += beta d (x = beta d with
 * accumulate 0: smoothing from x = 0, r = b, reading b for r). Step:
 * r = base - A d (base: r, or b the first time from x = 0),
 * d_next = c_d d + c_z Dinv r, x += beta d_next (d_next a separate buffer:
 * the neighbours read d). Dinv: 3x3 column-major blocks per vertex
 * (snh_block_jacobi_setup's). The step reads the level's stencil: it is
 * stencil.cl's, built with the stencil's width as the other stencil kernels
 * are, so that this program is built once. */

/* Also z = Dinv z for the power iterations (c = beta = 1, accumulate 0, x
 * and r the same buffer: each work-item reads its r before writing). */
__kernel void snh_chebyshev_start(__global const real* inverse, __global const real* r, const real c, const real beta,
                                  const int count, const int accumulate, __global real* d, __global real* x) {
  const int v = get_global_id(0);
  if (v >= count) return;
  real rv[3], z[3];
  for (int i = 0; i < 3; ++i) rv[i] = r[3 * v + i];
  block_inverse_apply(inverse, v, rv, z);
  for (int i = 0; i < 3; ++i) {
    const real dv = c * z[i];
    d[3 * v + i] = dv;
    x[3 * v + i] = accumulate ? x[3 * v + i] + beta * dv : beta * dv;
  }
}

/* fine += mask * P coarse: 8 (coarse vertex, weight) pairs per fine vertex. */
__kernel void snh_prolong_add(__global const real* coarse, __global const int* vertices, __global const real* weights,
                              __global const real* mask, const int count, __global real* fine) {
  const int v = get_global_id(0);
  if (v >= count) return;
  real s0 = SNH_R(0), s1 = SNH_R(0), s2 = SNH_R(0);
  for (int k = 0; k < 8; ++k) {
    const int c = vertices[8 * v + k];
    const real w = weights[8 * v + k];
    s0 += w * coarse[3 * c];
    s1 += w * coarse[3 * c + 1];
    s2 += w * coarse[3 * c + 2];
  }
  fine[3 * v] += mask[3 * v] * s0;
  fine[3 * v + 1] += mask[3 * v + 1] * s1;
  fine[3 * v + 2] += mask[3 * v + 2] * s2;
}

/* coarse = coarse_mask * P^T (fine_mask * fine): per coarse vertex, its fine
 * vertices and weights between offsets[c] and offsets[c + 1], in increasing
 * fine order (deterministic sums). */
__kernel void snh_restrict(__global const real* fine, __global const real* fine_mask, __global const int* offsets,
                           __global const int* vertices, __global const real* weights, __global const real* coarse_mask,
                           const int count, __global real* coarse) {
  const int c = get_global_id(0);
  if (c >= count) return;
  real s0 = SNH_R(0), s1 = SNH_R(0), s2 = SNH_R(0);
  for (int k = offsets[c]; k < offsets[c + 1]; ++k) {
    const int v = vertices[k];
    const real w = weights[k];
    s0 += w * fine_mask[3 * v] * fine[3 * v];
    s1 += w * fine_mask[3 * v + 1] * fine[3 * v + 1];
    s2 += w * fine_mask[3 * v + 2] * fine[3 * v + 2];
  }
  coarse[3 * c] = coarse_mask[3 * c] * s0;
  coarse[3 * c + 1] = coarse_mask[3 * c + 1] * s1;
  coarse[3 * c + 2] = coarse_mask[3 * c + 2] * s2;
}
