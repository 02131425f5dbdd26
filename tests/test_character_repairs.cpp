// Skinned files as artists hand them over (snh/character.h): weights that do
// not sum to 1 or are missing, skins wound inwards, open flaps and loose
// points, bones that touch the skin, geometry far from the flesh, and the
// scene file's "weights" and "resolution" keys. Each repair is warned of and
// its result checked; each defect class runs frames to the end.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
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

bool mentions(const std::vector<std::string>& lines, const std::string& text) {
  for (const std::string& l : lines)
    if (l.find(text) != std::string::npos) return true;
  return false;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += l + "\n";
  return s;
}

std::vector<std::pair<int32_t, double>> row(const SkinWeights& w, size_t v) {
  std::vector<std::pair<int32_t, double>> r;
  for (int32_t k = w.offset[v]; k < w.offset[v + 1]; ++k) r.push_back({w.joint[k], w.weight[k]});
  return r;
}

}  // namespace

TEST(CharacterRepairs, WeightsAreNormalizedByDefaultWithOneWarning) {
  const Character c = read_character(kData + "bad_weights.gltf");
  ASSERT_EQ(c.warnings.size(), 1u) << joined(c.warnings);
  EXPECT_NE(c.warnings[0].find("1 of 359 vertices"), std::string::npos) << c.warnings[0];
  EXPECT_NE(c.warnings[0].find("worst sum 0.5"), std::string::npos) << c.warnings[0];
  for (size_t v = 0; v < c.surface.vertex_count(); ++v) {
    double sum = 0.0;
    for (const auto& [j, w] : row(c.weights, v)) sum += w;
    ASSERT_NEAR(sum, 1.0, 1e-12) << "vertex " << v;
  }
  // The clean arm warns of nothing.
  EXPECT_TRUE(read_character(kArm).warnings.empty()) << joined(read_character(kArm).warnings);
}

TEST(CharacterRepairs, VerticesWithoutWeightsFollowTheirNearestWeightedVertex) {
  const Character c = read_character(kData + "unweighted.gltf");
  const Character arm = read_character(kArm);
  ASSERT_TRUE(mentions(c.warnings, "2 of 359 vertices have no weight")) << joined(c.warnings);
  for (size_t v : {5u, 40u}) {
    // The nearest other vertex with weights, found by brute force.
    size_t best = 0;
    double best_d = 1e300;
    for (size_t u = 0; u < c.surface.vertex_count(); ++u) {
      if (u == 5 || u == 40) continue;
      double d = 0.0;
      for (int k = 0; k < 3; ++k) d += std::pow(c.surface.positions(u, k) - c.surface.positions(v, k), 2);
      if (d < best_d) best_d = d, best = u;
    }
    EXPECT_EQ(row(c.weights, v), row(arm.weights, best)) << "vertex " << v << " should follow vertex " << best;
    EXPECT_FALSE(row(c.weights, v).empty());
  }
  CharacterReadOptions strict;
  strict.weights = WeightPolicy::strict;  // borrowing is no sum to refuse: strict reads it too
  EXPECT_EQ(row(read_character(kData + "unweighted.gltf", strict).weights, 5), row(c.weights, 5));
}

TEST(CharacterRepairs, InsideOutSkinVoxelizesLikeItsOutwardTwin) {
  const Character outward = read_character(kArm), inward = read_character(kData + "inside_out.gltf");
  const CharacterRig a = prepare_character(outward, 0.025), b = prepare_character(inward, 0.025);
  EXPECT_EQ(a.voxels.element_cell, b.voxels.element_cell);
  EXPECT_EQ(a.voxels.lattice.positions, b.voxels.lattice.positions);
  EXPECT_EQ(a.embedding.element, b.embedding.element);
  EXPECT_FALSE(mentions(a.warnings, "faces inwards")) << joined(a.warnings);
  ASSERT_TRUE(mentions(b.warnings, "faces inwards")) << joined(b.warnings);
  EXPECT_TRUE(mentions(b.warnings, "shell 0")) << joined(b.warnings);
  EXPECT_TRUE(mentions(b.warnings, inward.file)) << joined(b.warnings);
}

