/* splitmix64's output function (Steele, Lea and Flood, "Fast splittable
 * pseudorandom number generators", OOPSLA 2014): a one-to-one mix of 64-bit
 * integers. The obstacle contact set's signature (kernels/reduce.cl,
 * host/solver/model/vertex_terms.h) adds it up over the vertices in contact; the
 * sum wraps exactly modulo 2^64, so it is the same in any order, on the
 * device and on the host. Self-contained: C++ (after <cstdint>) and OpenCL C,
 * whose ulong is 64 bits. */
#ifndef SNH_MATH_MIX64_H
#define SNH_MATH_MIX64_H

#ifdef __OPENCL_C_VERSION__
typedef ulong snh_u64;
#else
typedef uint64_t snh_u64;
#endif

static inline snh_u64 snh_mix64(snh_u64 z) {
  z += (snh_u64)0x9e3779b97f4a7c15UL;
  z = (z ^ (z >> 30)) * (snh_u64)0xbf58476d1ce4e5b9UL;
  z = (z ^ (z >> 27)) * (snh_u64)0x94d049bb133111ebUL;
  return z ^ (z >> 31);
}

#endif
