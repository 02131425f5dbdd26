// Material parameters in the user's terms (Young's modulus E and Poisson's
// ratio nu, or the Lame moduli) and the Stable Neo-Hookean energy parameters
// they map to.
#pragma once

#include <optional>
#include <string>

namespace snh {

// Whether the energy carries the regularized origin barrier -mu/2 log(I_C + 1)
// (Smith et al. 2018, Eq. 14). The paper allows leaving it out for nu >= 0.4
// (App. D); unset (std::optional) does exactly that.
enum class Barrier { on, off };

std::optional<Barrier> parse_barrier(const std::string& text);  // "on", "off"; "auto": unset

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
                                              std::optional<Barrier> barrier = std::nullopt);
  static StableNeoHookean from_lame(const LameParameters& lame, std::optional<Barrier> barrier = std::nullopt);

  double alpha() const;         // the rest-stable shift of J (Eq. 14 or Eq. 13)
  LameParameters lame() const;  // the small-strain moduli this energy reproduces
  double poisson_ratio() const;
  double youngs_modulus() const;
};

LameParameters lame_from_youngs_modulus(double youngs_modulus, double poisson_ratio);

// The material family (one kernel file each under kernels/materials/):
// Stable Neo-Hookean, its stabilized Fung and Arruda-Boyce extensions
// (Smith et al. 2018, sec. 5.3) and the paper's comparison models.
enum class MaterialModel {
  stable_neo_hookean,  // "snh"
  fung,                // "fung"
  arruda_boyce,        // "arruda-boyce"
  corotational,        // "corotational"
  fixed_corotational,  // "fixed-corotational"
  stvk_kikuuwe,        // "stvk-kikuuwe"
  neohookean,          // "neohookean" (log J; optional inversion handling)
};

const char* to_string(MaterialModel model);
MaterialModel parse_material_model(const std::string& name);

// Model-specific settings for building a material from (E, nu). Stiffness-
// like ones are fractions of the Lame shear modulus so that the small-strain
// response stays (E, nu) whatever they are.
struct MaterialOptions {
  std::optional<Barrier> barrier;  // snh only; unset: see Barrier
  double fung_gamma = 0.1;         // gamma / mu_Lame
  double fung_mu1 = 0.5;           // exponent rate
  double arruda_boyce_beta1 = 0.1;
  double arruda_boyce_beta2 = 0.01;
  double kikuuwe_kappa = 10.0;  // kappa / mu_Lame
  double neohookean_j0 = 0.1;   // inversion handling below J0; 0: none (J <= 0 is an error)

  // Chen and Barbic, "Tuning Nonlinear Elastic Materials under Small and Large
  // Deformations", 2024 (arXiv:2412.18631), sec. 5: nonlinearity alpha > 0 (Eq. 16: psi(sigma^alpha) / alpha^2;
  // < 1 softens, > 1 stiffens at large strain; 1: the model as written). It
  // keeps the small-strain moduli.
  double alpha = 1.0;
  // Chen and Barbic 2024, sec. 6 (Eqs. 19-20): take the lambda_Lame part from another
  // model (the mu_Lame part stays this model's), with its own alpha (default:
  // `alpha`).
  std::optional<MaterialModel> lambda_model;
  std::optional<double> alpha_lambda;
};

// Any model with its own parameters (mu, lambda and c0, c1: Fung gamma, mu1;
// Arruda-Boyce beta1, beta2; StVK kappa; Neo-Hookean J0).
struct Material {
  MaterialModel model = MaterialModel::stable_neo_hookean;
  double mu = 0.0;
  double lambda = 0.0;
  double c0 = 0.0;
  double c1 = 0.0;
  bool barrier = true;
  // Extensions of Chen and Barbic 2024: psi = lambda_L / a1^2 psi_lambda^A(sigma^a1) +
  // mu_L / a2^2 psi_mu^B(sigma^a2), B = model, A = lambda_model (when set)
  // with its parameter lambda_c0 (Neo-Hookean J0), a1 = alpha_lambda,
  // a2 = alpha_mu. Defaults: the model as written.
  double alpha_lambda = 1.0;
  double alpha_mu = 1.0;
  std::optional<MaterialModel> lambda_model;
  double lambda_c0 = 0.0;

  Material() = default;
  Material(const StableNeoHookean& snh);  // NOLINT: implicit, every SNH is a Material

  // Normalized by (E, nu) (Chen and Barbic 2024, Eq. 15 and Table 1): every model gets the
  // same small-deformation Lame moduli. Throws snh::Error for out-of-range
  // values (E <= 0, nu outside the model's admissible range, bad options).
  static Material from_lame(MaterialModel model, const LameParameters& lame, const MaterialOptions& options = {});
  static Material from_youngs_modulus(MaterialModel model, double youngs_modulus, double poisson_ratio,
                                      const MaterialOptions& options = {});

  LameParameters lame() const;  // the small-strain moduli (closed form per model)

 private:
  static Material from_lame_as_written(MaterialModel model, const LameParameters& lame, const MaterialOptions& options);

 public:
  // True where the energy is defined for every F (false: Neo-Hookean without
  // inversion handling, undefined for J <= 0).
  bool defined_for_inversion() const;
  // True where the alpha/mixing path (alpha or mixing) is in use.
  bool adjusted() const;
  // "snh", or e.g. "snh alpha=1.5" / "corotational+lambda:neohookean".
  std::string description() const;
};

}  // namespace snh
