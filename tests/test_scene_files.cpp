// Scene files (data/scenes/*.json): the shipped built-in scenes match
// make_scene, the Gmsh-mesh example with gravity solves, the rigged arm
// example flexes its embedded surface, bones given as surface files hold and
// move the vertices inside them, and bad files get errors naming the key.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "snh/configuration.h"
#include "snh/error.h"
#include "snh/frames.h"
#include "snh/regions.h"
#include "snh/rig.h"
#include "snh/scene.h"
#include "snh/simulation.h"
#include "snh/surface.h"

namespace snh::test {
namespace {

const std::string kScenes = std::string(SNH_DATA_DIR) + "/scenes/";

TEST(SceneFiles, ShippedBuiltInScenesMatchMakeScene) {
  for (const std::string name : {"twist", "stretch", "scramble", "flex"}) {
    SCOPED_TRACE(name);
    const SceneFile f = load_scene(kScenes + name + ".json");
    const Scene built = make_scene(name, {});
    EXPECT_GT(f.scene.mesh.element_count(), 100u);
    EXPECT_EQ(f.scene.mesh.elements, built.mesh.elements);
    ASSERT_EQ(f.scene.mesh.positions.xyz().size(), built.mesh.positions.xyz().size());
    for (size_t i = 0; i < built.mesh.positions.xyz().size(); ++i)
      EXPECT_NEAR(f.scene.mesh.positions.xyz()[i], built.mesh.positions.xyz()[i], 1e-12);
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
  const SceneFile f = load_scene(kScenes + "gravity_tet.json");
  EXPECT_EQ(f.scene.mesh.type, ElementType::tet4);
  ASSERT_FALSE(f.scene.options.external_force.empty());
  double total = 0.0;
  for (size_t v = 0; v < f.scene.mesh.vertex_count(); ++v) total += f.scene.options.external_force(v, 2);
  EXPECT_NEAR(total, -9810.0 * 0.125, 1e-6);  // weight of a 1 x 0.5 x 0.25 box
  QuasistaticSolver solver(f.scene.mesh, f.material, f.scene.constraints, f.scene.options);
  const SolveResult r = solver.solve();
  EXPECT_TRUE(r.converged);
  // The stopping residual of a strain error of 1e-6 (SolveOptions::
  // strain_tolerance) with the mesh's mean vertex spacing (0.082), not with
  // its first element's first edge (0.175 on this Gmsh mesh: a tolerance 4.6x
  // looser, as scene files had it before).
  const double h = vertex_spacing(f.scene.mesh);
  EXPECT_NEAR(r.tolerance, 1e-6 * 1e5 * h * h * std::sqrt(static_cast<double>(f.scene.mesh.vertex_count())),
              1e-12 * r.tolerance);
  double tip = 0.0;
  for (size_t v = 0; v < f.scene.mesh.vertex_count(); ++v)
    if (f.scene.mesh.positions(v, 0) > 1.0 - 1e-9)
      tip = std::min(tip, r.positions(v, 2) - f.scene.mesh.positions(v, 2));
  EXPECT_LT(tip, -1e-3);
}

// A scene file's stopping strain scales by the smallest Young's modulus of
// its materials (here a soft region's, not the file's base material's), as
// SolveOptions::strain_tolerance does; an absolute tolerance stands alone.
TEST(SceneFiles, StrainToleranceFollowsTheLibrarysRule) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "snh_strain_tolerance_scene.json";
  const auto load = [&](const std::string& solver) {
    std::ofstream(path) << R"({"mesh": {"generator": "box", "cells": [4, 2, 2], "size": 0.25},
      "material": {"model": "snh", "E": 4.0, "nu": 0.45},
      "regions": [{"name": "soft", "select": {"box": {"min": [-1, -1, -1], "max": [0.5, 1, 1]}},
                   "material": {"model": "snh", "E": 1.0, "nu": 0.45}}],
      "constraints": [{"name": "left", "select": {"plane": {"axis": "x", "value": 0.0, "tolerance": 1e-9}}}],
      "solver": )" + solver + "}";
    return load_scene(path.string());
  };
  const SceneFile plain = load("{}");
  ASSERT_TRUE(plain.scene.options.strain_tolerance.has_value());
  EXPECT_EQ(*plain.scene.options.strain_tolerance, 1e-6);
  EXPECT_EQ(plain.scene.options.absolute_tolerance, 0.0);
  const double h = vertex_spacing(plain.scene.mesh);
  EXPECT_NEAR(h, std::cbrt(0.25 / 45.0), 1e-12);  // 45 vertices over a 1 x 0.5 x 0.5 box
  const double n = static_cast<double>(plain.scene.mesh.vertex_count());
  EXPECT_NEAR(
      resolve_configuration(plain.scene.options, plain.scene.mesh, plain.materials, DeviceInfo{}).absolute_tolerance,
      1e-6 * 1.0 * h * h * std::sqrt(n), 1e-15);
  const SceneFile given = load(R"({"strain_tolerance": 1e-5, "precision": "float"})");
  EXPECT_NEAR(
      resolve_configuration(given.scene.options, given.scene.mesh, given.materials, DeviceInfo{}).absolute_tolerance,
      1e-5 * h * h * std::sqrt(n), 1e-15);
  const SceneFile absolute = load(R"({"absolute_tolerance": 1e-3})");
  EXPECT_FALSE(absolute.scene.options.strain_tolerance.has_value());
  EXPECT_EQ(resolve_configuration(absolute.scene.options, absolute.scene.mesh, absolute.materials, DeviceInfo{})
                .absolute_tolerance,
            1e-3);
  std::filesystem::remove(path);
}

