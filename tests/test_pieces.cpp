// Lattice pieces (snh/pieces.h) and the rig seen (snh/rig.h's bone mesh): a
// fingertip that voxelizes into its own piece is refused by name, attached
// or dropped; either way its surface follows the arm as closely as the rest
// does, where left free it stays behind; the solver's rigid-motion check
// names a free piece under a load; bones are tessellated and written; a
// scene file reports its pieces and each bone's captured vertices.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "snh/animation.h"
#include "snh/error.h"
#include "snh/frames.h"
#include "snh/pieces.h"
#include "snh/rig.h"
#include "snh/scene.h"
#include "snh/simulation.h"
#include "support/errors.h"
#include "vtu_test_support.h"

namespace snh {
namespace {

using test::contains;
using test::error_of;

// The closed boundary of a box [lo, lo + n h] subdivided into cubes of side h.
TriangleSurface box_surface(int nx, int ny, int nz, double h, const std::array<double, 3>& lo) {
  return boundary_surface(make_box_lattice(nx, ny, nz, h, lo)).surface;
}

// Appends b's vertices and triangles to a (separate closed parts; the
// voxelizer counts their winding numbers together).
void append(TriangleSurface& a, const TriangleSurface& b) {
  const int32_t base = static_cast<int32_t>(a.vertex_count());
  for (size_t i = 0; i < b.vertex_count(); ++i)
    a.positions.push_back({b.positions(i, 0), b.positions(i, 1), b.positions(i, 2)});
  for (int32_t i : b.triangles) a.triangles.push_back(base + i);
}

// An arm [0, 2] x [0, 1]^2, a fingertip [2.25, 2.75] x [0.25, 0.75]^2 and a
// rod 0.1 thick joining them through the cell column x in [2, 2.25]: with
// cells of 0.25 no cell centre lies in the rod, so the tip is its own piece
// of 8 cells, one empty cell from the arm's 128.
TriangleSurface finger() {
  TriangleSurface s = box_surface(16, 8, 8, 0.125, {0, 0, 0});
  append(s, box_surface(4, 4, 4, 0.125, {2.25, 0.25, 0.25}));
  append(s, box_surface(9, 2, 2, 0.05, {1.9, 0.45, 0.45}));
  return s;
}

constexpr double kCell = 0.25;

// The bone holds the arm's vertices with x <= 1 (5 x 5 x 5 of them).
Bone arm_bone() {
  return Bone{"arm", boundary_surface(make_box_lattice(1, 1, 1, 1.02, {-0.01, -0.01, -0.01})).surface};
}

// The bone turned 20 degrees about z and moved up 0.3, in two frames.
Animation arm_motion() {
  Animation a;
  a.bones = {"arm"};
  for (int f = 0; f <= 2; ++f) {
    const double angle = M_PI / 18 * f, c = std::cos(angle), s = std::sin(angle);
    a.times.push_back(f);
    a.transforms.push_back({{c, -s, 0, 0, s, c, 0, 0.15 * f, 0, 0, 1, 0, 0, 0, 0, 1}});
  }
  return a;
}

struct Stretch {
  double piece = 0.0, rest = 0.0;  // the largest edge length ratio beyond the arm (x > 2) and within it
};

// The largest length ratio of the surface's edges at positions x.
Stretch edge_stretch(const TriangleSurface& s, const Points& x) {
  std::set<std::pair<int32_t, int32_t>> edges;
  for (size_t t = 0; t < s.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = s.triangles[3 * t + k], b = s.triangles[3 * t + (k + 1) % 3];
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  Stretch out;
  for (const auto& [a, b] : edges) {
    double rest = 0.0, now = 0.0;
    for (int d = 0; d < 3; ++d) {
      rest += std::pow(s.positions(a, d) - s.positions(b, d), 2);
      now += std::pow(x(a, d) - x(b, d), 2);
    }
    const double ratio = std::sqrt(now / rest);
    const bool beyond = s.positions(a, 0) > 2.0 + 1e-9 || s.positions(b, 0) > 2.0 + 1e-9;
    (beyond ? out.piece : out.rest) = std::max(beyond ? out.piece : out.rest, ratio);
  }
  return out;
}

// Runs the arm's motion on a lattice and returns the last frame's stretch.
Stretch run_arm(const Voxelization& v, const Embedding& e, const std::vector<ConstraintSet>& sets,
                const TriangleSurface& surface) {
  Simulation sim(v.lattice, StableNeoHookean::from_youngs_modulus(1.0, 0.45), sets);
  Points last;
  const auto records = run_frames(sim, arm_motion(), &e, {}, [&](const FrameRecord&, const Points&, const Points& s) {
    last = s;
    return true;
  });
  for (const FrameRecord& r : records) EXPECT_TRUE(r.converged) << "frame " << r.frame << ": " << r.status;
  return edge_stretch(surface, last);
}

TEST(Pieces, FingertipIsItsOwnPieceAndTheErrorNamesIt) {
  const TriangleSurface s = finger();
  const Voxelization v = voxelize(s, kCell);
  ASSERT_EQ(v.components, 2);
  ASSERT_EQ(v.lattice.element_count(), 136u);
  const auto pieces = mesh_pieces(v.lattice);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_EQ(pieces[0].size(), 128u);
  EXPECT_EQ(pieces[1].size(), 8u);
  std::vector<ConstraintSet> sets = bone_constraints(v.lattice, {arm_bone()});
  ASSERT_EQ(sets[0].vertices.size(), 125u);  // x in {0, 0.25, ..., 1}, 5 x 5 in y and z
  const std::string what = error_of([&] { resolve_pieces(v, embed(v, s), s, sets, {arm_bone()}, PieceOptions{}); });
  EXPECT_TRUE(contains(what, "falls into 2 pieces, and nothing holds 1 of them")) << what;
  EXPECT_TRUE(contains(what, "piece 2: 8 cells, bounding box (2.25, 0.25, 0.25) to (2.75, 0.75, 0.75)")) << what;
  EXPECT_TRUE(contains(what, "nearest bone 'arm' at 1.24")) << what;  // from x = 2.25 to the bone's x = 1.01
  EXPECT_TRUE(contains(what, "\"attach\"") && contains(what, "\"drop\"") && contains(what, "cell size")) << what;

  // What holds a piece: a constraint set's vertex, an obstacle's layer at
  // rest, inertia (a warning under a load).
  std::vector<ConstraintSet> held = sets;
  held.push_back(ConstraintSet::fixed("tip", {v.lattice.elements[8 * pieces[1][0]]}, {false, false, true}));
  PiecedLattice p = resolve_pieces(v, embed(v, s), s, held, {});
  EXPECT_FALSE(p.changed);
  EXPECT_EQ(p.pieces[1].hold, PieceHold::constraint);
  EXPECT_EQ(p.pieces[1].held_by, "tip");
  PieceOptions floor;
  floor.obstacles = {Obstacle::plane({0, 0, 0.2}, {0, 0, 1})};  // 0.05 below the tip
  floor.contact_thickness = 0.04;
  EXPECT_TRUE(contains(error_of([&] { resolve_pieces(v, embed(v, s), s, sets, {}, floor); }), "piece 2"));
  floor.contact_thickness = 0.06;
  p = resolve_pieces(v, embed(v, s), s, sets, {}, floor);
  EXPECT_EQ(p.pieces[1].hold, PieceHold::obstacle);
  EXPECT_EQ(p.pieces[1].held_by, "obstacles[0]");
  PieceOptions dynamic;
  dynamic.dynamic = true;
  p = resolve_pieces(v, embed(v, s), s, sets, {}, dynamic);
  EXPECT_EQ(p.pieces[1].hold, PieceHold::inertia);
  EXPECT_TRUE(p.warnings.empty());
  dynamic.loaded = true;
  p = resolve_pieces(v, embed(v, s), s, sets, {}, dynamic);
  ASSERT_EQ(p.warnings.size(), 1u);
  EXPECT_TRUE(contains(p.warnings[0], "piece 2: 8 cells")) << p.warnings[0];
  EXPECT_TRUE(contains(p.warnings[0], "falls")) << p.warnings[0];
  EXPECT_EQ(parse_piece_rule("drop"), PieceRule::drop);
  EXPECT_TRUE(contains(error_of([] { parse_piece_rule("glue"); }), "error, attach or drop"));
}

TEST(Pieces, AttachedOrDroppedFingertipStretchesNoMoreThanTheArm) {
  const TriangleSurface s = finger();
  const Voxelization v = voxelize(s, kCell);
  const Embedding e = embed(v, s);
  const std::vector<ConstraintSet> sets = bone_constraints(v.lattice, {arm_bone()});

  // Left free, the tip stays behind: the rod's edges across the gap stretch.
  const Stretch free = run_arm(v, e, sets, s);
  EXPECT_GT(free.piece, 2.0);
  EXPECT_LT(free.rest, 1.01);

  PieceOptions attach;
  attach.rule = PieceRule::attach;
  std::vector<ConstraintSet> attached_sets = sets;
  const PiecedLattice attached = resolve_pieces(v, e, s, attached_sets, {arm_bone()}, attach);
  EXPECT_TRUE(attached.changed);
  EXPECT_EQ(attached.voxels.components, 1);
  EXPECT_EQ(attached.pieces[1].outcome, "attached");
  EXPECT_EQ(attached.pieces[1].added_cells, 1);  // the empty cell (8, 1, 1) between (7, 1, 1) and (9, 1, 1)
  EXPECT_EQ(attached.pieces[1].joined_through, "surface");
  ASSERT_EQ(attached.voxels.lattice.element_count(), 137u);
  EXPECT_EQ(attached.voxels.element_cell.back(), (std::array<int, 3>{8, 1, 1}));
  // The given lattice's vertices keep their indices (the line glues no two of them).
  for (size_t k = 0; k < v.lattice.vertex_count(); ++k) EXPECT_EQ(attached.vertex_map[k], static_cast<int32_t>(k));
  EXPECT_EQ(attached.voxels.lattice.vertex_count(),
            v.lattice.vertex_count());  // the new cell's corners are its neighbours'
  EXPECT_EQ(attached_sets[0].vertices, sets[0].vertices);
  const Stretch a = run_arm(attached.voxels, attached.embedding, attached_sets, s);
  EXPECT_LE(a.piece, a.rest + 0.01) << a.piece << " vs " << a.rest;

  PieceOptions drop;
  drop.rule = PieceRule::drop;
  std::vector<ConstraintSet> dropped_sets = sets;
  const PiecedLattice dropped = resolve_pieces(v, e, s, dropped_sets, {arm_bone()}, drop);
  EXPECT_EQ(dropped.voxels.components, 1);
  EXPECT_EQ(dropped.pieces[1].outcome, "dropped");
  ASSERT_EQ(dropped.voxels.lattice.element_count(), 128u);
  EXPECT_EQ(dropped.voxels.element_cell.size(), 128u);
  ASSERT_EQ(dropped_sets[0].vertices.size(), sets[0].vertices.size());  // the same vertices, renumbered
  for (size_t k = 0; k < sets[0].vertices.size(); ++k) {
    EXPECT_EQ(dropped_sets[0].vertices[k], dropped.vertex_map[sets[0].vertices[k]]);
    EXPECT_EQ(dropped.voxels.lattice.vertex(dropped_sets[0].vertices[k]), v.lattice.vertex(sets[0].vertices[k]));
  }
  // At rest the surface is where it was (extrapolation reproduces it).
  const auto rest = embedded_positions(dropped.embedding, dropped.voxels.lattice, dropped.voxels.lattice.positions);
  for (size_t i = 0; i < rest.xyz().size(); ++i) ASSERT_NEAR(rest.xyz()[i], s.positions.xyz()[i], 1e-12) << i;
  const Stretch d = run_arm(dropped.voxels, dropped.embedding, dropped_sets, s);
  EXPECT_LE(d.piece, d.rest + 0.01) << d.piece << " vs " << d.rest;
}

// The arm and the fingertip of finger(), joined not straight across the
// empty cell column x in [2, 2.25] but by a bridge thinner than a cell (no
// cell centre in it) that runs below the tip, at z in [0.15, 0.24] (the
// lowest cell row), and rises into the tip's underside at x in [2.3, 2.4]:
// the straight line between the pieces' nearest cells, (7, 1, 1) to
// (9, 1, 1), crosses empty space; the bridge's skin crosses (8, 1, 0) and
// (9, 1, 0).
TriangleSurface bridged_tip() {
  TriangleSurface s = box_surface(16, 8, 8, 0.125, {0, 0, 0});
  append(s, box_surface(4, 4, 4, 0.125, {2.25, 0.25, 0.25}));
  TriangleSurface under = boundary_surface(make_box_lattice(1, 1, 1, 1.0, {0, 0, 0})).surface;
  for (size_t v = 0; v < under.vertex_count(); ++v) {  // [1.9, 2.4] x [0.45, 0.55] x [0.15, 0.24]
    under.positions(v, 0) = 1.9 + 0.5 * under.positions(v, 0);
    under.positions(v, 1) = 0.45 + 0.1 * under.positions(v, 1);
    under.positions(v, 2) = 0.15 + 0.09 * under.positions(v, 2);
  }
  append(s, under);
  append(s, box_surface(2, 2, 3, 0.05, {2.3, 0.45, 0.15}));  // up into the tip, to z = 0.3
  return s;
}

TEST(Pieces, AttachFollowsTheSurfaceAroundTheStraightLine) {
  const TriangleSurface s = bridged_tip();
  const Voxelization v = voxelize(s, kCell);
  ASSERT_EQ(v.components, 2);
  const auto pieces = mesh_pieces(v.lattice);
  ASSERT_EQ(pieces.size(), 2u);
  ASSERT_EQ(pieces[1].size(), 8u);
  // The cells the surface crosses, by the voxelizer's own cover.
  VoxelizeOptions cover;
  cover.cover_surface = true;
  const Voxelization covered = voxelize(s, kCell, cover);
  ASSERT_EQ(covered.dims, v.dims);
  const std::set<std::array<int, 3>> crossed_or_inside(covered.element_cell.begin(), covered.element_cell.end());
  EXPECT_FALSE(crossed_or_inside.count({8, 1, 1}));  // the straight line's cell: empty space

  const Embedding e = embed(v, s);
  const std::vector<ConstraintSet> sets = bone_constraints(v.lattice, {arm_bone()});
  PieceOptions attach;
  attach.rule = PieceRule::attach;
  std::vector<ConstraintSet> attached_sets = sets;
  const PiecedLattice attached = resolve_pieces(v, e, s, attached_sets, {arm_bone()}, attach);
  EXPECT_EQ(attached.voxels.components, 1);
  EXPECT_EQ(attached.pieces[1].joined_through, "surface");
  EXPECT_EQ(attached.pieces[1].added_cells, 2);
  ASSERT_EQ(attached.voxels.element_cell.size(), v.element_cell.size() + 2);
  EXPECT_EQ(attached.voxels.element_cell[v.element_cell.size()], (std::array<int, 3>{9, 1, 0}));
  EXPECT_EQ(attached.voxels.element_cell[v.element_cell.size() + 1], (std::array<int, 3>{8, 1, 0}));
  for (size_t k = v.element_cell.size(); k < attached.voxels.element_cell.size(); ++k)
    EXPECT_TRUE(crossed_or_inside.count(attached.voxels.element_cell[k]));
  // Along the bridge the skin follows the arm like the rest of it.
  const Stretch a = run_arm(attached.voxels, attached.embedding, attached_sets, s);
  EXPECT_LE(a.piece, a.rest + 0.01) << a.piece << " vs " << a.rest;
  EXPECT_LT(a.rest, 1.01);

  // Without a bridge the surface offers no path: the straight line, said so.
  TriangleSurface apart = box_surface(16, 8, 8, 0.125, {0, 0, 0});
  append(apart, box_surface(4, 4, 4, 0.125, {2.25, 0.25, 0.25}));
  const Voxelization va = voxelize(apart, kCell);
  std::vector<ConstraintSet> apart_sets = bone_constraints(va.lattice, {arm_bone()});
  const PiecedLattice line = resolve_pieces(va, embed(va, apart), apart, apart_sets, {arm_bone()}, attach);
  EXPECT_EQ(line.pieces[1].joined_through, "straight line");
  EXPECT_EQ(line.pieces[1].added_cells, 1);
  EXPECT_EQ(line.voxels.element_cell.back(), (std::array<int, 3>{8, 1, 1}));
  EXPECT_EQ(line.voxels.components, 1);
}

// A set that prescribes nothing holds nothing: when it lies wholly in a
// dropped piece, drop would leave it with no vertex; the error names it.
TEST(Pieces, DropRefusesToEmptyAConstraintSet) {
  const TriangleSurface s = finger();
  const Voxelization v = voxelize(s, kCell);
  std::vector<ConstraintSet> sets = bone_constraints(v.lattice, {arm_bone()});
  const auto pieces = mesh_pieces(v.lattice);
  sets.push_back(ConstraintSet::fixed("tip_marker", {v.lattice.elements[8 * pieces[1][0]]}, {false, false, false}));
  PieceOptions drop;
  drop.rule = PieceRule::drop;
  drop.rule_name = "embed.pieces";
  const std::string what = error_of([&] { resolve_pieces(v, embed(v, s), s, sets, {arm_bone()}, drop); });
  EXPECT_TRUE(contains(what, "constraint set 'tip_marker': all its 1 vertices are in dropped pieces")) << what;
  EXPECT_TRUE(contains(what, "embed.pieces \"drop\"")) << what;
}

TEST(Pieces, RigidMotionCheckNamesAFreePieceUnderALoad) {
  const TriangleSurface s = finger();
  const Voxelization v = voxelize(s, kCell);
  const std::vector<ConstraintSet> sets = bone_constraints(v.lattice, {arm_bone()});
  SolveOptions gravity;
  gravity.body_force = {0, 0, -1e-3};
  const std::string what =
      error_of([&] { Simulation(v.lattice, StableNeoHookean::from_youngs_modulus(1.0, 0.45), sets, gravity); });
  EXPECT_TRUE(contains(what,
                       "leave piece 2 of 2 (8 elements, rest bounding box (2.25, 0.25, 0.25) to (2.75, 0.75, "
                       "0.75)) free to move by translation along z"))
      << what;
  // Without a load: a warning naming the piece; the arm is held.
  Simulation quiet(v.lattice, StableNeoHookean::from_youngs_modulus(1.0, 0.45), sets);
  const SolveResult r = quiet.solve(1);
  bool named = false;
  for (const std::string& w : r.warnings) {
    named = named || (contains(w, "piece 2 of 2 (8 elements") && contains(w, "6 rigid motion(s) left free"));
    EXPECT_FALSE(contains(w, "piece 1 of 2")) << w;
  }
  EXPECT_TRUE(named);
  // Dynamics: inertia holds the piece (it falls).
  SolveOptions dynamic = gravity;
  dynamic.dynamics = DynamicsOptions{};
  dynamic.dynamics->time_step = 0.01;
  dynamic.dynamics->density = 1.0;
  EXPECT_NO_THROW(Simulation(v.lattice, StableNeoHookean::from_youngs_modulus(1.0, 0.45), sets, dynamic));
}

TEST(Pieces, CapsuleBoneMeshIsClosedAndWrittenWithItsBone) {
  const Capsule c{{0, 0, 0}, {1, 0, 0}, 0.25};
  const BoneMesh rest = bone_mesh({Bone{"upper", c}, Bone{"box", finger()}});
  ASSERT_FALSE(rest.surface.triangles.empty());
  // The capsule: 16 around, 4 rings per end, 2 poles; closed and outward.
  TriangleSurface capsule;
  size_t capsule_vertices = 0;
  while (capsule_vertices < rest.vertex_bone.size() && rest.vertex_bone[capsule_vertices] == 0) ++capsule_vertices;
  EXPECT_EQ(capsule_vertices, 2u + 8u * 16u);
  capsule.positions = Points::from_xyz(std::vector<double>(
      rest.surface.positions.xyz().begin(), rest.surface.positions.xyz().begin() + 3 * capsule_vertices));
  for (size_t t = 0; t < rest.triangle_bone.size(); ++t)
    if (rest.triangle_bone[t] == 0)
      capsule.triangles.insert(capsule.triangles.end(), rest.surface.triangles.begin() + 3 * t,
                               rest.surface.triangles.begin() + 3 * t + 3);
  EXPECT_NO_THROW(validate_closed_surface(capsule));
  const double exact = M_PI * 0.25 * 0.25 * 1.0 + 4.0 / 3.0 * M_PI * std::pow(0.25, 3);
  EXPECT_NEAR(enclosed_volume(capsule), exact, 0.05 * exact);
  EXPECT_LT(enclosed_volume(capsule), exact);  // inscribed
  for (size_t k = 0; k < capsule_vertices; ++k)
    EXPECT_NEAR(
        bone_distance(Bone{"upper", c}, {capsule.positions(k, 0), capsule.positions(k, 1), capsule.positions(k, 2)}),
        0.0, 1e-12);
  // A surface bone comes as it is.
  EXPECT_EQ(rest.surface.vertex_count() - capsule_vertices, finger().vertex_count());
  // Placed by a transform.
  Matrix4 up = identity_matrix4();
  up[11] = 2.0;
  const BoneMesh moved = bone_mesh({Bone{"upper", c}, Bone{"box", finger()}}, {up, identity_matrix4()});
  EXPECT_DOUBLE_EQ(moved.surface.positions(0, 2), rest.surface.positions(0, 2) + 2.0);
  EXPECT_DOUBLE_EQ(moved.surface.positions.xyz().back(), rest.surface.positions.xyz().back());
  const auto path = std::filesystem::temp_directory_path() / "snh_pieces_bones.vtu";
  write_bone_mesh_vtu(path.string(), moved);
  const std::string text = test::read_text(path);
  const auto bone = test::read_array(text, "bone");
  ASSERT_EQ(bone.size(), moved.surface.triangle_count());
  for (size_t t = 0; t < bone.size(); ++t) EXPECT_EQ(bone[t], moved.triangle_bone[t]);
  EXPECT_EQ(test::read_array(text, "connectivity").size(), moved.surface.triangles.size());
  EXPECT_TRUE(contains(error_of([&] { bone_mesh({Bone{"upper", c}}, {up, up}); }), "2 transforms for 1 bones"));
  std::filesystem::remove(path);
}

// A scene folder with the finger, its bone and a two-frame animation.
std::filesystem::path write_finger_scene(const std::string& pieces) {
  const auto folder = std::filesystem::temp_directory_path() / ("snh_pieces_" + (pieces.empty() ? "none" : pieces));
  std::filesystem::create_directories(folder);
  write_obj((folder / "finger.obj").string(), finger());
  write_obj((folder / "arm_bone.obj").string(), std::get<TriangleSurface>(arm_bone().shape));
  std::ofstream((folder / "move.json").string())
      << R"({"frames": [{"time": 0, "bones": {"arm": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}},
                        {"time": 1, "bones": {"arm": [[1,0,0,0],[0,1,0,0.1],[0,0,1,0],[0,0,0,1]]}}]})";
  std::ofstream((folder / "scene.json").string())
      << R"({"name": "finger", "embed": {"surface": "finger.obj", "cell": 0.25)"
      << (pieces.empty() ? "" : R"(, "pieces": ")" + pieces + "\"")
      << R"(}, "rig": {"bones": [{"name": "arm", "surface": "arm_bone.obj"}], "animation": "move.json"}})";
  return folder;
}

