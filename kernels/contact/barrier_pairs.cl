/* Barrier self-contact on the device (solver/contact/barrier_terms.h): the narrow
 * phase of Li et al. 2020, "Incremental Potential Contact", per candidate
 * pair, and its deterministic reductions.
 *
 * Pairs come as int4 vertex lists (surface vertex indices), a kind (0
 * point-triangle, 1 edge-edge) and the edge-edge mollifier's threshold.
 * Surface positions are W x: `carriers` lattice vertices and weights per
 * surface vertex (8 for an embedded surface, 1 with weight 1 for the mesh's
 * own boundary). Per pair: the squared distance, the barrier b, its
 * gradient (12) and its Hessian (12 x 12) projected to PSD by the cyclic
 * Jacobi method (psd_jacobi.h), all by the same headers as the host
 * reference (solver/contact/barrier_contact.cpp).
 *
 * No atomics anywhere. Per-vertex sums run through index lists built on the
 * host in pair order (a CSR of pair incidences, per surface vertex; a CSR of
 * the pairs' 3 x 3 blocks, per surface vertex pair; the transpose of W, per
 * lattice vertex): each work-item sums its own entries in list order. The
 * energy is summed span by span in index order, then the spans in order.
 * The same pairs give the same bits on every run.
 *
 * The pair math runs in double wherever the device has cl_khr_fp64, also in
 * a float solve (as the host reference does); what the solver's vectors
 * read (the force, the blocks, the diagonal) is stored in the build's
 * precision, store_real. */
#if SNH_DOUBLE
typedef double store_real;
#else
typedef float store_real;
#endif
#if defined(cl_khr_fp64) && !SNH_DOUBLE
#undef SNH_DOUBLE
#define SNH_DOUBLE 1
#endif
#include "contact/ccd.h"
#include "contact/ipc_barrier.h"
#include "contact/psd_jacobi.h"
#include "snh_portable.h"

/* Entries per span of the fixed-order energy and minimum. */
#define SNH_BARRIER_SPAN 256

/* The 12 coordinates of a pair's vertices. */
SNH_FN void barrier_gather(__global const real* q, const int4 v, real* out) {
  const int at[4] = {v.x, v.y, v.z, v.w};
  for (int i = 0; i < 4; ++i)
    for (int d = 0; d < 3; ++d) out[3 * i + d] = q[3 * at[i] + d];
}

/* q = W x, as the host's lift: per coordinate, weights in carrier order. */
__kernel void snh_barrier_lift(__global const real* x, __global const int* carrier, __global const real* weight,
                               const int carriers, const int count, __global real* q) {
  const int s = get_global_id(0);
  if (s >= count) return;
  for (int d = 0; d < 3; ++d) {
    real sum = SNH_R(0);
    for (int k = 0; k < carriers; ++k) sum += weight[carriers * s + k] * x[3 * carrier[carriers * s + k] + d];
    q[3 * s + d] = sum;
  }
}

/* The same from x in the solver's precision (the device's own positions,
 * never read back): each coordinate widened, then summed as above. */
__kernel void snh_barrier_lift_store(__global const store_real* x, __global const int* carrier,
                                     __global const real* weight, const int carriers, const int count,
                                     __global real* q) {
  const int s = get_global_id(0);
  if (s >= count) return;
  for (int d = 0; d < 3; ++d) {
    real sum = SNH_R(0);
    for (int k = 0; k < carriers; ++k) sum += weight[carriers * s + k] * (real)x[3 * carrier[carriers * s + k] + d];
    q[3 * s + d] = sum;
  }
}

/* 1 where x and the copy it is compared with differ (the lists built at
 * that copy hold for x where none does). */
__kernel void snh_barrier_differs(__global const store_real* x, __global const store_real* copy, const int count,
                                  __global int* differs) {
  const int i = get_global_id(0);
  if (i >= count) return;
  differs[i] = x[i] != copy[i] ? 1 : 0;
}