std::string error_of(const std::string& text) {
  // A file per test: ctest -j runs the tests of this file side by side.
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() /
      (std::string("snh_bad_scene_") + ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".json");
  std::ofstream(path) << text;
  try {
    load_scene(path.string());
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
  EXPECT_NE(error_of("{" + mesh + R"(, "solver": {"hessian": "exact"}})").find("solver.hessian: hessian: expected"),
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
  const SceneFile f = load_scene(path.string());
  EXPECT_EQ(f.material.model, MaterialModel::corotational);
  EXPECT_EQ(f.material.lambda_model, MaterialModel::neohookean);
  EXPECT_EQ(f.material.alpha_mu, 1.5);
  EXPECT_EQ(f.material.alpha_lambda, 0.75);
  const std::string mesh = R"("mesh": {"generator": "box", "cells": [2, 2, 2], "size": 0.5})";
  EXPECT_NE(error_of("{" + mesh + R"(, "material": {"alpha": -1}})").find("alpha"), std::string::npos);
  EXPECT_NE(error_of("{" + mesh + R"(, "material": {"lambda_model": "jelly"}})").find("jelly"), std::string::npos);
}

// solver.product_precision (SolveOptions::product_precision): float or
// double sets it, absent leaves it unset (the default), anything else is an
// error naming the key.
TEST(SceneFiles, ProductPrecisionKey) {
  const std::string mesh = R"("mesh": {"generator": "box", "cells": [2, 2, 2], "size": 0.5})";
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "snh_product_precision.json";
  std::ofstream(path) << "{" + mesh + R"(, "solver": {"product_precision": "double"}})";
  EXPECT_EQ(load_scene(path.string()).scene.options.product_precision, Precision::double_);
  std::ofstream(path) << "{" + mesh + "}";
  EXPECT_FALSE(load_scene(path.string()).scene.options.product_precision.has_value());
  EXPECT_NE(error_of("{" + mesh + R"(, "solver": {"product_precision": "half"}})").find("solver.product_precision"),
            std::string::npos);
}

// "automatic" (and the contact lengths' 0) in a scene file leaves the
// option unset (std::optional empty), as leaving the key out does.
TEST(SceneFiles, AutomaticLoadsAsUnset) {
  const std::string mesh = R"("mesh": {"generator": "box", "cells": [2, 2, 2], "size": 0.5})";
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "snh_automatic_scene.json";
  std::ofstream(path) << "{" + mesh + R"(, "material": {"nu": 0.45, "barrier": "auto"},
    "contact": {"self": true, "self_distance": 0, "friction_slip": 0, "self_stiffness": 0},
    "solver": {"preconditioner": "automatic", "product_precision": "automatic"}})";
  const SolveOptions automatic = load_scene(path.string()).scene.options;
  EXPECT_FALSE(automatic.preconditioner.has_value());
  EXPECT_FALSE(automatic.product.has_value());
  EXPECT_FALSE(automatic.product_precision.has_value());
  EXPECT_FALSE(automatic.contact.self_distance.has_value());
  EXPECT_FALSE(automatic.contact.friction_slip.has_value());
  EXPECT_FALSE(automatic.contact.self_stiffness.has_value());
  std::ofstream(path) << "{" + mesh + R"(, "contact": {"self": true, "self_distance": 0.01},
    "solver": {"preconditioner": "multigrid"}})";
  const SolveOptions given = load_scene(path.string()).scene.options;
  EXPECT_EQ(given.preconditioner, Preconditioner::multigrid);
  EXPECT_EQ(given.contact.self_distance, 0.01);
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
  const SceneFile f = load_scene(path.string());
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
  // The rig's kinematics alone: without self-contact the hand follows its
  // bone; with it (the scene's default) the folding flesh pushes back
  // (BarrierContact.RiggedScenesHaveSelfContactByDefaultAndFramesReportIt).
  SolveOptions solve = f.scene.options;
  solve.contact.self = false;
  Simulation sim(f.scene.mesh, uniform_material(f.scene.mesh, f.material), f.scene.constraints, solve);
  Points surface;
  FrameOptions options;
  options.load_steps = 3;
  const auto records =
      run_frames(sim, some, &f.embedded->embedding, options, [&](const FrameRecord&, const Points&, const Points& s) {
        surface = s;
        return true;
      });
  ASSERT_EQ(records.size(), 4u);
  for (const FrameRecord& r : records) EXPECT_TRUE(r.converged) << "frame " << r.frame << ": " << r.status;
  EXPECT_EQ(records.back().inverted_elements, 0);
  // make_arm.py: vertex 0 is the shoulder's tip (0, 0, 0), the last the hand's (4, 0, 0).
  const TriangleSurface& rest = f.embedded->surface;
  const size_t hand = rest.vertex_count() - 1;
  ASSERT_EQ(rest.positions(0, 0), 0.0);
  ASSERT_EQ(rest.positions(hand, 0), 4.0);
  const double angle = 100.0 * M_PI / 180.0;  // 2 from the elbow (2, 0, 0), rotated about y up towards +z
  const double expected[3] = {2.0 + 2.0 * std::cos(angle), 0.0, 2.0 * std::sin(angle)};
  for (int d = 0; d < 3; ++d) {
    EXPECT_NEAR(surface(0, d), 0.0, 0.02) << d;
    EXPECT_NEAR(surface(hand, d), expected[d], 0.05) << d;
  }
}

