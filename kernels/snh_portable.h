/* Portability layer: lets the element math in kernels/ compile unchanged as
 * OpenCL C 1.2 (device kernels) and as C++17 (host reference and tests).
 *
 * The floating type is `real`: double when SNH_DOUBLE is 1, float when 0. On the
 * host, the including translation unit wraps these headers in a namespace per
 * precision and includes <cmath> and <cfloat> first; nothing here includes a system header.
 * No native_* functions and no relaxed math: device and host must agree. */
#ifndef SNH_PORTABLE_H
#define SNH_PORTABLE_H

#ifndef SNH_DOUBLE
#error "define SNH_DOUBLE as 1 (double) or 0 (float) before including the snh kernels"
#endif

/* SNH_MIXED = 1 (OpenCL only): a double solve's Hessian products in float
 * (ProductVariants::set_float_products). The math, the linearization cache and
 * the rest data are float (SNH_DOUBLE becomes 0); the solver's vectors that
 * the kernels read and write (vector_real below) stay double.
 * SNH_FLOAT = 1 (OpenCL only): a float build in a double context, vectors
 * included (the multigrid's float V-cycle, MultigridOptions::float_cycle). */
#if SNH_MIXED || SNH_FLOAT
#undef SNH_DOUBLE
#define SNH_DOUBLE 0
#endif

#ifdef __OPENCL_C_VERSION__
#define SNH_IS_OPENCL 1
#else
#define SNH_IS_OPENCL 0
#endif

/* SNH_GPU = 1 (set by the host, OpenClContext::program): the device is a
 * GPU, whose work-items may run data-dependent loops at the cost of their
 * warp's slowest; pocl vectorizes a CPU kernel across work-items only
 * without them. */
#ifndef SNH_GPU
#define SNH_GPU 0
#endif

/* Clang (pocl) warns, once per call site, that 8-wide double vectors passed
 * to or returned from a function use another calling convention on x86
 * without AVX-512 (-Wpsabi): 157 warnings for the lanes program on an AVX2
 * CPU, which pocl reported to every user as "157 warnings generated". True
 * and harmless here: a program is one translation unit, its helpers are
 * inlined and pocl's builtins are built for the same target, so no call
 * crosses a boundary where the two conventions could meet. */
#if SNH_IS_OPENCL && defined(__clang__)
#pragma clang diagnostic ignored "-Wpsabi"
#endif

/* Helper functions: file-local and inlinable in both languages. In kernels
 * always inlined: pocl vectorizes a kernel across work-items only when its
 * body is one call-free loop nest, and LLVM's own heuristics leave the
 * larger helpers (SVD, eigensystem) out of line. */
#if SNH_IS_OPENCL
#define SNH_FN static inline __attribute__((always_inline))
#else
#define SNH_FN static inline
#endif
/* The SVD and the eigensystem: left to the compiler's inlining. They do not
 * vectorize across work-items on pocl 3.1 either way (docs/performance.md),
 * and forcing them inline at every call site of every material more than
 * doubled the kernels' build time. */
#define SNH_FN_LARGE static inline

/* Address space of device buffers; plain memory on the host. */
#if SNH_IS_OPENCL
#define SNH_GLOBAL __global
#else
#define SNH_GLOBAL
#endif

/* Fully unroll the next loop (constant trip count) in kernels, so that the
 * work-item loop pocl wraps around the kernel body is the innermost loop
 * and LLVM's loop vectorizer can run across work-items. The host compiler
 * decides for itself. */
#if SNH_IS_OPENCL
#define SNH_UNROLL _Pragma("unroll")
#else
#define SNH_UNROLL
#endif

/* A literal in the working precision; folded at compile time. */
#define SNH_R(x) ((real)(x))

#if SNH_IS_OPENCL
/* No fused multiply-add contraction: the host reference (C++17, ISO mode)
 * does not contract either, so both round the same expressions alike. */
#pragma OPENCL FP_CONTRACT OFF
#endif

/* Lanes (SNH_LANES = 8 or 16, OpenCL only; kernels/fem_lanes.cl): `real` is
 * a vector of 8 or 16 values, one per lane (a hex8 element's 8 quadrature
 * points, or two elements'),
 * so the per-point math below runs as SIMD on CPU devices, where
 * pocl's work-item vectorizer does not widen it (docs/performance.md).
 * scalar_real is the element type (buffers, material parameters) and
 * snh_mask what a comparison of two reals gives: int per point, or one
 * all-ones / zero integer per lane that ?: blends lane by lane. So the math
 * is written once: comparisons go into snh_mask, data-dependent choices are
 * ?: selects of reals (never of structs, never an if), and branches only
 * test ints or parameters. The host and every other kernel: SNH_LANES = 1,
 * real = scalar_real, snh_mask = int. */
