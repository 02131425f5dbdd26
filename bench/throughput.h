// `snh-gpu-bench throughput`: the device's own limits (streaming bandwidth,
// FMA peak) and the engine's kernels against them, with every Hessian-product
// variant side by side on the same mesh and a host CPU baseline.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace snh::bench {

// A variant row of double runs only: the cached product with float products
// (SolveOptions::product_precision), a double solve's default.
inline constexpr const char* kCachedFloatProducts = "cached-float-products";

struct ThroughputOptions {
  std::vector<std::string> element_types{"hex8", "tet4"};
  std::vector<std::string> precisions{"float", "double"};
  std::vector<int> sizes{8, 16};  // cells per side of the box lattice
  std::vector<std::string> variants{"recompute", "cached", kCachedFloatProducts, "element-matrices", "assembled"};
  double min_seconds = 0.2;  // per timed operation
  bool host_baseline = true;
  // CPU devices: the width of the lanes program's linearization and
  // recompute product, 8 or 16 (PointLanes::set_material_lanes); 0 lets
  // the engine choose (default_material_lanes). Not on GPUs, which run the
  // scalar kernels.
  int material_lanes = 0;
  std::string device;
  std::string out = "bench-results";
};

int run_throughput(const ThroughputOptions& options);
void add_throughput_command(CLI::App& app, int& exit_code);

}  // namespace snh::bench
