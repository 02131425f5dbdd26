/* The per-point kernels of fem.cl for CPU devices (the linearization, the
 * cached and recompute products, the element matrices, the block-Jacobi
 * blocks), written over lanes:
 * built with SNH_LANES = 8 or 16 (snh_portable.h), so `real` holds 8 or 16
 * points: the 8 quadrature points of one or two hex8 elements (a work-item
 * per element or per two, each element's points in 8 consecutive lanes, its
 * part) or the one point of 8 or 16 consecutive tet4 elements (a work-item
 * per 8 or 16 elements); lanes past the last element repeat it and store
 * nothing. The SVD, the material and the eigen-projection run as 8- or
 * 16-wide SIMD. 16 lanes in double are two independent AVX-512 vectors, whose
 * chains of dependent square roots and divisions fill each other's latency
 * (PointLanes::default_material_lanes: the linearization and recompute
 * product; the kernels that read the cache measured no faster, or slower,
 * at 16 and are built at 8). pocl's
 * work-item vectorizer leaves the scalar kernels' per-point math scalar (its
 * program build SLP-vectorizes the straight-line SVD into 2-wide pieces the
 * loop vectorizer cannot widen; docs/performance.md), so on a CPU these
 * kernels vectorize the math by construction instead. The math is the same
 * source as the scalar kernels and the host reference; with FP_CONTRACT off
 * and correctly rounded division and sqrt, each lane computes bit for bit
 * what the scalar kernel computes at that point, apart from exp, whose
 * vector and scalar versions may round differently
 * (tests/test_point_lanes.cpp).
 *
 * Same names, arguments and outputs as fem.cl's kernels: the host picks the
 * program and the launch (PointLanes::set_point_lanes). Built with the
 * same specialization defines as fem.cl (SNH_MODEL, SNH_BARRIER,
 * SNH_NONLINEAR, SNH_REGIONS, ...); tet4 lanes and 16 hex8 lanes hold
 * different elements, so they need one material for the mesh (no
 * SNH_REGIONS). */
#include "fem/element.h"
#include "materials/kernel_args.h"

#if (SNH_LANES != 8 && SNH_LANES != 16) || ((!SNH_HEX8 || SNH_LANES > 8) && SNH_REGIONS)
#error "fem_lanes.cl: SNH_LANES = 8 or 16, and tet4 or 16 lanes only without SNH_REGIONS (a material per work-item)"
#endif
#if SNH_CACHE_TILE != 1
#error "fem_lanes.cl: the value-major or point-major cache, not the tiled one (SNH_CACHE_TILE)"
#endif

#if SNH_UNIFORM_REST
#define REST_ELEMENT(e) 0
#else
#define REST_ELEMENT(e) (e)
#endif

/* Lane l of v (a private real). */
#define LANE(v, l) (((scalar_real*)&(v))[l])

#if SNH_HEX8
#if SNH_DOUBLE
typedef double8 lanes8;
typedef ulong8 lanes_shuffle;
#else
typedef float8 lanes8;
typedef uint8 lanes_shuffle;
#endif
/* A hex8 work-item's elements: SNH_LANES / 8, an element's points in 8
 * consecutive lanes (its part). */
#define SNH_LANE_ELEMENTS (SNH_LANES / 8)

/* Lane k: the sum of v[k]'s 8 lanes, in lane order ((v.s0 + v.s1) + v.s2)
 * + ... (the scalar kernels' order over the points, so bit for bit theirs),
 * for k = 0..7 at once: the 8 x 8 block transposed in three rounds of
 * shuffles (24 in all), then 7 vector additions, instead of 56 lane
 * extractions and additions one at a time. */
