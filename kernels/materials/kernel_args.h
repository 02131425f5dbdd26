/* The material's kernel arguments and build switches, shared by fem.cl and
 * probe.cl (OpenCL only). The host sets them with device::MaterialArgs
 * (host/device/material_args.h), in this order. */
#ifndef SNH_KERNEL_ARGS_H
#define SNH_KERNEL_ARGS_H

#include "materials/material.h"
#include "materials/material_record.h"

/* Material arguments of every kernel that evaluates the material. A
 * specialized build (the default) fixes the model, the barrier, the lambda
 * part's model and whether the alpha/mixing path is taken (SNH_MODEL,
 * SNH_BARRIER, SNH_LAMBDA_MODEL, SNH_NONLINEAR) and ignores the int
 * arguments; SNH_GENERAL_KERNEL = 1 builds one kernel for every material,
 * reading them at run time (the baseline the benchmark measures the
 * specialization against). */
#if SNH_GENERAL_KERNEL
#define MODEL model_arg
#define BARRIER barrier_arg
#define LAMBDA_MODEL lambda_model_arg
#else
#ifndef SNH_MODEL
#define SNH_MODEL SNH_MODEL_SNH
#endif
#ifndef SNH_LAMBDA_MODEL
#define SNH_LAMBDA_MODEL (-1)
#endif
#define MODEL SNH_MODEL
#define BARRIER SNH_BARRIER
#define LAMBDA_MODEL SNH_LAMBDA_MODEL
#endif

/* The material of element e: ELEMENT_MODEL(e), ELEMENT_BARRIER(e) and
 * ELEMENT_MATERIAL(e) (material_params), for the element kernels of fem.cl.
 *
 * SNH_REGIONS = 1 (a mesh whose regions have their own materials,
 * snh::MaterialMap) reads them from two buffers instead of the scalar
 * arguments: the table of SNH_MATERIAL_RECORD reals per material of the map
 * (material_record.h) and each element's index into it. A specialized
 * regions build still fixes the model, barrier, alpha/mixing path and lambda
 * model (all materials of the map share them) and reads only the parameters
 * per element; with SNH_GENERAL_KERNEL = 1 (materials of different models)
 * the model, barrier and lambda model come from the table too. Without
 * SNH_REGIONS the macros expand to the scalar arguments' MODEL, BARRIER and
 * MATERIAL: the kernels of a uniform material are exactly those of before
 * regions existed. */
#if SNH_REGIONS
#define MATERIAL_ARGS __global const scalar_real *material_table, __global const int *element_material
#define ELEMENT_RECORD(e) (material_table + SNH_MATERIAL_RECORD * element_material[e])
#if SNH_GENERAL_KERNEL
#define ELEMENT_MODEL(e) ((int)ELEMENT_RECORD(e)[SNH_MATERIAL_MODEL])
#define ELEMENT_BARRIER(e) ((int)ELEMENT_RECORD(e)[SNH_MATERIAL_BARRIER])
#define ELEMENT_LAMBDA_MODEL(e) ((int)ELEMENT_RECORD(e)[SNH_MATERIAL_LAMBDA_MODEL])
#else
#define ELEMENT_MODEL(e) SNH_MODEL
#define ELEMENT_BARRIER(e) SNH_BARRIER
#define ELEMENT_LAMBDA_MODEL(e) SNH_LAMBDA_MODEL
#endif
#define ELEMENT_MATERIAL(e) material_of_record(ELEMENT_RECORD(e), ELEMENT_LAMBDA_MODEL(e))

SNH_FN material_params material_of_record(__global const scalar_real *r, int lambda_model) {
  return material_make_general(r[SNH_MATERIAL_MU], r[SNH_MATERIAL_LAMBDA], r[SNH_MATERIAL_C0], r[SNH_MATERIAL_C1],
                               lambda_model, r[SNH_MATERIAL_C2], r[SNH_MATERIAL_ALPHA_LAMBDA],
                               r[SNH_MATERIAL_ALPHA_MU]);
}
#else
#define MATERIAL_ARGS                                                                                               \
  const scalar_real mu, const scalar_real lambda, const scalar_real c0, const scalar_real c1, const scalar_real c2, \
      const scalar_real alpha_lambda, const scalar_real alpha_mu, const int model_arg, const int barrier_arg,       \
      const int lambda_model_arg
#define MATERIAL material_make_general(mu, lambda, c0, c1, LAMBDA_MODEL, c2, alpha_lambda, alpha_mu)
#define ELEMENT_MODEL(e) MODEL
#define ELEMENT_BARRIER(e) BARRIER
#define ELEMENT_MATERIAL(e) MATERIAL
#endif

#endif /* SNH_KERNEL_ARGS_H */
