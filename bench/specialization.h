// `snh-gpu-bench specialization`: what leaving unused terms out of the
// kernels buys. Every material (and alpha and mixing settings) runs the engine's
// element kernels three ways on the same deformed lattice: specialized (the
// engine's default: model, barrier, alpha/mixing path and the lattice's
// shared rest shape fixed at build time), with the material read at run time
// (one kernel for every material), and fully general (material at run time
// and per-element rest data), and specialized to the model but always through
// the alpha/mixing parts (what a kernel carrying every term computes). Reports
// time per call and the ratios.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace snh::bench {

struct SpecializationOptions {
  // MODEL, MODEL alpha=A or MU_MODEL+lambda:LAMBDA_MODEL.
  std::vector<std::string> materials{"snh",
                                     "fung",
                                     "arruda-boyce",
                                     "corotational",
                                     "fixed-corotational",
                                     "stvk-kikuuwe",
                                     "neohookean",
                                     "snh alpha=2",
                                     "corotational+lambda:neohookean"};
  std::vector<std::string> element_types{"hex8", "tet4"};
  std::string precision = "double";
  int size = 12;             // cells per side of the box lattice
  double min_seconds = 0.1;  // per timed operation
  std::string device;
  std::string out = "bench-results";
};

int run_specialization(const SpecializationOptions& options);
void add_specialization_command(CLI::App& app, int& exit_code);

}  // namespace snh::bench
