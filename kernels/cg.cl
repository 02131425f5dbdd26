/* Preconditioned conjugate gradients with its scalars on the device
 * (host/solver/linear/device_cg.h): inner products are reduced to per-group partial
 * sums, and the kernel that needs a product's value (alpha in the update,
 * beta and the convergence test in the new direction) adds that product's
 * partials itself, in index order, in every work-group; no value crosses to
 * the host inside an iteration. The convergence test is the device's own, in
 * every iteration: the preconditioned residual (r.z) against tolerance^2
 * times r0.z0, ViennaCL's test; once it is met, or p.Ap <= 0, or a value is
 * not finite, alpha is 0 in every later update, so x and r stay those of
 * the iteration that stopped whenever the host reads the status. The host
 * reads a ring of SNH_CG_CHECK iterations' r.z and statuses once per check.
 *
 * Deterministic: each work-group g covers the entries [g SPAN, (g+1) SPAN),
 * its item l adds l, l + GROUP, ... in that order, and the group folds its
 * GROUP values in a fixed tree in local memory; partials are added in index
 * order by a fixed tree as well. No atomics. Sums are in double whatever the
 * working precision (built only where the device has cl_khr_fp64); vectors
 * and updates are in `real` (float and double from this one source;
 * SNH_FLOAT = 1 builds the float variant in a double context).
 *
 * The check buffer (doubles), K = SNH_CG_CHECK: [K totals of r.z, one per
 * iteration of the ring][K statuses][the live status][r0.z0][`groups`
 * partials of r0.z0]. Status: 0 running, 1 p.Ap <= 0 (negative curvature),
 * 2 alpha not finite (breakdown), 3 converged (or r0.z0 <= 0: x = 0),
 * 4 the relative residual not finite. Every group computes the same status
 * from the same totals, so a group that reads the live status another group
 * of the same launch has just written gets the value it would compute. */
#include "snh_portable.h"

#if !SNH_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#endif

#ifndef SNH_CG_CHECK
#define SNH_CG_CHECK 1
#endif
#define SNH_CG_GROUP 64
#ifndef SNH_CG_SPAN
#define SNH_CG_SPAN (SNH_CG_GROUP * 64)
#endif

#define SNH_CG_STATUS(k) (SNH_CG_CHECK + (k))
#define SNH_CG_LIVE (2 * SNH_CG_CHECK)
#define SNH_CG_R0Z0 (2 * SNH_CG_CHECK + 1)
#define SNH_CG_R0_PARTIALS (2 * SNH_CG_CHECK + 2)

/* Folds fold[0..GROUP) into fold[0] by a fixed tree; every item returns it. */
SNH_FN double snh_cg_fold(__local double* fold, const int l) {
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int h = SNH_CG_GROUP / 2; h > 0; h >>= 1) {
    if (l < h) fold[l] += fold[l + h];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  const double s = fold[0];
  barrier(CLK_LOCAL_MEM_FENCE);
  return s;
}

/* The sum of partial[0..groups), the same in every work-group. */
SNH_FN double snh_cg_total(__global const double* partial, const int groups, __local double* fold, const int l) {
  double s = 0.0;
  for (int i = l; i < groups; i += SNH_CG_GROUP) s += partial[i];
  fold[l] = s;
  return snh_cg_fold(fold, l);
}

/* partial[g] = sum of a[i] b[i] over group g's span. */
__kernel __attribute__((reqd_work_group_size(SNH_CG_GROUP, 1, 1))) void snh_cg_dot(__global const real* a,
                                                                                   __global const real* b, const int n,
                                                                                   __global double* partial) {
  __local double fold[SNH_CG_GROUP];
  const int l = (int)get_local_id(0), g = (int)get_group_id(0);
  const int begin = g * SNH_CG_SPAN, end = min(begin + SNH_CG_SPAN, n);
  double s = 0.0;
  for (int i = begin + l; i < end; i += SNH_CG_GROUP) s += (double)a[i] * (double)b[i];
  fold[l] = s;
  s = snh_cg_fold(fold, l);
  if (l == 0) partial[g] = s;
}

/* x = 0, r = b, z = b (the preconditioner then applies in place to z). */
__kernel void snh_cg_start(__global const real* b, const int n, __global real* x, __global real* r, __global real* z) {
  const int i = (int)get_global_id(0);
  if (i >= n) return;
  const real v = b[i];
  x[i] = (real)0;
  r[i] = v;
  z[i] = v;
}

/* p = z; partials of r.z into rz and the check buffer's r0.z0 slot;
 * clears the statuses. */
__kernel __attribute__((reqd_work_group_size(SNH_CG_GROUP, 1, 1))) void snh_cg_first_direction(
    __global const real* r, __global const real* z, const int n, __global real* p, __global double* rz,
    __global double* check, const int groups) {
  __local double fold[SNH_CG_GROUP];
  const int l = (int)get_local_id(0), g = (int)get_group_id(0);
  const int begin = g * SNH_CG_SPAN, end = min(begin + SNH_CG_SPAN, n);
  double srz = 0.0;
  for (int i = begin + l; i < end; i += SNH_CG_GROUP) {
    const real zi = z[i], ri = r[i];
    p[i] = zi;
    srz += (double)ri * (double)zi;
  }
  fold[l] = srz;
  srz = snh_cg_fold(fold, l);
  if (l == 0) {
    rz[g] = srz;
    check[SNH_CG_R0_PARTIALS + g] = srz;
  }
  if (g == 0)
    for (int k = l; k <= SNH_CG_CHECK; k += SNH_CG_GROUP) check[SNH_CG_STATUS(k)] = 0.0;
}