/* Per pair at q: energy b (without kappa) and squared distance, by the
 * distance alone (no derivatives): the energy's and the filter's pass over
 * every candidate. The same functions, so the same values as the terms
 * below and the host's ipc_*_potential. */
__kernel void snh_barrier_pair_energy(__global const real* q, __global const int4* vertex, __global const int* kind,
                                      __global const real* ex, const int count, const real sh, __global real* energy,
                                      __global real* distance) {
  const int i = get_global_id(0);
  if (i >= count) return;
  real y[12];
  int type;
  barrier_gather(q, vertex[i], y);
  real s, e;
  if (kind[i] == 0) {
    s = ipc_pt_distance(y, &type, 0, 0);
    e = ipc_barrier(s, sh);
  } else {
    s = ipc_ee_distance(y, &type, 0, 0);
    e = ipc_mollifier(ipc_edge_cross_squared(y, 0, 0), ex[i]) * ipc_barrier(s, sh);
  }
  energy[i] = e;
  distance[i] = s;
}

/* Per pair within dhat at q: the gradient (12 per pair) and, with
 * `hessian` set, the projected Hessian (144 per pair, row-major). */
__kernel void snh_barrier_pair_terms(__global const real* q, __global const int4* vertex, __global const int* kind,
                                     __global const real* ex, const int count, const real sh, const int hessian,
                                     __global real* gradient, __global real* projected) {
  const int i = get_global_id(0);
  if (i >= count) return;
  real y[12], g[12], h[144], s;
  barrier_gather(q, vertex[i], y);
  if (kind[i] == 0)
    ipc_pt_potential(y, sh, &s, g, h);
  else
    ipc_ee_potential(y, sh, ex[i], &s, g, h);
  for (int k = 0; k < 12; ++k) gradient[12 * i + k] = g[k];
  if (!hessian) return;
  if (s < sh) psd_project12(h); /* beyond dhat b and its derivatives are 0 */
  for (int k = 0; k < 144; ++k) projected[144 * i + k] = h[k];
}

/* Span g's energy sum, smallest squared distance (from sh) and count of
 * pairs within dhat, in index order. */
__kernel void snh_barrier_partials(__global const real* energy, __global const real* distance, const int count,
                                   const real sh, __global real* partial) {
  const int g = get_global_id(0);
  const int begin = g * SNH_BARRIER_SPAN;
  if (begin >= count) return;
  const int end = min(begin + SNH_BARRIER_SPAN, count);
  real e = SNH_R(0), m = sh, active = SNH_R(0);
  for (int i = begin; i < end; ++i) {
    e += energy[i];
    m = distance[i] < m ? distance[i] : m;
    active += distance[i] < sh ? SNH_R(1) : SNH_R(0);
  }
  partial[3 * g] = e;
  partial[3 * g + 1] = m;
  partial[3 * g + 2] = active;
}

/* One work-item: the spans in order (total: energy, min distance^2, count). */
__kernel void snh_barrier_total(__global const real* partial, const int spans, const real sh, __global real* total) {
  if (get_global_id(0) != 0) return;
  real e = SNH_R(0), m = sh, active = SNH_R(0);
  for (int g = 0; g < spans; ++g) {
    e += partial[3 * g];
    m = partial[3 * g + 1] < m ? partial[3 * g + 1] : m;
    active += partial[3 * g + 2];
  }
  total[0] = e;
  total[1] = m;
  total[2] = active;
}

/* gs = kappa sum of the pair gradients' rows at surface vertex s, over its
 * incidences (pair * 4 + corner) in pair order. */
__kernel void snh_barrier_surface_gradient(__global const real* gradient, __global const int* offsets,
                                           __global const int* incidence, const int count, const real kappa,
                                           __global real* gs) {
  const int s = get_global_id(0);
  if (s >= count) return;
  real g0 = SNH_R(0), g1 = SNH_R(0), g2 = SNH_R(0);
  for (int k = offsets[s]; k < offsets[s + 1]; ++k) {
    __global const real* row = gradient + 3 * incidence[k];
    g0 += kappa * row[0];
    g1 += kappa * row[1];
    g2 += kappa * row[2];
  }
  gs[3 * s] = g0;
  gs[3 * s + 1] = g1;
  gs[3 * s + 2] = g2;
}

