// Lame moduli <-> Stable Neo-Hookean energy parameters (Smith et al. 2018,
// sec. 3.4; Chen and Barbic 2024, Table 1) and the admissible ranges.
#include <cmath>
#include <sstream>

#include "snh/error.h"
#include "snh/material.h"

namespace snh {
namespace {

// Smallest lambda/mu (energy parameters, barrier on) for which the origin
// barrier creates no spurious minimum under uniform scaling (supplement,
// critical-point analysis: "beta = 0.152568262069702", nu ~ -0.85102).
constexpr double kMinBarrierLambdaOverMu = 0.152568262069702;
// App. D: the barrier may be left out for fleshy materials, nu >= 0.4.
constexpr double kMinPoissonWithoutBarrier = 0.4;

std::string number(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

double poisson_of(const LameParameters& l) { return l.lambda / (2.0 * (l.lambda + l.mu)); }

}  // namespace

std::optional<Barrier> parse_barrier(const std::string& text) {
  if (text == "on") return Barrier::on;
  if (text == "off") return Barrier::off;
  if (text == "auto") return std::nullopt;
  throw Error("barrier: expected on, off or auto, got '" + text + "'");
}

LameParameters lame_from_youngs_modulus(double e, double nu) {
  if (!std::isfinite(e) || !(e > 0.0))
    throw Error("material: Young's modulus E must be finite and > 0, got " + number(e));
  if (!std::isfinite(nu) || !(nu < 0.5) || !(nu > -1.0))
    throw Error("material: Poisson's ratio nu must lie in (-1, 0.5), got " + number(nu));
  LameParameters l;
  l.mu = e / (2.0 * (1.0 + nu));
  l.lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  return l;
}

StableNeoHookean StableNeoHookean::from_youngs_modulus(double e, double nu, std::optional<Barrier> barrier) {
  return from_lame(lame_from_youngs_modulus(e, nu), barrier);
}

StableNeoHookean StableNeoHookean::from_lame(const LameParameters& l, std::optional<Barrier> barrier) {
  if (!std::isfinite(l.mu) || !(l.mu > 0.0))
    throw Error("material: shear modulus mu must be finite and > 0, got " + number(l.mu));
  if (!std::isfinite(l.lambda) || !(l.lambda + 2.0 * l.mu / 3.0 > 0.0))
    throw Error("material: lambda must be finite with bulk modulus lambda + 2 mu / 3 > 0, got lambda = " +
                number(l.lambda));
  const double nu = poisson_of(l);
  StableNeoHookean m;
  m.barrier = !barrier ? nu < kMinPoissonWithoutBarrier : *barrier == Barrier::on;
  if (m.barrier) {
    // sec. 3.4: mu = 4/3 mu_Lame, lambda = lambda_Lame + 5/6 mu_Lame.
    m.mu = 4.0 / 3.0 * l.mu;
    m.lambda = l.lambda + 5.0 / 6.0 * l.mu;
    if (!(m.lambda / m.mu >= kMinBarrierLambdaOverMu))
      throw Error("material: nu = " + number(nu) +
                  " is outside the stable range [-0.851, 0.5) of the Stable Neo-Hookean energy (lambda/mu = " +
                  number(m.lambda / m.mu) + " < 0.1526)");
  } else {
    // Eq. 13 (Chen and Barbic 2024, Table 1): lambda_Lame = lambda - mu, mu_Lame = mu.
    if (!(nu >= kMinPoissonWithoutBarrier))
      throw Error("material: the origin barrier may only be left out for nu >= 0.4 (paper App. D), got nu = " +
                  number(nu));
    m.mu = l.mu;
    m.lambda = l.lambda + l.mu;
  }
  return m;
}

double StableNeoHookean::alpha() const { return barrier ? 1.0 + 0.75 * mu / lambda : 1.0 + mu / lambda; }

LameParameters StableNeoHookean::lame() const {
  LameParameters l;
  if (barrier) {
    l.mu = 0.75 * mu;
    l.lambda = lambda - 0.625 * mu;
  } else {
    l.mu = mu;
    l.lambda = lambda - mu;
  }
  return l;
}

double StableNeoHookean::poisson_ratio() const { return poisson_of(lame()); }

double StableNeoHookean::youngs_modulus() const {
  const LameParameters l = lame();
  return l.mu * (3.0 * l.lambda + 2.0 * l.mu) / (l.lambda + l.mu);
}

}  // namespace snh
