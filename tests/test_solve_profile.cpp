// The per-phase profile of a solve (SolveResult::profile, StepResult::profile):
// every part non-negative, the parts adding up to the total, the total the
// solve's wall time less its callbacks, the phases that ran non-zero and the
// preconditioner's zero without one; and timing leaves the results alone.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "snh/scenes.h"
#include "snh/simulation.h"

namespace snh::test {
namespace {

std::vector<double> parts(const SolveProfile& p) {
  return {p.linearization,
          p.products,
          p.preconditioner_setup,
          p.preconditioner_apply,
          p.cg_vector_work,
          p.line_search_energies,
          p.transfers,
          p.other};
}

void expect_consistent(const SolveProfile& p, const std::string& what) {
  double sum = 0.0;
  for (double s : parts(p)) {
    EXPECT_GE(s, 0.0) << what;
    sum += s;
  }
  EXPECT_NEAR(sum, p.total, 1e-9 * std::max(1.0, p.total)) << what;
}

Scene small_twist() {
  SceneParameters p;
  p.resolution = 3;
  return make_scene("twist", p);
}

SolveResult solve(const Scene& scene, Preconditioner preconditioner, SolveOptions options = {}) {
  SolveOptions o = scene.options;
  o.preconditioner = preconditioner;
  o.on_iteration = options.on_iteration;
  QuasistaticSolver solver(scene.mesh, scene.material, scene.constraints, o);
  return solver.solve();
}

TEST(SolveProfile, PartsAddUpToTheWallTime) {
  const Scene scene = small_twist();
  const SolveResult r = solve(scene, Preconditioner::block_jacobi);
  ASSERT_TRUE(r.converged);
  expect_consistent(r.profile, "solve");
  // No callbacks: the total is the solve's wall time (within the few clock
  // reads between the two).
  EXPECT_NEAR(r.profile.total, r.seconds, std::max(0.002, 0.01 * r.seconds));
  EXPECT_GT(r.profile.products, 0.0);
  EXPECT_GT(r.profile.linearization, 0.0);
  EXPECT_GT(r.profile.preconditioner_setup, 0.0);
  EXPECT_GT(r.profile.preconditioner_apply, 0.0);
  EXPECT_GT(r.profile.cg_vector_work, 0.0);
  EXPECT_GT(r.profile.line_search_energies, 0.0);
  EXPECT_GT(r.profile.transfers, 0.0);
  // The steps' profiles are the solve's, split.
  SolveProfile steps;
  ASSERT_EQ(r.steps.size(), 2u);
  for (const StepResult& s : r.steps) {
    expect_consistent(s.profile, "step " + std::to_string(s.step));
    EXPECT_GT(s.profile.products, 0.0);
    steps += s.profile;
  }
  EXPECT_NEAR(steps.products, r.profile.products, 1e-9);
  EXPECT_NEAR(steps.linearization, r.profile.linearization, 1e-9);
  EXPECT_LE(steps.total, r.profile.total + 1e-9);
  EXPECT_GT(r.device_memory_bytes, 10 * 3 * scene.mesh.vertex_count() * sizeof(double));
}

// The per-kernel seconds break the phases down: the element kernels that ran
// are there, each > 0, all of them within the device phases' total; the
// steps' kernels add up to the solve's.
TEST(SolveProfile, KernelSecondsBreakDownTheDevicePhases) {
  const Scene scene = small_twist();
  const SolveResult r = solve(scene, Preconditioner::block_jacobi);
  ASSERT_TRUE(r.converged);
  for (const char* name : {"snh_element_linearize", "snh_element_energy", "snh_element_forces", "snh_gather_vectors",
                           "snh_block_jacobi_apply"})
    EXPECT_TRUE(r.profile.kernels.count(name)) << name;
  double kernels = 0.0;
  for (const auto& [name, seconds] : r.profile.kernels) {
    EXPECT_GT(seconds, 0.0) << name;
    kernels += seconds;
  }
  const SolveProfile& p = r.profile;
  EXPECT_LE(kernels, p.total - p.other - p.transfers + 1e-6);
  EXPECT_LE(r.profile.kernels.at("snh_element_linearize"), p.linearization + 1e-6);
  SolveProfile steps;
  for (const StepResult& s : r.steps) steps += s.profile;
  ASSERT_EQ(steps.kernels.size(), r.profile.kernels.size());
  for (const auto& [name, seconds] : r.profile.kernels) EXPECT_NEAR(steps.kernels[name], seconds, 1e-9) << name;
}

TEST(SolveProfile, NoPreconditionerTimeWithoutOne) {
  const SolveResult r = solve(small_twist(), Preconditioner::none);
  ASSERT_TRUE(r.converged);
  expect_consistent(r.profile, "none");
  EXPECT_EQ(r.profile.preconditioner_setup, 0.0);
  EXPECT_EQ(r.profile.preconditioner_apply, 0.0);
  EXPECT_GT(r.profile.products, 0.0);
}

TEST(SolveProfile, CallbackTimeIsLeftOutAndResultsStayTheSame) {
  const Scene scene = small_twist();
  const SolveResult plain = solve(scene, Preconditioner::block_jacobi);
  SolveOptions slow;
  slow.on_iteration = [](const NewtonIteration&, const Points&) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  };
  const SolveResult r = solve(scene, Preconditioner::block_jacobi, slow);
  // Same iterations, bit for bit: the timers and queue waits change nothing.
  ASSERT_EQ(r.history.size(), plain.history.size());
  EXPECT_EQ(r.positions, plain.positions);
  int updates = 0;
  for (const StepResult& s : r.steps) updates += s.newton_iterations;
  ASSERT_GT(updates, 0);
  const double slept = 0.020 * updates;
  EXPECT_GE(r.seconds, r.profile.total + 0.9 * slept);
  expect_consistent(r.profile, "with callbacks");
  EXPECT_LT(r.profile.other, 0.5 * slept);
}

}  // namespace
}  // namespace snh::test
