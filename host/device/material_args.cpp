#include "device/material_args.h"

#include "materials/material_record.h"

namespace snh::device {

KernelConfig material_config(const Material& m, MaterialKernel build) {
  KernelConfig c;
  if (build == MaterialKernel::runtime) {
    c.general_material = true;
    return c;
  }
  c.model = m.model;
  c.barrier = m.barrier;
  c.nonlinear = m.adjusted() || build == MaterialKernel::all_terms;
  c.lambda_model = m.lambda_model;
  return c;
}

bool same_specialization(const Material& a, const Material& b) {
  return a.model == b.model && a.barrier == b.barrier && a.adjusted() == b.adjusted() &&
         a.lambda_model == b.lambda_model;
}

KernelConfig material_config(const MaterialMap& map, MaterialKernel build) {
  if (map.uniform()) return material_config(map.materials.front(), build);
  bool shared = build != MaterialKernel::runtime;
  for (const Material& m : map.materials) shared = shared && same_specialization(m, map.materials.front());
  KernelConfig c = material_config(map.materials.front(), shared ? build : MaterialKernel::runtime);
  c.regions = true;
  return c;
}

std::string material_defines(const Material& m, MaterialKernel build) { return material_config(m, build).defines(); }

std::string material_defines(const MaterialMap& map, MaterialKernel build) {
  return material_config(map, build).defines();
}

template <typename Real>
std::vector<Real> material_table(const MaterialMap& map) {
  std::vector<Real> table(SNH_MATERIAL_RECORD * map.materials.size());
  for (size_t k = 0; k < map.materials.size(); ++k) {
    const Material& m = map.materials[k];
    Real* r = table.data() + SNH_MATERIAL_RECORD * k;
    r[SNH_MATERIAL_MU] = Real(m.mu);
    r[SNH_MATERIAL_LAMBDA] = Real(m.lambda);
    r[SNH_MATERIAL_C0] = Real(m.c0);
    r[SNH_MATERIAL_C1] = Real(m.c1);
    r[SNH_MATERIAL_C2] = Real(m.lambda_c0);
    r[SNH_MATERIAL_ALPHA_LAMBDA] = Real(m.alpha_lambda);
    r[SNH_MATERIAL_ALPHA_MU] = Real(m.alpha_mu);
    r[SNH_MATERIAL_MODEL] = Real(static_cast<int>(m.model));
    r[SNH_MATERIAL_BARRIER] = Real(m.barrier ? 1 : 0);
    r[SNH_MATERIAL_LAMBDA_MODEL] = Real(m.lambda_model ? static_cast<int>(*m.lambda_model) : -1);
  }
  return table;
}

template <typename Real>
KernelArgs& add_material_args(KernelArgs& args, const Material& m) {
  const Real reals[] = {Real(m.mu),        Real(m.lambda),       Real(m.c0),      Real(m.c1),
                        Real(m.lambda_c0), Real(m.alpha_lambda), Real(m.alpha_mu)};
  for (Real r : reals) args.add(r);
  return args.add(static_cast<int>(m.model))
      .add(m.barrier ? 1 : 0)
      .add(m.lambda_model ? static_cast<int>(*m.lambda_model) : -1);
}

template <typename Real>
cl_uint set_material_args(cl_kernel k, cl_uint first, const Material& m) {
  KernelArgs args(k, first);
  return add_material_args<Real>(args, m).next();
}

template <typename Real>
MaterialArgs<Real>::MaterialArgs(OpenClContext& cl, const MaterialMap& map, MaterialKernel build)
    : config_(material_config(map, build)), uniform_(map.materials.front()) {
  if (map.uniform()) return;
  const std::vector<Real> table = material_table<Real>(map);
  table_ = cl.buffer(CL_MEM_READ_ONLY, table.size() * sizeof(Real), table.data());
  element_material_ =
      cl.buffer(CL_MEM_READ_ONLY, map.element_material.size() * sizeof(int32_t), map.element_material.data());
}

template <typename Real>
KernelArgs& MaterialArgs<Real>::add_to(KernelArgs& args) const {
  if (!table_) return add_material_args<Real>(args, uniform_);
  return args.add(table_.get()).add(element_material_.get());
}

template KernelArgs& add_material_args<float>(KernelArgs&, const Material&);
template KernelArgs& add_material_args<double>(KernelArgs&, const Material&);
template cl_uint set_material_args<float>(cl_kernel, cl_uint, const Material&);
template cl_uint set_material_args<double>(cl_kernel, cl_uint, const Material&);
template std::vector<float> material_table<float>(const MaterialMap&);
template std::vector<double> material_table<double>(const MaterialMap&);
template class MaterialArgs<float>;
template class MaterialArgs<double>;

}  // namespace snh::device