// A bar of 12 x 4 x 4 hexes (h = 0.2) rigged by two bones given as closed
// surface files: a box (OBJ) around the two end layers at x = 0 and 0.2,
// and a 16-sided cylinder (ASCII STL) along the bar's axis around the
// middle 3 x 3 vertices of the layers x = 2.2 and 2.4. Each bone's set is
// the lattice vertices inside its surface (counted here from the geometry),
// and over three frames (rest, a rotation about the bar's axis with a lift,
// then a non-rigid stretch and shear) the root stays, the tip vertices sit
// where the frame's matrix puts them and every frame converges.
TEST(SceneFiles, SurfaceFileBonesHoldTheVerticesInsideAndFollowTheirFrames) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "snh_surface_bones";
  fs::remove_all(dir);
  fs::create_directories(dir);
  {
    std::ofstream obj(dir / "root_bone.obj");
    const double lo[3] = {-0.1, -0.1, -0.1}, hi[3] = {0.3, 0.9, 0.9};
    for (int c = 0; c < 8; ++c)
      obj << "v " << (c & 1 ? hi : lo)[0] << " " << (c & 2 ? hi : lo)[1] << " " << (c & 4 ? hi : lo)[2] << "\n";
    // Outward quads as triangles (corner c = x + 2y + 4z, 1-based in OBJ).
    const int quads[6][4] = {{1, 3, 4, 2}, {5, 6, 8, 7}, {1, 2, 6, 5}, {3, 7, 8, 4}, {1, 5, 7, 3}, {2, 4, 8, 6}};
    for (const auto& q : quads)
      obj << "f " << q[0] << " " << q[1] << " " << q[2] << "\nf " << q[0] << " " << q[2] << " " << q[3] << "\n";
  }
  const double axis_y = 0.4, axis_z = 0.4, radius = 0.3, x0 = 2.1, x1 = 2.5;
  {
    std::ofstream stl(dir / "tip_bone.stl");
    stl.precision(17);
    const int sides = 16;
    const auto ring = [&](int k) {
      const double a = 2.0 * M_PI * k / sides;
      return std::array<double, 2>{axis_y + radius * std::cos(a), axis_z + radius * std::sin(a)};
    };
    const auto facet = [&](std::array<double, 3> a, std::array<double, 3> b, std::array<double, 3> c) {
      stl << "facet normal 0 0 0\nouter loop\n";
      for (const auto& p : {a, b, c}) stl << "vertex " << p[0] << " " << p[1] << " " << p[2] << "\n";
      stl << "endloop\nendfacet\n";
    };
    stl << "solid tip\n";
    for (int k = 0; k < sides; ++k) {
      const auto p = ring(k), q = ring(k + 1);
      // Side (outward: counter-clockwise seen from outside), then the caps.
      facet({x0, p[0], p[1]}, {x1, q[0], q[1]}, {x1, p[0], p[1]});
      facet({x0, p[0], p[1]}, {x0, q[0], q[1]}, {x1, q[0], q[1]});
      facet({x1, axis_y, axis_z}, {x1, p[0], p[1]}, {x1, q[0], q[1]});
      facet({x0, axis_y, axis_z}, {x0, q[0], q[1]}, {x0, p[0], p[1]});
    }
    stl << "endsolid tip\n";
  }
  // Frame 1: 30 degrees about the bar's axis (x) through the bone, lifted
  // 0.1 in z; frame 2: 10% longer along x and sheared (z += 0.2 x) about
  // the bone's start: not a rigid motion.
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  const Matrix4 turn = {
      1, 0, 0, 0, 0, c, -s, axis_y - c * axis_y + s * axis_z, 0, s, c, axis_z - s * axis_y - c * axis_z + 0.1,
      0, 0, 0, 1};
  const Matrix4 stretch = {1.1, 0, 0, -0.1 * x0, 0, 1, 0, 0, 0.2, 0, 1, -0.2 * x0, 0, 0, 0, 1};
  {
    nlohmann::json frames = nlohmann::json::array();
    const Matrix4 frame_matrices[3] = {identity_matrix4(), turn, stretch};
    for (int f = 0; f < 3; ++f) {
      nlohmann::json rows = nlohmann::json::array();
      for (int r = 0; r < 4; ++r)
        rows.push_back({frame_matrices[f][4 * r], frame_matrices[f][4 * r + 1], frame_matrices[f][4 * r + 2],
                        frame_matrices[f][4 * r + 3]});
      frames.push_back({{"time", f}, {"bones", {{"tip", rows}}}});
    }
    std::ofstream(dir / "bend.json") << nlohmann::json{{"frames", frames}}.dump();
    std::ofstream(dir / "scene.json") << R"({
      "mesh": {"generator": "box", "cells": [12, 4, 4], "size": 0.2},
      "material": {"model": "snh", "E": 1.0, "nu": 0.45},
      "rig": {"bones": [{"name": "root", "surface": "root_bone.obj"}, {"name": "tip", "surface": "tip_bone.stl"}],
              "animation": "bend.json"}})";
  }
  const SceneFile f = load_scene((dir / "scene.json").string());
  ASSERT_TRUE(f.rig);
  const Mesh& mesh = f.scene.mesh;
  ASSERT_EQ(mesh.element_count(), 192u);
  ASSERT_EQ(f.scene.constraints.size(), 2u);
  const ConstraintSet &root = f.scene.constraints[0], &tip = f.scene.constraints[1];
  EXPECT_EQ(root.name, "root");
  EXPECT_EQ(tip.name, "tip");
  std::vector<int32_t> in_root, in_tip;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const auto x = mesh.vertex(v);
    if (x[0] < 0.3) in_root.push_back(static_cast<int32_t>(v));
    if (x[0] > x0 && std::hypot(x[1] - axis_y, x[2] - axis_z) < 0.29) in_tip.push_back(static_cast<int32_t>(v));
  }
  EXPECT_EQ(in_root.size(), 2u * 25u);  // layers x = 0 and 0.2
  EXPECT_EQ(in_tip.size(), 2u * 9u);    // 3 x 3 around the axis on x = 2.2 and 2.4
  EXPECT_EQ(root.vertices, in_root);
  EXPECT_EQ(tip.vertices, in_tip);

  Simulation sim(mesh, uniform_material(mesh, f.material), f.scene.constraints, f.scene.options);
  FrameOptions options;
  options.load_steps = 1;
  const Matrix4 expected[3] = {identity_matrix4(), turn, stretch};
  int frame = 0;
  Points lifted;
  const auto records =
      run_frames(sim, f.rig->animation, nullptr, options, [&](const FrameRecord& r, const Points& x, const Points&) {
        EXPECT_TRUE(r.converged) << "frame " << r.frame << ": " << r.status;
        EXPECT_EQ(r.inverted_elements, 0);
        for (int32_t v : root.vertices)
          for (int d = 0; d < 3; ++d) EXPECT_NEAR(x(v, d), mesh.positions(v, d), 1e-12);
        const Matrix4& m = expected[frame];
        for (int32_t v : tip.vertices) {
          const auto p = mesh.vertex(v);
          for (int d = 0; d < 3; ++d)
            EXPECT_NEAR(x(v, d), m[4 * d] * p[0] + m[4 * d + 1] * p[1] + m[4 * d + 2] * p[2] + m[4 * d + 3], 1e-12)
                << "frame " << frame << " vertex " << v;
        }
        if (frame == 1) lifted = x;
        ++frame;
        return true;
      });
  EXPECT_EQ(records.size(), 3u);
  EXPECT_EQ(frame, 3);
  // The free flesh between the bones followed: the vertex on the axis at
  // x = 2, next to the tip bone, rose with the lift of frame 1 (0.1 at the
  // bone, 0 at the root).
  int32_t near_tip = -1;
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    if (std::abs(mesh.positions(v, 0) - 2.0) < 1e-9 && std::abs(mesh.positions(v, 1) - axis_y) < 1e-9 &&
        std::abs(mesh.positions(v, 2) - axis_z) < 1e-9)
      near_tip = static_cast<int32_t>(v);
  ASSERT_GE(near_tip, 0);
  ASSERT_EQ(lifted.size(), mesh.vertex_count());
  EXPECT_GT(lifted(near_tip, 2) - axis_z, 0.05);
  EXPECT_LT(lifted(near_tip, 2) - axis_z, 0.1);
  fs::remove_all(dir);
}

