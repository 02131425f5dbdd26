// Scene-file keys of dynamics and obstacles ("dynamics", "obstacles",
// "contact"; snh/scene.h): what they fill in, the errors naming the
// key, and the per-step "contacts" / "max_penetration" / "time" of the
// scene command's JSON.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "snh/error.h"
#include "snh/scene.h"
#include "snh/scenes.h"
#include "snh/simulation.h"

namespace snh::test {
namespace {

std::filesystem::path write_scene(const std::string& name, const std::string& text) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path;
}

std::string error_of(const std::string& text) {
  try {
    load_scene(write_scene("snh_bad_dynamics_scene.json", text).string());
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

const std::string kMesh = R"("mesh": {"generator": "box", "cells": [1, 1, 1], "size": 0.1})";

TEST(SceneFileDynamics, KeysFillTheOptions) {
  const SceneFile f = load_scene(write_scene("snh_dynamics_scene.json", "{" + kMesh + R"(,
    "dynamics": {"time_step": 0.02, "density": 950, "damping": {"mass": 0.5, "stiffness": 0.01}, "substeps": 3},
    "obstacles": [
      {"type": "plane", "point": [0, 0, -0.1], "normal": [0, 0, 2]},
      {"type": "sphere", "center": [0, 0, 1], "radius": 0.2,
       "keyframes": [{"t": 0, "translation": [0, 0, 0]}, {"t": 1, "translation": [0, 0, -0.5]}]},
      {"type": "cylinder", "point": [1, 0, 0], "axis": [0, 1, 0], "radius": 0.1,
       "keyframes": {"type": "keyframes", "axis": [0, 1, 0], "center": [1, 0, 0],
                     "keys": [{"t": 0}, {"t": 1, "angle": 1.0}]}}],
    "contact": {"stiffness": 500, "thickness": 0.01, "self": false},
    "solver": {"steps": 7}})")
                                     .string());
  const SolveOptions& o = f.scene.options;
  ASSERT_TRUE(o.dynamics.has_value());
  EXPECT_EQ(o.dynamics->time_step, 0.02);
  EXPECT_EQ(o.dynamics->density, 950.0);
  EXPECT_EQ(o.dynamics->damping.mass, 0.5);
  EXPECT_EQ(o.dynamics->damping.stiffness, 0.01);
  EXPECT_EQ(o.dynamics->substeps, 3);
  EXPECT_EQ(o.load_steps, 7);  // time steps
  ASSERT_EQ(o.obstacles.size(), 3u);
  EXPECT_EQ(o.obstacles[0].type, ObstacleType::plane);
  EXPECT_EQ(o.obstacles[0].direction[2], 2.0);
  EXPECT_FALSE(o.obstacles[0].motion);
  EXPECT_EQ(o.obstacles[1].type, ObstacleType::sphere);
  EXPECT_EQ(o.obstacles[1].radius, 0.2);
  ASSERT_TRUE(o.obstacles[1].motion);
  EXPECT_NEAR(o.obstacles[1].motion(0.5).apply(o.obstacles[1].point)[2], 0.75, 1e-12);
  EXPECT_EQ(o.obstacles[2].type, ObstacleType::cylinder);
  ASSERT_TRUE(o.obstacles[2].motion);
  // Rotation by 1 rad about y through (1, 0, 0) moves (2, 0, 0) to
  // (1 + cos 1, 0, -sin 1).
  const auto moved = o.obstacles[2].motion(1.0).apply({2.0, 0.0, 0.0});
  EXPECT_NEAR(moved[0], 1.0 + std::cos(1.0), 1e-12);
  EXPECT_NEAR(moved[2], -std::sin(1.0), 1e-12);
  EXPECT_EQ(o.contact.stiffness, 500.0);
  EXPECT_EQ(o.contact.thickness, 0.01);

  // Absent keys: quasistatic, no obstacles, as before.
  const SceneFile plain = load_scene(write_scene("snh_plain_scene.json", "{" + kMesh + "}").string());
  EXPECT_FALSE(plain.scene.options.dynamics.has_value());
  EXPECT_TRUE(plain.scene.options.obstacles.empty());
}

TEST(SceneFileDynamics, KeysNameTheirErrors) {
  auto error = [](const std::string& keys) { return error_of("{" + kMesh + ", " + keys + "}"); };
  EXPECT_NE(error(R"("dynamics": {"density": 1})").find("dynamics.time_step: missing"), std::string::npos);
  EXPECT_NE(error(R"("dynamics": {"time_step": 0.1})").find("dynamics.density: missing"), std::string::npos);
  EXPECT_NE(error(R"("dynamics": {"time_step": -1, "density": 1})").find("dynamics.time_step: must be > 0"),
            std::string::npos);
  EXPECT_NE(error(R"("dynamics": {"time_step": 0.1, "density": 1, "substeps": 0})").find("dynamics.substeps"),
            std::string::npos);
  EXPECT_NE(error(R"("dynamics": {"time_step": 0.1, "density": 1, "damping": {"viscous": 1}})")
                .find("dynamics.damping.viscous: unknown key"),
            std::string::npos);
  EXPECT_NE(error(R"("dynamics": {"time_step": 0.1, "density": 1, "damping": {"mass": -2}})")
                .find("dynamics.damping.mass: must be >= 0"),
            std::string::npos);
  EXPECT_NE(error(R"("dynamics": {"time_step": 0.1, "density": 1, "steps": 3})").find("dynamics.steps: unknown key"),
            std::string::npos);
  const std::string contact = R"("contact": {"stiffness": 10, "thickness": 0.01})";
  EXPECT_NE(error(R"("obstacles": {"type": "plane"}, )" + contact).find("obstacles: expected an array"),
            std::string::npos);
  EXPECT_NE(error(R"("obstacles": [{"type": "cone"}], )" + contact)
                .find("obstacles[0].type: expected plane, sphere or cylinder, got 'cone'"),
            std::string::npos);
  EXPECT_NE(error(R"("obstacles": [{"point": [0, 0, 0]}], )" + contact).find("obstacles[0].type: missing"),
            std::string::npos);
  EXPECT_NE(error(R"("obstacles": [{"type": "sphere", "center": [0, 0, 0]}], )" + contact)
                .find("obstacles[0].radius: missing"),
            std::string::npos);
  EXPECT_NE(
      error(R"("obstacles": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "radius": 1}], )" + contact)
          .find("obstacles[0].radius: unknown key"),
      std::string::npos);
  EXPECT_NE(error(R"("obstacles": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 0]}], )" + contact)
                .find("zero normal"),
            std::string::npos);
  EXPECT_NE(error(R"("obstacles": [{"type": "sphere", "center": [0, 0, 0], "radius": 1,
                                    "keyframes": [{"t": 1}, {"t": 0}]}], )" +
                  contact)
                .find("obstacles[0].keyframes.keys[1].t: key times must increase"),
            std::string::npos);
  EXPECT_NE(error(R"("obstacles": [{"type": "sphere", "center": [0, 0, 0], "radius": 1}])")
                .find("contact.stiffness: missing"),
            std::string::npos);
  EXPECT_EQ(error(R"("contact": {"stiffness": 1, "self": true})"), "no error");
  EXPECT_EQ(error(R"("contact": {"self": true, "self_stiffness": 2})"), "no error");
  EXPECT_NE(error(R"("contact": {"self": true, "self_method": "penalty"})").find("contact.stiffness: missing"),
            std::string::npos);
  EXPECT_EQ(error(R"("contact": {"self": true})"), "no error");  // the barrier needs no stiffness
  EXPECT_NE(error(R"("contact": {"self": true, "self_method": "springs"})").find("contact.self_method"),
            std::string::npos);
  EXPECT_NE(error(R"("contact": {"self": true, "self_distance": -1})").find("contact.self_distance"),
            std::string::npos);
  EXPECT_NE(error(R"("contact": {"stiffness": 1, "self": true, "self_stiffness": -1})").find("contact.self_stiffness"),
            std::string::npos);
  EXPECT_NE(error(R"("contact": {"stiffness": 1, "self": "no"})").find("contact.self: expected true or false"),
            std::string::npos);
  EXPECT_NE(error(R"("contact": {"stiffness": 1, "thickness": -1})").find("contact.thickness"), std::string::npos);
  EXPECT_EQ(error(R"("contact": {"stiffness": 1, "friction": 0.3, "friction_slip": 0.001})"), "no error");
  EXPECT_NE(error(R"("contact": {"stiffness": 1, "friction": -0.3})").find("contact.friction: must be >= 0"),
            std::string::npos);
  EXPECT_NE(error(R"("contact": {"stiffness": 1, "friction_slip": -1})").find("contact.friction_slip: must be >= 0"),
            std::string::npos);
  EXPECT_NE(
      error(R"("contact": {"stiffness": 1, "static_friction": 0.3})").find("contact.static_friction: unknown key"),
      std::string::npos);
  EXPECT_EQ(error(R"("obstacles": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "friction": 0.5}], )" +
                  contact),
            "no error");
  EXPECT_NE(
      error(R"("obstacles": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "friction": -1}], )" + contact)
          .find("obstacles[0].friction: must be >= 0"),
      std::string::npos);
  EXPECT_EQ(error(R"("contact": {"stiffness": 1, "self": false})"), "no error");
}

