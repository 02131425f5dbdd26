/* Device limits for the roofline in snh-gpu-bench throughput: a streaming
 * triad for bandwidth and FMA chains for arithmetic peak, in the working
 * precision, with scalar and 8-wide vector types (pocl vectorizes across
 * work-items only sometimes; the vector form gives it the width explicitly). */
#include "snh_portable.h"

#if SNH_DOUBLE
typedef double8 real8;
typedef double4 real4;
#else
typedef float8 real8;
typedef float4 real4;
#endif

/* a = b + s c: 3 reals moved, 2 flops per entry. */
__kernel void snh_triad(__global real* a, __global const real* b, __global const real* c, const real s, const int n) {
  const int i = get_global_id(0);
  if (i < n) a[i] = b[i] + s * c[i];
}

/* The same, 4 entries per work-item (n4 = n / 4). An H100 (NVIDIA's OpenCL,
 * work-groups of 64) ran the scalar triad at the same work-items per second
 * in either precision, so it read float at half the bytes per second of
 * double (1.2 against 2.4 TB/s over the same 3 x 256 MiB); the roofline
 * takes the faster of the two forms. */
__kernel void snh_triad4(__global real4* a, __global const real4* b, __global const real4* c, const real s,
                         const int n4) {
  const int i = get_global_id(0);
  if (i < n4) a[i] = b[i] + s * c[i];
}

/* SNH_FMA_ITERATIONS iterations of 8 independent scalar FMA chains:
 * 16 flops per chain and iteration. */
#define SNH_FMA_ITERATIONS 256
__kernel void snh_fma_scalar(__global real* out, const real m, const real k) {
  const int i = get_global_id(0);
  real x0 = (real)i, x1 = x0 + SNH_R(1), x2 = x0 + SNH_R(2), x3 = x0 + SNH_R(3);
  real x4 = x0 + SNH_R(4), x5 = x0 + SNH_R(5), x6 = x0 + SNH_R(6), x7 = x0 + SNH_R(7);
  for (int it = 0; it < SNH_FMA_ITERATIONS; ++it) {
    x0 = fma(x0, m, k);
    x1 = fma(x1, m, k);
    x2 = fma(x2, m, k);
    x3 = fma(x3, m, k);
    x4 = fma(x4, m, k);
    x5 = fma(x5, m, k);
    x6 = fma(x6, m, k);
    x7 = fma(x7, m, k);
  }
  out[i] = x0 + x1 + x2 + x3 + x4 + x5 + x6 + x7;
}

/* The same with 8-wide vectors: SNH_FMA_CHAINS (8, or 6 where the host
 * asks) chains x 8 lanes x 2 flops per iteration. 8-wide double is two
 * registers a chain on AVX2 (16 registers), where 8 chains and the two
 * constants do not fit: pocl spilled three chains to the stack in every
 * iteration (49.5 GFLOP/s against 94.4 with 6 chains on a Zen 3); the
 * roofline takes the faster of the two builds. */
#ifndef SNH_FMA_CHAINS
#define SNH_FMA_CHAINS 8
#endif
__kernel void snh_fma_vector(__global real* out, const real m, const real k) {
  const int i = get_global_id(0);
  real8 x0 = (real8)((real)i), x1 = x0 + SNH_R(1), x2 = x0 + SNH_R(2), x3 = x0 + SNH_R(3);
  real8 x4 = x0 + SNH_R(4), x5 = x0 + SNH_R(5);
#if SNH_FMA_CHAINS == 8
  real8 x6 = x0 + SNH_R(6), x7 = x0 + SNH_R(7);
#endif
  const real8 mv = (real8)(m), kv = (real8)(k);
  for (int it = 0; it < SNH_FMA_ITERATIONS; ++it) {
    x0 = fma(x0, mv, kv);
    x1 = fma(x1, mv, kv);
    x2 = fma(x2, mv, kv);
    x3 = fma(x3, mv, kv);
    x4 = fma(x4, mv, kv);
    x5 = fma(x5, mv, kv);
#if SNH_FMA_CHAINS == 8
    x6 = fma(x6, mv, kv);
    x7 = fma(x7, mv, kv);
#endif
  }
#if SNH_FMA_CHAINS == 8
  const real8 s = x0 + x1 + x2 + x3 + x4 + x5 + x6 + x7;
#else
  const real8 s = x0 + x1 + x2 + x3 + x4 + x5;
#endif
  out[i] = s.s0 + s.s1 + s.s2 + s.s3 + s.s4 + s.s5 + s.s6 + s.s7;
}

/* Square roots and divisions, whose units run at a fraction of the FMA rate
 * (on x86 CPUs one shared divide/square-root unit, not pipelined like the
 * FMAs): the per-point SVD and eigensystem need them (bench/throughput.cpp,
 * kSqrtPerPoint), so they bound the recomputing kernels below the FMA peak.
 * SNH_SLOW_ITERATIONS iterations of 8 independent 8-wide chains: x = sqrt(x
 * + k) (from x >= 1: no subnormals; the add runs beside it on its own
 * pipe), x = m / x (alternating between two values with full mantissas),
 * and 4 of each side by side (whether the two share a unit). 64 operations
 * per work-item and iteration. */
#define SNH_SLOW_ITERATIONS 32
#define SNH_SLOW_CHAINS(step)                                                     \
  real8 x0 = (real8)(SNH_R(1) + (real)i), x1 = x0 + SNH_R(1), x2 = x0 + SNH_R(2); \
  real8 x3 = x0 + SNH_R(3), x4 = x0 + SNH_R(4), x5 = x0 + SNH_R(5);               \
  real8 x6 = x0 + SNH_R(6), x7 = x0 + SNH_R(7);                                   \
  for (int it = 0; it < SNH_SLOW_ITERATIONS; ++it) {                              \
    step                                                                          \
  }                                                                               \
  const real8 s = x0 + x1 + x2 + x3 + x4 + x5 + x6 + x7;                          \
  out[i] = s.s0 + s.s1 + s.s2 + s.s3 + s.s4 + s.s5 + s.s6 + s.s7;

__kernel void snh_sqrt_vector(__global real* out, const real m) {
  const int i = get_global_id(0);
  const real8 k = (real8)(SNH_R(1) - m);
  SNH_SLOW_CHAINS(x0 = sqrt(x0 + k); x1 = sqrt(x1 + k); x2 = sqrt(x2 + k); x3 = sqrt(x3 + k); x4 = sqrt(x4 + k);
                  x5 = sqrt(x5 + k); x6 = sqrt(x6 + k); x7 = sqrt(x7 + k);)
}

__kernel void snh_div_vector(__global real* out, const real m) {
  const int i = get_global_id(0);
  const real8 mv = (real8)(m);
  SNH_SLOW_CHAINS(x0 = mv / x0; x1 = mv / x1; x2 = mv / x2; x3 = mv / x3; x4 = mv / x4; x5 = mv / x5; x6 = mv / x6;
                  x7 = mv / x7;)
}

__kernel void snh_sqrt_div_vector(__global real* out, const real m) {
  const int i = get_global_id(0);
  const real8 mv = (real8)(m), k = (real8)(SNH_R(1) - m);
  SNH_SLOW_CHAINS(x0 = sqrt(x0 + k); x1 = mv / x1; x2 = sqrt(x2 + k); x3 = mv / x3; x4 = sqrt(x4 + k); x5 = mv / x5;
                  x6 = sqrt(x6 + k); x7 = mv / x7;)
}
