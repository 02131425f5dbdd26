/* Material probe: any material's energy, PK1, projected Hessian, unprojected
 * eigenvalues and singular values at given deformation gradients, specialized
 * like fem.cl (kernel_args.h). Record layout per F, SNH_PROBE_RECORD reals:
 *   psi | P (9, column-major) | H (81, H[9 c + r] = d vec(P)_r / d vec(F)_c)
 *   | eigenvalues (9, ascending) | sigma (3) */
#include "materials/kernel_args.h"

#define SNH_PROBE_RECORD 103

__kernel void snh_probe(__global const real* deformation, const int count, MATERIAL_ARGS, __global real* out) {
  const int n = get_global_id(0);
  if (n >= count) return;
  mat3 f;
  for (int i = 0; i < 9; ++i) f.a[i] = deformation[9 * n + i];
  __global real* record = out + (size_t)SNH_PROBE_RECORD * n;

  record[0] = material_energy(MODEL, BARRIER, f, MATERIAL);
  const mat3 p = material_pk1(MODEL, BARRIER, f, MATERIAL);
  for (int i = 0; i < 9; ++i) record[1 + i] = p.a[i];

  const principal_hessian h = material_principal_hessian(MODEL, BARRIER, f, MATERIAL);
  const principal_hessian projected = principal_hessian_project(h);
  for (int c = 0; c < 9; ++c) {
    mat3 unit = mat3_zero();
    unit.a[c] = SNH_R(1);
    const mat3 column = principal_hessian_action(&projected, unit);
    for (int r = 0; r < 9; ++r) record[10 + 9 * c + r] = column.a[r];
  }

  real values[9];
  mat3 vectors[9];
  principal_hessian_eigensystem(&h, values, vectors);
  for (int i = 1; i < 9; ++i)
    for (int j = i; j > 0 && values[j - 1] > values[j]; --j) {
      const real t = values[j];
      values[j] = values[j - 1];
      values[j - 1] = t;
    }
  for (int i = 0; i < 9; ++i) record[91 + i] = values[i];
  for (int i = 0; i < 3; ++i) record[100 + i] = h.sigma.a[i];
}
