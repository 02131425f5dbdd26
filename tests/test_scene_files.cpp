// Scene files (data/scenes/*.json): the shipped built-in scenes match
// make_scene, the Gmsh-mesh example with gravity solves, the rigged arm
// example flexes its embedded surface, and bad files get errors naming the
// key.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "scene_file.h"
#include "snh/error.h"
#include "snh/frames.h"
#include "snh/regions.h"
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

// The shipped arm scene at a quarter of its elements (cell 0.25) on frames 0,
// 8, 16 and 24 of its animation: every frame converges, the shoulder stays
// and the forearm's tip follows the elbow's rotation.
TEST(SceneFiles, ArmExampleFlexesTheEmbeddedSurface) {
  nlohmann::json doc;
  std::ifstream(kScenes + "arm.json") >> doc;
  doc["embed"]["cell"] = 0.25;
  doc["embed"]["surface"] = kScenes + doc["embed"]["surface"].get<std::string>();
  doc["rig"]["animation"] = kScenes + doc["rig"]["animation"].get<std::string>();
  doc.erase("output");
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "snh_arm_coarse.json";
  std::ofstream(path) << doc.dump();
  const bench::SceneFile f = bench::load_scene_file(path.string());
  ASSERT_TRUE(f.embedded && f.rig);
  EXPECT_EQ(f.scene.mesh.element_count(), 137u);
  ASSERT_EQ(f.scene.constraints.size(), 2u);
  EXPECT_EQ(f.scene.constraints[1].name, "forearm");
  const Animation& all = f.rig->animation;
  ASSERT_EQ(all.frame_count(), 25u);
  Animation some;
  some.bones = all.bones;
  for (size_t frame : {0, 8, 16, 24}) {
    some.times.push_back(all.times[frame]);
    some.transforms.push_back(all.transforms[frame]);
  }
  Simulation sim(f.scene.mesh, uniform_material(f.scene.mesh, f.material), f.scene.constraints, f.scene.options);
  std::vector<double> surface;
  FrameOptions options;
  options.load_steps = 3;
  const auto records = run_frames(sim, some, &f.embedded->embedding, options,
                                  [&](const FrameRecord&, const std::vector<double>&, const std::vector<double>& s) {
                                    surface = s;
                                    return true;
                                  });
  ASSERT_EQ(records.size(), 4u);
  for (const FrameRecord& r : records) EXPECT_TRUE(r.converged) << "frame " << r.frame << ": " << r.status;
  EXPECT_EQ(records.back().inverted_elements, 0);
  // make_arm.py: vertex 0 is the shoulder's tip (0, 0, 0), the last the hand's (4, 0, 0).
  const TriangleSurface& rest = f.embedded->surface;
  const size_t hand = rest.vertex_count() - 1;
  ASSERT_EQ(rest.positions[0], 0.0);
  ASSERT_EQ(rest.positions[3 * hand], 4.0);
  const double angle = 100.0 * M_PI / 180.0;  // 2 from the elbow (2, 0, 0), rotated about y up towards +z
  const double expected[3] = {2.0 + 2.0 * std::cos(angle), 0.0, 2.0 * std::sin(angle)};
  for (int d = 0; d < 3; ++d) {
    EXPECT_NEAR(surface[d], 0.0, 0.02) << d;
    EXPECT_NEAR(surface[3 * hand + d], expected[d], 0.05) << d;
  }
}

TEST(SceneFiles, RigKeysNameTheirErrors) {
  const std::string surface = std::string(SNH_DATA_DIR) + "/arm/arm.obj";
  const std::string animation = std::string(SNH_DATA_DIR) + "/arm/arm_flexion.json";
  const std::string embed = R"("embed": {"surface": ")" + surface + R"(", "cell": 0.25})";
  const std::string mesh = R"("mesh": {"generator": "box", "cells": [2, 2, 2], "size": 0.5})";
  const std::string upper =
      R"({"name": "upper_arm", "capsule": {"a": [0.35, 0, 0], "b": [1.6, 0, 0], "radius": 0.25}})";
  const std::string fore = R"({"name": "forearm", "capsule": {"a": [2.4, 0, 0], "b": [3.55, 0, 0], "radius": 0.24}})";
  EXPECT_NE(error_of("{" + embed + ", " + mesh + "}").find("not both"), std::string::npos);
  EXPECT_NE(error_of(R"({"embed": {"surface": ")" + surface + R"("}})").find("embed.cell: missing"), std::string::npos);
  EXPECT_NE(error_of("{" + embed + R"(, "rig": {"bones": [)" + upper + R"(], "animation": ")" + animation + R"("}})")
                .find("rig.animation: the animation moves bone 'forearm', which is not in rig.bones"),
            std::string::npos);
  EXPECT_NE(
      error_of("{" + embed + R"(, "rig": {"bones": [)" + upper + ", " + fore +
               R"(, {"name": "far", "capsule": {"a": [9, 9, 9], "b": [9, 9, 9], "radius": 0.1}}], "animation": ")" +
               animation + R"("}})")
          .find("rig.bones: bone 'far' holds no lattice vertex"),
      std::string::npos);
  EXPECT_NE(error_of("{" + embed + R"(, "rig": {"bones": [{"name": "x"}], "animation": ")" + animation + R"("}})")
                .find("rig.bones[0]: expected one of \"capsule\" and \"surface\""),
            std::string::npos);
  EXPECT_NE(error_of("{" + mesh + R"(, "output": {"surface": "out/"}})").find("output.surface: needs \"embed\""),
            std::string::npos);
  EXPECT_EQ(bench::surface_obj_path("out/arm", "arm", 7), "out/arm_0007.obj");
  EXPECT_EQ(bench::surface_obj_path("out/", "arm", 12), "out/arm_0012.obj");
}

}  // namespace
}  // namespace snh::test