/* r -= mask .* W^T gs: lattice vertex v sums its surface entries
 * (s * carriers + k, ascending) of the transpose of W. */
__kernel void snh_barrier_force(__global const real* gs, __global const int* offsets, __global const int* entries,
                                __global const real* weight, const int carriers, const int count,
                                __global const store_real* mask, __global store_real* r) {
  const int v = get_global_id(0);
  if (v >= count) return;
  real f0 = SNH_R(0), f1 = SNH_R(0), f2 = SNH_R(0);
  for (int k = offsets[v]; k < offsets[v + 1]; ++k) {
    const int e = entries[k], s = e / carriers;
    f0 += weight[e] * gs[3 * s];
    f1 += weight[e] * gs[3 * s + 1];
    f2 += weight[e] * gs[3 * s + 2];
  }
  r[3 * v] -= mask[3 * v] * (store_real)f0;
  r[3 * v + 1] -= mask[3 * v + 1] * (store_real)f1;
  r[3 * v + 2] -= mask[3 * v + 2] * (store_real)f2;
}

/* The surface block b (a surface vertex pair): kappa times the sum of its
 * contributions (pair * 16 + 4 row corner + column corner) in pair order. */
__kernel void snh_barrier_surface_blocks(__global const real* hessian, __global const int* offsets,
                                         __global const int* contributions, const int count, const real kappa,
                                         __global store_real* blocks) {
  const int b = get_global_id(0);
  if (b >= count) return;
  real sum[9];
  for (int i = 0; i < 9; ++i) sum[i] = SNH_R(0);
  for (int k = offsets[b]; k < offsets[b + 1]; ++k) {
    const int c = contributions[k], pair = c / 16, v = (c / 4) % 4, w = c % 4;
    __global const real* h = hessian + 144 * pair;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) sum[3 * i + j] += kappa * h[12 * (3 * v + i) + 3 * w + j];
  }
  for (int i = 0; i < 9; ++i) blocks[9 * b + i] = (store_real)sum[i];
}

/* Block-Jacobi's part: the diagonal block of W^T H W at lattice vertex v,
 * sum over (s, k) carried by v, surface blocks (s, c) and corners l of c
 * carried by v of w_sk w_cl H_sc, in that order. */
__kernel void snh_barrier_diagonal(__global const int* rows, __global const int* columns,
                                   __global const store_real* blocks, __global const int* offsets,
                                   __global const int* entries, __global const int* carrier,
                                   __global const real* weight, const int carriers, const int count,
                                   __global store_real* diagonal) {
  const int v = get_global_id(0);
  if (v >= count) return;
  real sum[9];
  for (int i = 0; i < 9; ++i) sum[i] = SNH_R(0);
  for (int k = offsets[v]; k < offsets[v + 1]; ++k) {
    const int e = entries[k], s = e / carriers;
    for (int b = rows[s]; b < rows[s + 1]; ++b) {
      const int c = columns[b];
      for (int l = 0; l < carriers; ++l) {
        if (carrier[carriers * c + l] != v) continue;
        const real scale = weight[e] * weight[carriers * c + l];
        for (int i = 0; i < 9; ++i) sum[i] += scale * (real)blocks[9 * b + i];
      }
    }
  }
  for (int i = 0; i < 9; ++i) diagonal[9 * v + i] = (store_real)sum[i];
}

/* The product y += mask .* W^T H W (mask .* p), in the build's precision:
 * z = H W (mask .* p) per surface vertex (block CSR, columns ascending;
 * column t's W (mask .* p) gathered from its carriers), then y += mask .*
 * W^T z per lattice vertex. With one carrier of weight 1 (the mesh's own
 * boundary, W = I) the first pass adds to y itself: one launch. */