TEST(SceneFileDynamics, ShippedElbowLoadsWithSelfContact) {
  const SceneFile f = load_scene(std::string(SNH_DATA_DIR) + "/scenes/elbow.json");
  EXPECT_TRUE(f.scene.options.contact.self);
  EXPECT_EQ(f.scene.options.contact.stiffness, 20.0);
  EXPECT_EQ(f.scene.options.contact.thickness, 0.025);
  EXPECT_EQ(f.scene.options.load_steps, 28);
  EXPECT_EQ(f.scene.mesh.element_count(), 24u * 4 * 4);
  const Scene builtin = make_scene("elbow", {});
  ASSERT_EQ(builtin.constraints.size(), f.scene.constraints.size());
  for (size_t k = 0; k < builtin.constraints.size(); ++k)
    EXPECT_EQ(builtin.constraints[k].vertices, f.scene.constraints[k].vertices) << builtin.constraints[k].name;
}

TEST(SceneFileDynamics, ShippedDropBlockLoads) {
  const SceneFile f = load_scene(std::string(SNH_DATA_DIR) + "/scenes/drop_block.json");
  ASSERT_TRUE(f.scene.options.dynamics.has_value());
  EXPECT_EQ(f.scene.options.dynamics->substeps, 4);
  ASSERT_EQ(f.scene.options.obstacles.size(), 1u);
  EXPECT_EQ(f.scene.options.obstacles[0].type, ObstacleType::plane);
  EXPECT_EQ(f.scene.options.load_steps, 60);
}

