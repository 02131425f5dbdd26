// The drop scene (the paper's octopus test, Fig. 11, in miniature): the shipped
// Gmsh body reads cleanly, the built-in scene and data/scenes/drop.json
// describe the same scene, and a coarse run through `snh-gpu-bench scene
// drop` squashes the body, keeps it out of the obstacles beyond the contact
// layer, lets it recover its shape, and writes a .vtu per step and a .pvd
// with the simulated times.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "scene/obstacle_surface.h"
#include "snh/configuration.h"
#include "snh/loads.h"
#include "snh/mesh_io.h"
#include "snh/scene.h"
#include "snh/scenes.h"
#include "snh/shape.h"
#include "snh/simulation.h"

namespace snh::test {
namespace {

const std::string kData = SNH_DATA_DIR;

TEST(Drop, ShippedBlobMeshesReadCleanly) {
  for (const char* file : {"blob.msh", "blob_coarse.msh"}) {
    SCOPED_TRACE(file);
    const Mesh mesh = read_mesh(kData + "/meshes/" + file);
    EXPECT_EQ(mesh.type, ElementType::tet4);
    // Every vertex belongs to an element (no stray geometry points).
    std::vector<char> used(mesh.vertex_count(), 0);
    for (int32_t v : mesh.elements) used[static_cast<size_t>(v)] = 1;
    EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
    // No inverted or flat element at rest.
    const DeformationStatistics d = deformation_statistics(mesh, mesh.positions);
    EXPECT_EQ(d.inverted_elements, 0);
    EXPECT_NEAR(d.min_j, 1.0, 1e-12);
    EXPECT_NEAR(d.volume_ratio, 1.0, 1e-12);
  }
  EXPECT_EQ(read_mesh(kData + "/meshes/blob.msh").element_count(), 3005u);
  EXPECT_EQ(read_mesh(kData + "/meshes/blob_coarse.msh").element_count(), 700u);
}

TEST(Drop, ShapeDeviationIgnoresRigidMotion) {
  const Mesh mesh = read_mesh(kData + "/meshes/blob_coarse.msh");
  const RigidTransform t = RigidTransform::rotation_about({0.6, 0.0, 0.8}, 2.0, {0.1, -0.2, 0.3});
  Points x(mesh.vertex_count()), stretched = mesh.positions;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const auto p = t.apply(mesh.vertex(v));
    for (int k = 0; k < 3; ++k) x(v, k) = p[k] + 0.5;
    stretched(v, 2) *= 1.1;
  }
  EXPECT_LT(shape_deviation(mesh, x).rms_distance, 1e-12);
  EXPECT_GT(shape_deviation(mesh, x).radius_of_gyration, 0.02);  // the 10 x 10 x 8 cm ellipsoid
  // A 10% stretch along z is not rigid: the fit leaves a deviation of the
  // order of 10% of the body's extent along z.
  const ShapeDeviation s = shape_deviation(mesh, stretched);
  EXPECT_GT(s.relative(), 0.01);
  EXPECT_LT(s.relative(), 0.1);
}

TEST(Drop, BuiltInSceneMatchesTheSceneFile) {
  const SceneFile f = load_scene(kData + "/scenes/drop.json");
  const Scene built = make_scene("drop", scene_defaults("drop"));
  EXPECT_EQ(f.scene.mesh.elements, built.mesh.elements);
  EXPECT_EQ(f.scene.mesh.positions, built.mesh.positions);
  EXPECT_EQ(built.mesh.element_count(), 3005u);
  EXPECT_EQ(Material(built.material).mu, f.material.mu);
  EXPECT_EQ(Material(built.material).lambda, f.material.lambda);
  EXPECT_NEAR(built.material.poisson_ratio(), 0.46, 1e-12);
  const SolveOptions &a = built.options, &b = f.scene.options;
  ASSERT_TRUE(a.dynamics && b.dynamics);
  EXPECT_EQ(a.dynamics->time_step, b.dynamics->time_step);
  EXPECT_EQ(a.dynamics->density, b.dynamics->density);
  EXPECT_EQ(a.dynamics->damping.mass, b.dynamics->damping.mass);
  EXPECT_EQ(a.dynamics->damping.stiffness, b.dynamics->damping.stiffness);
  EXPECT_EQ(a.dynamics->substeps, b.dynamics->substeps);
  EXPECT_EQ(a.load_steps, b.load_steps);
  // Gravity: the built-in's body force lumped as the file's "body_force" is.
  const Points lumped = lump_body_force(built.mesh, a.body_force);
  ASSERT_EQ(lumped.size(), b.external_force.size());  // points
  for (size_t i = 0; i < lumped.size(); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(lumped(i, k), b.external_force(i, k), 1e-15);
  EXPECT_DOUBLE_EQ(a.body_force[2], -9.81 * a.dynamics->density);
  EXPECT_EQ(a.contact.stiffness, b.contact.stiffness);
  EXPECT_EQ(a.contact.thickness, b.contact.thickness);
  EXPECT_EQ(a.strain_tolerance, b.strain_tolerance);
  EXPECT_EQ(a.absolute_tolerance, b.absolute_tolerance);
  EXPECT_EQ(resolve_configuration(a, built.mesh, uniform_material(built.mesh, Material(built.material)), DeviceInfo{})
                .absolute_tolerance,
            resolve_configuration(b, f.scene.mesh, f.materials, DeviceInfo{}).absolute_tolerance);
  ASSERT_EQ(a.obstacles.size(), 6u);
  ASSERT_EQ(b.obstacles.size(), 6u);
  for (size_t k = 0; k < 6; ++k) {
    SCOPED_TRACE(k);
    // Three cylinders, two walls, the moving cylinder.
    const ObstacleType type = k == 3 || k == 4 ? ObstacleType::plane : ObstacleType::cylinder;
    EXPECT_EQ(a.obstacles[k].type, type);
    EXPECT_EQ(b.obstacles[k].type, type);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(a.obstacles[k].point[i], b.obstacles[k].point[i], 1e-15);
    EXPECT_EQ(a.obstacles[k].direction, b.obstacles[k].direction);
    EXPECT_EQ(a.obstacles[k].radius, b.obstacles[k].radius);
    EXPECT_EQ(bool(a.obstacles[k].motion), bool(b.obstacles[k].motion));
    if (!a.obstacles[k].motion) continue;
    for (double t : {0.0, 0.1, 0.3, 0.45, 0.5, 0.6, 0.69, 0.8, 1.0}) {
      const auto pa = a.obstacles[k].motion(t).apply(a.obstacles[k].point);
      const auto pb = b.obstacles[k].motion(t).apply(b.obstacles[k].point);
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(pa[i], pb[i], 1e-12) << "t = " << t;
    }
  }
  // The squash: the upper cylinder comes down to three contact thicknesses
  // above the middle lower one.
  const Obstacle &upper = a.obstacles[5], &middle = a.obstacles[1];
  const double gap = upper.motion(0.5).apply(upper.point)[2] - upper.radius - middle.point[2] - middle.radius;
  EXPECT_NEAR(gap, 3 * a.contact.thickness, 1e-12);
}

// What ParaView is shown of the obstacles: at t = 0.5 the upper cylinder's
// tube lies on its moved surface, the walls' squares on their planes, and
// every triangle faces the free side.
TEST(Drop, ObstacleSurfaceFollowsTheMotion) {
  const Scene scene = make_scene("drop", scene_defaults("drop"));
  for (size_t k = 0; k < scene.options.obstacles.size(); ++k) {
    SCOPED_TRACE(k);
    const Obstacle& o = scene.options.obstacles[k];
    const TriangleSurface s = scene_io::obstacle_surface({o}, 0.5, {0.0, 0.0, 0.0}, 0.2);
    ASSERT_GT(s.triangle_count(), 0u);
    const std::array<double, 3> p = o.motion ? o.motion(0.5).apply(o.point) : o.point;
    // Signed distance of x from the placed obstacle and its outward normal
    // (the axes and normals here are coordinate axes, so unit already).
    auto phi = [&](const double* x, std::array<double, 3>& n) {
      const std::array<double, 3> d{x[0] - p[0], x[1] - p[1], x[2] - p[2]};
      if (o.type == ObstacleType::plane) {
        n = o.direction;
        return d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
      }
      const double along = d[0] * o.direction[0] + d[1] * o.direction[1] + d[2] * o.direction[2];
      const std::array<double, 3> radial{d[0] - along * o.direction[0], d[1] - along * o.direction[1],
                                         d[2] - along * o.direction[2]};
      const double r = std::sqrt(radial[0] * radial[0] + radial[1] * radial[1] + radial[2] * radial[2]);
      n = {radial[0] / r, radial[1] / r, radial[2] / r};
      return r - o.radius;
    };
    std::array<double, 3> n;
    for (size_t v = 0; v < s.vertex_count(); ++v) EXPECT_NEAR(phi(s.positions.data() + 3 * v, n), 0.0, 1e-12);
    for (size_t t = 0; t < s.triangle_count(); ++t) {
      const double* a = s.positions.data() + 3 * s.triangles[3 * t];
      const double* b = s.positions.data() + 3 * s.triangles[3 * t + 1];
      const double* c = s.positions.data() + 3 * s.triangles[3 * t + 2];
      const std::array<double, 3> e{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, f{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      const std::array<double, 3> normal{e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2],
                                         e[0] * f[1] - e[1] * f[0]};
      const double centroid[3] = {(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3};
      phi(centroid, n);
      EXPECT_GT(normal[0] * n[0] + normal[1] * n[1] + normal[2] * n[2], 0.0) << "triangle " << t;
    }
  }
}

#ifdef SNH_BENCH_BINARY
// The coarse blob (700 tets) in 10 frames of 0.2 s (4 substeps of 50 ms;
// about 12 s on pocl) through the scene command: every step converged and
// finite, squashed (some element inverted while the upper cylinder is
// down) without a vertex deeper than the contact layer, and after release
// back to the volume and shape it had resting before the squash (within
// 0.1% and 0.5% of its radius of gyration; the rest of the difference from
// the rest shape is its sag under gravity); a .vtu per step and a .pvd
// listing them at the simulated times.
TEST(Drop, CoarseSquashAndReleaseThroughTheSceneCommand) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "snh_drop_test";
  std::filesystem::remove_all(dir);
  const std::string json_path = (dir / "drop.json").string();
  const int frames = 10;
  const std::string command = std::string(SNH_BENCH_BINARY) + " scene drop --res 1 --steps " + std::to_string(frames) +
                              " --vtu " + (dir / "vtu").string() + " --json " + json_path + " > " +
                              (dir.string() + ".log") + " 2>&1";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << command;
  nlohmann::json j;
  std::ifstream(json_path) >> j;
  EXPECT_EQ(j["elements"], 700);
  EXPECT_EQ(j["poisson_ratio"], 0.46);
  ASSERT_EQ(j["steps"].size(), static_cast<size_t>(frames));
  const double thickness = j["contact"]["thickness"].get<double>();
  double squashed_min_j = 1.0;
  for (size_t s = 0; s < j["steps"].size(); ++s) {
    const nlohmann::json& step = j["steps"][s];
    SCOPED_TRACE("step " + std::to_string(s + 1));
    EXPECT_TRUE(step["converged"].get<bool>()) << step["status"];
    ASSERT_TRUE(step.contains("volume_ratio"));  // only absent for a non-finite state
    ASSERT_TRUE(std::isfinite(step["rigid_fit_rms_relative"].get<double>()));
    EXPECT_LE(step["max_penetration"].get<double>(), thickness);
    EXPECT_NEAR(step["time"].get<double>(), 2.0 * (s + 1) / frames, 1e-12);
    const double t = (s + 1.0) / frames;
    if (t >= 0.45 && t <= 0.55) squashed_min_j = std::min(squashed_min_j, step["min_j"].get<double>());
  }
  EXPECT_LT(squashed_min_j, 0.0);
  // Step 3 (t = 0.3, 0.6 s): resting on the cylinders, the upper one not yet
  // down to the body.
  const nlohmann::json &before = j["steps"][2], &last = j["steps"].back();
  EXPECT_NEAR(last["volume_ratio"].get<double>(), before["volume_ratio"].get<double>(), 1e-3);
  EXPECT_NEAR(last["rigid_fit_rms_relative"].get<double>(), before["rigid_fit_rms_relative"].get<double>(), 5e-3);
  EXPECT_NEAR(last["volume_ratio"].get<double>(), 1.0, 0.01);
  EXPECT_LT(last["rigid_fit_rms_relative"].get<double>(), 0.02);
  RecordProperty("squashed_min_j", std::to_string(squashed_min_j));
  RecordProperty("final_volume_ratio", std::to_string(last["volume_ratio"].get<double>()));
  RecordProperty("final_rigid_fit_rms_relative", std::to_string(last["rigid_fit_rms_relative"].get<double>()));

  // ParaView: drop_0000.vtu (rest) .. drop_0010.vtu, the obstacles' surfaces
  // drop_obstacles_0000.vtu .., and drop.pvd listing each with its
  // simulated time, the body as part 0 and the obstacles as part 1.
  std::ifstream pvd(dir / "vtu" / "drop.pvd");
  ASSERT_TRUE(pvd.good());
  const std::string text((std::istreambuf_iterator<char>(pvd)), std::istreambuf_iterator<char>());
  const std::regex entry(R"re(<DataSet\s+timestep="([^"]+)"\s+group="[^"]*"\s+part="([01])"\s+file="([^"]+)")re");
  int count[2] = {0, 0};
  for (auto it = std::sregex_iterator(text.begin(), text.end(), entry); it != std::sregex_iterator(); ++it) {
    const int part = std::stoi((*it)[2].str());
    char name[64];
    std::snprintf(name, sizeof name, part == 0 ? "drop_%04d.vtu" : "drop_obstacles_%04d.vtu", count[part]);
    EXPECT_EQ((*it)[3].str(), name);
    EXPECT_TRUE(std::filesystem::exists(dir / "vtu" / name)) << name;
    EXPECT_NEAR(std::stod((*it)[1].str()), 2.0 * count[part] / frames, 1e-12) << name;
    ++count[part];
  }
  EXPECT_EQ(count[0], frames + 1);
  EXPECT_EQ(count[1], frames + 1);
}
#endif

}  // namespace
}  // namespace snh::test
