// Where users meet the exact self-intersection count: `snh intersections`
// on surfaces and meshes, and the scene key output.check_intersections on a
// shipped contact case run without self-contact, whose surface is clean at
// rest and passes through itself at the end (what intersection-free contact
// must bring to zero), with its records, JSON and warnings.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "scene/output_surface_check.h"
#include "snh/mesh_io.h"
#include "snh/scene.h"
#include "snh/surface.h"
#include "snh/surface_intersections.h"
#include "support/cli_run.h"
#include "support/errors.h"
#include "support/surface_shapes.h"

namespace snh::test {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Two spheres, the second moved halfway into the first.
TriangleSurface overlapping_spheres() {
  TriangleSurface s = icosphere(2, 1.0);
  const TriangleSurface t = icosphere(2, 1.0);
  const int32_t offset = int32_t(s.vertex_count());
  for (size_t v = 0; v < t.vertex_count(); ++v)
    s.positions.push_back({t.positions(v, 0) + 1.01, t.positions(v, 1) + 0.03, t.positions(v, 2) - 0.02});
  for (int32_t i : t.triangles) s.triangles.push_back(i + offset);
  return s;
}

TEST(IntersectionsCommand, CleanSurfacesAndMeshesExitZero) {
  const std::string sphere = std::string(SNH_DATA_DIR) + "/surfaces/sphere.stl";
  CliRun r = run_cli("intersections " + sphere);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("intersecting triangle pairs: 0"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("192 vertices, 380 triangles"), std::string::npos) << r.output;  // welded
  EXPECT_NE(r.output.find("clean: yes"), std::string::npos) << r.output;

  // Every triangle with its own corners (as at UV seams): welded, clean;
  // kept apart (--no-weld), neighbours touch.
  const fs::path dir = fresh_dir("snh_intersections_mesh");
  const TriangleSurface ball = icosphere(1, 1.0);
  TriangleSurface split;
  for (int32_t i : ball.triangles) {
    split.triangles.push_back(int32_t(split.vertex_count()));
    split.positions.push_back(
        {ball.positions(size_t(i), 0), ball.positions(size_t(i), 1), ball.positions(size_t(i), 2)});
  }
  write_obj((dir / "split.obj").string(), split);
  r = run_cli("intersections " + (dir / "split.obj").string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("repeated positions welded"), std::string::npos) << r.output;
  r = run_cli("intersections --no-weld " + (dir / "split.obj").string());
  EXPECT_EQ(r.status, 2) << r.output;

  write_mesh((dir / "cube.vtu").string(), make_box_lattice(3, 4, 2, 0.5));
  r = run_cli("intersections " + (dir / "cube.vtu").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("boundary of a hex8 mesh of 24 elements"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(std::to_string(2 * 2 * (3 * 4 + 4 * 2 + 3 * 2)) + " triangles"), std::string::npos)
      << r.output;
  fs::remove_all(dir);
}

TEST(IntersectionsCommand, IntersectingSurfaceExitsTwoWithTheCountAndPairs) {
  const fs::path dir = fresh_dir("snh_intersections_obj");
  const TriangleSurface s = overlapping_spheres();
  write_obj((dir / "two.obj").string(), s);
  const SelfIntersections expected = count_self_intersections(s);
  ASSERT_GT(expected.intersecting_pairs, 0u);
  const CliRun r =
      run_cli("intersections " + (dir / "two.obj").string() + " --pairs 3 --json " + (dir / "out.json").string());
  ASSERT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("intersecting triangle pairs: " + std::to_string(expected.intersecting_pairs)),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("clean: no"), std::string::npos) << r.output;
  nlohmann::json j;
  std::ifstream(dir / "out.json") >> j;
  EXPECT_EQ(j["surface_intersections"], expected.intersecting_pairs);
  ASSERT_EQ(j["first_pairs"].size(), 3u);
  EXPECT_EQ(j["first_pairs"][0][0], expected.first_pairs[0][0]);
  EXPECT_EQ(j["first_pairs"][0][1], expected.first_pairs[0][1]);
  EXPECT_EQ(j["clean"], false);
  fs::remove_all(dir);
}

TEST(IntersectionsCommand, BadFilesAreNamed) {
  const fs::path dir = fresh_dir("snh_intersections_bad");
  std::ofstream(dir / "bad.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n";
  const CliRun r = run_cli("intersections " + (dir / "bad.obj").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("bad.obj"), std::string::npos) << r.output;
  EXPECT_EQ(run_cli("intersections " + (dir / "none.stl").string()).status, 1);
  fs::remove_all(dir);
}

TEST(CheckIntersections, KeyIsABoolean) {
  const fs::path dir = fresh_dir("snh_check_key");
  std::ofstream(dir / "s.json") << R"({"mesh": {"generator": "box", "cells": [2, 1, 1]},
    "constraints": [{"select": {"plane": {"axis": "x", "value": 0}}}],
    "output": {"check_intersections": "yes"}})";
  const std::string m = error_of([&] { load_scene((dir / "s.json").string()); });
  EXPECT_TRUE(contains(m, "output.check_intersections")) << m;
  std::ofstream(dir / "s.json") << R"({"mesh": {"generator": "box", "cells": [2, 1, 1]},
    "constraints": [{"select": {"plane": {"axis": "x", "value": 0}}}],
    "output": {"check_intersections": true}})";
  EXPECT_TRUE(load_scene((dir / "s.json").string()).check_intersections);
  fs::remove_all(dir);
}

// The smallest shipped contact case, without self-contact and in fewer
// steps: clean at rest, intersecting at the end; each step's count is in
// the record, a warning and the JSON summary.
TEST(CheckIntersections, HandPushedIntoHeadPassesThroughItWithoutSelfContact) {
  SceneFile f = load_scene(std::string(SNH_DATA_DIR) + "/scenes/hand_head.json");
  ASSERT_TRUE(f.check_intersections);
  ASSERT_TRUE(f.embedded);
  SolveOptions options = f.scene.options;
  options.contact.self = false;
  options.contact.stiffness = 0.0;
  options.load_steps = 3;
  const scene_io::OutputSurfaceCheck check(f, f.scene.mesh);
  EXPECT_TRUE(check.count(f.scene.mesh.positions).clean());
  const SceneRun run = run_scene(f, options);
  ASSERT_EQ(run.surface_intersections.size(), 3u);
  EXPECT_TRUE(run.converged);
  const SelfIntersections& last = run.surface_intersections.back();
  EXPECT_GT(last.intersecting_pairs, 0u);
  bool warned = false;
  for (const std::string& w : run.warnings) warned = warned || contains(w, "step 3: surface_intersections: ");
  EXPECT_TRUE(warned);
  const fs::path dir = fresh_dir("snh_check_run");
  write_scene_json((dir / "out.json").string(), f, run);
  nlohmann::json j;
  std::ifstream(dir / "out.json") >> j;
  EXPECT_EQ(j["steps"][2]["surface_intersections"], last.intersecting_pairs);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace snh::test