TEST(Pieces, SceneFileRefusesAttachesOrDropsAndReportsPiecesAndBones) {
  const auto none = write_finger_scene("");
  const std::string what = error_of([&] { load_scene((none / "scene.json").string()); });
  EXPECT_TRUE(contains(what, "scene.json: embed.pieces: the lattice falls into 2 pieces")) << what;
  EXPECT_TRUE(contains(what, "embed.pieces \"attach\"")) << what;
  EXPECT_TRUE(contains(error_of([&] { load_scene((write_finger_scene("glue") / "scene.json").string()); }),
                       "embed.pieces: expected error, attach or drop, got 'glue'"));

  const SceneFile attached = load_scene((write_finger_scene("attach") / "scene.json").string());
  ASSERT_TRUE(attached.embedded);
  EXPECT_EQ(attached.scene.mesh.element_count(), 137u);
  EXPECT_EQ(attached.materials.element_material.size(), 137u);
  const auto report = scene_setup_report(attached);
  std::string all;
  for (const std::string& line : report) all += line + "\n";
  EXPECT_TRUE(contains(all, "lattice: 2 pieces (embed.pieces attach), now 1")) << all;
  EXPECT_TRUE(contains(all, "piece 1: 128 cells, held by constraint set 'arm'")) << all;
  EXPECT_TRUE(contains(all,
                       "piece 2: 8 cells, held by nothing, attached (cells added: 1, along the surface); nearest "
                       "bone 'arm' at 1.24"))
      << all;
  EXPECT_TRUE(contains(all, "bone 'arm': 125 lattice vertices")) << all;

  const auto folder = write_finger_scene("drop");
  const SceneFile dropped = load_scene((folder / "scene.json").string());
  EXPECT_EQ(dropped.scene.mesh.element_count(), 128u);
  // The run's JSON and the bones beside the lattice, per frame.
  SceneVtuSeries vtu((folder / "out").string(), dropped, dropped.scene.options);
  SceneRunOptions run;
  run.writers.push_back(vtu.writer());
  const SceneRun result = run_scene(dropped, dropped.scene.options, run);
  vtu.finish();
  EXPECT_TRUE(result.converged);
  const std::string bones0 = test::read_text(folder / "out" / "finger_bones_0000.vtu");
  const std::string bones1 = test::read_text(folder / "out" / "finger_bones_0001.vtu");
  ASSERT_FALSE(bones1.empty());
  // The bone moved up 0.1 in frame 1, and its mesh with it.
  const auto first_point = [](const std::string& vtu) {
    std::istringstream in(vtu.substr(vtu.find('>', vtu.find("<Points>") + 8) + 1));
    std::array<double, 3> p{};
    in >> p[0] >> p[1] >> p[2];
    return p;
  };
  const auto p0 = first_point(bones0), p1 = first_point(bones1);
  EXPECT_DOUBLE_EQ(p1[0], p0[0]);
  EXPECT_NEAR(p1[1], p0[1] + 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(p1[2], p0[2]);
  EXPECT_TRUE(contains(test::read_text(folder / "out" / "finger.pvd"), "finger_bones_0001.vtu"));
  write_scene_json((folder / "run.json").string(), dropped, result);
  const std::string json = test::read_text(folder / "run.json");
  EXPECT_TRUE(contains(json, "\"lattice_pieces\"")) << json.substr(0, 400);
  EXPECT_TRUE(contains(json, "\"outcome\": \"dropped\""));
  EXPECT_TRUE(contains(json, "\"vertices\": 125"));
  for (const auto& f : {none, folder}) std::filesystem::remove_all(f);
}

}  // namespace
}  // namespace snh
