// Fixed scale records for the writer's golden files: two resolutions of one
// scene and preconditioner (a slope), a multigrid record with its smoother,
// one that did not converge and one skipped with quotes and a comma in its
// reason.
#pragma once

#include <vector>

#include "scale.h"

namespace snh::test {

inline std::vector<bench::ScaleRecord> sample_scale_records() {
  std::vector<bench::ScaleRecord> out;
  auto record = [](const char* scene, int res, size_t elements, size_t dofs, const char* pre, double seconds) {
    bench::ScaleRecord r;
    r.scene = scene;
    r.resolution = res;
    r.element_type = "hex8";
    r.elements = elements;
    r.dofs = dofs;
    r.preconditioner = pre;
    r.load_steps = 4;
    r.newton_iterations = 7 * res;
    r.cg_iterations = 123 * res;
    r.cg_per_newton = static_cast<double>(r.cg_iterations) / r.newton_iterations;
    r.seconds = seconds;
    r.seconds_per_step = seconds / 4.0;
    r.device_memory_bytes = 1234567 * static_cast<size_t>(res);
    r.converged = true;
    r.status = "converged x4";
    r.product = "cached";
    r.product_precision = "double";
    r.device = "Portable Computing Language / cpu-x86-64";
    r.profile.linearization = 0.1 * seconds;
    r.profile.products = 0.4 * seconds;
    r.profile.preconditioner_setup = 0.05 * seconds;
    r.profile.preconditioner_apply = 0.15 * seconds;
    r.profile.cg_vector_work = 0.2 * seconds / 3.0;
    r.profile.line_search_energies = 0.03 * seconds;
    r.profile.transfers = 1e-5;
    r.profile.other = 2.5e-7;
    r.profile.total = seconds;
    r.profile.kernels["snh_element_linearize"] = 0.07 * seconds;
    r.profile.kernel_launches = 1000 * res;
    r.profile.blocking_readbacks = 17 * res;
    r.profile.bytes_to_host = 4096LL * res;
    r.profile.bytes_to_device = 1LL << 33;
    // By phase, adding up to the counts above; the linear solves' share
    // (products, preconditioner_apply, cg_vector_work): 750 launches and 8
    // read-backs per res.
    auto phase = [&r, res](const char* name, long long launches, long long reads) {
      DeviceTraffic& t = r.profile.traffic[name];
      t.kernel_launches = launches * res;
      t.blocking_readbacks = reads * res;
    };
    phase("linearization", 250, 0);
    phase("products", 400, 0);
    phase("preconditioner_apply", 150, 0);
    phase("cg_vector_work", 200, 8);
    phase("transfers", 0, 9);
    return r;
  };
  out.push_back(record("twist", 4, 64, 375, "block-jacobi", 0.123456789));
  out.push_back(record("twist", 8, 512, 2187, "block-jacobi", 1.987654321));
  bench::ScaleRecord mg = record("twist", 8, 512, 2187, "multigrid", 1234.5);
  mg.smoother = "optimized-fourth 2";
  mg.float_cycle = true;
  out.push_back(mg);
  bench::ScaleRecord stuck = record("stretch", 58, 306704, 969111, "none", 100.6);
  stuck.converged = false;
  stuck.status = "converged x7, stagnated x1";
  out.push_back(stuck);
  bench::ScaleRecord skipped = record("stretch", 58, 306704, 969111, "multigrid", 0.0);
  skipped.skipped = "multigrid: \"tet4\" meshes, not built, here";
  out.push_back(skipped);
  return out;
}

}  // namespace snh::test
