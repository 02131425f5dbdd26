// The device traffic a solve reports (SolveProfile::kernel_launches,
// blocking_readbacks, bytes_to_host, bytes_to_device and their split by
// phase) is what the engine asks of OpenCL: this test binary stands between
// the library and the OpenCL loader (its own clEnqueue* entry points count
// each call, then forward to the loader's), so the profile's figures are
// compared with the calls themselves, ViennaCL's included. Then CG on the
// device: one blocking read per cg_check_every iterations and none inside
// products or V-cycles, the same equilibria as ViennaCL's CG, and bitwise
// repeatable runs.
#include <dlfcn.h>
#include <gtest/gtest.h>

#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <string>

#include "snh/error.h"
#include "snh/scenes.h"
#include "snh/simulation.h"

namespace {

struct Calls {
  long long launches = 0, blocking_reads = 0, other_reads = 0, bytes_to_host = 0, bytes_to_device = 0;
};
Calls calls;

template <typename F>
F real_entry(const char* name) {
  void* f = dlsym(RTLD_NEXT, name);
  if (!f) std::abort();
  return reinterpret_cast<F>(f);
}

}  // namespace

extern "C" {

CL_API_ENTRY cl_int CL_API_CALL clEnqueueNDRangeKernel(cl_command_queue q, cl_kernel k, cl_uint dims,
                                                       const size_t* offset, const size_t* global, const size_t* local,
                                                       cl_uint waits, const cl_event* wait, cl_event* event) {
  using F = decltype(&clEnqueueNDRangeKernel);
  static const F real = real_entry<F>("clEnqueueNDRangeKernel");
  ++calls.launches;
  return real(q, k, dims, offset, global, local, waits, wait, event);
}

CL_API_ENTRY cl_int CL_API_CALL clEnqueueTask(cl_command_queue q, cl_kernel k, cl_uint waits, const cl_event* wait,
                                              cl_event* event) {
  using F = decltype(&clEnqueueTask);
  static const F real = real_entry<F>("clEnqueueTask");
  ++calls.launches;
  return real(q, k, waits, wait, event);
}

CL_API_ENTRY cl_int CL_API_CALL clEnqueueReadBuffer(cl_command_queue q, cl_mem b, cl_bool blocking, size_t offset,
                                                    size_t size, void* ptr, cl_uint waits, const cl_event* wait,
                                                    cl_event* event) {
  using F = decltype(&clEnqueueReadBuffer);
  static const F real = real_entry<F>("clEnqueueReadBuffer");
  (blocking ? calls.blocking_reads : calls.other_reads)++;
  calls.bytes_to_host += static_cast<long long>(size);
  return real(q, b, blocking, offset, size, ptr, waits, wait, event);
}

CL_API_ENTRY cl_int CL_API_CALL clEnqueueWriteBuffer(cl_command_queue q, cl_mem b, cl_bool blocking, size_t offset,
                                                     size_t size, const void* ptr, cl_uint waits, const cl_event* wait,
                                                     cl_event* event) {
  using F = decltype(&clEnqueueWriteBuffer);
  static const F real = real_entry<F>("clEnqueueWriteBuffer");
  calls.bytes_to_device += static_cast<long long>(size);
  return real(q, b, blocking, offset, size, ptr, waits, wait, event);
}

CL_API_ENTRY cl_mem CL_API_CALL clCreateBuffer(cl_context c, cl_mem_flags flags, size_t size, void* host,
                                               cl_int* status) {
  using F = decltype(&clCreateBuffer);
  static const F real = real_entry<F>("clCreateBuffer");
  if (flags & CL_MEM_COPY_HOST_PTR) calls.bytes_to_device += static_cast<long long>(size);
  return real(c, flags, size, host, status);
}

}  // extern "C"

