// A scene file loaded and run through the library alone (snh/scene.h): the
// records, the progress per step, and the outputs the writers make.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "snh/error.h"
#include "snh/scene.h"
#include "support/errors.h"
#include "support/scratch.h"

namespace snh::test {
namespace {

namespace fs = std::filesystem;

// A 3x1x1 bar pulled along x by a tenth of its length in two load steps.
const char* const kBar = R"({
  "name": "bar",
  "mesh": {"generator": "box", "cells": [3, 1, 1], "size": 1.0},
  "material": {"E": 10, "nu": 0.3},
  "constraints": [
    {"name": "left", "select": {"plane": {"axis": "x", "value": 0}}},
    {"name": "right", "select": {"plane": {"axis": "x", "value": 3}},
     "motion": {"translation": [0.3, 0, 0]}}
  ],
  "solver": {"steps": 2}
})";

TEST(SceneRun, LoadsAndRunsAFileWithRecordsProgressAndOutputs) {
  const fs::path dir = fresh_dir("snh_scene_run");
  std::ofstream(dir / "bar.json") << kBar;
  const SceneFile file = load_scene((dir / "bar.json").string());
  ASSERT_EQ(file.scene.constraints.size(), 2u);

  std::vector<SceneProgress> progress;
  std::vector<int> written;
  SceneVtuSeries vtu((dir / "vtu").string(), file, file.scene.options);
  SceneRunOptions run_options;
  run_options.progress = [&](const SceneProgress& p) { progress.push_back(p); };
  run_options.writers = {vtu.writer(), [&](int index, double, const Points& x, const Points& surface) {
                           EXPECT_EQ(x.size(), file.scene.mesh.vertex_count());
                           EXPECT_TRUE(surface.empty());  // no "embed"
                           written.push_back(index);
                         }};
  const SceneRun run = run_scene(file, file.scene.options, run_options);
  vtu.finish();

  EXPECT_TRUE(run.converged);
  ASSERT_EQ(run.result.steps.size(), 2u);
  ASSERT_EQ(run.steps.size(), 2u);
  EXPECT_EQ(written, (std::vector<int>{0, 1, 2}));
  ASSERT_EQ(progress.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    EXPECT_FALSE(progress[k].frame);
    EXPECT_EQ(progress[k].index, k + 1);
    EXPECT_EQ(progress[k].count, 2);
    EXPECT_EQ(progress[k].newton_iterations, run.result.steps[k].newton_iterations);
    EXPECT_EQ(progress[k].cg_iterations, run.result.steps[k].cg_iterations);
  }
  // Stretched: the shape is defined, volume grows a little, the right end
  // pulls the body towards +x and the left end holds it back.
  for (const SceneStep& s : run.steps) {
    EXPECT_TRUE(s.shape.defined);
    EXPECT_GT(s.shape.min_j, 0.0);
    ASSERT_TRUE(s.reactions.has_value());
    ASSERT_EQ(s.reactions->size(), 2u);
  }
  const std::vector<Reaction>& last = *run.steps.back().reactions;
  EXPECT_LT(last[0].force[0], 0.0);
  EXPECT_GT(last[1].force[0], 0.0);
  // They balance up to what Newton left: the x-residuals of the 8 free
  // vertices sum to minus the imbalance, so |sum| <= sqrt(8) |r|.
  const double residual = run.result.final_residual_norm;
  EXPECT_GT(residual, 0.0);
  EXPECT_LE(std::abs(last[0].force[0] + last[1].force[0]),
            std::sqrt(8.0) * residual + 1e-12 * std::abs(last[1].force[0]));

  write_scene_json((dir / "out" / "bar.json").string(), file, run);
  nlohmann::json j;
  std::ifstream(dir / "out" / "bar.json") >> j;
  EXPECT_EQ(j["scene"], "bar");
  EXPECT_EQ(j["converged"], true);
  ASSERT_EQ(j["steps"].size(), 2u);
  EXPECT_EQ(j["steps"][1]["reactions"][1]["name"], "right");
  EXPECT_DOUBLE_EQ(j["steps"][1]["reactions"][1]["force"][0].get<double>(), last[1].force[0]);
  for (const char* name : {"bar_0000.vtu", "bar_0001.vtu", "bar_0002.vtu", "bar.pvd"})
    EXPECT_TRUE(fs::exists(dir / "vtu" / name)) << name;
  fs::remove_all(dir);
}

TEST(SceneRun, MissingReferencedFileNamesItsResolvedPathAndKey) {
  const fs::path dir = fresh_dir("snh_scene_missing");
  fs::create_directories(dir / "scenes");
  const fs::path scene = dir / "scenes" / "s.json";
  std::ofstream(scene) << R"({"mesh": {"file": "../meshes/absent.msh"}})";
  const std::string e = error_of([&] { load_scene(scene.string()); });
  EXPECT_EQ(e.rfind(scene.string() + ": mesh.file: ", 0), 0u) << e;
  EXPECT_NE(e.find((dir / "scenes" / "../meshes/absent.msh").string()), std::string::npos) << e;
  std::ofstream(scene) << R"({"embed": {"surface": "none.obj", "cell": 0.1}})";
  const std::string surface = error_of([&] { load_scene(scene.string()); });
  EXPECT_NE(surface.find("embed.surface: "), std::string::npos) << surface;
  EXPECT_NE(surface.find((dir / "scenes" / "none.obj").string()), std::string::npos) << surface;
  fs::remove_all(dir);
}

TEST(SceneRun, UnknownKeysAreCheckedAgainstTheSchema) {
  const fs::path dir = fresh_dir("snh_scene_schema");
  const auto error = [&](const std::string& text) {
    std::ofstream(dir / "s.json") << text;
    return error_of([&] { load_scene((dir / "s.json").string()); });
  };
  const std::string mesh = R"("mesh": {"generator": "box", "cells": [2, 2, 2]})";
  EXPECT_NE(error("{" + mesh + R"(, "meshes": 1})").find("scene.meshes: unknown key"), std::string::npos);
  EXPECT_NE(error("{" + mesh + R"(, "constraints": [{"select": {"ids": [0]}, "motion": {"spin": 1}}]})")
                .find("constraints[0].motion.spin: unknown key"),
            std::string::npos);
  // A plane takes no radius, a sphere does.
  const std::string contact = R"(, "contact": {"stiffness": 10})";
  EXPECT_NE(error("{" + mesh + R"(, "obstacles": [{"type": "plane", "point": [0, 0, -1], "normal": [0, 0, 1],
                "radius": 1}])" +
                  contact + "}")
                .find("obstacles[0].radius: unknown key"),
            std::string::npos);
  std::ofstream(dir / "s.json") << "{" + mesh +
                                       R"(, "obstacles": [{"type": "sphere", "center": [0, 0, -2], "radius": 1}])" +
                                       contact + "}";
  EXPECT_NO_THROW(load_scene((dir / "s.json").string()));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace snh::test
