// Scene files (data/scenes/*.json): the shipped built-in scenes match
// make_scene, the Gmsh-mesh example with gravity solves, and bad files get
// errors naming the key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "scene_file.h"
#include "snh/error.h"
#include "snh/simulation.h"

namespace snh::test {
namespace {

const std::string kScenes = std::string(SNH_DATA_DIR) + "/scenes/";

TEST(SceneFiles, ShippedBuiltInScenesMatchMakeScene) {
  for (const std::string name : {"twist", "stretch", "scramble", "flex"}) {
    SCOPED_TRACE(name);
    const bench::SceneFile f = bench::load_scene_file(kScenes + name + ".json");
    const Scene built = make_scene(name, {});
    EXPECT_GT(f.scene.mesh.element_count(), 100u);
    EXPECT_EQ(f.scene.mesh.elements, built.mesh.elements);
    ASSERT_EQ(f.scene.mesh.positions.size(), built.mesh.positions.size());
    for (size_t i = 0; i < built.mesh.positions.size(); ++i)
      EXPECT_NEAR(f.scene.mesh.positions[i], built.mesh.positions[i], 1e-12);
    ASSERT_EQ(f.scene.constraints.size(), built.constraints.size());
    for (size_t c = 0; c < built.constraints.size(); ++c) {
      EXPECT_EQ(f.scene.constraints[c].vertices, built.constraints[c].vertices) << built.constraints[c].name;
      if (built.constraints[c].motion) {
        const RigidTransform a = f.scene.constraints[c].motion(0.5), b = built.constraints[c].motion(0.5);
        for (int i = 0; i < 9; ++i) EXPECT_NEAR(a.rotation[i], b.rotation[i], 1e-12);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(a.apply({0.3, 0.2, 0.1})[i], b.apply({0.3, 0.2, 0.1})[i], 1e-12);
      }
    }
    EXPECT_EQ(f.scene.options.load_steps, built.options.load_steps);
    EXPECT_EQ(f.material.mu, Material(built.material).mu);
  }
}

TEST(SceneFiles, GmshMeshWithPinnedWallAndGravitySags) {
  const bench::SceneFile f = bench::load_scene_file(kScenes + "gravity_tet.json");
  EXPECT_EQ(f.scene.mesh.type, ElementType::tet4);
  ASSERT_FALSE(f.scene.options.external_force.empty());
  double total = 0.0;
  for (size_t v = 0; v < f.scene.mesh.vertex_count(); ++v) total += f.scene.options.external_force[3 * v + 2];
  EXPECT_NEAR(total, -9810.0 * 0.125, 1e-6);  // weight of a 1 x 0.5 x 0.25 box
  QuasistaticSolver solver(f.scene.mesh, f.material, f.scene.constraints, f.scene.options);
  const SolveResult r = solver.solve();
  EXPECT_TRUE(r.converged);
  double tip = 0.0;
  for (size_t v = 0; v < f.scene.mesh.vertex_count(); ++v)
    if (f.scene.mesh.positions[3 * v] > 1.0 - 1e-9)
      tip = std::min(tip, r.positions[3 * v + 2] - f.scene.mesh.positions[3 * v + 2]);
  EXPECT_LT(tip, -1e-3);
}

std::string error_of(const std::string& text) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "snh_bad_scene.json";
  std::ofstream(path) << text;
  try {
    bench::load_scene_file(path.string());
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(SceneFiles, BadFilesNameTheKey) {
  const std::string mesh = R"("mesh": {"generator": "box", "cells": [2, 2, 2], "size": 0.5})";
  EXPECT_NE(error_of("{" + mesh + R"(, "materail": {}})").find("scene.materail: unknown key"), std::string::npos);
  EXPECT_NE(error_of("{" + mesh + R"(, "solver": {"steps": "two"}})").find("solver.steps: expected an integer"),
            std::string::npos);
  EXPECT_NE(error_of("{" + mesh + R"(, "material": {"nu": "half"}})").find("material.nu: expected a number"),
            std::string::npos);
  EXPECT_NE(error_of("{" + mesh + R"(, "constraints": [{"select": {"plane": {"axis": "z", "value": 7}}}]})")
                .find("constraints[0].select: selects no vertex"),
            std::string::npos);
  EXPECT_NE(error_of("{" + mesh + R"(, "constraints": [{"select": {"ids": [99]}}]})").find("out of range"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"mesh": {"file": "missing.msh"}})").find("missing.msh"), std::string::npos);
  EXPECT_NE(error_of("{" + mesh + R"(, "material": {"nu": 0.5}})").find("Poisson"), std::string::npos);
  EXPECT_NE(error_of("not json").find("not valid JSON"), std::string::npos);
}

TEST(SceneFiles, SeedFourMaterialKeys) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "snh_alpha_scene.json";
  std::ofstream(path) << R"({"mesh": {"generator": "box", "cells": [2, 2, 2], "size": 0.5},
    "material": {"model": "corotational", "nu": 0.45, "alpha": 1.5, "lambda_model": "neohookean",
                 "alpha_lambda": 0.75}})";
  const bench::SceneFile f = bench::load_scene_file(path.string());
  EXPECT_EQ(f.material.model, MaterialModel::corotational);
  EXPECT_EQ(f.material.lambda_model, MaterialModel::neohookean);
  EXPECT_EQ(f.material.alpha_mu, 1.5);
  EXPECT_EQ(f.material.alpha_lambda, 0.75);
  const std::string mesh = R"("mesh": {"generator": "box", "cells": [2, 2, 2], "size": 0.5})";
  EXPECT_NE(error_of("{" + mesh + R"(, "material": {"alpha": -1}})").find("alpha"), std::string::npos);
  EXPECT_NE(error_of("{" + mesh + R"(, "material": {"lambda_model": "jelly"}})").find("jelly"), std::string::npos);
}

}  // namespace
}  // namespace snh::test
