// The host CPU baseline (bench/host_baseline.h): it converges on small scenes
// to the device solver's equilibrium, and its product timing reports the
// stiffness's exact sparsity.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "host_baseline.h"
#include "snh/error.h"
#include "snh/scenes.h"
#include "snh/simulation.h"
#include "vector_compare.h"

namespace snh {
namespace {

using test::relative_difference;

void expect_host_matches_device(const std::string& name, const SceneParameters& parameters) {
  const Scene scene = make_scene(name, parameters);
  SolveOptions options = scene.options;
  options.precision = Precision::double_;
  options.hessian = HessianMode::projected;
  options.relative_tolerance = 1e-10;
  options.absolute_tolerance = 0.0;

  int callbacks = 0;
  const bench::HostBaselineResult host =
      bench::solve_on_host(scene, options, [&](const NewtonIteration&, const std::vector<double>& x) {
        ++callbacks;
        EXPECT_EQ(x.size(), scene.mesh.positions.xyz().size());
      });
  ASSERT_TRUE(host.converged) << name;
  ASSERT_EQ(host.steps.size(), static_cast<size_t>(options.load_steps));
  for (const StepResult& s : host.steps) EXPECT_EQ(s.status, StepStatus::converged) << name;
  EXPECT_GT(host.seconds, 0.0);
  EXPECT_GT(host.assembly_seconds, 0.0);
  EXPECT_GT(host.cg_seconds, 0.0);
  EXPECT_LE(host.assembly_seconds + host.cg_seconds, host.seconds);

  int newton = 0;
  double last_seconds = 0.0;
  for (const NewtonIteration& h : host.history) {
    EXPECT_TRUE(h.projected);
    EXPECT_GE(h.seconds, last_seconds);
    last_seconds = h.seconds;
    if (h.step_length > 0.0) {
      ++newton;
      EXPECT_GT(h.cg_iterations, 0);
      EXPECT_TRUE(h.cg_stop == CgStop::converged || h.cg_stop == CgStop::max_iterations) << h.cg_stop;
    }
  }
  EXPECT_EQ(callbacks, newton);

  QuasistaticSolver solver(scene.mesh, scene.material, scene.constraints, options);
  const SolveResult device = solver.solve();
  ASSERT_TRUE(device.converged) << name;
  EXPECT_LT(relative_difference(host.positions, device.positions.xyz()), 1e-6) << name;
  // The constrained vertices sit exactly at the same targets.
  for (const ConstraintSet& c : scene.constraints)
    for (int32_t v : c.vertices)
      for (int d = 0; d < 3; ++d) EXPECT_EQ(host.positions[3 * v + d], device.positions(v, d));
}

TEST(HostBaseline, TwistMatchesDeviceSolver) {
  SceneParameters p;
  p.resolution = 3;
  expect_host_matches_device("twist", p);
}

TEST(HostBaseline, StretchMatchesDeviceSolver) {
  SceneParameters p;
  p.resolution = 3;
  p.steps = 2;
  expect_host_matches_device("stretch", p);
}

TEST(HostBaseline, RejectsBadOptions) {
  SceneParameters p;
  p.resolution = 2;
  const Scene scene = make_scene("twist", p);
  SolveOptions options = scene.options;
  options.load_steps = 0;
  EXPECT_THROW(bench::solve_on_host(scene, options), Error);
  options = scene.options;
  options.external_force = Points(1);  // not one per vertex
  EXPECT_THROW(bench::solve_on_host(scene, options), Error);
}

TEST(HostBaseline, ProductTimingOnHexLattice) {
  // 2x2x2 cells, 3x3x3 vertices. Two lattice vertices share a cell exactly
  // when their indices differ by at most one along every axis: along an axis
  // of 3 vertices that is 3 + 2 * 2 = 7 ordered pairs, so 7^3 = 343 coupled
  // vertex pairs, each a dense 3x3 block.
  const Mesh mesh = make_box_lattice(2, 2, 2, 0.5);
  const StableNeoHookean material = StableNeoHookean::from_youngs_modulus(1.0, 0.45);
  std::vector<double> x = mesh.positions.xyz();
  for (size_t i = 0; i < x.size(); ++i) x[i] *= 1.0 + 0.01 * static_cast<double>(i % 3);
  const bench::HostProductTiming t = bench::time_host_product(mesh, material, x, 20);
  EXPECT_EQ(t.nonzeros, 343u * 9u);
  EXPECT_GT(t.assembly_seconds, 0.0);
  EXPECT_GT(t.product_seconds, 0.0);
  EXPECT_THROW(bench::time_host_product(mesh, material, x, 0), Error);
}

}  // namespace
}  // namespace snh
