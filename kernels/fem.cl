/* Finite-element kernels of the Newton-CG engine. Specialized at build time:
 *   SNH_DOUBLE        working precision
 *   SNH_HEX8          element type (1: hex8, 0: tet4)
 *   SNH_MODEL         material model (materials/material.h ids)
 *   SNH_BARRIER       Stable Neo-Hookean origin barrier (Eq. 14) or not (Eq. 13)
 *   SNH_NONLINEAR     Chen and Barbic 2024 alpha / mixing path (1) or the model as written (0)
 *   SNH_LAMBDA_MODEL  model of the lambda part when mixing (-1: the same)
 *   SNH_UNIFORM_REST  every element shares element 0's rest gradients (lattices)
 *   SNH_REGIONS       per-element materials from a table (kernel_args.h)
 *   SNH_INERTIA       implicit Euler's inertia term in the per-vertex kernels
 *                     (gather, block-Jacobi setup, assembled product)
 *   SNH_OBSTACLES     number of kinematic obstacles (0: none); their contact
 *                     penalty per vertex (contact/obstacle.h) joins the same
 *                     per-vertex kernels
 *   SNH_FRICTION      lagged Coulomb friction against the obstacles
 *                     (contact/obstacle.h, obstacle_friction) in
 *                     snh_contact_vertices; only with SNH_OBSTACLES
 *   SNH_SURFACE_CONTACT an embedded surface's points in contact with the
 *                     obstacles (contact/obstacle.h, surface_point_contact)
 *                     in snh_contact_vertices; only with SNH_OBSTACLES
 *   SNH_SELF_CONTACT  self-collision springs (solver/contact/self_contact.h): the
 *                     per-contact differences d_c = a_c^T u and their
 *                     per-vertex gather k a_i d_c in the same kernels
 *   SNH_SELF_BARRIER  barrier self-contact: block-Jacobi adds its diagonal
 *                     blocks (the products: contact/barrier_pairs.cl)
 *   SNH_MIXED         a double solve's products in float (snh_portable.h):
 *                     the program holds snh_element_product_cached and
 *                     snh_element_matrices (the multigrid's float fine level
 *                     from the float copies) alone
 * Element kernels write per-element nodal values; gather kernels sum them per
 * vertex over a fixed adjacency order, so results are bitwise reproducible
 * (no atomics). Layouts: x, p: xyz per vertex; elements: SNH_NODES ints per
 * element; gradients: [element][q][a][3]; weights: [element][q]. */
#include "contact/obstacle.h"
#include "fem/block_jacobi.h"
#include "fem/element_data.h"
#include "fem/vertex_terms.h"
#include "materials/kernel_args.h"
/* Self-contact arguments of the per-vertex kernels: per vertex v the entries
 * self_offsets[v] .. self_offsets[v + 1] of (contact c = self_entries[k],
 * coefficient k a_i = self_coefficients[k]), in contact order, and the
 * contacts' differences d_c (xyz) of snh_self_contact_differences. */
#define SNH_SELF_ARGS                                                                                         \
  __global const int *self_offsets, __global const int *self_entries, __global const real *self_coefficients, \
      __global const real *self_d
/* sum over v's entries of coefficient * d_c[r] */
#define SNH_SELF_SUM(v, r, out)                                    \
  for (int k_ = self_offsets[v]; k_ < self_offsets[(v) + 1]; ++k_) \
    out += self_coefficients[k_] * self_d[3 * self_entries[k_] + (r)];

#if !SNH_MIXED /* the kernels of the working precision */

