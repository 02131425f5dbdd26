#include "device/material_args.h"

#include "device/opencl_context.h"

namespace snh::device {

std::string material_defines(const Material& m, MaterialKernel build) {
  if (build == MaterialKernel::runtime) return "-DSNH_GENERAL_KERNEL=1";
  const bool parts = m.adjusted() || build == MaterialKernel::all_terms;
  std::string d = "-DSNH_MODEL=" + std::to_string(static_cast<int>(m.model)) +
                  " -DSNH_BARRIER=" + (m.barrier ? "1" : "0") + " -DSNH_NONLINEAR=" + (parts ? "1" : "0");
  if (m.lambda_model) d += " -DSNH_LAMBDA_MODEL=" + std::to_string(static_cast<int>(*m.lambda_model));
  return d;
}

namespace {
template <typename T>
void set(cl_kernel k, cl_uint index, const T& value) {
  check(clSetKernelArg(k, index, sizeof(T), &value), "clSetKernelArg");
}
}  // namespace

template <typename Real>
cl_uint set_material_args(cl_kernel k, cl_uint first, const Material& m) {
  const Real reals[] = {Real(m.mu),        Real(m.lambda),       Real(m.c0),      Real(m.c1),
                        Real(m.lambda_c0), Real(m.alpha_lambda), Real(m.alpha_mu)};
  cl_uint i = first;
  for (Real r : reals) set(k, i++, r);
  set(k, i++, static_cast<int>(m.model));
  set(k, i++, m.barrier ? 1 : 0);
  set(k, i++, m.lambda_model ? static_cast<int>(*m.lambda_model) : -1);
  return i;
}

template cl_uint set_material_args<float>(cl_kernel, cl_uint, const Material&);
template cl_uint set_material_args<double>(cl_kernel, cl_uint, const Material&);

}  // namespace snh::device