SNH_FN lanes8 lanes_sum8(const lanes8* v) {
  const lanes_shuffle even = (lanes_shuffle)(0, 8, 2, 10, 4, 12, 6, 14),
                      odd = (lanes_shuffle)(1, 9, 3, 11, 5, 13, 7, 15);
  const lanes_shuffle low2 = (lanes_shuffle)(0, 1, 8, 9, 4, 5, 12, 13),
                      high2 = (lanes_shuffle)(2, 3, 10, 11, 6, 7, 14, 15);
  const lanes_shuffle low4 = (lanes_shuffle)(0, 1, 2, 3, 8, 9, 10, 11),
                      high4 = (lanes_shuffle)(4, 5, 6, 7, 12, 13, 14, 15);
  lanes8 b[8], c[8], t[8];
  for (int k = 0; k < 8; k += 2) {
    b[k] = shuffle2(v[k], v[k + 1], even);    /* lanes 0, 2, 4, 6 of v[k] and v[k + 1], interleaved */
    b[k + 1] = shuffle2(v[k], v[k + 1], odd); /* lanes 1, 3, 5, 7 */
  }
  for (int k = 0; k < 8; k += 4)
    for (int j = 0; j < 2; ++j) {
      c[k + j] = shuffle2(b[k + j], b[k + j + 2], low2);      /* lanes j, j + 4 of v[k..k+3] */
      c[k + j + 2] = shuffle2(b[k + j], b[k + j + 2], high2); /* lanes j + 2, j + 6 */
    }
  for (int j = 0; j < 4; ++j) {
    t[j] = shuffle2(c[j], c[j + 4], low4);      /* lane j of v[0..7] */
    t[j + 4] = shuffle2(c[j], c[j + 4], high4); /* lane j + 4 */
  }
  lanes8 sum = t[0];
  for (int q = 1; q < 8; ++q) sum += t[q];
  return sum;
}
#endif

#if SNH_HEX8
/* Part k of a real: the 8 lanes of the work-item's k-th element. */
#define LANES_PART(v, k) (((lanes8*)&(v))[k])

/* The element of part k of work-item w (the last one past the end). */
SNH_FN size_t lanes_element(size_t w, int k, int count) {
  return min((size_t)SNH_LANE_ELEMENTS * w + k, (size_t)count - 1);
}

/* Node values, the same in every lane of a part. */
SNH_FN void lanes_load_nodes(__global const vector_real* x, __global const int* elements, size_t w, int count,
                             real* xs) {
  SNH_UNROLL
  for (int k = 0; k < SNH_LANE_ELEMENTS; ++k) {
    __global const int* nodes = elements + SNH_NODES * lanes_element(w, k, count);
    SNH_UNROLL
    for (int a = 0; a < SNH_NODES; ++a) {
      SNH_UNROLL
      for (int i = 0; i < 3; ++i) LANES_PART(xs[3 * a + i], k) = (lanes8)((scalar_real)x[3 * nodes[a] + i]);
    }
  }
}

/* Rest gradients: lane q of a part holds point q's (layout [element][3 a +
 * j][q]: one vector per value; point by point, 192 lane inserts per
 * element, measured slower: docs/performance.md, "Lanes kernels' loads and
 * stores"). With SNH_POINT_MAJOR (element_data.h's [element][q][3 a + j],
 * the GPUs' layout) point by point. */
SNH_FN void lanes_load_gradients(__global const scalar_real* gradients, size_t w, int count, real* g) {
  SNH_UNROLL
  for (int k = 0; k < SNH_LANE_ELEMENTS; ++k) {
    __global const scalar_real* src =
        gradients + (size_t)3 * SNH_NODES * SNH_QUADRATURE * REST_ELEMENT(lanes_element(w, k, count));
#if SNH_POINT_MAJOR
    SNH_UNROLL
    for (int l = 0; l < SNH_QUADRATURE; ++l) {
      SNH_UNROLL
      for (int i = 0; i < 3 * SNH_NODES; ++i) LANE(g[i], 8 * k + l) = src[3 * SNH_NODES * l + i];
    }
#else
    SNH_UNROLL
    for (int i = 0; i < 3 * SNH_NODES; ++i) LANES_PART(g[i], k) = vload8(i, src);
#endif
  }
}

SNH_FN real lanes_load_weights(__global const scalar_real* weights, size_t w, int count) {
  real out;
  SNH_UNROLL
  for (int k = 0; k < SNH_LANE_ELEMENTS; ++k)
    LANES_PART(out, k) = vload8(0, weights + SNH_QUADRATURE * REST_ELEMENT(lanes_element(w, k, count)));
  return out;
}

/* Work-item w's first point and how many lanes it stores. */
#define LANES_FIRST_POINT(w) (SNH_LANES * (w))
#define LANES_STORED(w, count) \
  (SNH_QUADRATURE * (int)min((size_t)SNH_LANE_ELEMENTS, (size_t)(count)-SNH_LANE_ELEMENTS * (w)))
#define LANES_ELEMENT(w) (SNH_LANE_ELEMENTS * (w))
#define LANES_ACTIVE(w, count) (SNH_LANE_ELEMENTS * (w) < (size_t)(count))
#else
/* The element of lane l of work-item w (the last one past the end). */
SNH_FN size_t lanes_element(size_t w, int l, int count) { return min((size_t)SNH_LANES * w + l, (size_t)count - 1); }

