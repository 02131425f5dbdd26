#include <vector>

#include "device/material_args.h"
#include "device/opencl_context.h"
#include "snh/error.h"
#include "snh/probe.h"

namespace snh {

namespace {
constexpr int kRecord = 103;  // SNH_PROBE_RECORD in kernels/probe.cl
}

struct MaterialProbe::Impl {
  Material material;
  device::OpenClContext cl;
  Impl(const Material& m, Precision p, const DeviceOptions& d) : material(m), cl(d, p) {}

  template <typename Real>
  std::vector<ProbeResult> evaluate(const std::vector<Matrix3>& fs) {
    const int count = static_cast<int>(fs.size());
    std::vector<Real> input(9 * fs.size());
    for (size_t n = 0; n < fs.size(); ++n)
      for (int i = 0; i < 9; ++i) input[9 * n + i] = static_cast<Real>(fs[n][i]);
    std::vector<Real> output(kRecord * fs.size());
    device::Buffer in =
        cl.buffer(CL_MEM_READ_ONLY, input.size() * sizeof(Real), input.empty() ? nullptr : input.data());
    device::Buffer out = cl.buffer(CL_MEM_WRITE_ONLY, output.size() * sizeof(Real));
    device::Kernel k = cl.kernel("probe.cl", device::material_defines(material), "snh_probe");
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
};

MaterialProbe::MaterialProbe(const Material& material, Precision precision, const DeviceOptions& device)
    : impl_(std::make_unique<Impl>(material, precision, device)) {}
MaterialProbe::~MaterialProbe() = default;
MaterialProbe::MaterialProbe(MaterialProbe&&) noexcept = default;
MaterialProbe& MaterialProbe::operator=(MaterialProbe&&) noexcept = default;

std::vector<ProbeResult> MaterialProbe::evaluate(const std::vector<Matrix3>& fs) {
  return impl_->cl.precision() == Precision::double_ ? impl_->evaluate<double>(fs) : impl_->evaluate<float>(fs);
}

const DeviceInfo& MaterialProbe::device() const { return impl_->cl.info(); }

}  // namespace snh
