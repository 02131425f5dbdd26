// The rig (snh/rig.h, snh/animation.h, snh/frames.h): bones' inside tests
// and distances, and their vertex sets (first listed bone wins, so sets are disjoint),
// 4x4 matrices as transforms, animations in JSON and CSV with errors naming
// file, line and bone, and frames solved with rigid, scaling and
// intersecting bones.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <set>
#include <string>

#include "snh/animation.h"
#include "snh/error.h"
#include "snh/frames.h"
#include "snh/rig.h"
#include "snh/selection.h"
#include "snh/simulation.h"
#include "support/errors.h"
#include "voxel_test_support.h"

namespace snh {
namespace {

using test::contains;
using test::error_of;

// A closed box surface [lo, hi], 12 triangles with outward normals.
TriangleSurface box_surface(const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
  TriangleSurface s;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) s.positions.push_back({i ? hi[0] : lo[0], j ? hi[1] : lo[1], k ? hi[2] : lo[2]});
  // Corner index i + 2j + 4k; each face as two counter-clockwise triangles seen from outside.
  s.triangles = {0, 2, 3, 0, 3, 1,   // z-
                 4, 5, 7, 4, 7, 6,   // z+
                 0, 1, 5, 0, 5, 4,   // y-
                 2, 6, 7, 2, 7, 3,   // y+
                 0, 4, 6, 0, 6, 2,   // x-
                 1, 3, 7, 1, 7, 5};  // x+
  return s;
}

TEST(RigBones, CapsuleHoldsThePointsWithinItsRadiusOfTheSegment) {
  const Bone bone{"b", Capsule{{0, 0, 0}, {2, 0, 0}, 0.5}};
  EXPECT_TRUE(bone_contains(bone, {1.0, 0.0, 0.0}));
  EXPECT_TRUE(bone_contains(bone, {1.0, 0.5, 0.0}));     // on the side
  EXPECT_FALSE(bone_contains(bone, {1.0, 0.3, 0.41}));   // 0.51 from the axis
  EXPECT_TRUE(bone_contains(bone, {-0.3, 0.28, 0.28}));  // in the round cap (0.497 from a)
  EXPECT_FALSE(bone_contains(bone, {-0.3, 0.3, 0.3}));   // just outside it (0.520 from a)
  EXPECT_TRUE(bone_contains(bone, {2.49, 0.0, 0.0}));
  EXPECT_FALSE(bone_contains(bone, {2.51, 0.0, 0.0}));
}

TEST(RigBones, DistanceToACapsuleAndToASurfaceBone) {
  const Bone capsule{"c", Capsule{{0, 0, 0}, {2, 0, 0}, 0.5}};
  EXPECT_DOUBLE_EQ(bone_distance(capsule, {1.0, 0.2, 0.0}), 0.0);   // inside
  EXPECT_DOUBLE_EQ(bone_distance(capsule, {1.0, 0.0, 1.5}), 1.0);   // beside the straight part
  EXPECT_DOUBLE_EQ(bone_distance(capsule, {-3.0, 0.0, 0.0}), 2.5);  // beyond the round end at a
  const Bone box{"b", box_surface({0, 0, 0}, {1, 1, 1})};
  EXPECT_DOUBLE_EQ(bone_distance(box, {0.5, 0.5, 0.5}), 0.0);
  EXPECT_DOUBLE_EQ(bone_distance(box, {0.5, 0.25, 1.75}), 0.75);               // above a face
  EXPECT_NEAR(bone_distance(box, {2.0, 2.0, 0.5}), std::sqrt(2.0), 1e-15);     // off an edge
  EXPECT_NEAR(bone_distance(box, {-1.0, -1.0, -1.0}), std::sqrt(3.0), 1e-15);  // off a corner
}

TEST(RigBones, SurfaceBoneHoldsTheLatticeVerticesInsideIt) {
  const Mesh lattice = make_box_lattice(6, 4, 4, 0.25);
  const TriangleSurface surface = box_surface({0.3, 0.2, 0.1}, {1.2, 0.8, 0.6});
  const auto sets = bone_constraints(lattice, {Bone{"inner", surface}});
  ASSERT_EQ(sets.size(), 1u);
  EXPECT_EQ(sets[0].name, "inner");
  EXPECT_EQ(sets[0].vertices, vertices_in_box(lattice, {0.3, 0.2, 0.1}, {1.2, 0.8, 0.6}));
  EXPECT_FALSE(sets[0].motion);
  // A surface with inward normals (reversed triangles) holds the same points.
  TriangleSurface reversed = surface;
  for (size_t t = 0; t < reversed.triangle_count(); ++t)
    std::swap(reversed.triangles[3 * t + 1], reversed.triangles[3 * t + 2]);
  EXPECT_FALSE(bone_contains(Bone{"r", reversed}, {0.5, 0.5, 0.5}));  // w = -1: outside by the rule
  EXPECT_TRUE(bone_contains(Bone{"s", surface}, {0.5, 0.5, 0.5}));
  EXPECT_FALSE(bone_contains(Bone{"s", surface}, {1.5, 0.5, 0.5}));
}

TEST(RigBones, IntersectingBonesGiveDisjointSetsTheFirstListedWins) {
  const Mesh lattice = make_box_lattice(8, 4, 4, 0.25);
  const Bone upper{"upper", Capsule{{0.25, 0.5, 0.5}, {1.25, 0.5, 0.5}, 0.3}};
  const Bone lower{"lower", Capsule{{0.75, 0.5, 0.5}, {1.75, 0.5, 0.5}, 0.3}};  // overlaps [0.75, 1.25]
  const auto sets = bone_constraints(lattice, {upper, lower});
  ASSERT_EQ(sets.size(), 2u);
  std::set<int32_t> first(sets[0].vertices.begin(), sets[0].vertices.end());
  for (int32_t v : sets[1].vertices) EXPECT_FALSE(first.count(v)) << "vertex " << v << " in both sets";
  size_t shared = 0;
  for (size_t v = 0; v < lattice.vertex_count(); ++v) {
    const bool a = bone_contains(upper, lattice.vertex(v)), b = bone_contains(lower, lattice.vertex(v));
    EXPECT_EQ(first.count(static_cast<int32_t>(v)) == 1, a) << v;
    const bool in_second =
        std::binary_search(sets[1].vertices.begin(), sets[1].vertices.end(), static_cast<int32_t>(v));
    EXPECT_EQ(in_second, b && !a) << v;
    shared += a && b;
  }
  EXPECT_GT(shared, 0u);  // the bones do intersect on lattice vertices
  // Listed the other way round, the shared vertices go to "lower".
  const auto swapped = bone_constraints(lattice, {lower, upper});
  EXPECT_EQ(swapped[0].vertices.size(), sets[1].vertices.size() + shared);
}

TEST(RigBones, ErrorsNameTheBone) {
  const Mesh lattice = make_box_lattice(4, 2, 2, 0.25);
  const Bone good{"good", Capsule{{0.0, 0.25, 0.25}, {1.0, 0.25, 0.25}, 0.1}};
  EXPECT_TRUE(contains(error_of([&] {
                         bone_constraints(lattice, {good, Bone{"far", Capsule{{5, 5, 5}, {6, 5, 5}, 0.1}}});
                       }),
                       "bone 'far' holds no lattice vertex"));
  EXPECT_TRUE(contains(
      error_of([&] {
        bone_constraints(lattice, {good, Bone{"inside_good", Capsule{{0.5, 0.25, 0.25}, {0.5, 0.25, 0.25}, 0.05}}});
      }),
      "went to bone 'good'"));
  EXPECT_TRUE(contains(error_of([&] { bone_constraints(lattice, {good, good}); }), "'good' is named twice"));
  EXPECT_TRUE(contains(error_of([&] {
                         bone_constraints(lattice, {Bone{"thin", Capsule{{0, 0, 0}, {1, 0, 0}, 0.0}}});
                       }),
                       "'thin'"));
  EXPECT_TRUE(contains(error_of([&] {
                         bone_constraints(lattice, {Bone{"", Capsule{{0, 0, 0}, {1, 0, 0}, 0.1}}});
                       }),
                       "has no name"));
  EXPECT_TRUE(contains(error_of([&] { bone_constraints(lattice, {Bone{"hollow", TriangleSurface{}}}); }), "'hollow'"));
}

TEST(RigTransforms, Matrix4AsATransformAboutAnyCentreIsTheSameMap) {
  // A rotation with translation and a non-rigid (scaling, shearing) matrix.
  const double c = std::cos(0.7), s = std::sin(0.7);
  const std::vector<Matrix4> matrices = {{c, -s, 0, 0.3, s, c, 0, -1.0, 0, 0, 1, 2.0, 0, 0, 0, 1},
                                         {1.2, 0.1, 0, 0.3, 0, 0.9, 0.2, 0, 0, 0, 1.1, -0.5, 0, 0, 0, 1}};
  const std::vector<std::array<double, 3>> centres = {{0, 0, 0}, {1.5, -0.25, 3.0}};
  for (const Matrix4& m : matrices)
    for (const auto& centre : centres) {
      const RigidTransform t = to_rigid_transform(m, centre);
      EXPECT_EQ(t.center, centre);
      for (const std::array<double, 3> x : {std::array<double, 3>{0.1, 0.2, 0.3}, {-2.0, 1.0, 0.5}}) {
        const auto y = t.apply(x);
        for (int r = 0; r < 3; ++r)
          EXPECT_NEAR(y[r], m[4 * r] * x[0] + m[4 * r + 1] * x[1] + m[4 * r + 2] * x[2] + m[4 * r + 3], 1e-14);
      }
    }
  Matrix4 projective = identity_matrix4();
  projective[14] = 0.1;
  EXPECT_TRUE(contains(error_of([&] { to_rigid_transform(projective); }), "not 0 0 0 1"));
}

// Every public matrix is row-major, m[3 row + col]: a quarter turn about z
// takes x to y, so its first row is 0 -1 0; a Matrix4's upper-left 3x3 goes
// to the rotation as it is.
TEST(RigTransforms, RotationsAreRowMajor) {
  const RigidTransform t = RigidTransform::rotation_about({0, 0, 1}, 0.5 * M_PI, {0, 0, 0});
  const std::array<double, 9> expected{0, -1, 0, 1, 0, 0, 0, 0, 1};
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(t.rotation[i], expected[i], 1e-15) << i;
  const auto y = t.apply({1, 0, 0});
  EXPECT_NEAR(y[0], 0.0, 1e-15);
  EXPECT_NEAR(y[1], 1.0, 1e-15);
  const Matrix4 m{1, 2, 3, 0.5, 4, 5, 6, 0.25, 7, 8, 10, 0, 0, 0, 0, 1};
  EXPECT_EQ(to_rigid_transform(m).rotation, (std::array<double, 9>{1, 2, 3, 4, 5, 6, 7, 8, 10}));
}

// ---- Animations ----

Matrix4 rotation_y(double angle, const std::array<double, 3>& about) {
  const double c = std::cos(angle), s = std::sin(angle);
  // x' = R (x - p) + p with R about y.
  Matrix4 m{c, 0, s, 0, 0, 1, 0, 0, -s, 0, c, 0, 0, 0, 0, 1};
  for (int r = 0; r < 3; ++r)
    m[4 * r + 3] = about[r] - (m[4 * r] * about[0] + m[4 * r + 1] * about[1] + m[4 * r + 2] * about[2]);
  return m;
}

std::string matrix_json(const Matrix4& m) {
  std::ostringstream s;
  s.precision(17);
  s << "[";
  for (int r = 0; r < 4; ++r)
    s << (r ? ", [" : "[") << m[4 * r] << ", " << m[4 * r + 1] << ", " << m[4 * r + 2] << ", " << m[4 * r + 3] << "]";
  s << "]";
  return s.str();
}

std::string matrix_csv(const Matrix4& m) {
  std::ostringstream s;
  s.precision(17);
  for (int i = 0; i < 16; ++i) s << "," << m[i];
  return s.str();
}

TEST(RigAnimation, JsonAndCsvGiveTheSameFrames) {
  std::string json = "{\"frames\": [";
  std::string csv = "frame,bone,m00,m01,m02,m03,m10,m11,m12,m13,m20,m21,m22,m23,m30,m31,m32,m33\n# elbow flexion\n";
  for (int f = 0; f < 3; ++f) {
    const Matrix4 fore = rotation_y(-0.3 * f, {1.0, 0.5, 0.5});
    Matrix4 scale = identity_matrix4();
    scale[0] = 1.0 + 0.1 * f;
    json += std::string(f ? ", " : "") + "{\"time\": " + std::to_string(f) +
            ", \"bones\": {\"forearm\": " + matrix_json(fore) + ", \"upper\": " + matrix_json(scale) + "}}";
    // CSV lines in any order.
    csv += std::to_string(f) + ",upper" + matrix_csv(scale) + "\n\n";
    csv += std::to_string(f) + ", forearm " + matrix_csv(fore) + "\r\n";
  }
  json += "]}";
  const Animation a = parse_animation_json(json, "anim.json");
  const Animation b = parse_animation_csv(csv, "anim.csv");
  ASSERT_EQ(a.frame_count(), 3u);
  EXPECT_EQ(a.bones, (std::vector<std::string>{"forearm", "upper"}));
  EXPECT_EQ(b.bones, (std::vector<std::string>{"upper", "forearm"}));
  EXPECT_EQ(a.times, b.times);
  for (size_t f = 0; f < 3; ++f) {
    EXPECT_EQ(a.transforms[f][0], b.transforms[f][1]);
    EXPECT_EQ(a.transforms[f][1], b.transforms[f][0]);
  }
  EXPECT_DOUBLE_EQ(a.transforms[2][1][0], 1.2);
}

TEST(RigAnimation, ErrorsNameFileLineAndBone) {
  const std::string id = matrix_csv(identity_matrix4());
  EXPECT_TRUE(contains(error_of([&] { parse_animation_csv("0,arm" + id + "\n1,arm,1,0\n", "a.csv"); }),
                       "a.csv:2: expected 18"));
  EXPECT_TRUE(contains(error_of([&] { parse_animation_csv("0,arm,1,0,0,0,0,x,0,0,0,0,1,0,0,0,0,1\n", "a.csv"); }),
                       "a.csv:1: bone 'arm': m11 'x' is not a number"));
  EXPECT_TRUE(contains(error_of([&] { parse_animation_csv("0,arm,1,0,0,0,0,1,0,0,0,0,1,0,0,0,1,1\n", "a.csv"); }),
                       "a.csv:1: bone 'arm': the last row"));
  EXPECT_TRUE(contains(error_of([&] { parse_animation_csv("0,arm" + id + "\n0,arm" + id + "\n", "a.csv"); }),
                       "a.csv:2: bone 'arm' of frame 0 was given already on line 1"));
  EXPECT_TRUE(
      contains(error_of([&] { parse_animation_csv("0,arm" + id + "\n0,leg" + id + "\n1,arm" + id + "\n", "a.csv"); }),
               "frame 1 has no line for bone 'leg'"));
  EXPECT_TRUE(contains(error_of([&] { parse_animation_csv("0,arm" + id + "\n2,arm" + id + "\n", "a.csv"); }),
                       "frame 1 has no line for bone 'arm'"));
  EXPECT_TRUE(
      contains(error_of([&] { parse_animation_csv("-1,arm" + id + "\n", "a.csv"); }), "a.csv:1: the frame '-1'"));

  const std::string m = matrix_json(identity_matrix4());
  EXPECT_TRUE(contains(
      error_of([&] { parse_animation_json("{\"frames\": [{\"bones\": {\"arm\": [[1, 0], [0, 1]]}}]}", "a.json"); }),
      "a.json: frames[0].bones.arm: expected 4 rows of 4 numbers"));
  EXPECT_TRUE(contains(error_of([&] {
                         parse_animation_json("{\"frames\": [{\"bones\": {\"arm\": " + m + ", \"leg\": " + m +
                                                  "}}, {\"bones\": {\"arm\": " + m + "}}]}",
                                              "a.json");
                       }),
                       "a.json: frames[1].bones: bone 'leg' is missing"));
  EXPECT_TRUE(contains(error_of([&] {
                         parse_animation_json("{\"frames\": [{\"time\": 1, \"bones\": {\"arm\": " + m +
                                                  "}}, {\"time\": 1, \"bones\": {\"arm\": " + m + "}}]}",
                                              "a.json");
                       }),
                       "a.json: frames[1].time: frame times must increase"));
  EXPECT_TRUE(
      contains(error_of([&] {
                 parse_animation_json(
                     "{\"frames\": [{\"bones\": {\"arm\": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 1, 1]]}}]}",
                     "a.json");
               }),
               "a.json: frames[0].bones.arm: the last row"));
  EXPECT_TRUE(
      contains(error_of([&] { parse_animation_json("{\"frame\": []}", "a.json"); }), "a.json: frame: unknown key"));
  EXPECT_TRUE(contains(error_of([&] { parse_animation_json("{\"frames\": [", "a.json"); }), "a.json: not valid JSON"));

  const auto folder = std::filesystem::temp_directory_path() / "snh_rig_animation";
  std::filesystem::create_directories(folder);
  std::ofstream((folder / "anim.CSV").string()) << "0,arm" << id << "\n";
  EXPECT_EQ(read_animation((folder / "anim.CSV").string()).bones, std::vector<std::string>{"arm"});
  std::ofstream((folder / "anim.txt").string()) << "0,arm" << id << "\n";
  EXPECT_TRUE(contains(error_of([&] { read_animation((folder / "anim.txt").string()); }), "expected .json or .csv"));
  EXPECT_TRUE(contains(error_of([&] { read_animation((folder / "missing.json").string()); }), "cannot open"));
}

// ---- Frames ----

TEST(RigFrames, ScalingAndIntersectingBonesSolveAndHoldTheirTargets) {
  // A 2 x 0.5 x 0.5 bar; "upper" grows by 15% along x about its centre while
  // "forearm", which intersects it, bends 30 degrees about the joint.
  const Mesh lattice = make_box_lattice(8, 2, 2, 0.25);
  const Bone upper{"upper", Capsule{{0.25, 0.25, 0.25}, {1.0, 0.25, 0.25}, 0.1}};
  const Bone forearm{"forearm", Capsule{{0.75, 0.25, 0.25}, {1.75, 0.25, 0.25}, 0.1}};
  std::vector<ConstraintSet> sets = bone_constraints(lattice, {upper, forearm});
  Simulation sim(lattice, StableNeoHookean::from_youngs_modulus(1.0, 0.45), sets);
  Animation a;
  a.bones = {"upper", "forearm"};
  const std::array<double, 3> joint{1.0, 0.25, 0.25};
  for (int f = 0; f <= 3; ++f) {
    Matrix4 grow = identity_matrix4();
    grow[0] = 1.0 + 0.05 * f;
    grow[3] = -0.625 * 0.05 * f;  // about x = 0.625
    a.times.push_back(f);
    a.transforms.push_back({grow, rotation_y(-M_PI / 18 * f, joint)});
  }
  int called = 0;
  const auto records =
      run_frames(sim, a, nullptr, {2, false}, [&](const FrameRecord& r, const Points& x, const Points& s) {
        EXPECT_EQ(r.frame, called++);
        EXPECT_EQ(x.size(), lattice.vertex_count());
        EXPECT_TRUE(s.empty());
        return true;
      });
  ASSERT_EQ(records.size(), 4u);
  for (const FrameRecord& r : records) {
    EXPECT_TRUE(r.converged) << "frame " << r.frame << ": " << r.status;
    EXPECT_EQ(r.inverted_elements, 0) << "frame " << r.frame;
    // Each frame's solve carries its profile (frame 0, at rest, needs no CG).
    EXPECT_EQ(r.profile.products > 0.0, r.cg_iterations > 0) << "frame " << r.frame;
    EXPECT_NEAR(r.profile.total, r.seconds, std::max(0.002, 0.01 * r.seconds)) << "frame " << r.frame;
  }
  // Every bone vertex sits on its last transform.
  for (size_t b = 0; b < 2; ++b)
    for (int32_t v : sets[b].vertices) {
      const Matrix4& m = a.transforms.back()[b];
      const auto p = lattice.vertex(v);
      for (int r = 0; r < 3; ++r)
        EXPECT_NEAR(sim.positions()(v, r), m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3],
                    1e-12);
    }
  // An animated bone the simulation lacks is named before any solve.
  Animation stray = a;
  stray.bones[1] = "tail";
  EXPECT_TRUE(contains(error_of([&] { run_frames(sim, stray, nullptr); }), "bone 'tail'"));
}

