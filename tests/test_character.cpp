// Skinned characters (snh/character.h): node transforms composed as glTF
// defines them, skin weights, bones from the skeleton, point caches byte by
// byte, bad files named with the item at fault, and the shipped arm example
// run end to end through `snh run` (pocl).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "snh/character.h"
#include "snh/error.h"
#include "snh/scene.h"
#include "support/errors.h"
#include "support/scratch.h"

namespace snh::test {
namespace {

namespace fs = std::filesystem;

const std::string kData = std::string(SNH_SOURCE_DIR) + "/tests/data/character/";
const std::string kArm = std::string(SNH_SOURCE_DIR) + "/examples/character/arm.gltf";

void expect_matrix(const Matrix4& m, const Matrix4& expected, const std::string& what) {
  for (int k = 0; k < 16; ++k) EXPECT_NEAR(m[k], expected[k], 1e-6) << what << " entry " << k;
}

TEST(CharacterRead, NodeTransformsComposeTranslationRotationScaleDownTheChain) {
  CharacterReadOptions options;
  options.clip = "move";
  options.fps = 2;  // frames at 0, 0.5 and 1 s
  const Character c = read_character(kData + "trs.gltf", options);
  ASSERT_EQ(c.joints.size(), 2u);
  EXPECT_EQ(c.joints[0].name, "root");
  EXPECT_EQ(c.joints[1].name, "tip");
  EXPECT_EQ(c.joints[0].parent, -1);
  EXPECT_EQ(c.joints[1].parent, 0);
  ASSERT_EQ(c.clip.frame_count(), 3u);
  EXPECT_EQ(c.clip.name, "move");
  EXPECT_EQ(c.clip.index, 1);
  EXPECT_DOUBLE_EQ(c.clip.times[1], 0.5);
  // Inverse binds are identities, so skinning matrices are world matrices.
  // root = T(1, 2, 3) Rz(90) S(2), whatever the frame (no channel).
  const Matrix4 root{0, -2, 0, 1, 2, 0, 0, 2, 0, 0, 2, 3, 0, 0, 0, 1};
  for (size_t f = 0; f < 3; ++f) expect_matrix(c.clip.skinning[f][0], root, "root, frame " + std::to_string(f));
  // tip at 0.5 s: T(1, 0, 0) Rx(45) S(2) (halfway keys; slerp), after root.
  const double r2 = std::sqrt(2.0);
  expect_matrix(c.clip.skinning[1][1], {0, -2 * r2, 2 * r2, 1, 4, 0, 0, 4, 0, 2 * r2, 2 * r2, 3, 0, 0, 0, 1},
                "tip 0.5 s");
  // tip at 1 s: T(1.5, 0, 0) Rx(90) S(3).
  expect_matrix(c.clip.skinning[2][1], {0, 0, 6, 1, 6, 0, 0, 5, 0, 6, 0, 3, 0, 0, 0, 1}, "tip 1 s");
  // tip at 0 s: T(0.5, 0, 0), no rotation, S(1).
  expect_matrix(c.clip.skinning[0][1], {0, -2, 0, 1, 2, 0, 0, 3, 0, 0, 2, 3, 0, 0, 0, 1}, "tip 0 s");
  // Clips are listed, the first by default.
  ASSERT_EQ(c.clip_names.size(), 3u);
  EXPECT_EQ(c.clip_names[0], "idle");
  options.clip.clear();
  EXPECT_EQ(read_character(kData + "trs.gltf", options).clip.name, "idle");
  options.clip_index = 1;
  EXPECT_EQ(read_character(kData + "trs.gltf", options).clip.name, "move");
  // glTF STEP keys hold until the next key: at 0.5 s the tip is still at
  // T(0.5, 0, 0), at 1 s at T(1.5, 0, 0).
  options.clip = "jump";
  const Character step = read_character(kData + "trs.gltf", options);
  expect_matrix(step.clip.skinning[1][1], {0, -2, 0, 1, 2, 0, 0, 3, 0, 0, 2, 3, 0, 0, 0, 1}, "step 0.5 s");
  expect_matrix(step.clip.skinning[2][1], {0, -2, 0, 1, 2, 0, 0, 5, 0, 0, 2, 3, 0, 0, 0, 1}, "step 1 s");
}

TEST(CharacterRead, ComposeTrsIsTranslationTimesRotationTimesScale) {
  const double h = std::sin(M_PI / 4), w = std::cos(M_PI / 4);
  expect_matrix(compose_trs({1, 2, 3}, {w, 0, 0, h}, {2, 2, 2}), {0, -2, 0, 1, 2, 0, 0, 2, 0, 0, 2, 3, 0, 0, 0, 1},
                "T Rz(90) S(2)");
  const Matrix4 m = compose_trs({0.3, -1, 2}, {0.9, 0.1, -0.3, 0.2}, {1, 2, 0.5});
  expect_matrix(multiply_matrix4(m, inverse_matrix4(m)), identity_matrix4(), "M M^-1");
}

TEST(CharacterRead, SurfaceKeepsTheFileVertexOrderWeightsAndWeldsTheSeam) {
  const Character c = read_character(kArm);
  // 21 rings of 17 (the seam repeats a column) and two cap centres.
  ASSERT_EQ(c.surface.vertex_count(), 359u);
  EXPECT_EQ(c.surface.triangle_count(), 672u);
  EXPECT_EQ(c.welded.vertex_count(), 359u - 21u);
  EXPECT_EQ(c.welded.triangle_count(), 672u);
  EXPECT_NO_THROW(validate_closed_surface(c.welded));
  for (int ring = 0; ring < 21; ++ring) EXPECT_EQ(c.welded_index[ring * 17], c.welded_index[ring * 17 + 16]);
  // Vertex order: ring r, segment s is r * 17 + s at x = 0.02 r.
  EXPECT_NEAR(c.surface.positions(170, 0), 0.2, 1e-7);
  EXPECT_NEAR(c.surface.positions(170, 1), 0.05, 1e-7);
  ASSERT_EQ(c.joints.size(), 3u);
  EXPECT_EQ(c.joints[1].name, "elbow");
  EXPECT_NEAR(c.joints[1].rest_position[0], 0.2, 1e-7);
  // At x = 0.2 the shoulder and the elbow share the vertex equally
  // (smoothstep(1/2)); the tip's centre is the wrist's alone.
  ASSERT_EQ(c.weights.vertex_count(), 359u);
  ASSERT_EQ(c.weights.offset[171] - c.weights.offset[170], 2);
  EXPECT_EQ(c.weights.joint[c.weights.offset[170]], 0);
  EXPECT_NEAR(c.weights.weight[c.weights.offset[170]], 0.5, 1e-6);
  EXPECT_NEAR(c.weights.weight[c.weights.offset[170] + 1], 0.5, 1e-6);
  ASSERT_EQ(c.weights.offset[359] - c.weights.offset[358], 1);
  EXPECT_EQ(c.weights.joint[c.weights.offset[358]], 2);
  // The clip: 1 s at 30 fps; at 1 s the elbow has turned 90 degrees about
  // +z, so the tip's centre (0.4, 0, 0) is skinned to (0.2, 0.2, 0).
  ASSERT_EQ(c.clip.frame_count(), 31u);
  const Points skinned = linear_blend_skinning(c.surface.positions, c.weights, c.clip.skinning[30]);
  EXPECT_NEAR(skinned(358, 0), 0.2, 1e-6);
  EXPECT_NEAR(skinned(358, 1), 0.2, 1e-6);
  EXPECT_NEAR(skinned(358, 2), 0.0, 1e-6);
  const Points rest = linear_blend_skinning(c.surface.positions, c.weights, c.clip.skinning[0]);
  for (size_t i = 0; i < rest.size(); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(rest(i, k), c.surface.positions(i, k), 1e-6);
}

TEST(CharacterRead, BadFilesNameTheFileAndTheItem) {
  const auto message = [](const std::string& file, CharacterReadOptions options = {}) {
    return error_of([&] { read_character(kData + file, options); });
  };
  std::string e = message("no_skin.gltf");
  EXPECT_NE(e.find(kData + "no_skin.gltf"), std::string::npos) << e;
  EXPECT_NE(e.find("no skinned mesh"), std::string::npos) << e;
  e = message("no_animation.gltf");
  EXPECT_NE(e.find(kData + "no_animation.gltf"), std::string::npos) << e;
  EXPECT_NE(e.find("no animation"), std::string::npos) << e;
  CharacterReadOptions without;
  without.require_clip = false;
  EXPECT_FALSE(read_character(kData + "no_animation.gltf", without).has_clip);
  CharacterReadOptions unknown;
  unknown.clip = "wave";
  e = error_of([&] { read_character(kArm, unknown); });
  EXPECT_NE(e.find(kArm), std::string::npos) << e;
  EXPECT_NE(e.find("no animation clip named 'wave'"), std::string::npos) << e;
  EXPECT_NE(e.find("'bend'"), std::string::npos) << e;
  e = message("nan_key.gltf");
  EXPECT_NE(e.find(kData + "nan_key.gltf"), std::string::npos) << e;
  EXPECT_NE(e.find("node 'elbow': rotation key 1 is not finite"), std::string::npos) << e;
  CharacterReadOptions strict;
  strict.weights = WeightPolicy::strict;
  e = message("bad_weights.gltf", strict);
  EXPECT_NE(e.find(kData + "bad_weights.gltf"), std::string::npos) << e;
  EXPECT_NE(e.find("vertex 7"), std::string::npos) << e;
  EXPECT_NE(e.find("sum to 0.5"), std::string::npos) << e;
  CharacterReadOptions normalize;
  normalize.weights = WeightPolicy::normalize;
  const Character c = read_character(kData + "bad_weights.gltf", normalize);
  double sum = 0.0;
  for (int32_t k = c.weights.offset[7]; k < c.weights.offset[8]; ++k) sum += c.weights.weight[k];
  EXPECT_NEAR(sum, 1.0, 1e-12);
  CharacterReadOptions range;
  range.last_frame = 31;
  e = error_of([&] { read_character(kArm, range); });
  EXPECT_NE(e.find("frames 0..31 are outside the clip's frames 0..30"), std::string::npos) << e;
  e = error_of([&] { read_character(kData + "missing.gltf"); });
  EXPECT_NE(e.find(kData + "missing.gltf"), std::string::npos) << e;
}

TEST(CharacterBones, CapsulesRunJointToChildWithARadiusFromTheSkin) {
  const Character c = read_character(kArm);
  // The wrist is a leaf: by default its segment continues the elbow's
  // direction three quarters of the way to the farthest skin it weighs
  // most (the cap at x = 0.4), trimmed like the others; without
  // leaf_from_skin it gets no bone.
  CharacterBoneOptions no_leaves;
  no_leaves.leaf_from_skin = false;
  CharacterBones b = character_bones(c);
  ASSERT_EQ(b.bones.size(), 3u);
  EXPECT_EQ(b.bones[2].name, "wrist");
  const Capsule& wrist = std::get<Capsule>(b.bones[2].shape);
  EXPECT_GT(wrist.a[0], 0.35);
  EXPECT_LT(wrist.b[0], 0.35 + 0.75 * 0.05 + 1e-6);
  EXPECT_NEAR(wrist.a[1], 0.0, 1e-7);
  EXPECT_GT(wrist.radius, 0.0);
  b = character_bones(c, no_leaves);
  ASSERT_EQ(b.bones.size(), 2u);
  EXPECT_EQ(b.bones[0].name, "shoulder");
  EXPECT_EQ(b.bones[1].name, "elbow");
  // Half the distance to the 16-sided tube's facets: R cos(pi / 16); the
  // axis trimmed at both ends by 0.1 of the segment's 0.15 m plus the radius.
  const double facet = 0.05 * std::cos(M_PI / 16), r = 0.5 * facet, trim = 0.015 + r;
  const Capsule& shoulder = std::get<Capsule>(b.bones[0].shape);
  EXPECT_NEAR(shoulder.radius, r, 1e-6);
  EXPECT_NEAR(shoulder.a[0], 0.05 + trim, 1e-6);
  EXPECT_NEAR(shoulder.b[0], 0.2 - trim, 1e-6);
  EXPECT_NEAR(shoulder.a[1], 0.0, 1e-7);
  CharacterBoneOptions joint_to_joint;
  joint_to_joint.joint_clearance = -1;
  const CharacterBones full = character_bones(c, joint_to_joint);
  const Capsule& elbow = std::get<Capsule>(full.bones[1].shape);
  EXPECT_NEAR(elbow.a[0], 0.2, 1e-7);
  EXPECT_NEAR(elbow.b[0], 0.35, 1e-7);
  EXPECT_NEAR(elbow.radius, r, 1e-6);
  // The animation: each bone's skinning matrix per frame.
  ASSERT_EQ(b.animation.frame_count(), 31u);
  ASSERT_EQ(b.animation.bones, (std::vector<std::string>{"shoulder", "elbow"}));
  expect_matrix(b.animation.transforms[30][1], c.clip.skinning[30][1], "elbow at 1 s");

  CharacterBoneOptions options;
  options.radius_fraction = 0.25;
  options.leaf_from_skin = false;
  options.exclude = {"sh*"};
  options.radius["elbow"] = 0.01;
  b = character_bones(c, options);
  ASSERT_EQ(b.bones.size(), 1u);
  EXPECT_EQ(b.bones[0].name, "elbow");
  EXPECT_DOUBLE_EQ(std::get<Capsule>(b.bones[0].shape).radius, 0.01);
  options.exclude.clear();
  options.radius.clear();
  b = character_bones(c, options);
  EXPECT_NEAR(std::get<Capsule>(b.bones[0].shape).radius, 0.25 * facet, 1e-6);

  CharacterBoneOptions bad;
  bad.exclude = {"finger*"};
  EXPECT_NE(error_of([&] { character_bones(c, bad); }).find("'finger*' matches no joint"), std::string::npos);
  bad = {};
  bad.radius["knee"] = 0.1;
  EXPECT_NE(error_of([&] { character_bones(c, bad); }).find("no joint named 'knee'"), std::string::npos);
  // The wrist's segment would leave the tube through its cap: left out, or
  // given touching_radius, with one warning naming it.
  CharacterBoneOptions leaf;
  leaf.leaf_fraction = 0.5;
  b = character_bones(c, leaf);
  ASSERT_EQ(b.bones.size(), 2u);
  ASSERT_EQ(b.warnings.size(), 1u);
  EXPECT_NE(b.warnings[0].find("'wrist'"), std::string::npos) << b.warnings[0];
  EXPECT_NE(b.warnings[0].find("left out"), std::string::npos) << b.warnings[0];
  leaf.touching_radius = 0.01;
  b = character_bones(c, leaf);
  ASSERT_EQ(b.bones.size(), 3u);
  EXPECT_EQ(b.bones[2].name, "wrist");
  EXPECT_DOUBLE_EQ(std::get<Capsule>(b.bones[2].shape).radius, 0.01);
  EXPECT_NE(b.warnings.at(0).find("given the radius 0.01"), std::string::npos) << b.warnings[0];
  bad = {};
  bad.exclude = {"*"};
  EXPECT_NE(error_of([&] { character_bones(c, bad); }).find("no bone left"), std::string::npos);
}

TEST(CharacterRig, LatticeEmbeddingAndWeightsCoverTheSurfaceInFileOrder) {
  const Character c = read_character(kArm);
  const CharacterRig rig = prepare_character(c, 0.025);
  ASSERT_EQ(rig.embedding.element.size(), c.surface.vertex_count());
  const Points x = embedded_positions(rig.embedding, rig.voxels.lattice, rig.voxels.lattice.positions);
  for (size_t i = 0; i < x.size(); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(x(i, k), c.surface.positions(i, k), 1e-9);
  ASSERT_EQ(rig.constraints.size(), 3u);
  EXPECT_EQ(rig.constraints[0].name, "shoulder");
  EXPECT_EQ(rig.constraints[2].name, "wrist");
  EXPECT_FALSE(rig.constraints[1].vertices.empty());
  EXPECT_FALSE(rig.constraints[2].vertices.empty());
  ASSERT_EQ(rig.lattice_weights.vertex_count(), rig.voxels.lattice.vertex_count());
  for (size_t v = 0; v < rig.lattice_weights.vertex_count(); ++v) {
    double sum = 0.0;
    for (int32_t k = rig.lattice_weights.offset[v]; k < rig.lattice_weights.offset[v + 1]; ++k)
      sum += rig.lattice_weights.weight[k];
    EXPECT_NEAR(sum, 1.0, 1e-12);
  }
}

TEST(CharacterSurface, PlyKeepsTheFileVertexOrder) {
  const Character c = read_character(kArm);
  const fs::path dir = fresh_dir("snh_character_ply");
  Points moved = c.surface.positions;
  for (size_t i = 0; i < moved.size(); ++i) moved(i, 0) += 1.0;
  write_surface_ply((dir / "arm.ply").string(), c.surface, moved);
  const TriangleSurface back = read_surface((dir / "arm.ply").string());
  ASSERT_EQ(back.vertex_count(), 359u);
  EXPECT_EQ(back.triangles, c.surface.triangles);
  for (size_t i = 0; i < moved.size(); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(back.positions(i, k), moved(i, k), 1e-6);
  EXPECT_NE(error_of([&] {
              write_surface_ply((dir / "x.ply").string(), c.surface, Points{Vec3{1, 2, 3}});
            }).find("x.ply"),
            std::string::npos);
  fs::remove_all(dir);
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(PointCache, Pc2AndMddByteLayoutAndRoundTrip) {
  const fs::path dir = fresh_dir("snh_point_cache");
  PointCache cache;
  cache.point_count = 2;
  cache.start_frame = 5;
  cache.sample_rate = 1;
  cache.samples = {{1, 2, 3, 4, 5, 6}, {-1, 0.5f, 0.25f, 1e-3f, 7, 8}};
  cache.times = {5.0 / 24, 6.0 / 24};
  const std::string pc2 = (dir / "a.pc2").string(), mdd = (dir / "a.mdd").string();
  write_pc2(pc2, cache);
  write_mdd(mdd, cache);
  const std::string p = file_bytes(pc2);
  ASSERT_EQ(p.size(), 32u + 2 * 2 * 12);
  EXPECT_EQ(std::memcmp(p.data(), "POINTCACHE2\0", 12), 0);
  const auto le32 = [&](const std::string& b, size_t at) {
    uint32_t u = 0;
    for (int i = 0; i < 4; ++i) u |= uint32_t(static_cast<unsigned char>(b[at + i])) << (8 * i);
    return u;
  };
  const auto be32 = [&](const std::string& b, size_t at) {
    uint32_t u = 0;
    for (int i = 0; i < 4; ++i) u |= uint32_t(static_cast<unsigned char>(b[at + i])) << (8 * (3 - i));
    return u;
  };
  const auto as_float = [](uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
  };
  EXPECT_EQ(le32(p, 12), 1u);  // version
  EXPECT_EQ(le32(p, 16), 2u);  // points
  EXPECT_EQ(as_float(le32(p, 20)), 5.0f);
  EXPECT_EQ(as_float(le32(p, 24)), 1.0f);
  EXPECT_EQ(le32(p, 28), 2u);  // samples
  EXPECT_EQ(as_float(le32(p, 32)), 1.0f);
  EXPECT_EQ(as_float(le32(p, 32 + 4 * 6)), -1.0f);  // the second sample's first x
  const std::string m = file_bytes(mdd);
  ASSERT_EQ(m.size(), 8u + 2 * 4 + 2 * 2 * 12);
  EXPECT_EQ(be32(m, 0), 2u);  // frames
  EXPECT_EQ(be32(m, 4), 2u);  // points
  EXPECT_EQ(as_float(be32(m, 8)), static_cast<float>(5.0 / 24));
  EXPECT_EQ(as_float(be32(m, 16)), 1.0f);
  EXPECT_EQ(as_float(be32(m, 16 + 4 * 7)), 0.5f);

  for (const PointCache& back : {read_pc2(pc2), read_mdd(mdd)}) {
    EXPECT_EQ(back.point_count, 2u);
    EXPECT_EQ(back.samples, cache.samples);
  }
  EXPECT_EQ(read_pc2(pc2).start_frame, 5.0);
  EXPECT_FLOAT_EQ(static_cast<float>(read_mdd(mdd).times[1]), static_cast<float>(6.0 / 24));

  // Damaged and wrong-sized caches are refused, naming the file.
  std::ofstream(dir / "short.pc2", std::ios::binary).write(p.data(), 40);
  EXPECT_NE(error_of([&] { read_pc2((dir / "short.pc2").string()); }).find("short.pc2"), std::string::npos);
  EXPECT_NE(error_of([&] { read_mdd(pc2); }).find("a.pc2"), std::string::npos);
  PointCache wrong = cache;
  wrong.samples[1].pop_back();
  EXPECT_NE(error_of([&] { write_pc2(pc2, wrong); }).find("sample 1 has 5 coordinates"), std::string::npos);
  EXPECT_NE(error_of([&] { write_point_cache((dir / "a.abc").string(), cache); }).find(".pc2 or .mdd"),
            std::string::npos);
  fs::remove_all(dir);
}

std::string run_cli(const std::string& arguments, int& status) {
  std::string out;
  FILE* pipe = popen((std::string(SNH_CLI_BINARY) + " " + arguments + " 2>&1").c_str(), "r");
  if (!pipe) return out;
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
  const int s = pclose(pipe);
  status = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
  return out;
}

TEST(CharacterScene, ArmExampleRunsEndToEndAndCachesTheSurface) {
  const fs::path dir = fresh_dir("snh_character_arm");
  const std::string scene = std::string(SNH_SOURCE_DIR) + "/examples/character/arm.json";
  int status = -1;
  const std::string out = run_cli(
      "run " + scene + " --quiet --json " + (dir / "arm.json").string() + " --surface " + (dir / "obj/").string(),
      status);
  ASSERT_EQ(status, 0) << out;
  // The caches land in the working directory's paths the scene names.
  for (const char* f : {"arm.pc2", "arm.mdd", "arm_lbs.pc2"}) {
    ASSERT_TRUE(fs::exists(f)) << f;
    fs::rename(f, dir / f);
  }
  const PointCache simulated = read_pc2((dir / "arm.pc2").string());
  const PointCache skinned = read_pc2((dir / "arm_lbs.pc2").string());
  const PointCache mdd = read_mdd((dir / "arm.mdd").string());
  EXPECT_EQ(simulated.point_count, 359u);
  ASSERT_EQ(simulated.samples.size(), 11u);
  EXPECT_EQ(mdd.samples, simulated.samples);
  EXPECT_FLOAT_EQ(static_cast<float>(mdd.times[10]), 1.0f);
  for (const auto& sample : simulated.samples)
    for (float v : sample) ASSERT_TRUE(std::isfinite(v));
  // The tip's centre (vertex 358) starts at (0.4, 0, 0) and is carried by
  // the bent forearm towards the skinned (0.2, 0.2, 0).
  const auto& first = simulated.samples.front();
  const auto& last = simulated.samples.back();
  EXPECT_NEAR(first[3 * 358], 0.4, 1e-3);
  EXPECT_NEAR(skinned.samples.back()[3 * 358], 0.2, 1e-5);
  EXPECT_NEAR(skinned.samples.back()[3 * 358 + 1], 0.2, 1e-5);
  EXPECT_NEAR(last[3 * 358], 0.2, 0.03);
  EXPECT_NEAR(last[3 * 358 + 1], 0.2, 0.03);
  // Per frame, the distance from the skinned surface in the JSON summary.
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir / "arm.json"));
  ASSERT_EQ(j["frames"].size(), 11u);
  EXPECT_EQ(j["frames"][0]["frame"], 0);
  EXPECT_LT(j["frames"][0]["lbs_max_distance"].get<double>(), 1e-3);
  EXPECT_GT(j["frames"][10]["lbs_max_distance"].get<double>(), 0.0);
  EXPECT_TRUE(fs::exists(dir / "obj" / "character_arm_0010.obj"));
  fs::remove_all(dir);
}

TEST(CharacterScene, SkinnedGuessReachesTheSameFrames) {
  CharacterReadOptions read;
  read.fps = 10;
  read.last_frame = 3;
  const Character c = read_character(kArm, read);
  const CharacterRig rig = prepare_character(c, 0.025);
  const Material material = Material::from_youngs_modulus(MaterialModel::stable_neo_hookean, 2e4, 0.45);
  std::vector<Points> surfaces[2];
  for (int guess = 0; guess < 2; ++guess) {
    Simulation sim(rig.voxels.lattice, material, rig.constraints);
    CharacterFrameOptions options;
    options.skinned_guess = guess == 1;
    const auto frames = run_character_frames(
        sim, c, rig, options, [&](const CharacterFrame&, const Points&, const Points& surface, const Points&) {
          surfaces[guess].push_back(surface);
          return true;
        });
    ASSERT_EQ(frames.size(), 4u);
    for (const CharacterFrame& f : frames) EXPECT_TRUE(f.record.converged) << "frame " << f.record.frame;
    EXPECT_EQ(frames[3].record.frame, 3);
  }
  for (size_t f = 0; f < 4; ++f)
    for (size_t i = 0; i < surfaces[0][f].size(); ++i)
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(surfaces[0][f](i, k), surfaces[1][f](i, k), 1e-4);
}

TEST(CharacterScene, SectionKeysAndConflictsAreChecked) {
  const fs::path dir = fresh_dir("snh_character_scene");
  fs::copy_file(kArm, dir / "arm.gltf");
  const auto write = [&](const std::string& text) {
    std::ofstream(dir / "s.json") << text;
    return (dir / "s.json").string();
  };
  const std::string base = R"("character": {"file": "arm.gltf", "fps": 10, "frames": [0, 2], "cell": 0.025,
                                               "bones": {"radius": {"elbow": 0.02}}})";
  const SceneFile f = load_scene(write("{" + base + "}"));
  ASSERT_TRUE(f.character && f.rig && f.embedded);
  EXPECT_EQ(f.rig->animation.frame_count(), 3u);
  EXPECT_EQ(f.embedded->surface.vertex_count(), 359u);
  EXPECT_DOUBLE_EQ(std::get<Capsule>(f.rig->bones[1].shape).radius, 0.02);
  EXPECT_EQ(f.scene.constraints.size(), 3u);  // shoulder, elbow and the wrist (a leaf, from the skin)
  std::string e = error_of([&] { load_scene(write("{" + base + R"(, "mesh": {"cells": [1, 1, 1]}})")); });
  EXPECT_NE(e.find("s.json: character: replaces"), std::string::npos) << e;
  e = error_of([&] { load_scene(write(R"({"mesh": {"cells": [1, 1, 1]}, "output": {"pc2": "a.pc2"}})")); });
  EXPECT_NE(e.find("output.pc2: needs \"character\""), std::string::npos) << e;
  e = error_of([&] { load_scene(write(R"({"character": {"file": "arm.gltf", "cell": 0.025, "clip": "wave"}})")); });
  EXPECT_NE(e.find("character.file"), std::string::npos) << e;
  EXPECT_NE(e.find("'bend'"), std::string::npos) << e;
  e = error_of([&] { load_scene(write(R"({"character": {"file": "arm.gltf", "cell": 0.025, "colour": 1}})")); });
  EXPECT_NE(e.find("character.colour: unknown key"), std::string::npos) << e;
  e = error_of([&] { load_scene(write(R"({"character": {"file": "arm.gltf", "frames": [3, 1], "cell": 0.025}})")); });
  EXPECT_NE(e.find("character.frames"), std::string::npos) << e;
  e = error_of([&] { load_scene(write(R"({"character": {"file": "arm.gltf"}})")); });
  EXPECT_NE(e.find("character.cell: missing"), std::string::npos) << e;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace snh::test