/* Strain energy of each element, sum_q w_q psi(F_q), and its smallest J. */
__kernel void snh_element_energy(__global const real* x, __global const int* elements, __global const real* gradients,
                                 __global const real* weights, const int count, MATERIAL_ARGS, __global real* energy,
                                 __global real* min_j) {
  const int e = get_global_id(0);
  if (e >= count) return;
  real xs[3 * SNH_NODES], g[3 * SNH_NODES];
  load_nodes(x, elements + SNH_NODES * e, xs);
  real sum = SNH_R(0), smallest = SNH_R(0);
  for (int q = 0; q < SNH_QUADRATURE; ++q) {
    load_gradients(gradients, e, q, g);
    const mat3 f = element_deformation_gradient(xs, g);
    sum += load_weight(weights, e, q) * material_energy(ELEMENT_MODEL(e), ELEMENT_BARRIER(e), f, ELEMENT_MATERIAL(e));
    const real j = mat3_det(f);
    smallest = q == 0 ? j : fmin(smallest, j);
  }
  energy[e] = sum;
  min_j[e] = smallest;
}

/* Elastic forces per element node: -sum_q w_q P_q dN_a/dX. */
__kernel void snh_element_forces(__global const real* x, __global const int* elements, __global const real* gradients,
                                 __global const real* weights, const int count, MATERIAL_ARGS, __global real* out) {
  const int e = get_global_id(0);
  if (e >= count) return;
  real xs[3 * SNH_NODES], g[3 * SNH_NODES], f[3 * SNH_NODES];
  load_nodes(x, elements + SNH_NODES * e, xs);
  for (int i = 0; i < 3 * SNH_NODES; ++i) f[i] = SNH_R(0);
  for (int q = 0; q < SNH_QUADRATURE; ++q) {
    load_gradients(gradients, e, q, g);
    const mat3 p =
        material_pk1(ELEMENT_MODEL(e), ELEMENT_BARRIER(e), element_deformation_gradient(xs, g), ELEMENT_MATERIAL(e));
    element_scatter(p, g, -load_weight(weights, e, q), f);
  }
  for (int i = 0; i < 3 * SNH_NODES; ++i) out[3 * SNH_NODES * e + i] = f[i];
}

/* Once per Newton iteration: SVD and eigensystem at every point, clamped to
 * PSD when `project` (else the true Hessian, for Newton near a solution). */
__kernel void snh_element_linearize(__global const real* x, __global const int* elements,
                                    __global const real* gradients, const int count, MATERIAL_ARGS, const int project,
                                    __global real* cache
#if SNH_DOUBLE
                                    ,
                                    __global float* cache_float /* null, or the float copy (SNH_MIXED) */
#endif
) {
  const size_t e = get_global_id(0);
  if (e >= (size_t)count) return;
  real xs[3 * SNH_NODES], g[3 * SNH_NODES];
  load_nodes(x, elements + SNH_NODES * e, xs);
  for (int q = 0; q < SNH_QUADRATURE; ++q) {
    load_gradients(gradients, e, q, g);
    principal_hessian h = material_principal_hessian(ELEMENT_MODEL(e), ELEMENT_BARRIER(e),
                                                     element_deformation_gradient(xs, g), ELEMENT_MATERIAL(e));
    if (project) h = principal_hessian_project(h);
    linearization_store(&h, SNH_CACHE_AT(cache, e, q));
  }
#if SNH_DOUBLE
  if (cache_float)
    linearization_copy_float(SNH_CACHE_AT(cache, e, 0), SNH_LINEARIZATION_SIZE * SNH_QUADRATURE,
                             SNH_CACHE_ELEMENT_STRIDE, SNH_CACHE_AT(cache_float, e, 0));
#endif
}

#endif /* !SNH_MIXED */

/* Projected Hessian times p, per element, reusing the linearization. With
 * SNH_MIXED (the program holds this kernel alone) p and out are double, the
 * rest float. */
