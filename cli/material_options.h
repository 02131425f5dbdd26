// The material options shared by subcommands: --E/--nu or --mu/--lambda
// (Lame moduli), --barrier, --model and its settings, --alpha / --lambda-model /
// --alpha-lambda (Chen and Barbic 2024), --precision, --device.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "enum_names.h"
#include "snh/device.h"
#include "snh/material.h"

namespace snh::cli {

// The --model / --lambda-model choices (snh::parse_material_model's names).
inline const std::vector<std::string> kModelNames = {
    "snh", "fung", "arruda-boyce", "corotational", "fixed-corotational", "stvk-kikuuwe", "neohookean"};

// A material written "MODEL", "MODEL alpha=A" or "MU_MODEL+lambda:LAMBDA_MODEL"
// (Chen and Barbic 2024, Eqs. 16, 19; both may combine): its model, with alpha and the
// lambda part's model set in `options`.
inline MaterialModel parse_material_label(const std::string& text, snh::MaterialOptions& options) {
  std::string name = text;
  const size_t alpha = name.find(" alpha=");
  if (alpha != std::string::npos) {
    options.alpha = std::stod(name.substr(alpha + 7));
    name = name.substr(0, alpha);
  }
  const size_t plus = name.find("+lambda:");
  if (plus != std::string::npos) {
    options.lambda_model = parse_material_model(name.substr(plus + 8));
    name = name.substr(0, plus);
  }
  return parse_material_model(name);
}

struct MaterialOptions {
  double youngs_modulus = 1.0e5;
  double poisson_ratio = 0.45;
  double lame_mu = 0.0;
  double lame_lambda = 0.0;
  std::string barrier = "auto";
  std::string model = "snh";
  snh::MaterialOptions model_options;
  std::string lambda_model;
  double alpha_lambda = 0.0;
  std::string precision = "double";
  std::string device;

  void add_to(CLI::App& command) {
    auto* e = command.add_option("--E", youngs_modulus, "Young's modulus")->capture_default_str();
    auto* nu = command.add_option("--nu", poisson_ratio, "Poisson's ratio, in [-0.851, 0.5)")->capture_default_str();
    auto* mu = command.add_option("--mu", lame_mu, "Lame shear modulus (instead of --E/--nu)");
    auto* lambda = command.add_option("--lambda", lame_lambda, "Lame first parameter (with --mu)");
    mu->needs(lambda)->excludes(e)->excludes(nu);
    lambda->needs(mu)->excludes(e)->excludes(nu);
    command.add_option("--barrier", barrier, "origin barrier: on, off, auto (off for nu >= 0.4)")
        ->check(CLI::IsMember({"on", "off", "auto"}))
        ->capture_default_str();
    command
        .add_option("--model", model,
                    "material: snh, fung, arruda-boyce, corotational, fixed-corotational, stvk-kikuuwe, neohookean "
                    "(all normalized to the same small-strain E, nu)")
        ->check(CLI::IsMember(kModelNames))
        ->capture_default_str();
    command.add_option("--fung-gamma", model_options.fung_gamma, "fung: gamma / mu_Lame")->capture_default_str();
    command.add_option("--fung-mu1", model_options.fung_mu1, "fung: exponent rate mu1")->capture_default_str();
    command.add_option("--ab-beta1", model_options.arruda_boyce_beta1, "arruda-boyce: beta1")->capture_default_str();
    command.add_option("--ab-beta2", model_options.arruda_boyce_beta2, "arruda-boyce: beta2")->capture_default_str();
    command.add_option("--kappa", model_options.kikuuwe_kappa, "stvk-kikuuwe: compression penalty kappa / mu_Lame")
        ->capture_default_str();
    command
        .add_option("--j0", model_options.neohookean_j0,
                    "neohookean: inversion handling below J0 (0: none, J <= 0 is an error)")
        ->capture_default_str();
    command
        .add_option("--alpha", model_options.alpha,
                    "nonlinearity (Chen and Barbic 2024, Eq. 16): psi(sigma^alpha) / alpha^2, same small-strain E, nu; "
                    "< 1 softer, > 1 stiffer at large strain")
        ->capture_default_str();
    command.add_option("--lambda-model", lambda_model,
                       "take the lambda_Lame (volume) part from this model, the mu_Lame part stays --model's "
                       "(Chen and Barbic 2024, Eq. 19)");
    command.add_option("--alpha-lambda", alpha_lambda,
                       "nonlinearity of the lambda_Lame part (Eq. 20; default --alpha)");
    command.add_option("--precision", precision, "float or double")
        ->check(CLI::IsMember(precision_names()))
        ->capture_default_str();
    command.add_option("--device", device,
                       "substring of '<platform> / <device>' (default: $SNH_DEVICE, first GPU, first device)");
    mu_given_ = mu;
    alpha_lambda_given_ = command.get_option("--alpha-lambda");
  }

  Material material() const {
    snh::MaterialOptions o = model_options;
    o.barrier = parse_barrier(barrier);
    if (!lambda_model.empty()) o.lambda_model = parse_material_model(lambda_model);
    if (alpha_lambda_given_ && alpha_lambda_given_->count() > 0) o.alpha_lambda = alpha_lambda;
    const MaterialModel m = parse_material_model(model);
    if (mu_given_ && mu_given_->count() > 0) return Material::from_lame(m, {lame_mu, lame_lambda}, o);
    return Material::from_youngs_modulus(m, youngs_modulus, poisson_ratio, o);
  }

 private:
  CLI::Option* mu_given_ = nullptr;
  CLI::Option* alpha_lambda_given_ = nullptr;
};

}  // namespace snh::cli