TEST(RigFrames, EmbeddedSurfaceFollowsABentBone) {
  // Points embedded in a bar whose far half is a bone bent 60 degrees: a
  // point whose cell lies wholly in the bone moves exactly with it.
  const Voxelization v = test::box_voxelization(8, 2, 2, 0.25, {0, 0, 0});
  const std::array<double, 3> joint{1.0, 0.25, 0.25};
  const Bone upper{"upper", Capsule{{0.0, 0.25, 0.25}, {0.5, 0.25, 0.25}, 0.4}};
  const Bone forearm{"forearm", Capsule{{1.5, 0.25, 0.25}, {2.0, 0.25, 0.25}, 0.4}};  // every vertex with x >= 1.5
  Simulation sim(v.lattice, StableNeoHookean::from_youngs_modulus(1.0, 0.45),
                 bone_constraints(v.lattice, {upper, forearm}));
  TriangleSurface tip;
  tip.positions = {{1.9, 0.1, 0.4}, {0.3, 0.2, 0.1}};
  const Embedding e = embed(v, tip);
  Animation a;
  a.bones = {"forearm"};
  for (int f = 0; f <= 4; ++f) {
    a.times.push_back(f);
    a.transforms.push_back({rotation_y(-M_PI / 12 * f, joint)});
  }
  Points last;
  run_frames(sim, a, &e, {}, [&](const FrameRecord& r, const Points&, const Points& s) {
    EXPECT_TRUE(r.converged) << r.frame;
    last = s;
    return true;
  });
  const Matrix4 m = a.transforms.back()[0];
  for (int r = 0; r < 3; ++r) {
    EXPECT_NEAR(last(0, r), m[4 * r] * 1.9 + m[4 * r + 1] * 0.1 + m[4 * r + 2] * 0.4 + m[4 * r + 3], 1e-12);
    EXPECT_NEAR(last(1, r), tip.positions(1, r), 1e-12);  // in the fixed bone
  }
}

}  // namespace
}  // namespace snh