__kernel void snh_element_product_cached(__global const vector_real* p, __global const int* elements,
                                         __global const real* gradients, __global const real* weights, const int count,
                                         __global const real* cache, __global vector_real* out) {
  const size_t e = get_global_id(0);
  if (e >= (size_t)count) return;
  real ps[3 * SNH_NODES], g[3 * SNH_NODES], y[3 * SNH_NODES];
  load_nodes(p, elements + SNH_NODES * e, ps);
  for (int i = 0; i < 3 * SNH_NODES; ++i) y[i] = SNH_R(0);
  SNH_UNROLL
  for (int q = 0; q < SNH_QUADRATURE; ++q) {
    load_gradients(gradients, e, q, g);
    const principal_hessian h = linearization_load(SNH_CACHE_AT(cache, e, q));
    element_product(&h, ps, g, load_weight(weights, e, q), y);
  }
  for (int i = 0; i < 3 * SNH_NODES; ++i) out[3 * SNH_NODES * e + i] = y[i];
}

#if !SNH_MIXED
/* The same, recomputing SVD and eigensystem from x at every product. */
__kernel void snh_element_product_recompute(__global const real* p, __global const int* elements,
                                            __global const real* gradients, __global const real* weights,
                                            const int count, __global const real* x, MATERIAL_ARGS, const int project,
                                            __global real* out) {
  const size_t e = get_global_id(0);
  if (e >= (size_t)count) return;
  real xs[3 * SNH_NODES], ps[3 * SNH_NODES], g[3 * SNH_NODES], y[3 * SNH_NODES];
  load_nodes(x, elements + SNH_NODES * e, xs);
  load_nodes(p, elements + SNH_NODES * e, ps);
  for (int i = 0; i < 3 * SNH_NODES; ++i) y[i] = SNH_R(0);
  for (int q = 0; q < SNH_QUADRATURE; ++q) {
    load_gradients(gradients, e, q, g);
    principal_hessian h = material_principal_hessian(ELEMENT_MODEL(e), ELEMENT_BARRIER(e),
                                                     element_deformation_gradient(xs, g), ELEMENT_MATERIAL(e));
    if (project) h = principal_hessian_project(h);
    element_product(&h, ps, g, load_weight(weights, e, q), y);
  }
  for (int i = 0; i < 3 * SNH_NODES; ++i) out[3 * SNH_NODES * e + i] = y[i];
}

/* The 3x3 diagonal blocks K_aa of each element's projected stiffness,
 * column-major per node: out[(e * NODES + a) * 9 + 3 d + i]. Projected even
 * when the cache holds the true Hessian, so the preconditioner stays SPD. */
__kernel void snh_element_diagonal(__global const int* elements, __global const real* gradients,
                                   __global const real* weights, const int count, __global const real* cache,
                                   __global real* out) {
  const int e = get_global_id(0);
  if (e >= count) return;
  real g[3 * SNH_NODES], vg[3 * SNH_NODES], k[9 * SNH_NODES];
  for (int i = 0; i < 9 * SNH_NODES; ++i) k[i] = SNH_R(0);
  for (int q = 0; q < SNH_QUADRATURE; ++q) {
    load_gradients(gradients, e, q, g);
    const principal_hessian h = principal_hessian_project(linearization_load(SNH_CACHE_AT(cache, e, q)));
    const real w = load_weight(weights, e, q);
    element_rotated_gradients(&h, g, vg);
    for (int a = 0; a < SNH_NODES; ++a)
      for (int d = 0; d < 3; ++d) {
        /* Column d of K_aa: node a's rows of the rank-one column (a, d). */
        const mat3 m = element_column_frame(&h, vg, a, d);
        for (int i = 0; i < 3; ++i)
          k[9 * a + 3 * d + i] +=
              w * (M3(m, i, 0) * vg[3 * a] + M3(m, i, 1) * vg[3 * a + 1] + M3(m, i, 2) * vg[3 * a + 2]);
      }
  }
  for (int i = 0; i < 9 * SNH_NODES; ++i) out[9 * SNH_NODES * e + i] = k[i];
}

