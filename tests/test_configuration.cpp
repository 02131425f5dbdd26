// The resolved configuration (snh/configuration.h): each unset option's choice
// made by its rule, with its reason; given values kept; resolving twice
// changes nothing; the Simulation, its results, `snh run --explain` and the
// JSON summary all report the same choices.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "snh/configuration.h"
#include "snh/error.h"
#include "snh/mesh.h"
#include "snh/simulation.h"
#include "support/cli_run.h"
#include "support/scratch.h"

namespace snh {
namespace {

const Material kRubber = StableNeoHookean::from_youngs_modulus(1e5, 0.45);

DeviceInfo cpu_device() {
  DeviceInfo d;
  d.platform = "test";
  d.name = "cpu";
  d.has_fp64 = true;
  return d;
}

DeviceInfo gpu_device() {
  DeviceInfo d = cpu_device();
  d.name = "gpu";
  d.is_gpu = true;
  return d;
}

ResolvedConfiguration resolve(const SolveOptions& options, const Mesh& mesh, const DeviceInfo& device = cpu_device()) {
  return resolve_configuration(options, mesh, uniform_material(mesh, kRubber), device);
}

TEST(Configuration, LargeLatticeGetsMultigridWithItsReason) {
  const Mesh mesh = make_box_lattice(12, 12, 12, 0.1);  // 6,591 DOFs
  const ResolvedConfiguration c = resolve(SolveOptions{}, mesh);
  EXPECT_EQ(c.options.preconditioner, Preconditioner::multigrid);
  EXPECT_NE(c.setting("preconditioner").reason.find("6,591 DOFs"), std::string::npos)
      << c.setting("preconditioner").reason;
  // CPU device with multigrid: the cached linearization.
  EXPECT_EQ(c.options.product, ProductVariant::cached);
  EXPECT_EQ(c.options.multigrid.fine_level, MultigridFineLevel::built);
  EXPECT_EQ(c.options.multigrid.smoother_degree, 1);
  EXPECT_EQ(c.options.multigrid.chebyshev_kind, ChebyshevKind::optimized_fourth);
  EXPECT_EQ(c.options.multigrid.rebuild_every, 2);
  EXPECT_TRUE(c.options.multigrid.float_cycle);
  EXPECT_EQ(c.setting("multigrid.coarse_solve").value, "host");
  EXPECT_EQ(c.options.product_precision, Precision::single);
  for (const ResolvedSetting& s : c.settings) {
    EXPECT_FALSE(s.value.empty()) << s.name;
    EXPECT_FALSE(s.reason.empty()) << s.name;
  }
}

// Unset is std::optional (docs/design.md, "Conventions of the public API"):
// the defaults leave every choice empty, and the resolution fills each one
// it uses.
TEST(Configuration, DefaultsAreUnsetAndTheResolutionFillsThem) {
  const SolveOptions defaults;
  EXPECT_FALSE(defaults.preconditioner.has_value());
  EXPECT_FALSE(defaults.product.has_value());
  EXPECT_FALSE(defaults.product_precision.has_value());
  EXPECT_FALSE(defaults.multigrid.smoother_degree.has_value());
  EXPECT_FALSE(defaults.multigrid.chebyshev_kind.has_value());
  EXPECT_FALSE(defaults.multigrid.rebuild_every.has_value());
  EXPECT_FALSE(defaults.multigrid.fine_level.has_value());
  EXPECT_FALSE(defaults.contact.self_distance.has_value());
  EXPECT_FALSE(defaults.contact.self_stiffness.has_value());
  EXPECT_FALSE(defaults.contact.friction_slip.has_value());
  EXPECT_FALSE(defaults.contact.self_broad_phase.has_value());

  // Multigrid (a lattice of 6,591 DOFs).
  const Mesh mesh = make_box_lattice(12, 12, 12, 0.1);
  const SolveOptions mg = resolve(defaults, mesh).options;
  EXPECT_TRUE(mg.preconditioner.has_value());
  EXPECT_TRUE(mg.product.has_value());
  EXPECT_TRUE(mg.product_precision.has_value());
  EXPECT_TRUE(mg.multigrid.smoother_degree.has_value());
  EXPECT_TRUE(mg.multigrid.chebyshev_kind.has_value());
  EXPECT_TRUE(mg.multigrid.rebuild_every.has_value());
  EXPECT_TRUE(mg.multigrid.fine_level.has_value());
  EXPECT_TRUE(mg.multigrid.rebuild_each_load_step.has_value());

  // Barrier self-contact and friction against an obstacle.
  SolveOptions contact;
  contact.contact.self = true;
  contact.contact.stiffness = 1e4;
  contact.contact.friction = 0.5;
  contact.obstacles.push_back(Obstacle::plane({0, 0, -0.01}, {0, 0, 1}));
  const SolveOptions barrier = resolve(contact, make_box_lattice(4, 4, 4, 0.1)).options;
  EXPECT_TRUE(barrier.contact.self_broad_phase.has_value());
  EXPECT_GT(barrier.contact.self_distance.value_or(0.0), 0.0);
  EXPECT_GT(barrier.contact.friction_slip.value_or(0.0), 0.0);
  EXPECT_FALSE(barrier.contact.self_stiffness.has_value());  // the penalty's, not used

  // Penalty self-contact: its stiffness, the obstacles' unless given.
  contact.contact.self_method = SelfContactMethod::penalty;
  contact.preconditioner = Preconditioner::block_jacobi;
  const SolveOptions penalty = resolve(contact, make_box_lattice(4, 4, 4, 0.1)).options;
  EXPECT_EQ(penalty.contact.self_stiffness, 1e4);
}

TEST(Configuration, SmallOrTetMeshesGetBlockJacobi) {
  const ResolvedConfiguration small = resolve(SolveOptions{}, make_box_lattice(4, 4, 4, 0.1));
  EXPECT_EQ(small.options.preconditioner, Preconditioner::block_jacobi);
  EXPECT_NE(small.setting("preconditioner").reason.find("below multigrid's 5,000"), std::string::npos);
  const ResolvedConfiguration tet = resolve(SolveOptions{}, make_tet_box(12, 12, 12, 0.1));
  EXPECT_EQ(tet.options.preconditioner, Preconditioner::block_jacobi);
  EXPECT_EQ(tet.setting("preconditioner").reason, "the mesh is not a hex8 lattice");
  EXPECT_EQ(tet.options.product, ProductVariant::assembled);   // CPU device, no multigrid
  EXPECT_THROW(small.setting("multigrid.fine_level"), Error);  // no multigrid, no multigrid settings
}

TEST(Configuration, PerVertexTermsGiveTheCurrentFineLevel) {
  const Mesh mesh = make_box_lattice(12, 12, 12, 0.1);
  SolveOptions options;
  options.obstacles.push_back(Obstacle::plane({0, 0, -0.01}, {0, 0, 1}));
  options.contact.stiffness = 1e4;
  const ResolvedConfiguration c = resolve(options, mesh);
  EXPECT_EQ(c.options.multigrid.fine_level, MultigridFineLevel::current);
  EXPECT_FALSE(c.options.multigrid.float_cycle);  // needs a built fine level
  options.multigrid.fine_level = MultigridFineLevel::built;
  EXPECT_THROW(resolve(options, mesh), Error);
}

TEST(Configuration, BarrierReachAndBroadPhaseFollowTheSurfaceAndDevice) {
  const Mesh mesh = make_box_lattice(6, 6, 6, 0.1);
  SolveOptions options;
  options.contact.self = true;
  const ResolvedConfiguration cpu = resolve(options, mesh);
  EXPECT_EQ(cpu.options.preconditioner, Preconditioner::block_jacobi);
  EXPECT_EQ(cpu.options.contact.self_broad_phase, SelfBroadPhase::host);
  // 1% of the mean rest surface edge L: the boundary quads as two
  // triangles, two sides and one diagonal per quad, L = (2 + sqrt 2) h / 3;
  // kappa = E L^2 / dhat^3, E from the material's own mu and lambda.
  const double edge = (2.0 + std::sqrt(2.0)) * 0.1 / 3.0, dhat = 0.01 * edge;
  EXPECT_NEAR(cpu.options.contact.self_distance.value(), dhat, 1e-15);
  const double youngs = kRubber.mu * (3 * kRubber.lambda + 2 * kRubber.mu) / (kRubber.lambda + kRubber.mu);
  const double kappa = youngs * edge * edge / (dhat * dhat * dhat);
  EXPECT_NEAR(cpu.barrier_stiffness, kappa, kappa * 1e-12);
  EXPECT_EQ(resolve(options, mesh, gpu_device()).options.contact.self_broad_phase, SelfBroadPhase::device);
  options.contact.self_distance = 2e-3;
  const ResolvedConfiguration given = resolve(options, mesh);
  EXPECT_EQ(given.options.contact.self_distance, 2e-3);
  EXPECT_EQ(given.setting("contact.self_distance").reason, "given");
}

TEST(Configuration, GivenValuesStayAndResolvingTwiceChangesNothing) {
  const Mesh mesh = make_box_lattice(12, 12, 12, 0.1);
  SolveOptions options;
  options.preconditioner = Preconditioner::block_jacobi;
  options.product = ProductVariant::element_matrices;
  options.relative_tolerance = 1e-8;
  const ResolvedConfiguration c = resolve(options, mesh);
  EXPECT_EQ(c.setting("preconditioner").value, "block-jacobi");
  EXPECT_EQ(c.setting("preconditioner").reason, "given");
  EXPECT_EQ(c.setting("product").reason, "given");
  // element matrices keep double products whatever was asked.
  EXPECT_EQ(c.options.product_precision, Precision::double_);
  EXPECT_EQ(c.relative_tolerance, 1e-8);
  EXPECT_EQ(c.absolute_tolerance, 0.0);  // an explicit relative criterion stands alone
  for (const SolveOptions& o : {SolveOptions{}, options}) {
    const ResolvedConfiguration once = resolve(o, mesh);
    const ResolvedConfiguration twice = resolve(once.options, mesh);
    ASSERT_EQ(once.settings.size(), twice.settings.size());
    for (size_t i = 0; i < once.settings.size(); ++i) {
      EXPECT_EQ(once.settings[i].name, twice.settings[i].name);
      EXPECT_EQ(once.settings[i].value, twice.settings[i].value) << once.settings[i].name;
    }
    EXPECT_EQ(once.absolute_tolerance, twice.absolute_tolerance);
  }
}

TEST(Configuration, CombinationsThatCannotRunAreRefused) {
  SolveOptions options;
  options.preconditioner = Preconditioner::multigrid;
  EXPECT_THROW(resolve(options, make_tet_box(4, 4, 4, 0.1)), Error);
  options.contact.self = true;
  options.contact.self_method = SelfContactMethod::penalty;
  options.contact.stiffness = 1e4;
  try {
    resolve(options, make_box_lattice(4, 4, 4, 0.1));
    FAIL() << "multigrid with the penalty was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("self-contact penalty"), std::string::npos) << e.what();
  }
}

TEST(Configuration, SimulationRunsWithWhatItReports) {
  const Mesh mesh = make_box_lattice(12, 4, 4, 0.1);
  std::vector<int32_t> left;
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    if (mesh.positions(v, 0) < 1e-9) left.push_back(static_cast<int32_t>(v));
  SolveOptions options;
  options.body_force = {0, 0, -1e3};
  Simulation sim(mesh, kRubber, {ConstraintSet::fixed("left", left)}, options);
  const ResolvedConfiguration& c = sim.configuration();
  const ResolvedConfiguration again = resolve_configuration(options, mesh, sim.materials(), sim.device());
  ASSERT_EQ(c.settings.size(), again.settings.size());
  for (size_t i = 0; i < c.settings.size(); ++i) EXPECT_EQ(c.settings[i].value, again.settings[i].value);
  const SolveResult r = sim.solve();
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.preconditioner, c.options.preconditioner);
  EXPECT_EQ(r.product, c.options.product);
  EXPECT_EQ(r.tolerance, c.absolute_tolerance);
  EXPECT_EQ(sim.tolerance(), c.absolute_tolerance);
  EXPECT_EQ(r.product_precision, *c.options.product_precision);
}

TEST(Configuration, ExplainPrintsItAndTheJsonCarriesIt) {
  const std::filesystem::path dir = test::fresh_dir("configuration_explain");
  const std::string scene = (dir / "pull.json").string(), json = (dir / "summary.json").string();
  {
    std::ofstream out(scene);
    out << R"({"mesh": {"generator": "box", "cells": [4, 4, 4], "size": 0.25},
      "material": {"model": "snh", "E": 1.0, "nu": 0.45},
      "constraints": [
        {"name": "bottom", "select": {"plane": {"axis": "z", "value": 0.0, "tolerance": 1e-9}}},
        {"name": "top", "select": {"plane": {"axis": "z", "value": 1.0, "tolerance": 1e-9}},
         "motion": {"type": "rigid", "translation": [0, 0, 0.1]}}],
      "output": {"json": ")"
        << json << R"("}})";
  }
  const test::CliRun explained = test::run_cli("run --explain " + scene);
  ASSERT_EQ(explained.status, 0) << explained.output;
  EXPECT_NE(explained.output.find("resolved configuration of"), std::string::npos) << explained.output;
  EXPECT_NE(explained.output.find("preconditioner"), std::string::npos) << explained.output;
  EXPECT_NE(explained.output.find("absolute_tolerance"), std::string::npos) << explained.output;
  EXPECT_FALSE(std::filesystem::exists(json)) << "--explain solved and wrote the summary";

  const test::CliRun ran = test::run_cli("run -q " + scene);
  ASSERT_EQ(ran.status, 0) << ran.output;
  std::ifstream in(json);
  const nlohmann::json summary = nlohmann::json::parse(in);
  ASSERT_TRUE(summary.contains("resolved"));
  const nlohmann::json& resolved = summary["resolved"];
  EXPECT_EQ(resolved["preconditioner"]["value"], summary["preconditioner"]);
  EXPECT_EQ(resolved["product"]["value"], summary["product"]);
  EXPECT_FALSE(resolved["preconditioner"]["reason"].get<std::string>().empty());
  // The explained line for the preconditioner names the same value.
  const std::string line = "preconditioner  ";
  const size_t at = explained.output.find(line);
  ASSERT_NE(at, std::string::npos);
  EXPECT_NE(explained.output.find(resolved["preconditioner"]["value"].get<std::string>(), at), std::string::npos);
}

}  // namespace
}  // namespace snh
