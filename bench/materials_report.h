// `snh-gpu-bench materials`: the paper's stretch comparison across material
// models and Poisson's ratios, and homogeneous uniaxial force-stretch curves.
#pragma once

#include <CLI/CLI.hpp>

namespace snh::bench {

void add_materials_command(CLI::App& app, int& exit_code);

}  // namespace snh::bench
