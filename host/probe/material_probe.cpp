#include <string>
#include <vector>

#include "device/material_args.h"
#include "device/opencl_context.h"
#include "probe/probe_kernel.h"
#include "snh/error.h"
#include "snh/probe.h"

namespace snh {

namespace probe {

namespace {

constexpr int kRecord = 103;  // SNH_PROBE_RECORD in kernels/probe.cl

template <typename Real>
std::vector<ProbeResult> evaluate_in(device::OpenClContext& cl, const Material& material,
                                     const std::vector<Matrix3>& fs, const std::string& extra_defines) {
  const int count = static_cast<int>(fs.size());
  std::vector<Real> input(9 * fs.size());
  for (size_t n = 0; n < fs.size(); ++n)
    for (int i = 0; i < 9; ++i) input[9 * n + i] = static_cast<Real>(fs[n][i]);
  std::vector<Real> output(kRecord * fs.size());
  device::Buffer in = cl.buffer(CL_MEM_READ_ONLY, input.size() * sizeof(Real), input.empty() ? nullptr : input.data());
  device::Buffer out = cl.buffer(CL_MEM_WRITE_ONLY, output.size() * sizeof(Real));
  const std::string defines = device::material_defines(material) + (extra_defines.empty() ? "" : " " + extra_defines);
  device::Kernel k = cl.kernel("probe.cl", defines, "snh_probe");
  cl_mem in_mem = in.get(), out_mem = out.get();
  device::check(clSetKernelArg(k.get(), 0, sizeof(cl_mem), &in_mem), "clSetKernelArg");
  device::check(clSetKernelArg(k.get(), 1, sizeof(int), &count), "clSetKernelArg");
  const cl_uint next = device::set_material_args<Real>(k.get(), 2, material);
  device::check(clSetKernelArg(k.get(), next, sizeof(cl_mem), &out_mem), "clSetKernelArg");
  cl.run(k.get(), fs.size());
  if (!output.empty()) cl.read(out.get(), output.size() * sizeof(Real), output.data());

  std::vector<ProbeResult> results(fs.size());
  for (size_t n = 0; n < fs.size(); ++n) {
    const Real* r = output.data() + kRecord * n;
    ProbeResult& res = results[n];
    res.psi = r[0];
    for (int i = 0; i < 9; ++i) res.P[i] = r[1 + i];
    for (int i = 0; i < 81; ++i) res.H[i] = r[10 + i];
    for (int i = 0; i < 9; ++i) res.eigenvalues[i] = r[91 + i];
    for (int i = 0; i < 3; ++i) res.sigma[i] = r[100 + i];
  }
  return results;
}

}  // namespace

std::vector<ProbeResult> evaluate(device::OpenClContext& cl, const Material& material, const std::vector<Matrix3>& fs,
                                  const std::string& extra_defines) {
  return cl.precision() == Precision::double_ ? evaluate_in<double>(cl, material, fs, extra_defines)
                                              : evaluate_in<float>(cl, material, fs, extra_defines);
}

}  // namespace probe

struct MaterialProbe::Impl {
  Material material;
  device::OpenClContext cl;
  Impl(const Material& m, Precision p, const DeviceOptions& d) : material(m), cl(d, p) {}
};

MaterialProbe::MaterialProbe(const Material& material, Precision precision, const DeviceOptions& device)
    : impl_(std::make_unique<Impl>(material, precision, device)) {}
MaterialProbe::~MaterialProbe() = default;
MaterialProbe::MaterialProbe(MaterialProbe&&) noexcept = default;
MaterialProbe& MaterialProbe::operator=(MaterialProbe&&) noexcept = default;

std::vector<ProbeResult> MaterialProbe::evaluate(const std::vector<Matrix3>& fs) {
  return probe::evaluate(impl_->cl, impl_->material, fs);
}

const DeviceInfo& MaterialProbe::device() const { return impl_->cl.info(); }

}  // namespace snh
