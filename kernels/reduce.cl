/* Deterministic partial sums and minima for the Newton loop's energies,
 * norms and dot products (host/solver/linear/device_reduction.h), so that only one
 * double per SNH_REDUCE_SPAN entries crosses to the host instead of every
 * entry. Work-group g covers the entries [g SPAN, (g + 1) SPAN); its item l
 * adds the entries l, l + GROUP, l + 2 GROUP, ... in that order, and the
 * group then folds its GROUP values in a fixed tree in local memory. No
 * atomics: the same input gives bitwise the same partials on the same device.
 * Sums accumulate in double whatever the working precision (as the host did
 * with every entry), so the program is built only where the device has
 * cl_khr_fp64. The obstacle contact set's signature sums 64-bit integers. */
#include "math/mix64.h"
#include "snh_portable.h"

#if !SNH_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#endif

#define SNH_REDUCE_GROUP 64
#define SNH_REDUCE_SPAN (SNH_REDUCE_GROUP * 64)

/* The sum of the group's values v, folded in a fixed tree in local memory
 * (fold: SNH_REDUCE_GROUP entries), returned to every item. Every item of
 * the group calls it (it holds barriers). */
#define SNH_GROUP_SUM(type)                                        \
  SNH_FN type group_sum_##type(__local type* fold, const type v) { \
    const int l = (int)get_local_id(0);                            \
    fold[l] = v;                                                   \
    barrier(CLK_LOCAL_MEM_FENCE);                                  \
    for (int h = SNH_REDUCE_GROUP / 2; h > 0; h >>= 1) {           \
      if (l < h) fold[l] += fold[l + h];                           \
      barrier(CLK_LOCAL_MEM_FENCE);                                \
    }                                                              \
    return fold[0];                                                \
  }
SNH_GROUP_SUM(double)
SNH_GROUP_SUM(ulong)

/* mode 0: sum a; 1: sum a^2; 2: sum a b (b is read only in mode 2). */
__kernel __attribute__((reqd_work_group_size(SNH_REDUCE_GROUP, 1, 1))) void snh_partial_sums(
    __global const real* a, __global const real* b, const int n, const int mode, __global double* partial) {
  __local double fold[SNH_REDUCE_GROUP];
  const int l = (int)get_local_id(0), g = (int)get_group_id(0);
  const int begin = g * SNH_REDUCE_SPAN;
  const int end = min(begin + SNH_REDUCE_SPAN, n);
  double s = 0.0;
  for (int i = begin + l; i < end; i += SNH_REDUCE_GROUP) {
    const double x = (double)a[i];
    s += mode == 0 ? x : mode == 1 ? x * x : x * (double)b[i];
  }
  const double sum = group_sum_double(fold, s);
  if (l == 0) partial[g] = sum;
}

/* The smallest entry of each span, by x < m (a NaN entry is passed over
 * unless it is the span's first). */
__kernel __attribute__((reqd_work_group_size(SNH_REDUCE_GROUP, 1, 1))) void snh_partial_minima(
    __global const real* a, const int n, __global double* partial) {
  __local double fold[SNH_REDUCE_GROUP];
  const int l = (int)get_local_id(0), g = (int)get_group_id(0);
  const int begin = g * SNH_REDUCE_SPAN;
  const int end = min(begin + SNH_REDUCE_SPAN, n);
  double m = (double)a[begin];
  for (int i = begin + l; i < end; i += SNH_REDUCE_GROUP) {
    const double x = (double)a[i];
    m = x < m ? x : m;
  }
  fold[l] = m;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int h = SNH_REDUCE_GROUP / 2; h > 0; h >>= 1) {
    if (l < h) fold[l] = fold[l + h] < fold[l] ? fold[l + h] : fold[l];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (l == 0) partial[g] = fold[0];
}

/* sum f x and sum |f x| over each span into partial[g] and partial[groups + g]:
 * the external forces' work at x, f kept in double as the host holds it. */