SNH_FN void lanes_load_nodes(__global const vector_real* x, __global const int* elements, size_t w, int count,
                             real* xs) {
  SNH_UNROLL
  for (int l = 0; l < SNH_LANES; ++l) {
    __global const int* nodes = elements + SNH_NODES * lanes_element(w, l, count);
    SNH_UNROLL
    for (int a = 0; a < SNH_NODES; ++a) {
      SNH_UNROLL
      for (int i = 0; i < 3; ++i) LANE(xs[3 * a + i], l) = (scalar_real)x[3 * nodes[a] + i];
    }
  }
}

SNH_FN void lanes_load_gradients(__global const scalar_real* gradients, size_t w, int count, real* g) {
  SNH_UNROLL
  for (int l = 0; l < SNH_LANES; ++l) {
    __global const scalar_real* src = gradients + (size_t)3 * SNH_NODES * REST_ELEMENT(lanes_element(w, l, count));
    SNH_UNROLL
    for (int i = 0; i < 3 * SNH_NODES; ++i) LANE(g[i], l) = src[i];
  }
}

SNH_FN real lanes_load_weights(__global const scalar_real* weights, size_t w, int count) {
  real out;
  SNH_UNROLL
  for (int l = 0; l < SNH_LANES; ++l) LANE(out, l) = weights[REST_ELEMENT(lanes_element(w, l, count))];
  return out;
}

#define LANES_FIRST_POINT(w) (SNH_LANES * (w))
#define LANES_STORED(w, count) ((int)min((size_t)SNH_LANES, (size_t)(count)-SNH_LANES * (w)))
#define LANES_ELEMENT(w) (SNH_LANES * (w))
#define LANES_ACTIVE(w, count) (SNH_LANES * (w) < (size_t)(count))
#endif

#if SNH_CACHE_GROUP == 8
/* hex8: an element's 8 points, lane q point q, each cached value of them one
 * vector (element.h's layout, values 8 apart, elements 240 apart); the
 * work-item's elements part by part (lanes / 8 of them stored). */
#define LANES_ELEMENT_CACHE (SNH_LINEARIZATION_SIZE * SNH_CACHE_GROUP)

SNH_FN void lanes_value_store(const real* v, int value, int parts, __global scalar_real* out) {
  SNH_UNROLL
  for (int k = 0; k < SNH_LANE_ELEMENTS; ++k)
    if (k < parts) vstore8(LANES_PART(*v, k), 0, out + LANES_ELEMENT_CACHE * k + SNH_CACHE_STRIDE * value);
}

/* Parts past the stored ones repeat the last. */
SNH_FN real lanes_value_load(__global const scalar_real* in, int value, int parts) {
  real v;
  SNH_UNROLL
  for (int k = 0; k < SNH_LANE_ELEMENTS; ++k)
    LANES_PART(v, k) = vload8(0, in + LANES_ELEMENT_CACHE * min(k, parts - 1) + SNH_CACHE_STRIDE * value);
  return v;
}

SNH_FN void lanes_linearization_store(const principal_hessian* h, int lanes, __global scalar_real* out) {
  const int parts = lanes / SNH_QUADRATURE;
  SNH_UNROLL
  for (int i = 0; i < 9; ++i) lanes_value_store(&h->u.a[i], i, parts, out);
  SNH_UNROLL
  for (int i = 0; i < 9; ++i) lanes_value_store(&h->v.a[i], 9 + i, parts, out);
  SNH_UNROLL
  for (int i = 0; i < 6; ++i) lanes_value_store(&h->block.a[i], 18 + i, parts, out);
  SNH_UNROLL
  for (int i = 0; i < 3; ++i) lanes_value_store(&h->twist.a[i], 24 + i, parts, out);
  SNH_UNROLL
  for (int i = 0; i < 3; ++i) lanes_value_store(&h->flip.a[i], 27 + i, parts, out);
}