/* Per vertex: out = mask * (sign * sum of its element-node values + external
 * + vertex terms). adjacency lists the (element * NODES + node) slots of each
 * vertex, in increasing order, between offsets[v] and offsets[v + 1].
 *
 * Vertex terms (SNH_INERTIA; incremental potential of implicit Euler,
 * snh::DynamicsOptions): inertia_mass holds c m_v, c = (1 + a h) / h^2 with
 * the lumped mass m_v, and inertia_target the point y the inertia pulls
 * toward. vertex_mode 1 (residual, u = x): -c m_v (x_v - y_v); 2 (Hessian
 * product, u = p): + c m_v p_v; 0: none. `sign` carries the elastic scale
 * (1 + b / h) of Rayleigh stiffness damping. Obstacles (SNH_OBSTACLES > 0):
 * mode 1 adds the contact force of snh_contact_vertices at x, mode 2 the
 * contact Hessian block times p_v. */
__kernel void snh_gather_vectors(__global const real* element_values, __global const int* offsets,
                                 __global const int* adjacency, __global const real* mask,
                                 __global const real* external_force, const int use_external, const real sign,
                                 const int vertex_count, __global real* out
#if SNH_VERTEX_TERMS
                                 ,
                                 __global const real* u, const int vertex_mode
#endif
#if SNH_INERTIA
                                 ,
                                 __global const real* inertia_mass, __global const real* inertia_target
#endif
#if SNH_OBSTACLES
                                 ,
                                 __global const real* contact_force, __global const real* contact_blocks
#endif
#if SNH_SELF_CONTACT
                                 ,
                                 SNH_SELF_ARGS
#endif
) {
  const int v = get_global_id(0);
  if (v >= vertex_count) return;
  real s0 = SNH_R(0), s1 = SNH_R(0), s2 = SNH_R(0);
  for (int k = offsets[v]; k < offsets[v + 1]; ++k) {
    const int slot = 3 * adjacency[k];
    s0 += element_values[slot];
    s1 += element_values[slot + 1];
    s2 += element_values[slot + 2];
  }
  s0 *= sign;
  s1 *= sign;
  s2 *= sign;
  if (use_external) {
    s0 += external_force[3 * v];
    s1 += external_force[3 * v + 1];
    s2 += external_force[3 * v + 2];
  }
#if SNH_INERTIA
  if (vertex_mode == 1) {
    const real m = inertia_mass[v];
    s0 -= m * (u[3 * v] - inertia_target[3 * v]);
    s1 -= m * (u[3 * v + 1] - inertia_target[3 * v + 1]);
    s2 -= m * (u[3 * v + 2] - inertia_target[3 * v + 2]);
  } else if (vertex_mode == 2) {
    const real m = inertia_mass[v];
    s0 += m * u[3 * v];
    s1 += m * u[3 * v + 1];
    s2 += m * u[3 * v + 2];
  }
#endif
#if SNH_OBSTACLES
  if (vertex_mode == 1) {
    s0 += contact_force[3 * v];
    s1 += contact_force[3 * v + 1];
    s2 += contact_force[3 * v + 2];
  } else if (vertex_mode == 2) {
    __global const real* b = contact_blocks + 9 * v;
    const real p0 = u[3 * v], p1 = u[3 * v + 1], p2 = u[3 * v + 2];
    s0 += b[0] * p0 + b[3] * p1 + b[6] * p2;
    s1 += b[1] * p0 + b[4] * p1 + b[7] * p2;
    s2 += b[2] * p0 + b[5] * p1 + b[8] * p2;
  }
#endif
#if SNH_SELF_CONTACT
  /* residual (u = x): -k a_i d_c; product (u = p): +k a_i d_c */
  if (vertex_mode != 0) {
    real c0 = SNH_R(0), c1 = SNH_R(0), c2 = SNH_R(0);
    SNH_SELF_SUM(v, 0, c0)
    SNH_SELF_SUM(v, 1, c1)
    SNH_SELF_SUM(v, 2, c2)
    const real sg = vertex_mode == 1 ? SNH_R(-1) : SNH_R(1);
    s0 += sg * c0;
    s1 += sg * c1;
    s2 += sg * c2;
  }
#endif
  out[3 * v] = mask[3 * v] * s0;
  out[3 * v + 1] = mask[3 * v + 1] * s1;
  out[3 * v + 2] = mask[3 * v + 2] * s2;
}