__kernel void snh_barrier_surface_product(__global const int* rows, __global const int* columns,
                                          __global const store_real* blocks, __global const int* carrier,
                                          __global const store_real* weight, const int carriers, const int count,
                                          __global const store_real* mask, __global const store_real* p,
                                          __global store_real* z, __global store_real* y) {
  const int s = get_global_id(0);
  if (s >= count) return;
  store_real s0 = 0, s1 = 0, s2 = 0;
  for (int k = rows[s]; k < rows[s + 1]; ++k) {
    const int t = columns[k];
    store_real q0 = 0, q1 = 0, q2 = 0;
    for (int l = 0; l < carriers; ++l) {
      const int c = 3 * carrier[carriers * t + l];
      const store_real w = weight[carriers * t + l];
      q0 += w * (mask[c] * p[c]);
      q1 += w * (mask[c + 1] * p[c + 1]);
      q2 += w * (mask[c + 2] * p[c + 2]);
    }
    __global const store_real* b = blocks + 9 * k;
    s0 += b[0] * q0 + b[1] * q1 + b[2] * q2;
    s1 += b[3] * q0 + b[4] * q1 + b[5] * q2;
    s2 += b[6] * q0 + b[7] * q1 + b[8] * q2;
  }
  if (carriers == 1) {
    y[3 * s] += mask[3 * s] * s0;
    y[3 * s + 1] += mask[3 * s + 1] * s1;
    y[3 * s + 2] += mask[3 * s + 2] * s2;
    return;
  }
  z[3 * s] = s0;
  z[3 * s + 1] = s1;
  z[3 * s + 2] = s2;
}

__kernel void snh_barrier_spread_product(__global const store_real* z, __global const int* offsets,
                                         __global const int* entries, __global const store_real* weight,
                                         const int carriers, const int count, __global const store_real* mask,
                                         __global store_real* y) {
  const int v = get_global_id(0);
  if (v >= count) return;
  store_real y0 = 0, y1 = 0, y2 = 0;
  for (int k = offsets[v]; k < offsets[v + 1]; ++k) {
    const int e = entries[k], s = e / carriers;
    y0 += weight[e] * z[3 * s];
    y1 += weight[e] * z[3 * s + 1];
    y2 += weight[e] * z[3 * s + 2];
  }
  y[3 * v] += mask[3 * v] * y0;
  y[3 * v + 1] += mask[3 * v + 1] * y1;
  y[3 * v + 2] += mask[3 * v + 2] * y2;
}

/* CCD: pair i's additive-CCD time of impact along q + t dq over [0, 1]. */
__kernel void snh_barrier_ccd(__global const real* q, __global const real* dq, __global const int4* vertex,
                              __global const int* kind, const int count, __global real* toi) {
  const int i = get_global_id(0);
  if (i >= count) return;
  real y[12], dy[12];
  barrier_gather(q, vertex[i], y);
  barrier_gather(dq, vertex[i], dy);
  toi[i] = ccd_additive(y, dy, kind[i], SNH_R(1));
}

/* The smallest time of impact: per span, then (one work-item) over spans;
 * a minimum, so the result does not depend on the order either way. */
__kernel void snh_barrier_min_partials(__global const real* values, const int count, __global real* partial) {
  const int g = get_global_id(0);
  const int begin = g * SNH_BARRIER_SPAN;
  if (begin >= count) return;
  const int end = min(begin + SNH_BARRIER_SPAN, count);
  real m = SNH_R(1);
  for (int i = begin; i < end; ++i) m = values[i] < m ? values[i] : m;
  partial[g] = m;
}

__kernel void snh_barrier_min_total(__global const real* partial, const int spans, __global real* total) {
  if (get_global_id(0) != 0) return;
  real m = SNH_R(1);
  for (int g = 0; g < spans; ++g) m = partial[g] < m ? partial[g] : m;
  total[0] = m;
}