SNH_FN principal_hessian lanes_linearization_load(__global const scalar_real* in, int lanes) {
  const int parts = lanes / SNH_QUADRATURE;
  principal_hessian h;
  SNH_UNROLL
  for (int i = 0; i < 9; ++i) h.u.a[i] = lanes_value_load(in, i, parts);
  SNH_UNROLL
  for (int i = 0; i < 9; ++i) h.v.a[i] = lanes_value_load(in, 9 + i, parts);
  SNH_UNROLL
  for (int i = 0; i < 6; ++i) h.block.a[i] = lanes_value_load(in, 18 + i, parts);
  SNH_UNROLL
  for (int i = 0; i < 3; ++i) h.twist.a[i] = lanes_value_load(in, 24 + i, parts);
  SNH_UNROLL
  for (int i = 0; i < 3; ++i) h.flip.a[i] = lanes_value_load(in, 27 + i, parts);
  SNH_UNROLL
  for (int i = 0; i < 3; ++i) h.sigma.a[i] = SNH_R(0);
  return h;
}
#else
/* Point-major cache (tet4; hex8 with SNH_POINT_MAJOR): lanes
 * 0 .. lanes - 1 at out + 30 l, lane by lane
 * (value by value measured slower: docs/performance.md, "Lanes kernels'
 * loads and stores"). */
SNH_FN void lanes_linearization_store(const principal_hessian* h, int lanes, __global scalar_real* out) {
  SNH_UNROLL
  for (int l = 0; l < SNH_LANES; ++l) {
    if (l < lanes) { /* not `break`: a loop with an early exit is not unrolled (pocl warned) */
      __global scalar_real* o = out + SNH_LINEARIZATION_SIZE * l;
      SNH_UNROLL
      for (int i = 0; i < 9; ++i) o[i] = LANE(h->u.a[i], l);
      SNH_UNROLL
      for (int i = 0; i < 9; ++i) o[9 + i] = LANE(h->v.a[i], l);
      SNH_UNROLL
      for (int i = 0; i < 6; ++i) o[18 + i] = LANE(h->block.a[i], l);
      SNH_UNROLL
      for (int i = 0; i < 3; ++i) o[24 + i] = LANE(h->twist.a[i], l);
      SNH_UNROLL
      for (int i = 0; i < 3; ++i) o[27 + i] = LANE(h->flip.a[i], l);
    }
  }
}

/* Lanes 0 .. lanes - 1 from in + 30 l; the lanes past them repeat the last. */
SNH_FN principal_hessian lanes_linearization_load(__global const scalar_real* in, int lanes) {
  principal_hessian h;
  SNH_UNROLL
  for (int l = 0; l < SNH_LANES; ++l) {
    __global const scalar_real* s = in + SNH_LINEARIZATION_SIZE * min(l, lanes - 1);
    SNH_UNROLL
    for (int i = 0; i < 9; ++i) LANE(h.u.a[i], l) = s[i];
    SNH_UNROLL
    for (int i = 0; i < 9; ++i) LANE(h.v.a[i], l) = s[9 + i];
    SNH_UNROLL
    for (int i = 0; i < 6; ++i) LANE(h.block.a[i], l) = s[18 + i];
    SNH_UNROLL
    for (int i = 0; i < 3; ++i) LANE(h.twist.a[i], l) = s[24 + i];
    SNH_UNROLL
    for (int i = 0; i < 3; ++i) LANE(h.flip.a[i], l) = s[27 + i];
  }
  SNH_UNROLL
  for (int i = 0; i < 3; ++i) h.sigma.a[i] = SNH_R(0);
  return h;
}
#endif

/* n values per element from v[n]: a hex8 element's points summed in the
 * scalar kernel's order (point 0 first), tet4 lanes per element. */
SNH_FN void lanes_store_per_element(const real* v, int n, size_t w, int count, __global vector_real* out) {
#if SNH_HEX8
  const int parts = LANES_STORED(w, count) / SNH_QUADRATURE;
  SNH_UNROLL
  for (int k = 0; k < SNH_LANE_ELEMENTS; ++k) {
    if (k < parts) {
      __global vector_real* o = out + (size_t)n * (LANES_ELEMENT(w) + k);
      for (int i = 0; i < n; i += 8) { /* n: 24 or 72 */
        lanes8 part[8];
        SNH_UNROLL
        for (int j = 0; j < 8; ++j) part[j] = LANES_PART(v[i + j], k);
#if SNH_MIXED
        vstore8(convert_double8(lanes_sum8(part)), 0, o + i);
#else
        vstore8(lanes_sum8(part), 0, o + i);
#endif
      }
    }
  }
#else
  const int lanes = LANES_STORED(w, count);
  SNH_UNROLL
  for (int l = 0; l < SNH_LANES; ++l) {
    if (l < lanes) { /* as in lanes_linearization_store */
      SNH_UNROLL
      for (int i = 0; i < n; ++i) out[n * (SNH_LANES * w + l) + i] = LANE(v[i], l);
    }
  }
#endif
}

