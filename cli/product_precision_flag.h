// --product-precision, which `scene` and `scale` share
// (SolveOptions::product_precision): registered and applied once here.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "enum_names.h"
#include "snh/simulation.h"

namespace snh::cli {

inline void add_product_precision_option(CLI::App* cmd, std::string& value) {
  cmd->add_option("--product-precision", value,
                  "double solves: CG's Hessian products (cached variant) in float with double vectors (automatic), "
                  "or in double (SolveOptions::product_precision)")
      ->check(CLI::IsMember(names_with({"automatic"}, precision_names())))
      ->capture_default_str();
}

// "automatic" leaves the option unset.
inline void apply_product_precision(const std::string& value, SolveOptions& options) {
  if (value != "automatic") options.product_precision = parse_precision(value);
}

}  // namespace snh::cli
