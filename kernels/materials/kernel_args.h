/* The material's kernel arguments and build switches, shared by fem.cl and
 * probe.cl (OpenCL only). The host sets them with device::set_material_args
 * (host/device/material_args.h), in this order. */
#ifndef SNH_KERNEL_ARGS_H
#define SNH_KERNEL_ARGS_H

#include "materials/material.h"

/* Material arguments of every kernel that evaluates the material. A
 * specialized build (the default) fixes the model, the barrier, the lambda
 * part's model and whether the seed 004 path is taken (SNH_MODEL,
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
#define MATERIAL_ARGS                                                                                     \
  const real mu, const real lambda, const real c0, const real c1, const real c2, const real alpha_lambda, \
      const real alpha_mu, const int model_arg, const int barrier_arg, const int lambda_model_arg
#define MATERIAL material_make_general(mu, lambda, c0, c1, LAMBDA_MODEL, c2, alpha_lambda, alpha_mu)

#endif /* SNH_KERNEL_ARGS_H */
