#include <string>
#include <vector>

#include "device/kernel_args.h"
#include "device/material_args.h"
#include "device/opencl_context.h"
#include "fem/matrix_order.h"
#include "probe/probe_kernel.h"
#include "snh/error.h"
#include "snh/probe.h"

namespace snh {

namespace probe {

namespace {

constexpr int kRecord = 103;  // SNH_PROBE_RECORD in kernels/probe.cl

template <typename Real>
std::vector<ProbeResult> evaluate_in(device::OpenClContext& cl, const Material& material,
                                     const std::vector<Matrix3>& fs, bool gpu_build) {
  const int count = static_cast<int>(fs.size());
  std::vector<Real> input(9 * fs.size());
  // The kernel takes and returns the column-major vec(F); Matrix3 and
  // ProbeResult are row-major.
  using fem::transposed_index;
  for (size_t n = 0; n < fs.size(); ++n)
    for (int i = 0; i < 9; ++i) input[9 * n + transposed_index(i)] = static_cast<Real>(fs[n][i]);
  std::vector<Real> output(kRecord * fs.size());
  device::Buffer in = cl.buffer(CL_MEM_READ_ONLY, input.size() * sizeof(Real), input.empty() ? nullptr : input.data());
  device::Buffer out = cl.buffer(CL_MEM_WRITE_ONLY, output.size() * sizeof(Real));
  device::KernelConfig config = device::material_config(material);
  config.gpu = gpu_build;
  device::Kernel k = cl.kernel("probe.cl", config, "snh_probe");
  device::KernelArgs args(k.get());
  args.add(in.get()).add(count);
  device::add_material_args<Real>(args, material).add(out.get());
  cl.run(args.bind(), fs.size());
  if (!output.empty()) cl.read(out.get(), output.size() * sizeof(Real), output.data());

  std::vector<ProbeResult> results(fs.size());
  for (size_t n = 0; n < fs.size(); ++n) {
    const Real* r = output.data() + kRecord * n;
    ProbeResult& res = results[n];
    res.psi = r[0];
    for (int i = 0; i < 9; ++i) res.P[i] = r[1 + transposed_index(i)];
    // The kernel's H[9 c + r] = d vec(P)_r / d vec(F)_c.
    for (int a = 0; a < 9; ++a)
      for (int b = 0; b < 9; ++b) res.H[9 * a + b] = r[10 + 9 * transposed_index(b) + transposed_index(a)];
    for (int i = 0; i < 9; ++i) res.eigenvalues[i] = r[91 + i];
    for (int i = 0; i < 3; ++i) res.sigma[i] = r[100 + i];
  }
  return results;
}

}  // namespace

std::vector<ProbeResult> evaluate(device::OpenClContext& cl, const Material& material, const std::vector<Matrix3>& fs,
                                  bool gpu_build) {
  return cl.precision() == Precision::double_ ? evaluate_in<double>(cl, material, fs, gpu_build)
                                              : evaluate_in<float>(cl, material, fs, gpu_build);
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