TEST(CharacterRepairs, ShellInsideAnotherFacingInwardsStaysACavity) {
  // A closed box with an inward-facing smaller box inside it: a hollow. The
  // inner shell is no inside-out skin and is kept as it is.
  const auto box = [](TriangleSurface& s, double lo, double hi, bool inward) {
    const int32_t base = static_cast<int32_t>(s.vertex_count());
    for (int k = 0; k < 8; ++k) s.positions.push_back({k & 1 ? hi : lo, k & 2 ? hi : lo, k & 4 ? hi : lo});
    const int32_t faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                  {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    for (const auto& f : faces) {
      s.triangles.insert(s.triangles.end(),
                         {base + f[0], base + (inward ? f[2] : f[1]), base + (inward ? f[1] : f[2])});
    }
  };
  TriangleSurface hollow;
  box(hollow, 0.0, 1.0, false);
  box(hollow, 0.3, 0.7, true);
  const Voxelization v = voxelize(hollow, 0.1);
  EXPECT_EQ(v.element_cell.size(), 1000u - 64u);
  EXPECT_FALSE(mentions(v.warnings, "faces inwards")) << joined(v.warnings);
  // Both wound inwards (a mirrored file): the outer one is the skin, turned
  // outwards with the inner one, which stays a cavity.
  TriangleSurface mirrored;
  box(mirrored, 0.0, 1.0, true);
  box(mirrored, 0.3, 0.7, false);
  const Voxelization m = voxelize(mirrored, 0.1);
  EXPECT_EQ(m.element_cell, v.element_cell);
  EXPECT_TRUE(mentions(m.warnings, "inside out or mirrored")) << joined(m.warnings);
}

TEST(CharacterRepairs, FlapAndLoosePointsAreCarriedToFirstOrder) {
  const Character c = read_character(kData + "flap.gltf");
  ASSERT_EQ(c.surface.vertex_count(), 365u);  // 359, the fin's 4 and 2 loose points
  const double cell = 0.025;
  const CharacterRig rig = prepare_character(c, cell);
  ASSERT_EQ(rig.embedding.element.size(), 365u);
  EXPECT_GE(rig.vertices_outside, 3);  // the fin's far edge and a loose point
  EXPECT_GT(rig.max_outside_distance, cell);
  EXPECT_LT(rig.max_outside_distance, 3 * cell);
  ASSERT_TRUE(mentions(rig.warnings, "lie more than a cell outside the lattice")) << joined(rig.warnings);
  // Weights sum to 1, and the rest and an affine map of the lattice are
  // reproduced exactly at every vertex, carried ones included.
  for (size_t v = 0; v < 365; ++v) {
    double sum = 0.0;
    for (int a = 0; a < 8; ++a) sum += rig.embedding.weights[8 * v + a];
    EXPECT_NEAR(sum, 1.0, 1e-12) << "vertex " << v;
  }
  Points x = rig.voxels.lattice.positions;
  const double angle = 0.7, cs = std::cos(angle), sn = std::sin(angle);
  for (size_t i = 0; i < x.size(); ++i) {
    const double px = x(i, 0), py = x(i, 1), pz = x(i, 2);
    x(i, 0) = cs * px - sn * py + 0.1;
    x(i, 1) = sn * px + cs * py - 0.2;
    x(i, 2) = 1.5 * pz;
  }
  const Points rest = embedded_positions(rig.embedding, rig.voxels.lattice, rig.voxels.lattice.positions);
  const Points moved = embedded_positions(rig.embedding, rig.voxels.lattice, x);
  for (size_t v = 0; v < 365; ++v) {
    const double* p = c.surface.positions.data() + 3 * v;
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(rest(v, d), p[d], 1e-12) << "vertex " << v;
    EXPECT_NEAR(moved(v, 0), cs * p[0] - sn * p[1] + 0.1, 1e-12) << "vertex " << v;
    EXPECT_NEAR(moved(v, 1), sn * p[0] + cs * p[1] - 0.2, 1e-12) << "vertex " << v;
    EXPECT_NEAR(moved(v, 2), 1.5 * p[2], 1e-12) << "vertex " << v;
  }
}

TEST(CharacterRepairs, GeometryFarFromTheFleshIsAnErrorNamingTheVertex) {
  Character c = read_character(kArm);
  const size_t v = c.surface.vertex_count();
  c.surface.positions.push_back({1.5, 0.0, 0.0});
  c.welded_index.push_back(static_cast<int32_t>(c.welded.vertex_count()));
  c.welded.positions.push_back({1.5, 0.0, 0.0});
  c.weights.joint.push_back(0);
  c.weights.weight.push_back(1.0);
  c.weights.offset.push_back(static_cast<int32_t>(c.weights.joint.size()));
  const std::string e = error_of([&] { prepare_character(c, 0.025); });
  EXPECT_NE(e.find(kArm), std::string::npos) << e;
  EXPECT_NE(e.find("surface vertex " + std::to_string(v)), std::string::npos) << e;
  EXPECT_NE(e.find("far from everything"), std::string::npos) << e;
}

TEST(CharacterRepairs, BoneTouchingTheSkinGetsAFloorRadiusOrIsLeftOut) {
  const Character c = read_character(kData + "tail.gltf");
  ASSERT_EQ(c.joints.size(), 4u);
  const double cell = 0.025;
  const CharacterRig rig = prepare_character(c, cell);
  // The wrist's segment runs to the tail joint past the tube's cap.
  ASSERT_TRUE(mentions(rig.warnings, "'wrist'")) << joined(rig.warnings);
  bool found = false;
  for (const Bone& b : rig.bones.bones)
    if (b.name == "wrist") {
      found = true;
      EXPECT_DOUBLE_EQ(std::get<Capsule>(b.shape).radius, 0.9 * cell);
    }
  EXPECT_TRUE(found);
  CharacterPrepareOptions out;
  out.touching_radius_cells = 0.0;
  const CharacterRig without = prepare_character(c, cell, out);
  for (const Bone& b : without.bones.bones) EXPECT_NE(b.name, "wrist");
  EXPECT_TRUE(mentions(without.warnings, "left out")) << joined(without.warnings);
  // bones.radius still decides.
  out.bones.radius["wrist"] = 0.02;
  const CharacterRig given = prepare_character(c, cell, out);
  EXPECT_FALSE(mentions(given.warnings, "'wrist'")) << joined(given.warnings);
}

TEST(CharacterRepairs, ResolutionChoosesTheCellAlongTheLongestSide) {
  const Character arm = read_character(kArm);
  // The file's float positions: the tube is 0.4f long.
  const double cell = character_cell(arm, 16);
  EXPECT_DOUBLE_EQ(cell, static_cast<double>(0.4f) / 16);
  EXPECT_NE(error_of([&] { character_cell(arm, 0); }).find("resolution must be >= 1"), std::string::npos);
  const fs::path dir = fresh_dir("snh_character_resolution");
  fs::copy_file(kArm, dir / "arm.gltf");
  fs::copy_file(kData + "bad_weights.gltf", dir / "bad_weights.gltf");
  const auto write = [&](const std::string& character) {
    const fs::path p = dir / "scene.json";
    std::ofstream(p) << R"({"material": {"E": 2e4, "nu": 0.45}, "character": )" << character << "}";
    return p.string();
  };
  const SceneFile by_resolution = load_scene(write(R"({"file": "arm.gltf", "fps": 10, "resolution": 16})"));
  std::ostringstream given;
  given.precision(17);
  given << R"({"file": "arm.gltf", "fps": 10, "cell": )" << cell << "}";
  const SceneFile by_cell = load_scene(write(given.str()));
  EXPECT_DOUBLE_EQ(by_resolution.character->rig.cell, cell);
  EXPECT_EQ(by_resolution.scene.mesh.positions, by_cell.scene.mesh.positions);
  const std::vector<std::string> report = scene_setup_report(by_resolution);
  EXPECT_TRUE(mentions(report, "cell 0.025 (16 cells along the longest side)")) << joined(report);
  EXPECT_TRUE(mentions(report, "bind pose 0.4 x 0.1 x 0.1")) << joined(report);
  std::string e = error_of([&] { load_scene(write(R"({"file": "arm.gltf", "cell": 0.025, "resolution": 16})")); });
  EXPECT_NE(e.find("not both"), std::string::npos) << e;
  e = error_of([&] { load_scene(write(R"({"file": "arm.gltf", "resolution": 0})")); });
  EXPECT_NE(e.find("character.resolution"), std::string::npos) << e;
  e = error_of([&] { load_scene(write(R"({"file": "arm.gltf"})")); });
  EXPECT_NE(e.find("character.cell"), std::string::npos) << e;
  // "weights": normalize by default (warned in the report), strict refuses.
  const SceneFile normalized = load_scene(write(R"({"file": "bad_weights.gltf", "resolution": 16})"));
  EXPECT_TRUE(mentions(scene_setup_report(normalized), "warning: skin weights: 1 of 359 vertices"));
  e = error_of([&] { load_scene(write(R"({"file": "bad_weights.gltf", "resolution": 16, "weights": "strict"})")); });
  EXPECT_NE(e.find("sum to 0.5"), std::string::npos) << e;
  e = error_of([&] { load_scene(write(R"({"file": "bad_weights.gltf", "resolution": 16, "weights": "loose"})")); });
  EXPECT_NE(e.find("character.weights"), std::string::npos) << e;
  fs::remove_all(dir);
}

// Each defect class runs frames to the end, converged and with no inverted
// element, and says what it repaired: the arm's variants (make_arm.py) and
// the creature as Blender's exporters write it (data/characters).
struct DefectCase {
  const char* file;     // under the source folder
  const char* lattice;  // the scene's "cell" or "resolution" entry
  int last_frame;
  const char* warning;
};

class CharacterDefectRuns : public ::testing::TestWithParam<DefectCase> {};

TEST_P(CharacterDefectRuns, RunToTheLastFrameWithTheirWarning) {
  const DefectCase& d = GetParam();
  const fs::path source = fs::path(SNH_SOURCE_DIR) / d.file;
  const std::string name = source.filename().string();
  const fs::path dir = fresh_dir("snh_character_defect_" + name);
  fs::copy_file(source, dir / name);
  const fs::path scene = dir / "scene.json";
  std::ofstream(scene) << R"({"material": {"E": 2e4, "nu": 0.45}, "character": {"file": ")" << name << R"(", "fps": )"
                       << (d.last_frame > 4 ? 24 : 10) << R"(, "frames": [0, )" << d.last_frame << "], " << d.lattice
                       << R"(}, "solver": {"steps": 1}})";
  const SceneFile f = load_scene(scene.string());
  std::vector<std::string> report = scene_setup_report(f);
  for (const std::string& w : f.character->rig.voxels.warnings) report.push_back("warning: " + w);
  EXPECT_TRUE(mentions(report, d.warning)) << joined(report);
  const SceneRun run = run_scene(f, f.scene.options);
  ASSERT_EQ(run.frames.size(), static_cast<size_t>(d.last_frame + 1));
  for (const FrameRecord& r : run.frames) {
    EXPECT_TRUE(r.converged) << name << " frame " << r.frame;
    EXPECT_EQ(r.inverted_elements, 0) << name << " frame " << r.frame;
    EXPECT_TRUE(r.warnings.empty()) << name << " frame " << r.frame << ": " << joined(r.warnings);
  }
  ASSERT_EQ(run.skin_deviation.size(), run.frames.size());
  EXPECT_LT(run.skin_deviation[0].max_distance, 1e-5) << name << ": frame 0 is the bind pose";
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(
    ArmDefects, CharacterDefectRuns,
    ::testing::Values(DefectCase{"tests/data/character/bad_weights.gltf", "\"cell\": 0.025", 4, "do not sum to 1"},
                      DefectCase{"tests/data/character/unweighted.gltf", "\"cell\": 0.025", 4, "have no weight"},
                      DefectCase{"tests/data/character/inside_out.gltf", "\"cell\": 0.025", 4, "faces inwards"},
                      DefectCase{"tests/data/character/flap.gltf", "\"cell\": 0.025", 4, "more than a cell outside"},
                      DefectCase{"tests/data/character/tail.gltf", "\"cell\": 0.025", 4, "touch or cross the skin"}));

INSTANTIATE_TEST_SUITE_P(
    BlenderExports, CharacterDefectRuns,
    ::testing::Values(
        DefectCase{"data/characters/inside_out.gltf", "\"resolution\": 25", 20, "faces inwards"},
        DefectCase{"data/characters/open_sheets.gltf", "\"resolution\": 25", 20, "more than a cell outside"},
        DefectCase{"data/characters/thin_tail.gltf", "\"resolution\": 25", 20, "touch or cross the skin"},
        DefectCase{"data/characters/unnormalized.gltf", "\"resolution\": 25", 20, "have no weight"},
        DefectCase{"data/characters/unnormalized.fbx", "\"resolution\": 25", 20, "do not sum to 1"},
        DefectCase{"data/characters/centimetres.fbx", "\"resolution\": 25", 20, "cell 6.02"},
        DefectCase{"data/characters/missing_joint.dae", "\"resolution\": 25", 20, "have no node in the hierarchy"}));

}  // namespace snh::test