/* Per vertex: inverse of its assembled 3x3 diagonal block, constrained rows
 * and columns replaced by the identity. A singular block (a vertex whose
 * elements are all flat) falls back to the inverse of its diagonal. */
__kernel void snh_block_jacobi_setup(__global const real* element_blocks, __global const int* offsets,
                                     __global const int* adjacency, __global const real* mask, const int vertex_count,
                                     __global real* inverse
#if SNH_VERTEX_TERMS
                                     ,
                                     const real elastic_scale
#endif
#if SNH_INERTIA
                                     ,
                                     __global const real* inertia_mass
#endif
#if SNH_OBSTACLES
                                     ,
                                     __global const real* contact_blocks
#endif
#if SNH_SELF_CONTACT
                                     ,
                                     __global const real* self_diagonal
#endif
#if SNH_SELF_BARRIER
                                     ,
                                     __global const real* barrier_diagonal
#endif
) {
  const int v = get_global_id(0);
  if (v >= vertex_count) return;
  mat3 b = mat3_zero();
  for (int k = offsets[v]; k < offsets[v + 1]; ++k)
    for (int i = 0; i < 9; ++i) b.a[i] += element_blocks[9 * adjacency[k] + i];
#if SNH_VERTEX_TERMS
  for (int i = 0; i < 9; ++i) b.a[i] *= elastic_scale;
#endif
#if SNH_INERTIA
  for (int d = 0; d < 3; ++d) M3(b, d, d) += inertia_mass[v];
#endif
#if SNH_OBSTACLES
  for (int i = 0; i < 9; ++i) b.a[i] += contact_blocks[9 * v + i];
#endif
#if SNH_SELF_CONTACT
  /* the springs' diagonal blocks: sum over v's contacts of k a_v^2 I */
  for (int d = 0; d < 3; ++d) M3(b, d, d) += self_diagonal[v];
#endif
#if SNH_SELF_BARRIER
  /* the barrier's projected diagonal block (symmetric: either order) */
  for (int i = 0; i < 9; ++i) b.a[i] += barrier_diagonal[9 * v + i];
#endif
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) M3(b, r, c) *= mask[3 * v + r] * mask[3 * v + c];
  for (int d = 0; d < 3; ++d)
    if (mask[3 * v + d] == SNH_R(0)) M3(b, d, d) = SNH_R(1);
  const real det = mat3_det(b);
  const real scale = fmax(fmax(fabs(M3(b, 0, 0)), fabs(M3(b, 1, 1))), fabs(M3(b, 2, 2)));
  mat3 inv;
  if (fabs(det) > SNH_R(1e3) * SNH_EPS * scale * scale * scale && scale > SNH_R(0)) {
    const mat3 cof = mat3_cofactor(b); /* symmetric b: inverse = cof / det */
    for (int i = 0; i < 9; ++i) inv.a[i] = cof.a[i] / det;
  } else {
    inv = mat3_zero();
    for (int d = 0; d < 3; ++d) M3(inv, d, d) = M3(b, d, d) > SNH_R(0) ? SNH_R(1) / M3(b, d, d) : SNH_R(1);
  }
  for (int i = 0; i < 9; ++i) inverse[9 * v + i] = inv.a[i] * mask[3 * v + i % 3] * mask[3 * v + i / 3];
}

