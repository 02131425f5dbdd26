// The solver's defaults are written once (snh::defaults): the library, scene
// files and the command line start from the same values, and load stepping
// places targets as documented.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "snh/configuration.h"
#include "snh/scene.h"
#include "snh/simulation.h"
#include "solver/simulation/load_stepping.h"

namespace snh::test {
namespace {

TEST(SolverDefaults, SolveOptionsStartFromThem) {
  const SolveOptions options;
  EXPECT_EQ(options.max_newton_iterations, defaults::max_newton_iterations);
  EXPECT_EQ(options.max_cg_iterations, defaults::max_cg_iterations);
  EXPECT_EQ(options.load_steps, defaults::load_steps);
  EXPECT_FALSE(options.strain_tolerance.has_value());
  EXPECT_EQ(defaults::strain_tolerance(Precision::double_), 1e-6);
  EXPECT_EQ(defaults::strain_tolerance(Precision::single), 1e-4);
}

// A scene file that leaves the solver settings out solves as a program that
// leaves SolveOptions alone.
TEST(SolverDefaults, SceneFilesTakeTheLibrarysDefaults) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "snh_solver_defaults_scene.json";
  for (const char* precision : {"double", "float"}) {
    SCOPED_TRACE(precision);
    std::ofstream(path) << R"({"mesh": {"generator": "box", "cells": [2, 2, 2], "size": 0.5},
      "material": {"model": "snh", "E": 1.0, "nu": 0.45},
      "constraints": [{"name": "left", "select": {"plane": {"axis": "x", "value": 0.0, "tolerance": 1e-9}}}],
      "solver": {"precision": ")" +
                               std::string(precision) + R"("}})";
    const SceneFile file = load_scene(path.string());
    const SolveOptions& options = file.scene.options;
    const SolveOptions library;
    EXPECT_EQ(options.max_newton_iterations, library.max_newton_iterations);
    EXPECT_EQ(options.max_cg_iterations, library.max_cg_iterations);
    EXPECT_EQ(options.load_steps, library.load_steps);
    ASSERT_TRUE(options.strain_tolerance.has_value());
    EXPECT_EQ(*options.strain_tolerance, defaults::strain_tolerance(options.precision));
    EXPECT_FALSE(file.tolerance_given);
    // The library's rule gives the same tolerance with the strain unset.
    SolveOptions unset = options;
    unset.strain_tolerance.reset();
    EXPECT_EQ(resolve_configuration(unset, file.scene.mesh, file.materials, DeviceInfo{}).absolute_tolerance,
              resolve_configuration(options, file.scene.mesh, file.materials, DeviceInfo{}).absolute_tolerance);
  }
  std::filesystem::remove(path);
}

// A transform between two rotations moves the set rigidly: halfway from the
// identity to a quarter turn about z is an eighth turn about the centre.
TEST(LoadStepping, TransformTargetsFollowTheSlerp) {
  const Mesh mesh = make_box_lattice(1, 1, 1, 1.0);
  ConstraintSet set;
  set.name = "all";
  for (size_t v = 0; v < mesh.vertex_count(); ++v) set.vertices.push_back(static_cast<int32_t>(v));
  solver::SetTarget target;
  target.kind = solver::SetTarget::Kind::transform;
  target.from = RigidTransform::identity();
  target.from_known = true;
  target.to = RigidTransform::rotation_about({0.0, 0.0, 1.0}, M_PI / 2, {0.5, 0.5, 0.0});
  std::vector<double> x = mesh.positions.xyz();
  solver::record_start(set, x, target);
  solver::place_target(mesh, set, target, 0.5, x);
  const RigidTransform eighth = RigidTransform::rotation_about({0.0, 0.0, 1.0}, M_PI / 4, {0.5, 0.5, 0.0});
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const std::array<double, 3> expected = eighth.apply(mesh.vertex(v));
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(x[3 * v + d], expected[d], 1e-12) << "vertex " << v << " axis " << d;
  }
}

TEST(LoadStepping, ForcesRampLinearly) {
  const std::vector<double> from = {1.0, -2.0, 0.0}, to = {3.0, 2.0, -4.0};
  std::vector<double> out;
  solver::ramp_force(from, to, solver::load_fraction(1, 4), out);
  EXPECT_EQ(out, (std::vector<double>{1.5, -1.0, -1.0}));
}

}  // namespace
}  // namespace snh::test
