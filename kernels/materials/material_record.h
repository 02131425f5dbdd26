/* One entry of the per-element material table of SNH_REGIONS builds
 * (kernel_args.h): SNH_MATERIAL_RECORD reals per material of a
 * snh::MaterialMap, at these offsets. Plain C macros, so the host that fills
 * the table (host/device/material_args.cpp) and the kernels that read it
 * share one layout. Model ids, the barrier flag and the lambda part's model
 * (-1: the material's own) are stored as reals: small integers, exact in
 * float. */
#ifndef SNH_MATERIAL_RECORD_H
#define SNH_MATERIAL_RECORD_H

#define SNH_MATERIAL_MU 0
#define SNH_MATERIAL_LAMBDA 1
#define SNH_MATERIAL_C0 2
#define SNH_MATERIAL_C1 3
#define SNH_MATERIAL_C2 4 /* the lambda part's parameter (Neo-Hookean J0) */
#define SNH_MATERIAL_ALPHA_LAMBDA 5
#define SNH_MATERIAL_ALPHA_MU 6
#define SNH_MATERIAL_MODEL 7
#define SNH_MATERIAL_BARRIER 8
#define SNH_MATERIAL_LAMBDA_MODEL 9
#define SNH_MATERIAL_RECORD 10

#endif /* SNH_MATERIAL_RECORD_H */