/* z_v = inverse_v r_v */
__kernel void snh_block_jacobi_apply(__global const real* inverse, __global const real* r, const int vertex_count,
                                     __global real* z) {
  const int v = get_global_id(0);
  if (v >= vertex_count) return;
  real rv[3], zv[3]; /* r and z may alias */
  for (int i = 0; i < 3; ++i) rv[i] = r[3 * v + i];
  block_inverse_apply(inverse, v, rv, zv);
  for (int i = 0; i < 3; ++i) z[3 * v + i] = zv[i];
}

#endif /* !SNH_MIXED */

/* Per element, the projected stiffness K_e = sum_q w_q B_q^T H_q B_q
 * (24 x 24 for hex8, 12 x 12 for tet4), column-major:
 * out[e * (3N)^2 + (3 b + d) * 3N + 3 a + i]. Column (b, d) is the response
 * to dF = e_d (dN_b/dX)^T. Its 3x3 diagonal blocks also go to
 * diagonal_blocks, column-major per node: [e][9 b + 3 d + i] (the
 * block-Jacobi preconditioner's, as snh_element_diagonal writes them). */
__kernel void snh_element_matrices(__global const int* elements, __global const real* gradients,
                                   __global const real* weights, const int count, __global const real* cache,
                                   __global matrix_real* out, __global vector_real* diagonal_blocks) {
  const int e = get_global_id(0);
  if (e >= count) return;
  element_linearization l;
  element_linearization_load(gradients, weights, cache, e, &l);
  /* Column by column, its lower triangle (rows of nodes a >= b) summed over
   * the points in private memory and written at both places; its diagonal
   * block's entries go to the block-Jacobi blocks as well. */
  __global matrix_real* k = out + (size_t)SNH_DOFS * SNH_DOFS * e;
  __global vector_real* blocks = diagonal_blocks + (size_t)9 * SNH_NODES * e;
  for (int b = 0; b < SNH_NODES; ++b)
    for (int d = 0; d < 3; ++d) {
      real column[SNH_DOFS];
      element_stiffness_column_from(&l, b, d, b, column);
      for (int i = 3 * b + d; i < SNH_DOFS; ++i) element_matrix_store(k, SNH_DOFS, 3 * b + d, i, column[i]);
      for (int i = d; i < 3; ++i) blocks[9 * b + 3 * d + i] = blocks[9 * b + 3 * i + d] = column[3 * b + i];
    }
}

#if !SNH_MIXED

/* y_e = K_e p_e from the stored element matrices. */
__kernel void snh_element_matrix_product(__global const real* p, __global const int* elements,
                                         __global const matrix_real* matrices, const int count, __global real* out) {
  const int e = get_global_id(0);
  if (e >= count) return;
  real ps[SNH_DOFS], y[SNH_DOFS];
  load_nodes(p, elements + SNH_NODES * e, ps);
  for (int i = 0; i < SNH_DOFS; ++i) y[i] = SNH_R(0);
  __global const matrix_real* k = matrices + (size_t)SNH_DOFS * SNH_DOFS * e;
  for (int c = 0; c < SNH_DOFS; ++c) {
    const real pc = ps[c];
    for (int r = 0; r < SNH_DOFS; ++r) y[r] += (real)k[SNH_DOFS * c + r] * pc;
  }
  for (int i = 0; i < SNH_DOFS; ++i) out[SNH_DOFS * e + i] = y[i];
}

/* The same with a work-item per row (count * SNH_DOFS work-items, the GPUs'
 * kernel): consecutive work-items read consecutive entries of each column
 * and write consecutive values, where a work-item per element reads each
 * entry (3 nodes)^2 words from its neighbour's. Row r summed over the
 * columns in the same order as above: the same values. */
