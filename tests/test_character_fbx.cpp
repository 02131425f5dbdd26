// FBX characters read through ufbx (host/character/fbx_reader.h) against
// what Blender 3.4 reads from the same file: bend.fbx, a tube skinned to 3
// bones and bent over 10 frames, made and exported by Blender
// (tests/data/character/make_fbx.py, which also wrote bend.json from
// Blender's own FBX import: vertices, raw weights and the armature-deformed
// mesh at a few frames, in the mesh object's local space).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "character/fbx_reader.h"
#include "snh/character.h"
#include "snh/error.h"
#include "support/errors.h"

namespace snh::test {
namespace {

const std::string kData = std::string(SNH_SOURCE_DIR) + "/tests/data/character/";
const std::string kBend = kData + "bend.fbx";

const nlohmann::json& blender() {
  static const nlohmann::json doc = nlohmann::json::parse(std::ifstream(kData + "bend.json"));
  return doc;
}

CharacterReadOptions at_blender_fps() {
  CharacterReadOptions options;
  options.fps = blender()["fps"].get<double>();
  return options;
}

int joint_named(const Character& c, const std::string& name) {
  for (size_t j = 0; j < c.joints.size(); ++j)
    if (c.joints[j].name == name) return static_cast<int>(j);
  return -1;
}

bool is_identity(const Matrix4& m, double tolerance) {
  for (int k = 0; k < 16; ++k)
    if (std::abs(m[k] - (k % 5 == 0 ? 1.0 : 0.0)) > tolerance) return false;
  return true;
}

TEST(CharacterFbx, SurfaceIsTheControlPointsAsBlenderImportsThem) {
  const Character c = read_character(kBend, at_blender_fps());
  const nlohmann::json& ref = blender();
  // Control points, not polygon corners: 20 rings of 16 and a loose vertex
  // (assimp 5.2 gives one vertex per corner, 1248 here, and drops the loose
  // one).
  ASSERT_EQ(c.surface.vertex_count(), ref["vertex_count"].get<size_t>());
  ASSERT_EQ(c.surface.vertex_count(), 321u);
  double worst = 0.0;
  for (size_t v = 0; v < c.surface.vertex_count(); ++v)
    for (int d = 0; d < 3; ++d) {
      const double expected = ref["positions"][v][d].get<double>();
      EXPECT_NEAR(c.surface.positions(v, d), expected, 1e-6 * (1.0 + std::abs(expected)))
          << "vertex " << v << " axis " << d;
      worst = std::max(worst, std::abs(c.surface.positions(v, d) - expected));
    }
  EXPECT_LT(worst, 1e-6);
  // 19 x 16 quads and two 16-sided caps, triangulated; every index a
  // control point, the loose one in no triangle.
  EXPECT_EQ(c.surface.triangle_count(), 19u * 16u * 2u + 2u * 14u);
  const size_t loose = ref["loose_vertex"].get<size_t>();
  for (int32_t i : c.surface.triangles) {
    ASSERT_GE(i, 0);
    ASSERT_LT(static_cast<size_t>(i), c.surface.vertex_count());
    EXPECT_NE(static_cast<size_t>(i), loose);
  }
  // Distinct control points: the weld keeps every vertex.
  EXPECT_EQ(c.welded.vertex_count(), c.surface.vertex_count());
  EXPECT_EQ(c.welded.triangle_count(), c.surface.triangle_count());
}

TEST(CharacterFbx, JointsAndRawWeightsAreTheFileClusters) {
  const Character c = detail::read_fbx_character(kBend, at_blender_fps());
  const nlohmann::json& ref = blender();
  ASSERT_EQ(c.joints.size(), 3u);
  EXPECT_EQ(c.joints[0].name, "root");
  EXPECT_EQ(c.joints[1].name, "mid");
  EXPECT_EQ(c.joints[2].name, "tip");
  EXPECT_EQ(c.joints[0].parent, -1);
  EXPECT_EQ(c.joints[1].parent, 0);
  EXPECT_EQ(c.joints[2].parent, 1);
  // The bones run up the tube's axis, 1 apart, in the mesh's own space (the
  // mesh object sits 0.05, -0.02, 0 from the armature, turned 30 degrees).
  for (size_t j = 0; j < 3; ++j) {
    const std::array<double, 3>& p = c.joints[j].rest_position;
    EXPECT_NEAR(p[2], double(j), 1e-5) << c.joints[j].name;
    EXPECT_NEAR(std::hypot(p[0], p[1]), std::hypot(0.05, 0.02), 1e-5) << c.joints[j].name;
  }
  EXPECT_TRUE(c.welded_index.empty());
  EXPECT_TRUE(c.warnings.empty()) << c.warnings.front();
  // Weights as the file stores them (Blender's vertex groups after import):
  // not normalized, rows sorted by joint.
  ASSERT_EQ(c.weights.vertex_count(), c.surface.vertex_count());
  double smallest_sum = 2.0;
  for (size_t v = 0; v < c.weights.vertex_count(); ++v) {
    const nlohmann::json& groups = ref["weights"][v];
    ASSERT_EQ(static_cast<size_t>(c.weights.offset[v + 1] - c.weights.offset[v]), groups.size()) << "vertex " << v;
    double sum = 0.0;
    for (int32_t k = c.weights.offset[v]; k < c.weights.offset[v + 1]; ++k) {
      if (k > c.weights.offset[v]) {
        EXPECT_LT(c.weights.joint[k - 1], c.weights.joint[k]) << "vertex " << v;
      }
      const std::string& name = c.joints[c.weights.joint[k]].name;
      ASSERT_TRUE(groups.contains(name)) << "vertex " << v << " joint " << name;
      EXPECT_NEAR(c.weights.weight[k], groups[name].get<double>(), 1e-7) << "vertex " << v << " joint " << name;
      sum += c.weights.weight[k];
    }
    smallest_sum = std::min(smallest_sum, sum);
  }
  EXPECT_NEAR(smallest_sum, 0.5, 1e-7);  // the loose vertex: 0.5 to 'mid' alone
  const size_t loose = ref["loose_vertex"].get<size_t>();
  ASSERT_EQ(c.weights.offset[loose + 1] - c.weights.offset[loose], 1);
  EXPECT_EQ(c.weights.joint[c.weights.offset[loose]], 1);
  // read_character normalizes them.
  const Character n = read_character(kBend, at_blender_fps());
  for (size_t v = 0; v < n.weights.vertex_count(); ++v) {
    double sum = 0.0;
    for (int32_t k = n.weights.offset[v]; k < n.weights.offset[v + 1]; ++k) sum += n.weights.weight[k];
    EXPECT_NEAR(sum, 1.0, 1e-12) << "vertex " << v;
  }
}

TEST(CharacterFbx, LinearBlendSkinningMatchesBlendersArmatureDeform) {
  const Character c = read_character(kBend, at_blender_fps());
  const nlohmann::json& ref = blender();
  ASSERT_TRUE(c.has_clip);
  ASSERT_EQ(c.clip_names.size(), 1u);
  EXPECT_EQ(c.clip.name, c.clip_names[0]);
  // 11 frames at the file's 24 fps: 0..10.
  ASSERT_EQ(c.clip.frame_count(), 11u);
  EXPECT_NEAR(c.clip.times.back(), 10.0 / 24.0, 1e-12);
  for (const Matrix4& m : c.clip.skinning[0]) EXPECT_TRUE(is_identity(m, 1e-6));  // the bind pose
  double scale = 0.0;
  for (double x : c.surface.positions.xyz()) scale = std::max(scale, std::abs(x));
  for (const nlohmann::json& frame : ref["frames"]) {
    const int f = frame["frame"].get<int>();
    ASSERT_LT(static_cast<size_t>(f), c.clip.frame_count());
    const Points x = linear_blend_skinning(c.surface.positions, c.weights, c.clip.skinning[f]);
    double worst = 0.0, moved = 0.0;
    for (size_t v = 0; v < c.surface.vertex_count(); ++v)
      for (int d = 0; d < 3; ++d) {
        worst = std::max(worst, std::abs(x(v, d) - frame["positions"][v][d].get<double>()));
        moved = std::max(moved, std::abs(x(v, d) - c.surface.positions(v, d)));
      }
    EXPECT_LT(worst, 1e-4 * scale) << "frame " << f;
    if (f >= 3) {
      EXPECT_GT(moved, 0.05 * scale) << "frame " << f << " should bend the tube";
    }
  }
}

TEST(CharacterFbx, ClipSelectionAndFrameRangeFollowTheOtherFormats) {
  CharacterReadOptions options = at_blender_fps();
  options.first_frame = 2;
  options.last_frame = 6;
  const Character part = read_character(kBend, options);
  const Character all = read_character(kBend, at_blender_fps());
  ASSERT_EQ(part.clip.frame_count(), 5u);
  EXPECT_EQ(part.clip.first_frame, 2);
  EXPECT_NEAR(part.clip.times[0], 2.0 / 24.0, 1e-12);
  for (size_t j = 0; j < part.joints.size(); ++j)
    for (int k = 0; k < 16; ++k) EXPECT_NEAR(part.clip.skinning[0][j][k], all.clip.skinning[2][j][k], 1e-12);
  options = at_blender_fps();
  options.last_frame = 11;
  std::string e = error_of([&] { read_character(kBend, options); });
  EXPECT_NE(e.find(kBend), std::string::npos) << e;
  EXPECT_NE(e.find("frames 0..11 are outside the clip's frames 0..10 at 24 fps"), std::string::npos) << e;
  options = {};
  options.clip = "wave";
  e = error_of([&] { read_character(kBend, options); });
  EXPECT_NE(e.find("no animation clip named 'wave' (clips: 0 '" + all.clip_names[0] + "')"), std::string::npos) << e;
  options = {};
  options.clip_index = 1;
  e = error_of([&] { read_character(kBend, options); });
  EXPECT_NE(e.find("no animation clip 1"), std::string::npos) << e;
  options = at_blender_fps();
  options.clip = all.clip_names[0];
  EXPECT_EQ(read_character(kBend, options).clip.index, 0);
  e = error_of([&] { read_character(kData + "missing.FBX"); });
  EXPECT_NE(e.find(kData + "missing.FBX: cannot read the file (ufbx: "), std::string::npos) << e;
  // Strict weights name the vertex (the loose one sums to 0.5).
  options = at_blender_fps();
  options.weights = WeightPolicy::strict;
  options.weight_tolerance = 0.1;
  e = error_of([&] { read_character(kBend, options); });
  EXPECT_NE(e.find("vertex 320: its skin weights sum to 0.5"), std::string::npos) << e;
}

TEST(CharacterFbx, JointWithoutItsBoneNodeIsHeldAtTheBindPose) {
  // bend.fbx with the connection from bone 'tip' to its cluster pointed at
  // no object.
  const Character c = read_character(kData + "bend_missing_bone.fbx", at_blender_fps());
  const Character full = read_character(kBend, at_blender_fps());
  ASSERT_EQ(c.joints.size(), 3u);
  const int tip = joint_named(c, "tip");
  ASSERT_GE(tip, 0);
  EXPECT_EQ(c.joints[tip].parent, -1);
  // Besides the normalized loose vertex (bend.fbx's own), one warning names the joint.
  ASSERT_EQ(c.warnings.size(), full.warnings.size() + 1);
  EXPECT_NE(c.warnings[0].find("held at the bind pose: 'tip'"), std::string::npos) << c.warnings[0];
  ASSERT_EQ(c.clip.frame_count(), full.clip.frame_count());
  for (size_t f = 0; f < c.clip.frame_count(); ++f) {
    EXPECT_TRUE(is_identity(c.clip.skinning[f][tip], 0.0)) << "frame " << f;
    for (const char* name : {"root", "mid"}) {
      const int a = joint_named(c, name), b = joint_named(full, name);
      for (int k = 0; k < 16; ++k)
        EXPECT_NEAR(c.clip.skinning[f][a][k], full.clip.skinning[f][b][k], 1e-12) << name << " frame " << f;
    }
  }
  EXPECT_FALSE(is_identity(full.clip.skinning.back()[joint_named(full, "tip")], 1e-3));
  EXPECT_EQ(c.surface.positions, full.surface.positions);
  EXPECT_EQ(c.weights.weight, full.weights.weight);
}

}  // namespace
}  // namespace snh::test
