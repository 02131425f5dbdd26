// `snh-gpu-bench errtime`: force residual and error against a reference
// solution as functions of wall time, per Newton iteration, for each scene,
// precision and preconditioner (and the host CPU baseline), with each device
// series' kernel launches and blocking read-backs per CG and per Newton
// iteration (iteration_traffic.h). Writes errtime.csv, errtime.json,
// errtime.md and one errtime_<scene>.png per scene.
#pragma once

#include <string>
#include <vector>

namespace snh::bench {

struct ErrtimeOptions {
  std::vector<std::string> scenes{"stretch", "twist", "scramble", "flex"};
  int resolution = 0;                     // 0: default_errtime_resolution(scene)
  std::string element = "hex8";           // hex8 or tet4
  std::string precision = "both";         // float, double, both
  std::string preconditioner = "both";    // block-jacobi, multigrid, none, both (block-jacobi and none), all
  std::string variant = "automatic";      // automatic, cached, recompute, element-matrices, assembled
  std::string hessian = "adaptive";       // adaptive, projected
  bool host_baseline = true;              // also the Eigen host solve (double) as series "host-eigen"
  std::string device;                     // substring of "<platform> / <device>"
  std::string out_dir = "bench-results";  // errtime.* written here
  double youngs_modulus = 1.0;
  double poisson_ratio = 0.49;
  unsigned seed = 1;                   // scramble's initial positions
  double absolute_tolerance = 1e-7;    // the series' Newton stop (relative: none)
  double reference_tolerance = 1e-10;  // the reference's relative stop per load step
  bool plots = true;                   // run bench/plot_errtime.py
};

// The resolution errtime uses for `scene` when ErrtimeOptions::resolution is
// 0: small enough for the whole default run to take about two minutes on a
// two-core CPU with pocl.
int default_errtime_resolution(const std::string& scene);

// Runs the measurement and writes the files; returns the process exit code
// (0 unless no series could run at all).
int run_errtime(const ErrtimeOptions& options);

}  // namespace snh::bench