__kernel void snh_element_matrix_product_rows(__global const real* p, __global const int* elements,
                                              __global const matrix_real* matrices, const int count,
                                              __global real* out) {
  const size_t i = get_global_id(0);
  if (i >= (size_t)SNH_DOFS * count) return;
  const size_t e = i / SNH_DOFS;
  __global const int* nodes = elements + SNH_NODES * e;
  __global const matrix_real* k = matrices + (size_t)SNH_DOFS * SNH_DOFS * e + i % SNH_DOFS;
  real y = SNH_R(0);
  SNH_UNROLL
  for (int b = 0; b < SNH_NODES; ++b) {
    __global const real* pb = p + 3 * nodes[b];
    for (int d = 0; d < 3; ++d) y += (real)k[SNH_DOFS * (3 * b + d)] * pb[d];
  }
  out[i] = y;
}

/* y = mask * y, elementwise (after an assembled product); with vertex terms
 * y = mask * (elastic_scale * y + c m_v p + contact block p), the gather's. */
__kernel void snh_apply_mask(__global const real* mask, const int size, __global real* y
#if SNH_VERTEX_TERMS
                             ,
                             const real elastic_scale, __global const real* p
#endif
#if SNH_INERTIA
                             ,
                             __global const real* inertia_mass
#endif
#if SNH_OBSTACLES
                             ,
                             __global const real* contact_blocks
#endif
#if SNH_SELF_CONTACT
                             ,
                             SNH_SELF_ARGS
#endif
) {
  const int i = get_global_id(0);
  if (i >= size) return;
#if SNH_VERTEX_TERMS
  real s = elastic_scale * y[i];
#if SNH_INERTIA
  s += inertia_mass[i / 3] * p[i];
#endif
#if SNH_OBSTACLES
  {
    const int v = i / 3, r = i % 3;
    __global const real* b = contact_blocks + 9 * v;
    s += b[r] * p[3 * v] + b[3 + r] * p[3 * v + 1] + b[6 + r] * p[3 * v + 2];
  }
#endif
#if SNH_SELF_CONTACT
  SNH_SELF_SUM(i / 3, i % 3, s)
#endif
  y[i] = mask[i] * s;
#else
  y[i] *= mask[i];
#endif
}

#if SNH_OBSTACLES
/* Per vertex, the obstacles' contact penalty at x (contact/obstacle.h):
 * energy, force (xyz), Gauss-Newton Hessian block (column-major) and the
 * deepest g = thickness - phi (0: no contact). With SNH_FRICTION, plus the
 * lagged friction potential from the step's start positions x_start, the
 * friction anchors (3 per vertex and obstacle), the obstacles' records at
 * the step's start (start_obstacles) and their friction records. */
__kernel void snh_contact_vertices(__global const real* x, __global const real* obstacles, const real stiffness,
                                   const real thickness, const int vertex_count, __global real* energy,
                                   __global real* force, __global real* blocks, __global real* depth
#if SNH_FRICTION
                                   ,
                                   __global const real* x_start, __global const real* anchors,
                                   __global const real* start_obstacles, __global const real* friction, const real slip
#endif
#if SNH_SURFACE_CONTACT
                                   ,
                                   __global const int* surface_offsets, __global const int* surface_entries,
                                   __global const int* surface_vertices, __global const real* surface_weights
#endif
) {
  const int v = get_global_id(0);
  if (v >= vertex_count) return;
  const real xv[3] = {x[3 * v], x[3 * v + 1], x[3 * v + 2]};
  real f[3] = {SNH_R(0), SNH_R(0), SNH_R(0)}, h[9], g = SNH_R(0);
  for (int i = 0; i < 9; ++i) h[i] = SNH_R(0);
  real e = obstacle_contact(obstacles, SNH_OBSTACLES, stiffness, thickness, xv, f, h, &g);
#if SNH_FRICTION
  const real x0[3] = {x_start[3 * v], x_start[3 * v + 1], x_start[3 * v + 2]};
  e += obstacle_friction(start_obstacles, friction, SNH_OBSTACLES, stiffness, thickness, slip, x0,
                         anchors + 3 * SNH_OBSTACLES * v, xv, f, h);
#endif
#if SNH_SURFACE_CONTACT
  /* The embedded surface points whose cell holds v, in point order (entry =
   * 8 point + slot): each point's share on v (contact/obstacle.h). */
  for (int k = surface_offsets[v]; k < surface_offsets[v + 1]; ++k) {
    const int entry = surface_entries[k], point = entry / 8;
    e += surface_point_contact(obstacles, SNH_OBSTACLES, stiffness, thickness, x, surface_vertices + 8 * point,
                               surface_weights + 8 * point, entry - 8 * point, f, h, &g);
  }
#endif
  energy[v] = e;
  for (int i = 0; i < 3; ++i) force[3 * v + i] = f[i];
  for (int i = 0; i < 9; ++i) blocks[9 * v + i] = h[i];
  depth[v] = g;
}
#endif

