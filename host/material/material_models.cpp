// Building each material model from (E, nu) so that all share the same
// small-strain stiffness (Chen and Barbic 2024, Eq. 15 and Table 1), and their Lame
// parameters in closed form (Chen and Barbic 2024, Eqs. 3-4, worked out per model; the
// tests check them against finite differences of psi(sigma)).
#include <cmath>
#include <sstream>
#include <string>

#include "snh/error.h"
#include "snh/material.h"

namespace snh {

namespace {

struct ModelName {
  MaterialModel model;
  const char* name;
};
constexpr ModelName kNames[] = {{MaterialModel::stable_neo_hookean, "snh"},
                                {MaterialModel::fung, "fung"},
                                {MaterialModel::arruda_boyce, "arruda-boyce"},
                                {MaterialModel::corotational, "corotational"},
                                {MaterialModel::fixed_corotational, "fixed-corotational"},
                                {MaterialModel::stvk_kikuuwe, "stvk-kikuuwe"},
                                {MaterialModel::neohookean, "neohookean"}};

std::string number(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

// The shortest decimal that reads back as x (0.8, not 0.80000000000000004).
std::string shortest(double x) {
  for (int digits = 1; digits < 17; ++digits) {
    std::ostringstream s;
    s.precision(digits);
    s << x;
    if (std::stod(s.str()) == x) return s.str();
  }
  return number(x);
}

void require(bool ok, const std::string& what) {
  if (!ok) throw Error("material: " + what);
}

}  // namespace

const char* to_string(MaterialModel model) {
  for (const ModelName& n : kNames)
    if (n.model == model) return n.name;
  return "?";
}

MaterialModel parse_material_model(const std::string& name) {
  for (const ModelName& n : kNames)
    if (name == n.name) return n.model;
  throw Error("material: unknown model '" + name +
              "' (known: snh, fung, arruda-boyce, corotational, fixed-corotational, stvk-kikuuwe, neohookean)");
}

Material::Material(const StableNeoHookean& snh)
    : model(MaterialModel::stable_neo_hookean), mu(snh.mu), lambda(snh.lambda), barrier(snh.barrier) {}

Material Material::from_youngs_modulus(MaterialModel model, double e, double nu, const MaterialOptions& o) {
  return from_lame(model, lame_from_youngs_modulus(e, nu), o);
}

Material Material::from_lame(MaterialModel model, const LameParameters& l, const MaterialOptions& o) {
  Material m = from_lame_as_written(model, l, o);
  const double alpha_lambda = o.alpha_lambda.value_or(o.alpha);
  require(std::isfinite(o.alpha) && o.alpha > 0.0 && o.alpha <= 10.0,
          "alpha must lie in (0, 10], got " + number(o.alpha));
  require(std::isfinite(alpha_lambda) && alpha_lambda > 0.0 && alpha_lambda <= 10.0,
          "alpha of the lambda part must lie in (0, 10], got " + number(alpha_lambda));
  m.alpha_mu = o.alpha;
  m.alpha_lambda = alpha_lambda;
  if (o.lambda_model && *o.lambda_model != model) {
    m.lambda_model = o.lambda_model;
    if (*o.lambda_model == MaterialModel::neohookean) {
      require(o.neohookean_j0 >= 0.0 && o.neohookean_j0 < 1.0, "neohookean: J0 must lie in [0, 1)");
      m.lambda_c0 = o.neohookean_j0;
    }
  } else if (model == MaterialModel::neohookean) {
    m.lambda_c0 = m.c0;
  }
  return m;
}

bool Material::adjusted() const { return alpha_lambda != 1.0 || alpha_mu != 1.0 || lambda_model.has_value(); }

bool Material::defined_for_inversion() const {
  if (model == MaterialModel::neohookean && c0 <= 0.0) return false;
  return !(lambda_model == MaterialModel::neohookean && lambda_c0 <= 0.0);
}

std::string Material::description() const {
  std::string out = to_string(model);
  if (lambda_model) out += std::string("+lambda:") + to_string(*lambda_model);
  if (alpha_mu != 1.0 || alpha_lambda != 1.0) {
    out += " alpha=" + shortest(alpha_mu);
    if (alpha_lambda != alpha_mu) out += " alpha_lambda=" + shortest(alpha_lambda);
  }
  return out;
}

Material Material::from_lame_as_written(MaterialModel model, const LameParameters& l, const MaterialOptions& o) {
  if (model == MaterialModel::stable_neo_hookean) return StableNeoHookean::from_lame(l, o.barrier);
  require(std::isfinite(l.mu) && l.mu > 0.0, "shear modulus mu must be finite and > 0, got " + number(l.mu));
  require(std::isfinite(l.lambda) && l.lambda + 2.0 * l.mu / 3.0 > 0.0,
          "lambda must be finite with bulk modulus lambda + 2 mu / 3 > 0, got lambda = " + number(l.lambda));
  Material m;
  m.model = model;
  m.barrier = false;
  switch (model) {
    case MaterialModel::fung: {
      // gamma_I(I) = mu0 + gamma mu1 = mu_L; lambda_L = gamma_F + lambda - gamma_I
      // with gamma_F(I) = 2 gamma mu1^2 (see the derivation in materials tests).
      require(o.fung_gamma >= 0.0 && o.fung_mu1 > 0.0 && std::isfinite(o.fung_gamma) && std::isfinite(o.fung_mu1),
              "fung: gamma must be >= 0 and mu1 > 0");
      m.c0 = o.fung_gamma * l.mu;
      m.c1 = o.fung_mu1;
      m.mu = l.mu - m.c0 * m.c1;
      require(m.mu > 0.0, "fung: gamma * mu1 must stay below 1 (the linear part mu0 = mu_L (1 - gamma mu1) > 0)");
      m.lambda = l.lambda + l.mu - 2.0 * m.c0 * m.c1 * m.c1;
      break;
    }
    case MaterialModel::arruda_boyce: {
      require(o.arruda_boyce_beta1 >= 0.0 && o.arruda_boyce_beta2 >= 0.0, "arruda-boyce: beta1, beta2 must be >= 0");
      m.c0 = o.arruda_boyce_beta1;
      m.c1 = o.arruda_boyce_beta2;
      // gamma_I(I) = mu (1 + 3 beta1 + 9 beta2) = mu_L; gamma_F(I) = 2 mu (beta1 + 6 beta2).
      m.mu = l.mu / (1.0 + 3.0 * m.c0 + 9.0 * m.c1);
      m.lambda = l.lambda + l.mu - 2.0 * m.mu * (m.c0 + 6.0 * m.c1);
      break;
    }
    case MaterialModel::stvk_kikuuwe:
      require(o.kikuuwe_kappa >= 0.0, "stvk-kikuuwe: kappa must be >= 0");
      m.mu = l.mu;
      m.lambda = l.lambda;
      m.c0 = o.kikuuwe_kappa * l.mu;
      break;
    case MaterialModel::neohookean:
      require(o.neohookean_j0 >= 0.0 && o.neohookean_j0 < 1.0, "neohookean: J0 must lie in [0, 1)");
      m.mu = l.mu;
      m.lambda = l.lambda;
      m.c0 = o.neohookean_j0;
      break;
    default:  // corotational, fixed-corotational: (mu, lambda) are the Lame moduli
      m.mu = l.mu;
      m.lambda = l.lambda;
      break;
  }
  require(m.lambda > 0.0 || model != MaterialModel::fung,
          "fung: lambda = " + number(m.lambda) + " <= 0 for these settings");
  return m;
}

LameParameters Material::lame() const {
  switch (model) {
    case MaterialModel::stable_neo_hookean: {
      StableNeoHookean s;
      s.mu = mu;
      s.lambda = lambda;
      s.barrier = barrier;
      return s.lame();
    }
    case MaterialModel::fung: {
      const double gi = mu + c0 * c1;
      return {gi, 2.0 * c0 * c1 * c1 + lambda - gi};
    }
    case MaterialModel::arruda_boyce: {
      const double gi = mu * (1.0 + 3.0 * c0 + 9.0 * c1);
      return {gi, 2.0 * mu * (c0 + 6.0 * c1) + lambda - gi};
    }
    default:
      return {mu, lambda};
  }
}

}  // namespace snh