#ifdef SNH_BENCH_BINARY
// `snh-gpu-bench scene --file` on the coarse arm (cell 0.25) with frames 0,
// 12 and 24 of its animation: per frame the embedded surface as OBJ, the
// lattice and the surface as .vtu parts of one .pvd, and the JSON record
// with what ran (here multigrid with double products, from the file).
TEST(SceneFiles, RiggedSceneCommandWritesTheSurfacePerFrameAndAPvd) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "snh_arm_command";
  fs::remove_all(dir);
  fs::create_directories(dir);
  nlohmann::json animation;
  std::ifstream(std::string(SNH_DATA_DIR) + "/arm/arm_flexion.json") >> animation;
  nlohmann::json frames = nlohmann::json::array();
  for (int f : {0, 12, 24}) frames.push_back(animation["frames"][f]);
  std::ofstream(dir / "three.json") << nlohmann::json{{"frames", frames}}.dump();
  nlohmann::json doc;
  std::ifstream(kScenes + "arm.json") >> doc;
  doc["embed"]["cell"] = 0.25;
  doc["embed"]["surface"] = kScenes + doc["embed"]["surface"].get<std::string>();
  doc["rig"]["animation"] = "three.json";
  doc["solver"]["preconditioner"] = "multigrid";  // the record reports what ran
  doc["contact"] = {{"self", false}};             // a quicker run: the record is what is checked
  doc["solver"]["product_precision"] = "double";
  doc["output"] = {
      {"vtu", (dir / "vtu").string()}, {"surface", (dir / "obj/").string()}, {"json", (dir / "run.json").string()}};
  std::ofstream(dir / "arm.json") << doc.dump();
  const int status = std::system((std::string(SNH_BENCH_BINARY) + " scene --file " + (dir / "arm.json").string() +
                                  " > " + (dir / "log.txt").string() + " 2>&1")
                                     .c_str());
  std::ostringstream log;
  log << std::ifstream(dir / "log.txt").rdbuf();
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << log.str();
  EXPECT_NE(log.str().find("frame 3/3"), std::string::npos) << log.str();  // progress per frame
  const TriangleSurface rest = read_surface(kScenes + "../arm/arm.obj");
  for (int f = 0; f < 3; ++f) {
    const TriangleSurface s = read_surface(surface_obj_path((dir / "obj/").string(), "arm", f));
    EXPECT_EQ(s.triangles, rest.triangles);
    if (f == 0) {
      for (size_t i = 0; i < s.positions.xyz().size(); ++i)
        EXPECT_NEAR(s.positions.xyz()[i], rest.positions.xyz()[i], 1e-9);
    }
    if (f == 2) {  // the hand (4, 0, 0) turned 100 degrees about the elbow (2, 0, 0), as in the in-process test
      const size_t hand = rest.vertex_count() - 1;
      EXPECT_NEAR(s.positions(hand, 0), 2.0 + 2.0 * std::cos(100.0 * M_PI / 180.0), 0.05);
      EXPECT_NEAR(s.positions(hand, 2), 2.0 * std::sin(100.0 * M_PI / 180.0), 0.05);
    }
  }
  std::ostringstream pvd;
  pvd << std::ifstream(dir / "vtu" / "arm.pvd").rdbuf();
  for (const char* file : {"arm_0000.vtu", "arm_surface_0000.vtu", "arm_0002.vtu", "arm_surface_0002.vtu"}) {
    EXPECT_TRUE(fs::exists(dir / "vtu" / file)) << file;
    EXPECT_NE(pvd.str().find(std::string("file=\"") + file + "\""), std::string::npos) << pvd.str();
  }
  EXPECT_NE(pvd.str().find("part=\"1\" file=\"arm_surface_0002.vtu\""), std::string::npos) << pvd.str();
  nlohmann::json run;
  std::ifstream(dir / "run.json") >> run;
  EXPECT_EQ(run["converged"], true);
  EXPECT_EQ(run["frames"].size(), 3u);
  // What ran, as in the plain scene record.
  EXPECT_EQ(run["element_type"], "hex8");
  EXPECT_EQ(run["precision"], "double");
  EXPECT_FALSE(run["device"].get<std::string>().empty());
  EXPECT_NE(run["kernel_specialization"].get<std::string>().find("-DSNH_HEX8=1"), std::string::npos);
  EXPECT_EQ(run["preconditioner"], "multigrid");
  EXPECT_EQ(run["product_precision"], "double");
  EXPECT_TRUE(run["product"].is_string());
  EXPECT_GT(run["multigrid_smoother_degree"].get<int>(), 0);
  EXPECT_TRUE(run["multigrid_float_cycle"].get<bool>());  // double, quasistatic: a built fine level
  EXPECT_EQ(run["hessian"], "adaptive");
  EXPECT_GT(run["device_memory_bytes"].get<size_t>(), 0u);
  fs::remove_all(dir);
}