#ifdef SNH_BENCH_BINARY
// A 1-hex block dropped 1 cm onto a plane through `snh-gpu-bench scene
// --file`: every step of the JSON has contacts, max_penetration and time;
// the block first falls freely, then rests on its four bottom vertices.
TEST(SceneFileDynamics, SceneCommandReportsContactsPerStep) {
  const std::filesystem::path scene = write_scene("snh_drop_scene.json", "{" + kMesh + R"(,
    "material": {"E": 100000, "nu": 0.3},
    "body_force": [0, 0, -9810],
    "dynamics": {"time_step": 0.01, "density": 1000, "damping": {"mass": 20}},
    "obstacles": [{"type": "plane", "point": [0, 0, -0.02], "normal": [0, 0, 1]}],
    "contact": {"stiffness": 1000, "thickness": 0.01, "self": false},
    "solver": {"steps": 60}})");
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "snh_drop_scene_out.json";
  std::filesystem::remove(out);
  const std::string command = std::string(SNH_BENCH_BINARY) + " scene --file " + scene.string() + " --json " +
                              out.string() + " > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << command;
  nlohmann::json j;
  std::ifstream(out) >> j;
  ASSERT_EQ(j["steps"].size(), 60u);
  EXPECT_NE(j["kernel_specialization"].get<std::string>().find("-DSNH_OBSTACLES=1"), std::string::npos);
  EXPECT_NE(j["kernel_specialization"].get<std::string>().find("-DSNH_INERTIA=1"), std::string::npos);
  EXPECT_EQ(j["dynamics"]["time_step"], 0.01);
  for (size_t s = 0; s < j["steps"].size(); ++s) {
    ASSERT_TRUE(j["steps"][s].contains("contacts")) << s;
    ASSERT_TRUE(j["steps"][s].contains("max_penetration")) << s;
    EXPECT_NEAR(j["steps"][s]["time"].get<double>(), 0.01 * (s + 1), 1e-12) << s;
  }
  EXPECT_EQ(j["steps"][0]["contacts"], 0);  // 1 cm above the layer
  EXPECT_EQ(j["steps"].back()["contacts"], 4);
  const double expected = 1000 * 9.81 * 1e-3 / (4 * 1000.0);
  EXPECT_NEAR(j["steps"].back()["max_penetration"].get<double>(), expected, 0.01 * expected);
}
#endif

}  // namespace
}  // namespace snh::test