#if SNH_FRICTION
/* Per vertex and obstacle, after a step ending at x: the friction anchors for
 * the next step (contact/obstacle.h, obstacle_friction_anchor), in place. */
__kernel void snh_friction_anchors(__global const real* x, __global const real* x_start, __global const real* obstacles,
                                   __global const real* start_obstacles, __global const real* friction,
                                   const real thickness, const real slip, const int vertex_count,
                                   __global real* anchors) {
  const int v = get_global_id(0);
  if (v >= vertex_count) return;
  const real xv[3] = {x[3 * v], x[3 * v + 1], x[3 * v + 2]};
  const real x0[3] = {x_start[3 * v], x_start[3 * v + 1], x_start[3 * v + 2]};
  for (int o = 0; o < SNH_OBSTACLES; ++o) {
    __global real* a = anchors + 3 * (SNH_OBSTACLES * v + o);
    const real before[3] = {a[0], a[1], a[2]};
    real after[3];
    obstacle_friction_anchor(start_obstacles + SNH_OBSTACLE_RECORD * o, friction + SNH_FRICTION_RECORD * o,
                             obstacles + SNH_OBSTACLE_RECORD * o, thickness, slip, x0, before, xv, after);
    for (int i = 0; i < 3; ++i) a[i] = after[i];
  }
}
#endif

#if SNH_SELF_CONTACT
/* Per self-contact c (solver/contact/self_contact.h): d_c = u_s - sum_j w_j u_j,
 * i.e. a_c^T u with a_c = [1, -w0, -w1, -w2] over pairs[4c..4c+3] =
 * (s, j0, j1, j2); u = x gives the spring, u = p the Hessian's a^T p. */
__kernel void snh_self_contact_differences(__global const real* u, __global const int* pairs,
                                           __global const real* weights, const int count, __global real* d) {
  const int c = get_global_id(0);
  if (c >= count) return;
  const int s = pairs[4 * c], j0 = pairs[4 * c + 1], j1 = pairs[4 * c + 2], j2 = pairs[4 * c + 3];
  const real w0 = weights[3 * c], w1 = weights[3 * c + 1], w2 = weights[3 * c + 2];
  for (int r = 0; r < 3; ++r)
    d[3 * c + r] = u[3 * s + r] - (w0 * u[3 * j0 + r] + w1 * u[3 * j1 + r] + w2 * u[3 * j2 + r]);
}
#endif

#if SNH_DOUBLE
/* out = (float)in over n values: the linearization cache and the rest data
 * of a double solve whose products run in float (SNH_MIXED). */
__kernel void snh_narrow(__global const real* in, const int n, __global float* out) {
  const int i = get_global_id(0);
  if (i < n) out[i] = (float)in[i];
}

/* out = (double)in over n values: a float V-cycle's result for a double
 * solve's CG (solver/multigrid/multigrid.h). */
__kernel void snh_widen(__global const float* in, const int n, __global real* out) {
  const int i = get_global_id(0);
  if (i < n) out[i] = (real)in[i];
}
#endif
#endif /* !SNH_MIXED */
