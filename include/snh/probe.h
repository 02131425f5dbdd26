// Evaluate the material at given deformation gradients on the OpenCL device:
// what `snh-gpu-bench probe` prints, for a host application or a test.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "snh/device.h"
#include "snh/material.h"

namespace snh {

// Row-major 3x3, like every matrix of the API: m[3 * row + column]. (The
// kernels work on the paper's column-major vec(F); MaterialProbe converts.)
using Matrix3 = std::array<double, 9>;

struct ProbeResult {
  double psi = 0.0;
  Matrix3 P{};  // first Piola-Kirchhoff stress
  // The projected Hessian, H[9 * a + b] = d P_a / d F_b with a, b the
  // row-major flat indices of P and F (a = 3 * row + column).
  std::array<double, 81> H{};
  std::array<double, 9> eigenvalues{};  // of the unprojected Hessian, ascending
  std::array<double, 3> sigma{};        // rotation-variant singular values of F
};

class MaterialProbe {
 public:
  MaterialProbe(const Material& material, Precision precision, const DeviceOptions& device = {});
  ~MaterialProbe();
  MaterialProbe(MaterialProbe&&) noexcept;
  MaterialProbe& operator=(MaterialProbe&&) noexcept;

  // One result per F; F entries are rounded to the working precision first.
  std::vector<ProbeResult> evaluate(const std::vector<Matrix3>& deformation_gradients);
  const DeviceInfo& device() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace snh
