// The material options shared by subcommands: --E/--nu or --mu/--lambda
// (Lame moduli), --barrier, --precision, --device.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "snh/device.h"
#include "snh/material.h"

namespace snh::bench {

struct MaterialOptions {
  double youngs_modulus = 1.0e5;
  double poisson_ratio = 0.45;
  double lame_mu = 0.0;
  double lame_lambda = 0.0;
  std::string barrier = "auto";
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
    command.add_option("--precision", precision, "float or double")
        ->check(CLI::IsMember({"float", "double"}))
        ->capture_default_str();
    command.add_option("--device", device,
                       "substring of '<platform> / <device>' (default: $SNH_DEVICE, first GPU, first device)");
    mu_given_ = mu;
  }

  StableNeoHookean material() const {
    const Barrier b = parse_barrier(barrier);
    if (mu_given_ && mu_given_->count() > 0) return StableNeoHookean::from_lame({lame_mu, lame_lambda}, b);
    return StableNeoHookean::from_youngs_modulus(youngs_modulus, poisson_ratio, b);
  }

 private:
  CLI::Option* mu_given_ = nullptr;
};

}  // namespace snh::bench