#if !SNH_MIXED /* SNH_MIXED: the cached product alone (fem.cl) */
/* fem.cl's snh_element_linearize. */
__kernel void snh_element_linearize(__global const scalar_real* x, __global const int* elements,
                                    __global const scalar_real* gradients, const int count, MATERIAL_ARGS,
                                    const int project, __global scalar_real* cache
#if SNH_DOUBLE
                                    ,
                                    __global float* cache_float /* null, or the float copy (SNH_MIXED) */
#endif
) {
  const size_t w = get_global_id(0);
  if (!LANES_ACTIVE(w, count)) return;
  const size_t e = LANES_ELEMENT(w);
  real xs[3 * SNH_NODES], g[3 * SNH_NODES];
  lanes_load_nodes(x, elements, w, count, xs);
  lanes_load_gradients(gradients, w, count, g);
  principal_hessian h = material_principal_hessian(ELEMENT_MODEL(e), ELEMENT_BARRIER(e),
                                                   element_deformation_gradient(xs, g), ELEMENT_MATERIAL(e));
  if (project) h = principal_hessian_project(h);
  const size_t first = SNH_CACHE_POINT((size_t)LANES_FIRST_POINT(w));
  lanes_linearization_store(&h, LANES_STORED(w, count), cache + first);
#if SNH_DOUBLE
  if (cache_float)
    linearization_copy_float(cache + first, SNH_LINEARIZATION_SIZE * LANES_STORED(w, count), 1, cache_float + first);
#endif
}

/* fem.cl's snh_element_product_recompute. */
__kernel void snh_element_product_recompute(__global const scalar_real* p, __global const int* elements,
                                            __global const scalar_real* gradients, __global const scalar_real* weights,
                                            const int count, __global const scalar_real* x, MATERIAL_ARGS,
                                            const int project, __global scalar_real* out) {
  const size_t w = get_global_id(0);
  if (!LANES_ACTIVE(w, count)) return;
  const size_t e = LANES_ELEMENT(w);
  real xs[3 * SNH_NODES], ps[3 * SNH_NODES], g[3 * SNH_NODES], y[3 * SNH_NODES];
  lanes_load_nodes(x, elements, w, count, xs);
  lanes_load_nodes(p, elements, w, count, ps);
  lanes_load_gradients(gradients, w, count, g);
  SNH_UNROLL
  for (int i = 0; i < 3 * SNH_NODES; ++i) y[i] = SNH_R(0);
  principal_hessian h = material_principal_hessian(ELEMENT_MODEL(e), ELEMENT_BARRIER(e),
                                                   element_deformation_gradient(xs, g), ELEMENT_MATERIAL(e));
  if (project) h = principal_hessian_project(h);
  element_product(&h, ps, g, lanes_load_weights(weights, w, count), y);
  lanes_store_per_element(y, 3 * SNH_NODES, w, count, out);
}

#endif /* !SNH_MIXED */

/* fem.cl's snh_element_matrices: the stiffness from the cached
 * linearization, column by column (element.h's rank-one columns), its lower
 * triangle only (element_matrix_store mirrors it), the points in lanes; a
 * hex8 column's points summed in the scalar kernel's order. (The lower
 * triangle only, measured faster: docs/performance.md, "Lanes kernels'
 * loads and stores".)
 * SNH_MIXED: from the float copies, in float, the diagonal blocks written
 * in double (a double solve's multigrid fine level with float products). */