namespace snh::test {
namespace {

Scene twist(int resolution = 3) {
  SceneParameters p;
  p.resolution = resolution;
  return make_scene("twist", p);
}

struct Traced {
  SolveResult result;
  Calls calls;  // the OpenCL calls made during solve()
};

Traced run(const Scene& scene, Preconditioner preconditioner, int check_every,
           HessianMode hessian = HessianMode::adaptive, const std::array<double, 3>& body_force = {0.0, 0.0, 0.0},
           const std::function<void(SolveOptions&)>& adjust = {}) {
  SolveOptions o = scene.options;
  if (body_force != std::array<double, 3>{0.0, 0.0, 0.0}) o.body_force = body_force;
  o.hessian = hessian;
  o.preconditioner = preconditioner;
  o.cg_check_every = check_every;
  // A V-cycle with a coarse level at this size (the default coarsest level
  // would be the whole mesh).
  o.multigrid.coarsest_dofs = 60;
  o.multigrid.coarse_solve_on_device = true;
  if (adjust) adjust(o);
  QuasistaticSolver solver(scene.mesh, scene.material, scene.constraints, o);
  const Calls before = calls;
  Traced r;
  r.result = solver.solve();
  r.calls.launches = calls.launches - before.launches;
  r.calls.blocking_reads = calls.blocking_reads - before.blocking_reads;
  r.calls.other_reads = calls.other_reads - before.other_reads;
  r.calls.bytes_to_host = calls.bytes_to_host - before.bytes_to_host;
  r.calls.bytes_to_device = calls.bytes_to_device - before.bytes_to_device;
  return r;
}

// A linear solve's share of the traffic: its products, preconditioner
// applications and CG's own work.
DeviceTraffic cg_traffic(const SolveProfile& p) {
  DeviceTraffic t;
  for (const char* phase : {"products", "preconditioner_apply", "cg_vector_work"})
    if (p.traffic.count(phase)) t += p.traffic.at(phase);
  return t;
}

// The rest, less the preconditioner's set-up: the Newton loop's own traffic.
DeviceTraffic outside_linear_solves(const SolveProfile& p) {
  DeviceTraffic outside;
  for (const auto& [phase, t] : p.traffic)
    if (phase != "products" && phase != "preconditioner_apply" && phase != "cg_vector_work" &&
        phase != "preconditioner_setup")
      outside += t;
  return outside;
}

int newton_iterations(const SolveResult& r) {
  int n = 0;
  for (const StepResult& s : r.steps) n += s.newton_iterations;
  return n;
}

int cg_iterations(const SolveResult& r) {
  int n = 0;
  for (const StepResult& s : r.steps) n += s.cg_iterations;
  return n;
}

// One per Newton iteration that solved (with HessianMode::projected: no
// retry on the projection).
int linear_solves(const SolveResult& r) {
  int n = 0;
  for (const NewtonIteration& h : r.history)
    if (h.cg_stop != CgStop::none) ++n;
  return n;
}

void expect_counts_are_the_calls(const Traced& r, const std::string& what) {
  const SolveProfile& p = r.result.profile;
  EXPECT_EQ(p.kernel_launches, r.calls.launches) << what;
  EXPECT_EQ(p.blocking_readbacks, r.calls.blocking_reads) << what;
  EXPECT_EQ(r.calls.other_reads, 0) << what;
  EXPECT_EQ(p.bytes_to_host, r.calls.bytes_to_host) << what;
  EXPECT_EQ(p.bytes_to_device, r.calls.bytes_to_device) << what;
  // The phases add up to the totals.
  DeviceTraffic sum;
  for (const auto& [phase, t] : p.traffic) sum += t;
  EXPECT_EQ(sum.kernel_launches, p.kernel_launches) << what;
  EXPECT_EQ(sum.blocking_readbacks, p.blocking_readbacks) << what;
  EXPECT_EQ(sum.bytes_to_host, p.bytes_to_host) << what;
  // The steps' traffic is the solve's, split.
  long long launches = 0, reads = 0;
  for (const StepResult& s : r.result.steps) {
    launches += s.profile.kernel_launches;
    reads += s.profile.blocking_readbacks;
  }
  EXPECT_LE(launches, p.kernel_launches) << what;
  EXPECT_LE(reads, p.blocking_readbacks) << what;
  EXPECT_GT(launches, 0) << what;
}

TEST(DeviceTraffic, CountsAreTheOpenClCallsWithBlockJacobi) {
  const Traced r = run(twist(), Preconditioner::block_jacobi, 8);
  ASSERT_TRUE(r.result.converged);
  expect_counts_are_the_calls(r, "block-jacobi");
}

TEST(DeviceTraffic, CountsAreTheOpenClCallsWithMultigrid) {
  const Traced r = run(twist(4), Preconditioner::multigrid, 8);
  ASSERT_TRUE(r.result.converged);
  expect_counts_are_the_calls(r, "multigrid");
}

TEST(DeviceTraffic, CountsAreTheOpenClCallsWithViennaClCg) {
  const Traced r = run(twist(), Preconditioner::block_jacobi, 0);
  ASSERT_TRUE(r.result.converged);
  // ViennaCL's CG queues its own kernels and reads behind the engine's
  // counts: only what the engine itself queued is counted, never more.
  EXPECT_LE(r.result.profile.kernel_launches, r.calls.launches);
  EXPECT_LE(r.result.profile.blocking_readbacks, r.calls.blocking_reads);
  EXPECT_GT(r.calls.blocking_reads - r.result.profile.blocking_readbacks, cg_iterations(r.result));
}

// Checked every iteration, CG reads exactly once per iteration; products and
// the preconditioner never read.
TEST(DeviceTraffic, CgCheckedEveryIterationReadsOncePerIteration) {
  const Traced r = run(twist(), Preconditioner::block_jacobi, 1, HessianMode::projected);
  ASSERT_TRUE(r.result.converged);
  const SolveProfile& p = r.result.profile;
  EXPECT_EQ(p.cg_iterations_past_convergence, 0);
  EXPECT_EQ(cg_traffic(p).blocking_readbacks, cg_iterations(r.result));
  EXPECT_EQ(p.traffic.at("products").blocking_readbacks, 0);
  EXPECT_EQ(p.traffic.at("preconditioner_apply").blocking_readbacks, 0);
}

void expect_reads_per_check(Preconditioner preconditioner, int resolution, int k) {
  const Traced r = run(twist(resolution), preconditioner, k, HessianMode::projected);
  ASSERT_TRUE(r.result.converged);
  const SolveProfile& p = r.result.profile;
  // Those reported (up to each solve's stop) and those run past them.
  const long long run_iterations = cg_iterations(r.result) + p.cg_iterations_past_convergence;
  const long long solves = linear_solves(r.result);
  ASSERT_GT(solves, 0);
  // ceil(iterations / k) per linear solve.
  const long long reads = cg_traffic(p).blocking_readbacks;
  EXPECT_GE(reads * k, run_iterations);
  EXPECT_LE(reads * k, run_iterations + solves * (k - 1));
  EXPECT_LE(p.cg_iterations_past_convergence, solves * (k - 1));
  // None inside a product or a V-cycle.
  EXPECT_EQ(p.traffic.at("products").blocking_readbacks, 0);
  if (p.traffic.count("preconditioner_apply")) {
    EXPECT_EQ(p.traffic.at("preconditioner_apply").blocking_readbacks, 0);
  }
}

TEST(DeviceTraffic, CgReadsOncePerCheckWithBlockJacobi) { expect_reads_per_check(Preconditioner::block_jacobi, 3, 4); }

TEST(DeviceTraffic, CgReadsOncePerCheckWithMultigrid) { expect_reads_per_check(Preconditioner::multigrid, 4, 8); }

// The device CG reaches the equilibrium ViennaCL's CG reaches, within the
// Newton tolerance, and repeats itself bit for bit.
void expect_same_equilibrium(const Scene& scene, Preconditioner preconditioner) {
  const Traced old = run(scene, preconditioner, 0);
  const Traced a = run(scene, preconditioner, 8);
  const Traced b = run(scene, preconditioner, 8);
  ASSERT_TRUE(old.result.converged);
  ASSERT_TRUE(a.result.converged);
  EXPECT_EQ(a.result.positions, b.result.positions);
  ASSERT_EQ(a.result.history.size(), b.result.history.size());
  for (size_t i = 0; i < a.result.history.size(); ++i)
    EXPECT_EQ(a.result.history[i].energy, b.result.history[i].energy) << i;
  // Both stop at |r| <= tolerance; the positions differ by at most what
  // that residual moves at the material's smallest stiffness, far below
  // the mesh spacing.
  const std::vector<double>&xa = a.result.positions.xyz(), &xo = old.result.positions.xyz();
  ASSERT_EQ(xa.size(), xo.size());
  double diff = 0.0, extent = 0.0;
  for (size_t i = 0; i < xa.size(); ++i) {
    diff = std::max(diff, std::abs(xa[i] - xo[i]));
    extent = std::max(extent, std::abs(xo[i]));
  }
  EXPECT_LT(diff, 1e-5 * extent);
  const double e_old = old.result.history.back().energy, e_new = a.result.history.back().energy;
  EXPECT_NEAR(e_new, e_old, 1e-8 * std::abs(e_old));
  EXPECT_LE(a.result.final_residual_norm, a.result.tolerance);
}

TEST(DeviceTraffic, DeviceCgFindsViennaClsEquilibriumWithBlockJacobi) {
  expect_same_equilibrium(twist(), Preconditioner::block_jacobi);
}

TEST(DeviceTraffic, DeviceCgFindsViennaClsEquilibriumWithMultigrid) {
  expect_same_equilibrium(twist(4), Preconditioner::multigrid);
}

TEST(DeviceTraffic, DeviceCgFindsViennaClsEquilibriumInTheStretch) {
  SceneParameters p;
  p.resolution = 3;
  expect_same_equilibrium(make_scene("stretch", p), Preconditioner::block_jacobi);
}

// The device stops CG itself at the iteration that met the tolerance (x and
// r stay from then on), so the check interval changes only how many
// iterations run past it: the same solution, bit for bit, and the same
// reported iterations and relative residuals for every k.
void expect_independent_of_check_interval(const Scene& scene, Preconditioner preconditioner) {
  const Traced every = run(scene, preconditioner, 1);
  ASSERT_TRUE(every.result.converged);
  EXPECT_EQ(every.result.profile.cg_iterations_past_convergence, 0);
  for (int k : {2, 5, 8}) {
    const Traced r = run(scene, preconditioner, k);
    ASSERT_TRUE(r.result.converged) << k;
    EXPECT_EQ(r.result.positions, every.result.positions) << k;
    ASSERT_EQ(r.result.history.size(), every.result.history.size()) << k;
    for (size_t i = 0; i < r.result.history.size(); ++i) {
      EXPECT_EQ(r.result.history[i].cg_iterations, every.result.history[i].cg_iterations) << k << " " << i;
      EXPECT_EQ(r.result.history[i].cg_relative_residual, every.result.history[i].cg_relative_residual)
          << k << " " << i;
      EXPECT_EQ(r.result.history[i].energy, every.result.history[i].energy) << k << " " << i;
    }
  }
}

TEST(DeviceTraffic, DeviceCgResultDoesNotDependOnTheCheckIntervalWithBlockJacobi) {
  expect_independent_of_check_interval(twist(), Preconditioner::block_jacobi);
}

TEST(DeviceTraffic, DeviceCgResultDoesNotDependOnTheCheckIntervalWithMultigrid) {
  expect_independent_of_check_interval(twist(4), Preconditioner::multigrid);
}

// On the first Newton iteration both CGs solve the same system from the same
// start: the device CG stops where ViennaCL's does (its test: the
// preconditioned residual r.z against r0.z0) and reports that residual,
// which differs only by the rounding of the two CGs' inner products.
TEST(DeviceTraffic, DeviceCgStopsWhereViennaClsCgStops) {
  for (Preconditioner preconditioner : {Preconditioner::block_jacobi, Preconditioner::multigrid}) {
    const Scene scene = twist(4);
    const Traced old = run(scene, preconditioner, 0);
    const Traced now = run(scene, preconditioner, 4);
    ASSERT_FALSE(old.result.history.empty());
    ASSERT_FALSE(now.result.history.empty());
    const NewtonIteration &a = old.result.history.front(), &b = now.result.history.front();
    EXPECT_EQ(a.residual_norm, b.residual_norm);
    EXPECT_EQ(b.cg_iterations, a.cg_iterations);
    EXPECT_NEAR(b.cg_relative_residual, a.cg_relative_residual, 1e-6 * a.cg_relative_residual);
  }
}

// The Newton loop's own reads (norms, dots, the energy with its minimum J
// and its external work) are a few doubles each, whatever the DOF count,
// and a constant number per Newton iteration; CG reads once per k
// iterations; the V-cycle (its coarsest solve on the device) never.
struct NewtonReads {
  double reads_per_newton = 0.0;  // outside the linear solves and the preconditioner's set-up
  double bytes_per_read = 0.0;    // of those
  long long dofs = 0;
};

NewtonReads newton_reads(int resolution, Preconditioner preconditioner, int k, const std::array<double, 3>& force) {
  SceneParameters parameters;
  parameters.resolution = resolution;
  parameters.steps = 1;
  const Traced r = run(make_scene("twist", parameters), preconditioner, k, HessianMode::projected, force);
  EXPECT_TRUE(r.result.converged) << resolution;
  const SolveProfile& p = r.result.profile;
  const DeviceTraffic outside = outside_linear_solves(p);
  const int newton = newton_iterations(r.result);
  EXPECT_GT(newton, 0);
  // CG: one read of 2 k + 2 doubles per k iterations; none in a V-cycle.
  const DeviceTraffic cg = cg_traffic(p);
  const long long run_iterations = cg_iterations(r.result) + p.cg_iterations_past_convergence;
  EXPECT_LE(cg.blocking_readbacks * k, run_iterations + linear_solves(r.result) * (k - 1)) << resolution;
  EXPECT_EQ(cg.bytes_to_host, cg.blocking_readbacks * static_cast<long long>((2 * k + 2) * sizeof(double)));
  if (p.traffic.count("preconditioner_apply")) {
    EXPECT_EQ(p.traffic.at("preconditioner_apply").blocking_readbacks, 0);
  }
  // Less each step's result, read once at its end (double here).
  NewtonReads out;
  out.dofs = static_cast<long long>(r.result.positions.xyz().size());
  const long long steps = static_cast<long long>(r.result.steps.size());
  const long long reads = outside.blocking_readbacks - steps;
  const long long bytes = outside.bytes_to_host - steps * out.dofs * static_cast<long long>(sizeof(double));
  EXPECT_GT(reads, 0);
  out.reads_per_newton = static_cast<double>(reads) / newton;
  out.bytes_per_read = static_cast<double>(bytes) / std::max<long long>(1, reads);
  return out;
}

void expect_constant_newton_reads(Preconditioner preconditioner, int small, int large,
                                  const std::array<double, 3>& force) {
  const int k = 4;
  const NewtonReads a = newton_reads(small, preconditioner, k, force);
  const NewtonReads b = newton_reads(large, preconditioner, k, force);
  // More than two reduction groups (4,096 entries) at the larger size, so a
  // read of per-group partials or of whole vectors would grow.
  ASSERT_GT(b.dofs, 2 * 4096);
  ASSERT_GT(b.dofs, 4 * a.dofs);
  for (const NewtonReads& r : {a, b}) {
    // The residual norm, the slope, one energy and one residual norm per
    // line-search trial, the descent at the accepted step: with full steps
    // about five, and never more than the line search's trials allow.
    EXPECT_GT(r.reads_per_newton, 2.0);
    EXPECT_LE(r.reads_per_newton, 8.0);
    // At most the energy's five doubles in one read.
    EXPECT_LE(r.bytes_per_read, 5.0 * sizeof(double));
  }
  // The same reads at both sizes (the mix of energies, norms and dots
  // shifts a little with the line search's trials); per-group partials
  // would make the larger size's reads three times as large.
  EXPECT_LE(b.bytes_per_read, 1.1 * a.bytes_per_read);
  EXPECT_GE(b.bytes_per_read, a.bytes_per_read / 1.1);
}

TEST(DeviceTraffic, NewtonReadsAFewDoublesPerIterationWhateverTheSizeWithBlockJacobi) {
  expect_constant_newton_reads(Preconditioner::block_jacobi, 3, 14, {0.0, 0.0, 0.0});
}

TEST(DeviceTraffic, NewtonReadsAFewDoublesPerIterationWhateverTheSizeWithMultigrid) {
  expect_constant_newton_reads(Preconditioner::multigrid, 4, 14, {0.0, 0.0, 0.0});
}

// The external forces' work is a dot product on the device: the energy with
// a body force reads no vector either.
TEST(DeviceTraffic, EnergyWithExternalForceReadsNoVector) {
  expect_constant_newton_reads(Preconditioner::multigrid, 4, 14, {0.0, 0.0, -0.2});
}

// A multigrid build reads once or twice whatever the DOF count, the levels
// and the power iterations: every estimated level's lambda_max in one read
// and, with the coarsest solve on the host, the coarsest level's cell
// matrices for its factor. A reused hierarchy with a current fine level
// re-estimates the fine bound at each linearization: one read.
TEST(DeviceTraffic, MultigridBuildReadsOnceOrTwiceWhateverTheLevels) {
  for (bool device_coarse : {true, false})
    for (MultigridFineLevel fine : {MultigridFineLevel::built, MultigridFineLevel::current})
      for (int resolution : {4, 14}) {
        const Traced r = run(twist(resolution), Preconditioner::multigrid, 4, HessianMode::projected, {0.0, 0.0, 0.0},
                             [&](SolveOptions& o) {
                               o.multigrid.coarse_solve_on_device = device_coarse;
                               o.multigrid.fine_level = fine;
                               o.multigrid.rebuild_every = fine == MultigridFineLevel::built ? 1 : 3;
                             });
        const std::string what = std::string(device_coarse ? "device" : "host") + " coarsest solve, " +
                                 to_string(fine) + " fine level, res " + std::to_string(resolution);
        ASSERT_TRUE(r.result.converged) << what;
        long long builds = 0;
        for (const StepResult& s : r.result.steps) builds += s.preconditioner_builds;
        const long long linearizations = linear_solves(r.result);
        ASSERT_GT(builds, 0) << what;
        if (fine == MultigridFineLevel::built) {
          EXPECT_EQ(builds, linearizations) << what;
        } else {
          EXPECT_LT(builds, linearizations) << what;
        }
        const DeviceTraffic& setup = r.result.profile.traffic.at("preconditioner_setup");
        EXPECT_EQ(setup.blocking_readbacks, (device_coarse ? 1 : 2) * builds + (linearizations - builds)) << what;
      }
}

// Implicit Euler's inertia energy is a device reduction too: a dynamics
// step's Newton loop reads a few doubles per iteration whatever the size,
// and bytes to host per Newton iteration (less each substep's result, all
// of x once) do not grow with the DOF count.
struct DynamicsReads {
  double reads_per_newton = 0.0, bytes_per_newton = 0.0;
  long long dofs = 0;
};

DynamicsReads dynamics_reads(int resolution, Preconditioner preconditioner) {
  SceneParameters parameters;
  parameters.resolution = resolution;
  parameters.steps = 3;
  const Scene scene = make_scene("twist", parameters);
  const int substeps = 2;
  const Traced r = run(scene, preconditioner, 4, HessianMode::projected, {0.0, 0.0, 0.0}, [&](SolveOptions& o) {
    o.dynamics = DynamicsOptions{};
    o.dynamics->time_step = 0.01;
    o.dynamics->density = 1000.0;
    o.dynamics->damping.mass = 0.5;
    o.dynamics->substeps = substeps;
  });
  EXPECT_TRUE(r.result.converged) << resolution;
  const SolveProfile& p = r.result.profile;
  const DeviceTraffic outside = outside_linear_solves(p);
  const int newton = newton_iterations(r.result);
  EXPECT_GT(newton, 0);
  DynamicsReads out;
  out.dofs = static_cast<long long>(r.result.positions.xyz().size());
  const long long solves = static_cast<long long>(r.result.steps.size()) * substeps;
  const long long bytes = outside.bytes_to_host - solves * out.dofs * static_cast<long long>(sizeof(double));
  out.reads_per_newton = static_cast<double>(outside.blocking_readbacks - solves) / newton;
  out.bytes_per_newton = static_cast<double>(bytes) / newton;
  return out;
}

void expect_constant_dynamics_reads(Preconditioner preconditioner) {
  const DynamicsReads a = dynamics_reads(4, preconditioner);
  const DynamicsReads b = dynamics_reads(14, preconditioner);
  ASSERT_GT(b.dofs, 2 * 4096);
  ASSERT_GT(b.dofs, 4 * a.dofs);
  for (const DynamicsReads& r : {a, b}) {
    EXPECT_GT(r.reads_per_newton, 2.0) << r.dofs;
    EXPECT_LE(r.reads_per_newton, 8.0) << r.dofs;
    // The energy's sums in one read of at most six doubles, the norms and
    // dots one double each: a read of x (3 DOF doubles per vertex) would
    // add dofs * 8 bytes per energy.
    EXPECT_LE(r.bytes_per_newton, 8.0 * 6 * sizeof(double)) << r.dofs;
  }
  EXPECT_LE(b.bytes_per_newton, 1.5 * a.bytes_per_newton);
}

TEST(DeviceTraffic, DynamicsReadsAFewDoublesPerNewtonIterationWithBlockJacobi) {
  expect_constant_dynamics_reads(Preconditioner::block_jacobi);
}

TEST(DeviceTraffic, DynamicsReadsAFewDoublesPerNewtonIterationWithMultigrid) {
  expect_constant_dynamics_reads(Preconditioner::multigrid);
}

// With obstacles, multigrid asks at each linearization whether the contact
// set changed (a changed set rebuilds the hierarchy): an integer hash
// reduced on the device, so the bytes read per linearization do not grow
// with the lattice, where reading every vertex's depth would (8 bytes a
// vertex).
struct ContactReads {
  double bytes_per_linearization = 0.0;
  long long vertices = 0;
  int contacts = 0;
};

ContactReads contact_reads(int resolution) {
  SceneParameters parameters;
  parameters.resolution = resolution;
  parameters.steps = 1;
  const Scene scene = make_scene("twist", parameters);
  const double h = 1.0 / resolution;
  // A wall facing the side x = 0, its layer half a cell thick and just
  // reaching that side at rest: the twist turns the middle layers' corners
  // into it.
  const Traced r =
      run(scene, Preconditioner::multigrid, 4, HessianMode::projected, {0.0, 0.0, 0.0}, [&](SolveOptions& o) {
        o.obstacles = {Obstacle::plane({-0.5 * h, 0.0, 0.0}, {1.0, 0.0, 0.0})};
        o.contact.thickness = 0.5 * h;
        o.contact.stiffness = 10.0 * h;
      });
  EXPECT_TRUE(r.result.converged) << resolution;
  EXPECT_NE(r.result.kernel_specialization.find("-DSNH_OBSTACLES=1"), std::string::npos);
  const SolveProfile& p = r.result.profile;
  ContactReads out;
  out.vertices = static_cast<long long>(r.result.positions.size());
  out.contacts = r.result.steps.back().contacts;
  // Less each step's result: x, and the depths for its contact count and
  // deepest penetration.
  const long long steps = static_cast<long long>(r.result.steps.size());
  const long long bytes = outside_linear_solves(p).bytes_to_host - steps * 4 * out.vertices * sizeof(double);
  const int linearizations = linear_solves(r.result);
  EXPECT_GT(linearizations, 1) << resolution;
  out.bytes_per_linearization = static_cast<double>(bytes) / std::max(1, linearizations);
  return out;
}

TEST(DeviceTraffic, ContactSetCheckReadsAFewBytesPerLinearizationWhateverTheSize) {
  const ContactReads a = contact_reads(4);
  const ContactReads b = contact_reads(16);
  // More than one reduction group (4,096 entries) at the larger size.
  ASSERT_GT(b.vertices, 4096);
  ASSERT_GT(b.vertices, 4 * a.vertices);
  for (const ContactReads& r : {a, b}) {
    EXPECT_GT(r.contacts, 0) << r.vertices;
    EXPECT_LE(r.bytes_per_linearization, 8.0 * 6 * sizeof(double)) << r.vertices;
  }
  // Reading every depth: 1,066 and 39,370 bytes per linearization here.
  EXPECT_LE(b.bytes_per_linearization, 1.1 * a.bytes_per_linearization);
}

// Barrier self-contact runs on the device from the solver's own x and p:
// its broad phase reads an int per count that sizes a buffer, its energy
// and step bound a few doubles. A Newton iteration reads a bounded number
// of small values whatever the size; a read of x (or of a pair list) would
// grow with it. Two res x res x 2 lattices, B a tenth of a cell above A, B's
// top pressed down 0.08 cells: B's bottom face within dhat (0.05 cells) of
// A's top.
struct BarrierReads {
  double reads_per_newton = 0.0, bytes_per_read = 0.0;
  int pairs = 0;
  long long dofs = 0;
};

BarrierReads barrier_reads(int resolution) {
  SceneParameters parameters;
  parameters.resolution = resolution;
  parameters.steps = 1;
  Scene scene = make_scene("twist", parameters);
  const double h = 1.0 / resolution;
  const double tolerance_per_root_vertex =
      scene.options.absolute_tolerance / std::sqrt(static_cast<double>(scene.mesh.vertex_count()));
  scene.mesh = make_box_lattice(resolution, resolution, 2, h);
  const Mesh b = make_box_lattice(resolution, resolution, 2, h, {0.0, 0.0, 2.1 * h});
  const int32_t first_b = static_cast<int32_t>(scene.mesh.vertex_count());
  for (size_t v = 0; v < b.vertex_count(); ++v) scene.mesh.positions.push_back(b.vertex(v));
  for (int32_t v : b.elements) scene.mesh.elements.push_back(v + first_b);
  ConstraintSet bottom{"bottom", {}, {}, {}}, top{"top", {}, {}, {}};
  for (size_t v = 0; v < scene.mesh.vertex_count(); ++v) {
    const double z = scene.mesh.positions(v, 2);
    if (std::abs(z) < 1e-9) bottom.vertices.push_back(static_cast<int32_t>(v));
    if (std::abs(z - 4.1 * h) < 1e-9) top.vertices.push_back(static_cast<int32_t>(v));
  }
  top.motion = [h](double t) { return RigidTransform::translation_by({0.0, 0.0, -0.08 * h * t}); };
  scene.constraints = {bottom, top};
  scene.options.absolute_tolerance =
      tolerance_per_root_vertex * std::sqrt(static_cast<double>(scene.mesh.vertex_count()));
  const Traced r =
      run(scene, Preconditioner::block_jacobi, 4, HessianMode::projected, {0.0, 0.0, 0.0}, [&](SolveOptions& o) {
        o.contact.self = true;
        o.contact.self_method = SelfContactMethod::barrier;
        o.contact.self_distance = 0.05 * h;
        o.contact.self_broad_phase = SelfBroadPhase::device;  // what a GPU runs (the CPU's default reads x)
        // Enough iterations to press B against the barrier; the reads per
        // iteration are what is measured, not where Newton ends.
        o.max_newton_iterations = 12;
      });
  const SolveProfile& p = r.result.profile;
  DeviceTraffic outside;
  for (const auto& [phase, t] : p.traffic)
    if (phase != "products" && phase != "preconditioner_apply" && phase != "cg_vector_work" &&
        phase != "preconditioner_setup")
      outside += t;
  int newton = 0;
  BarrierReads out;
  for (const StepResult& s : r.result.steps) {
    newton += s.newton_iterations;
    out.pairs = std::max(out.pairs, s.self_contact_pairs);
  }
  EXPECT_GT(newton, 0);
  // Less each step's result, read once at its end (double here).
  out.dofs = static_cast<long long>(r.result.positions.xyz().size());
  const long long steps = static_cast<long long>(r.result.steps.size());
  const long long reads = outside.blocking_readbacks - steps;
  const long long bytes = outside.bytes_to_host - steps * out.dofs * static_cast<long long>(sizeof(double));
  out.reads_per_newton = static_cast<double>(reads) / newton;
  out.bytes_per_read = static_cast<double>(bytes) / std::max<long long>(1, reads);
  return out;
}

TEST(DeviceTraffic, NewtonWithBarrierSelfContactReadsAFewValuesWhateverTheSize) {
  const BarrierReads a = barrier_reads(4);
  const BarrierReads b = barrier_reads(12);
  ASSERT_GT(b.dofs, 4 * a.dofs);
  for (const BarrierReads& r : {a, b}) {
    // Pairs within dhat: the barrier acted.
    EXPECT_GT(r.pairs, 0) << r.dofs;
    // Per Newton iteration (about 20 here): the elastic loop's few reads,
    // and the barrier's in its residual and its linearization (4 each:
    // cell entries, candidates, pairs within dhat, blocks), step bound (3)
    // and each energy (3); none of a vector.
    EXPECT_GT(r.reads_per_newton, 2.0) << r.dofs;
    EXPECT_LE(r.reads_per_newton, 30.0) << r.dofs;
    // At most the energy's five doubles in one read.
    EXPECT_LE(r.bytes_per_read, 5.0 * sizeof(double)) << r.dofs;
  }
  // The same mix of reads at both sizes: more surface pairs are not more
  // reads (the line search's trials shift the mix a little).
  EXPECT_LE(b.reads_per_newton, 1.5 * a.reads_per_newton);
  EXPECT_LE(b.bytes_per_read, 1.25 * a.bytes_per_read);
  EXPECT_GE(b.bytes_per_read, a.bytes_per_read / 1.25);
}

TEST(DeviceTraffic, NegativeCheckIntervalIsRefused) {
  const Scene scene = twist();
  SolveOptions o = scene.options;
  o.cg_check_every = -1;
  EXPECT_THROW(QuasistaticSolver(scene.mesh, scene.material, scene.constraints, o).solve(), Error);
}

}  // namespace
}  // namespace snh::test