/* alpha = (r.z) / (p.Ap) from their partials; x += alpha p, r -= alpha Ap,
 * z = r (for the preconditioner); the live status after this update. */
__kernel __attribute__((reqd_work_group_size(SNH_CG_GROUP, 1, 1))) void snh_cg_update(
    __global const real* p, __global const real* q, const int n, __global const double* rz, __global const double* pq,
    __global real* x, __global real* r, __global real* z, __global double* check, const int groups) {
  __local double fold[SNH_CG_GROUP];
  const int l = (int)get_local_id(0), g = (int)get_group_id(0);
  const double was = check[SNH_CG_LIVE];
  const double sum_r0z0 = snh_cg_total(check + SNH_CG_R0_PARTIALS, groups, fold, l);
  const double sum_rz = snh_cg_total(rz, groups, fold, l);
  const double sum_pq = snh_cg_total(pq, groups, fold, l);
  double state = was;
  double alpha = 0.0;
  if (was == 0.0) {
    if (!(sum_r0z0 > 0.0)) {
      state = 3.0; /* nothing to solve (ViennaCL returns x = 0) */
    } else if (!(sum_pq > 0.0)) {
      state = isfinite(sum_pq) ? 1.0 : 2.0;
    } else {
      alpha = sum_rz / sum_pq;
      if (!isfinite(alpha)) state = 2.0;
    }
    if (state != 0.0) alpha = 0.0;
  }
  const real a = (real)alpha;
  const int begin = g * SNH_CG_SPAN, end = min(begin + SNH_CG_SPAN, n);
  /* Stopped: x and r stay (0 times a non-finite p would not). */
  const int moving = state == 0.0;
  for (int i = begin + l; i < end; i += SNH_CG_GROUP) {
    real ri = r[i];
    if (moving) {
      x[i] += a * p[i];
      ri -= a * q[i];
      r[i] = ri;
    }
    z[i] = ri;
  }
  if (g == 0 && l == 0) check[SNH_CG_LIVE] = state;
}

/* The convergence test on (r.z)_new / r0.z0; beta = (r.z)_new / (r.z)_old
 * from their partials; p = z + beta p (kept once stopped). The ring's
 * `slot` gets this iteration's r.z and status. */
__kernel __attribute__((reqd_work_group_size(SNH_CG_GROUP, 1, 1))) void snh_cg_direction(
    __global const real* z, const int n, __global const double* rz_new, __global const double* rz_old,
    __global double* check, const int groups, const int slot, const double tolerance_squared, __global real* p) {
  __local double fold[SNH_CG_GROUP];
  const int l = (int)get_local_id(0), g = (int)get_group_id(0);
  /* No early return: every item reaches the barriers below (pocl). */
  double state = check[SNH_CG_LIVE];
  const double sum_r0z0 = snh_cg_total(check + SNH_CG_R0_PARTIALS, groups, fold, l);
  const double sum_new = snh_cg_total(rz_new, groups, fold, l);
  const double sum_old = snh_cg_total(rz_old, groups, fold, l);
  if (state == 0.0) {
    const double relative = fabs(sum_new / sum_r0z0);
    if (!isfinite(relative))
      state = 4.0;
    else if (relative < tolerance_squared)
      state = 3.0;
  }
  const real b = (real)(sum_new / sum_old);
  const int begin = g * SNH_CG_SPAN, end = min(begin + SNH_CG_SPAN, n);
  if (state == 0.0)
    for (int i = begin + l; i < end; i += SNH_CG_GROUP) p[i] = z[i] + b * p[i];
  if (g == 0 && l == 0) {
    check[slot] = sum_new;
    check[SNH_CG_STATUS(slot)] = state;
    check[SNH_CG_LIVE] = state;
    check[SNH_CG_R0Z0] = sum_r0z0;
  }
}

/* y = x + alpha p (the line search's trial points; alpha in double). */
__kernel void snh_cg_axpy(__global const real* x, const double alpha, __global const real* p, const int n,
                          __global real* y) {
  const int i = (int)get_global_id(0);
  if (i >= n) return;
  y[i] = x[i] + (real)alpha * p[i];
}

/* y = x. */
__kernel void snh_cg_copy(__global const real* x, const int n, __global real* y) {
  const int i = (int)get_global_id(0);
  if (i >= n) return;
  y[i] = x[i];
}

/* v = v / sqrt(sum of partial) where that sum is positive and finite (left
 * as it is otherwise): the multigrid's power iteration normalizes on the
 * device and reads only its final estimate. */
__kernel __attribute__((reqd_work_group_size(SNH_CG_GROUP, 1, 1))) void snh_cg_normalize(__global real* v, const int n,
                                                                                         __global const double* partial,
                                                                                         const int groups) {
  __local double fold[SNH_CG_GROUP];
  const int l = (int)get_local_id(0), g = (int)get_group_id(0);
  const double s = snh_cg_total(partial, groups, fold, l);
  const real scale = (real)(1.0 / sqrt(s));
  const int begin = g * SNH_CG_SPAN, end = min(begin + SNH_CG_SPAN, n);
  if (s > 0.0 && isfinite(s))
    for (int i = begin + l; i < end; i += SNH_CG_GROUP) v[i] *= scale;
}
