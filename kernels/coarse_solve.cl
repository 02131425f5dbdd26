/* The multigrid's coarsest solve on the device (host/solver/multigrid.cpp):
 * x = A^-1 b with the dense inverse that the set-up computed on the host
 * from the coarsest level's LDL^T factor. A^-1 is symmetric, so column i is
 * row i: work-item i reads column i, entry j at j n + i, so that neighbouring
 * work-items read neighbouring words (coalesced on GPUs, vectorized across
 * work-items by pocl). Each x_i sums j = 0, 1, ... in order: deterministic.
 * Constrained DOFs have zero rows in the inverse (x_i = 0 there). */
#include "snh_portable.h"

__kernel void snh_coarse_inverse_apply(__global const real* inverse, __global const real* b, const int n,
                                       __global real* x) {
  const int i = (int)get_global_id(0);
  if (i >= n) return;
  real s = (real)0;
  for (int j = 0; j < n; ++j) s += inverse[j * n + i] * b[j];
  x[i] = s;
}