__kernel void snh_element_matrices(__global const int* elements, __global const scalar_real* gradients,
                                   __global const scalar_real* weights, const int count,
                                   __global const scalar_real* cache, __global matrix_real* out,
                                   __global vector_real* diagonal_blocks) {
  (void)elements;
  const size_t w = get_global_id(0);
  if (!LANES_ACTIVE(w, count)) return;
  const int lanes = LANES_STORED(w, count);
  real g[SNH_DOFS], vg[SNH_DOFS];
  lanes_load_gradients(gradients, w, count, g);
  const real qw = lanes_load_weights(weights, w, count);
  const principal_hessian h = lanes_linearization_load(cache + SNH_CACHE_POINT((size_t)LANES_FIRST_POINT(w)), lanes);
  element_rotated_gradients(&h, g, vg);
  for (int b = 0; b < SNH_NODES; ++b)
    for (int d = 0; d < 3; ++d) {
      real column[SNH_DOFS];
      SNH_UNROLL
      for (int i = 0; i < SNH_DOFS; ++i) column[i] = SNH_R(0);
      element_column_scatter_from(element_column_frame(&h, vg, b, d), vg, qw, b, column);
#if SNH_HEX8
      for (int part = 0; part < lanes / SNH_QUADRATURE; ++part) {
        const size_t e = LANES_ELEMENT(w) + part;
        __global matrix_real* k = out + (size_t)SNH_DOFS * SNH_DOFS * e;
        __global vector_real* block = diagonal_blocks + (size_t)9 * SNH_NODES * e + 9 * b;
        for (int i = 3 * b + d; i < SNH_DOFS; ++i) {
          scalar_real sum = LANE(column[i], 8 * part);
          SNH_UNROLL
          for (int q = 1; q < SNH_QUADRATURE; ++q) sum += LANE(column[i], 8 * part + q);
          element_matrix_store(k, SNH_DOFS, 3 * b + d, i, sum);
          if (i / 3 == b) block[3 * d + i % 3] = block[3 * (i % 3) + d] = sum;
        }
      }
#else
      for (int l = 0; l < lanes; ++l) {
        const size_t e = SNH_LANES * w + l;
        __global matrix_real* k = out + (size_t)SNH_DOFS * SNH_DOFS * e;
        __global vector_real* block = diagonal_blocks + (size_t)9 * SNH_NODES * e + 9 * b;
        for (int i = 3 * b + d; i < SNH_DOFS; ++i) element_matrix_store(k, SNH_DOFS, 3 * b + d, i, LANE(column[i], l));
        for (int i = d; i < 3; ++i) block[3 * d + i] = block[3 * i + d] = LANE(column[3 * b + i], l);
      }
#endif
    }
}

/* fem.cl's snh_element_product_cached: the linearization read back into
 * lanes. */
__kernel void snh_element_product_cached(__global const vector_real* p, __global const int* elements,
                                         __global const scalar_real* gradients, __global const scalar_real* weights,
                                         const int count, __global const scalar_real* cache,
                                         __global vector_real* out) {
  const size_t w = get_global_id(0);
  if (!LANES_ACTIVE(w, count)) return;
  const int lanes = LANES_STORED(w, count);
  real ps[3 * SNH_NODES], g[3 * SNH_NODES], y[3 * SNH_NODES];
  lanes_load_nodes(p, elements, w, count, ps);
  lanes_load_gradients(gradients, w, count, g);
  SNH_UNROLL
  for (int i = 0; i < 3 * SNH_NODES; ++i) y[i] = SNH_R(0);
  const principal_hessian h = lanes_linearization_load(cache + SNH_CACHE_POINT((size_t)LANES_FIRST_POINT(w)), lanes);
  element_product(&h, ps, g, lanes_load_weights(weights, w, count), y);
  lanes_store_per_element(y, 3 * SNH_NODES, w, count, out);
}

#if !SNH_MIXED
/* fem.cl's snh_element_diagonal: the 3x3 diagonal blocks K_aa of the
 * projected stiffness (projected even when the cache holds the true
 * Hessian), the points in lanes. */
__kernel void snh_element_diagonal(__global const int* elements, __global const scalar_real* gradients,
                                   __global const scalar_real* weights, const int count,
                                   __global const scalar_real* cache, __global scalar_real* out) {
  (void)elements;
  const size_t w = get_global_id(0);
  if (!LANES_ACTIVE(w, count)) return;
  const int lanes = LANES_STORED(w, count);
  real g[3 * SNH_NODES], vg[3 * SNH_NODES], k[9 * SNH_NODES];
  lanes_load_gradients(gradients, w, count, g);
  const real qw = lanes_load_weights(weights, w, count);
  const principal_hessian h =
      principal_hessian_project(lanes_linearization_load(cache + SNH_CACHE_POINT((size_t)LANES_FIRST_POINT(w)), lanes));
  element_rotated_gradients(&h, g, vg);
  for (int a = 0; a < SNH_NODES; ++a)
    for (int d = 0; d < 3; ++d) {
      /* Column d of K_aa: node a's rows of the rank-one column (a, d). */
      const mat3 m = element_column_frame(&h, vg, a, d);
      SNH_UNROLL
      for (int i = 0; i < 3; ++i)
        k[9 * a + 3 * d + i] =
            SNH_R(0) + qw * (M3(m, i, 0) * vg[3 * a] + M3(m, i, 1) * vg[3 * a + 1] + M3(m, i, 2) * vg[3 * a + 2]);
    }
  lanes_store_per_element(k, 9 * SNH_NODES, w, count, out);
}
#endif /* !SNH_MIXED */
