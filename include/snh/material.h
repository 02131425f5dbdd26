// Material parameters in the user's terms (Young's modulus E and Poisson's
// ratio nu, or the Lame moduli) and the Stable Neo-Hookean energy parameters
// they map to.
#pragma once

#include <string>

namespace snh {

// Whether the energy carries the regularized origin barrier -mu/2 log(I_C + 1)
// (Smith et al. 2018, Eq. 14). The paper allows leaving it out for nu >= 0.4
// (App. D); `automatic` does exactly that.
enum class Barrier { on, off, automatic };

Barrier parse_barrier(const std::string& text);  // "on", "off", "auto"

struct LameParameters {
  double mu = 0.0;      // shear modulus
  double lambda = 0.0;  // first Lame parameter
};

// The energy's own (mu, lambda) and whether the barrier term is present.
// Build it from E and nu or from the Lame moduli: the constructors apply the
// paper's reparameterization (sec. 3.4) so that the energy's small-strain
// response is linear elasticity with the given moduli.
struct StableNeoHookean {
  double mu = 0.0;
  double lambda = 0.0;
  bool barrier = true;

  // Throws snh::Error for E <= 0, nu >= 0.5, nu outside the stable range
  // [-0.851, 0.5) with the barrier (supplement, sec. on critical points) or
  // nu < 0.4 without it (App. D), and for non-finite values.
  static StableNeoHookean from_youngs_modulus(double youngs_modulus, double poisson_ratio,
                                              Barrier barrier = Barrier::automatic);
  static StableNeoHookean from_lame(const LameParameters& lame, Barrier barrier = Barrier::automatic);

  double alpha() const;         // the rest-stable shift of J (Eq. 14 or Eq. 13)
  LameParameters lame() const;  // the small-strain moduli this energy reproduces
  double poisson_ratio() const;
  double youngs_modulus() const;
};

LameParameters lame_from_youngs_modulus(double youngs_modulus, double poisson_ratio);

}  // namespace snh