__kernel __attribute__((reqd_work_group_size(SNH_REDUCE_GROUP, 1, 1))) void snh_partial_work(
    __global const real* x, __global const double* f, const int n, const int groups, __global double* partial) {
  __local double fold[SNH_REDUCE_GROUP];
  __local double size[SNH_REDUCE_GROUP];
  const int l = (int)get_local_id(0), g = (int)get_group_id(0);
  const int begin = g * SNH_REDUCE_SPAN;
  const int end = min(begin + SNH_REDUCE_SPAN, n);
  double s = 0.0, m = 0.0;
  for (int i = begin + l; i < end; i += SNH_REDUCE_GROUP) {
    const double w = f[i] * (double)x[i];
    s += w;
    m += fabs(w);
  }
  const double work = group_sum_double(fold, s), magnitude = group_sum_double(size, m);
  if (l == 0) {
    partial[g] = work;
    partial[groups + g] = magnitude;
  }
}

/* sum over each span of 1/2 c_v (x_i - y_i)^2, v = i / 3, into partial[g]:
 * implicit Euler's inertia energy (host/solver/newton/implicit_euler.h) at x, with
 * the target y and the per-vertex coefficients c kept in double as the host
 * holds them, each term the host's own (VertexTerms::add_inertia_energy). */
__kernel __attribute__((reqd_work_group_size(SNH_REDUCE_GROUP, 1, 1))) void snh_partial_inertia(
    __global const real* x, __global const double* y, __global const double* c, const int n, __global double* partial) {
  __local double fold[SNH_REDUCE_GROUP];
  const int l = (int)get_local_id(0), g = (int)get_group_id(0);
  const int begin = g * SNH_REDUCE_SPAN;
  const int end = min(begin + SNH_REDUCE_SPAN, n);
  double s = 0.0;
  for (int i = begin + l; i < end; i += SNH_REDUCE_GROUP) {
    const double d = (double)x[i] - y[i];
    s += 0.5 * c[i / 3] * d * d;
  }
  const double sum = group_sum_double(fold, s);
  if (l == 0) partial[g] = sum;
}

/* The obstacle contact set (solver/model/vertex_terms.h): over each span, the
 * number of vertices v with depth[v] > 0 and the sum of snh_mix64(v) over
 * them, into partial[2 g] and partial[2 g + 1]. Integer sums wrap exactly
 * modulo 2^64: the same value in any order. */
__kernel __attribute__((reqd_work_group_size(SNH_REDUCE_GROUP, 1, 1))) void snh_partial_contact_set(
    __global const real* depth, const int n, __global ulong* partial) {
  __local ulong counts[SNH_REDUCE_GROUP];
  __local ulong hashes[SNH_REDUCE_GROUP];
  const int l = (int)get_local_id(0), g = (int)get_group_id(0);
  const int begin = g * SNH_REDUCE_SPAN;
  const int end = min(begin + SNH_REDUCE_SPAN, n);
  ulong count = 0, hash = 0;
  for (int i = begin + l; i < end; i += SNH_REDUCE_GROUP)
    if (depth[i] > SNH_R(0)) {
      ++count;
      hash += snh_mix64((ulong)i);
    }
  const ulong group_count = group_sum_ulong(counts, count), group_hash = group_sum_ulong(hashes, hash);
  if (l == 0) {
    partial[2 * g] = group_count;
    partial[2 * g + 1] = group_hash;
  }
}

/* total[0], total[1] = the groups' counts and hashes of
 * snh_partial_contact_set, summed by one work-item. */
__kernel void snh_contact_set_total(__global const ulong* partial, const int groups, __global ulong* total) {
  if (get_global_id(0) != 0) return;
  ulong count = 0, hash = 0;
  for (int g = 0; g < groups; ++g) {
    count += partial[2 * g];
    hash += partial[2 * g + 1];
  }
  total[0] = count;
  total[1] = hash;
}

/* total[slot] = the sum (minimum: 1) of partial[offset..offset + groups) in
 * index order (0 for no groups),
 * by one work-item: the order, and so the value, the host's loop over the
 * same partials gives, while only the total crosses to the host. */
__kernel void snh_partial_total(__global const double* partial, const int offset, const int groups, const int minimum,
                                __global double* total, const int slot) {
  if (get_global_id(0) != 0) return;
  double s = groups > 0 ? partial[offset] : 0.0;
  for (int g = 1; g < groups; ++g) {
    const double p = partial[offset + g];
    s = minimum ? (p < s ? p : s) : s + p;
  }
  total[slot] = s;
}