#ifndef SNH_LANES
#define SNH_LANES 1
#endif
#if SNH_LANES != 1 && ((SNH_LANES != 8 && SNH_LANES != 16) || !SNH_IS_OPENCL)
#error "SNH_LANES is 1, or 8 or 16 in OpenCL kernels"
#endif

#if SNH_DOUBLE
#if SNH_IS_OPENCL
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#endif
typedef double scalar_real;
#if SNH_LANES == 8
typedef double8 real;
typedef long8 snh_mask;
#elif SNH_LANES == 16
typedef double16 real;
typedef long16 snh_mask;
#else
typedef double real;
typedef int snh_mask;
#endif
#define SNH_EPS DBL_EPSILON
#define SNH_REAL_MIN DBL_MIN
#else
typedef float scalar_real;
#if SNH_LANES == 8
typedef float8 real;
typedef int8 snh_mask;
#elif SNH_LANES == 16
typedef float16 real;
typedef int16 snh_mask;
#else
typedef float real;
typedef int snh_mask;
#endif
#define SNH_EPS FLT_EPSILON
#define SNH_REAL_MIN FLT_MIN
#endif

/* The solver's vectors in the kernels (positions, directions, per-element
 * nodal values before the gather): scalar_real, double with SNH_MIXED. */
#if SNH_MIXED
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double vector_real;
#else
typedef scalar_real vector_real;
#endif

#if !SNH_IS_OPENCL
/* Host side: the OpenCL built-ins used by the element math, mapped to <cmath>.
 * The including file has already included <cmath> and <cfloat>. */
using std::acos;
using std::cos;
using std::exp;
using std::expm1;
using std::fabs;
using std::fmax;
using std::fmin;
using std::isfinite;
using std::log;
using std::log1p;
using std::pow;
using std::sqrt;
#endif

/* 2^-floor(log2 m) for a normal, positive, finite m below the largest
 * power of two (so that m times it lies in [1, 2)): built from m's exponent
 * bits, so scaling by it is exact and needs no division. Per lane with
 * SNH_LANES = 8 or 16. */
#if SNH_DOUBLE
#define SNH_MANTISSA_BITS 52
#define SNH_EXPONENT_MASK 0x7ff
#define SNH_EXPONENT_BIAS 1023
#else
#define SNH_MANTISSA_BITS 23
#define SNH_EXPONENT_MASK 0xff
#define SNH_EXPONENT_BIAS 127
#endif
#if SNH_IS_OPENCL
#if SNH_DOUBLE && SNH_LANES == 8
typedef ulong8 snh_bits;
#define SNH_AS_BITS(x) as_ulong8(x)
#define SNH_FROM_BITS(b) as_double8(b)
#elif SNH_DOUBLE && SNH_LANES == 16
typedef ulong16 snh_bits;
#define SNH_AS_BITS(x) as_ulong16(x)
#define SNH_FROM_BITS(b) as_double16(b)
#elif SNH_LANES == 16
typedef uint16 snh_bits;
#define SNH_AS_BITS(x) as_uint16(x)
#define SNH_FROM_BITS(b) as_float16(b)
#elif SNH_DOUBLE
typedef ulong snh_bits;
#define SNH_AS_BITS(x) as_ulong(x)
#define SNH_FROM_BITS(b) as_double(b)
#elif SNH_LANES == 8
typedef uint8 snh_bits;
#define SNH_AS_BITS(x) as_uint8(x)
#define SNH_FROM_BITS(b) as_float8(b)
#else
typedef uint snh_bits;
#define SNH_AS_BITS(x) as_uint(x)
#define SNH_FROM_BITS(b) as_float(b)
#endif
#else
#if SNH_DOUBLE
typedef unsigned long long snh_bits;
#else
typedef unsigned int snh_bits;
#endif
static inline snh_bits snh_as_bits(real x) {
  snh_bits b;
  __builtin_memcpy(&b, &x, sizeof b);
  return b;
}
static inline real snh_from_bits(snh_bits b) {
  real x;
  __builtin_memcpy(&x, &b, sizeof x);
  return x;
}
#define SNH_AS_BITS(x) snh_as_bits(x)
#define SNH_FROM_BITS(b) snh_from_bits(b)
#endif
SNH_FN real snh_pow2_inverse(real m) {
  const snh_bits exponent = (SNH_AS_BITS(m) >> SNH_MANTISSA_BITS) & (snh_bits)SNH_EXPONENT_MASK;
  return SNH_FROM_BITS(((snh_bits)(2 * SNH_EXPONENT_BIAS) - exponent) << SNH_MANTISSA_BITS);
}

#endif /* SNH_PORTABLE_H */