// `scene --file` with solver flags: those given override the file's solver
// settings (a float run without a tolerance in the file stops at float's
// default strain, as the named scenes do); flags that build a named scene
// are errors naming the flag, not silently ignored.
TEST(SceneFiles, CommandLineSolverFlagsOverrideTheFile) {
  const std::filesystem::path json_path = std::filesystem::temp_directory_path() / "snh_flags_over_file.json";
  const auto run = [&](const std::string& flags, nlohmann::json* j) {
    std::filesystem::remove(json_path);
    const std::string command = std::string(SNH_BENCH_BINARY) + " scene --file " + kScenes + "soft_stiff_bar.json " +
                                flags + " --json " + json_path.string() + " 2>&1";
    std::string output;
    if (FILE* pipe = popen(command.c_str(), "r")) {
      char buffer[512];
      while (fgets(buffer, sizeof buffer, pipe)) output += buffer;
      const int status = pclose(pipe);
      if (j && WIFEXITED(status) && WEXITSTATUS(status) == 0) std::ifstream(json_path) >> *j;
    }
    return output;
  };
  nlohmann::json plain, given, single;
  run("", &plain);
  ASSERT_TRUE(plain.is_object());
  EXPECT_EQ(plain["hessian"], "adaptive");
  EXPECT_EQ(plain["precision"], "double");
  run("--preconditioner none --variant cached --hessian projected --steps 2", &given);
  ASSERT_TRUE(given.is_object());
  EXPECT_EQ(given["preconditioner"], "none");
  EXPECT_EQ(given["product"], "cached");
  EXPECT_EQ(given["hessian"], "projected");
  EXPECT_EQ(given["steps"].size(), 2u);
  EXPECT_EQ(given["converged"], true);
  run("--precision float", &single);
  ASSERT_TRUE(single.is_object());
  EXPECT_EQ(single["precision"], "float");
  EXPECT_EQ(single["converged"], true);
  // Float's default strain (1e-4) against double's (1e-6).
  EXPECT_NEAR(single["tolerance"].get<double>() / plain["tolerance"].get<double>(), 100.0, 1e-9);
  for (const std::string flag : {"--res 3", "--nu 0.3", "--E 2", "--model fung", "--strain-tol 1e-5"}) {
    const std::string output = run(flag, nullptr);
    EXPECT_NE(output.find(flag.substr(0, flag.find(' ')) + " builds a named scene"), std::string::npos) << output;
  }
}
#endif

