// Evaluate the material at given deformation gradients on the OpenCL device:
// what `snh-gpu-bench probe` prints, for a host application or a test.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "snh/device.h"
#include "snh/material.h"

namespace snh {

// Column-major 3x3: m[3 * column + row], the paper's vec(F).
using Matrix3 = std::array<double, 9>;

struct ProbeResult {
  double psi = 0.0;
  Matrix3 P{};                          // first Piola-Kirchhoff stress
  std::array<double, 81> H{};           // projected Hessian, H[9 * c + r] = d vec(P)_r / d vec(F)_c
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