TEST(SceneFiles, RigKeysNameTheirErrors) {
  const std::string surface = std::string(SNH_DATA_DIR) + "/arm/arm.obj";
  const std::string animation = std::string(SNH_DATA_DIR) + "/arm/arm_flexion.json";
  const std::string embed = R"("embed": {"surface": ")" + surface + R"(", "cell": 0.25})";
  const std::string mesh = R"("mesh": {"generator": "box", "cells": [2, 2, 2], "size": 0.5})";
  const std::string upper =
      R"({"name": "upper_arm", "capsule": {"a": [0.35, 0, 0], "b": [1.6, 0, 0], "radius": 0.25}})";
  const std::string fore = R"({"name": "forearm", "capsule": {"a": [2.4, 0, 0], "b": [3.55, 0, 0], "radius": 0.24}})";
  EXPECT_NE(error_of("{" + embed + ", " + mesh + "}").find("not both"), std::string::npos);
  const std::string covered = R"({"embed": {"surface": ")" + surface + R"(", "cell": 0.25, "cover_surface": )";
  EXPECT_NE(error_of(covered + "1}}").find("embed.cover_surface: expected true or false"), std::string::npos);
  {
    const std::filesystem::path path = std::filesystem::temp_directory_path() / "snh_arm_cover.json";
    std::ofstream(path) << covered + "true}}";
    const SceneFile f = load_scene(path.string());
    EXPECT_GT(f.scene.mesh.element_count(), 137u);  // the centre-inside lattice of the arm at 0.25 has 137
    for (double w : f.embedded->embedding.weights) EXPECT_GE(w, -1e-9);  // no surface vertex outside its cell
  }
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
  EXPECT_EQ(surface_obj_path("out/arm", "arm", 7), "out/arm_0007.obj");
  EXPECT_EQ(surface_obj_path("out/", "arm", 12), "out/arm_0012.obj");
}

}  // namespace
}  // namespace snh::test
