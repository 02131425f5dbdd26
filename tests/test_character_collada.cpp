// Collada characters in the file's own vertex order: one surface vertex per
// <vertices> entry of the skinned geometry, as Blender's and Maya's Collada
// importers give them (assimp splits them per polygon corner;
// host/character/collada_vertices.h collapses the corners back). The
// creature of data/characters (make_characters.py) as .dae against the
// file's own numbers and against the same creature as glTF.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "character/collada_vertices.h"
#include "snh/character.h"
#include "support/scratch.h"

namespace snh::test {
namespace {

const std::string kCharacters = std::string(SNH_SOURCE_DIR) + "/data/characters/";

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += l + "\n";
  return s;
}

// The numbers of the <float_array> with this id.
std::vector<double> float_array(const std::string& text, const std::string& id) {
  const size_t at = text.find("<float_array id=\"" + id + "\"");
  if (at == std::string::npos) return {};
  const size_t begin = text.find('>', at) + 1, end = text.find("</float_array>", begin);
  std::istringstream in(text.substr(begin, end - begin));
  std::vector<double> out;
  for (double v; in >> v;) out.push_back(v);
  return out;
}

// Replaces the first `from` at or after `after` (a marker) with `to`.
bool replace_after(std::string& text, const std::string& after, const std::string& from, const std::string& to) {
  const size_t a = text.find(after);
  if (a == std::string::npos) return false;
  const size_t k = text.find(from, a);
  if (k == std::string::npos) return false;
  text.replace(k, from.size(), to);
  return true;
}

double weight_sum(const SkinWeights& w, size_t v) {
  double s = 0.0;
  for (int32_t k = w.offset[v]; k < w.offset[v + 1]; ++k) s += w.weight[k];
  return s;
}

}  // namespace

TEST(CharacterCollada, VerticesAreTheFilesVerticesInOrder) {
  const std::string path = kCharacters + "creature.dae";
  const Character c = read_character(path);
  EXPECT_TRUE(c.warnings.empty()) << joined(c.warnings);
  // 266 <vertices> (assimp gives 1,584 corners) and 528 triangles.
  ASSERT_EQ(c.surface.vertex_count(), 266u);
  ASSERT_EQ(c.surface.triangle_count(), 528u);
  const std::vector<double> file = float_array(read_text(path), "body-mesh-positions-array");
  ASSERT_EQ(file.size(), 3u * 266u);
  for (size_t k = 0; k < file.size(); ++k) ASSERT_EQ(c.surface.positions.xyz()[k], file[k]) << "value " << k;
  ASSERT_EQ(c.weights.vertex_count(), 266u);
  for (size_t v = 0; v < 266; ++v) EXPECT_NEAR(weight_sum(c.weights, v), 1.0, 1e-9) << "vertex " << v;
  // Closed: every edge is shared by exactly two triangles, once each way.
  std::map<std::pair<int32_t, int32_t>, int> edges;
  for (size_t t = 0; t < c.surface.triangle_count(); ++t)
    for (int e = 0; e < 3; ++e) ++edges[{c.surface.triangles[3 * t + e], c.surface.triangles[3 * t + (e + 1) % 3]}];
  for (const auto& [e, n] : edges) {
    EXPECT_EQ(n, 1) << e.first << "-" << e.second;
    EXPECT_EQ(edges.count({e.second, e.first}), 1u) << e.first << "-" << e.second;
  }
  // Nothing left for the weld to join.
  EXPECT_EQ(c.welded.vertex_count(), 266u);
}

TEST(CharacterCollada, TrianglesAreTheGltfCreaturesUpToVertexOrder) {
  const Character dae = read_character(kCharacters + "creature.dae");
  const Character gltf = read_character(kCharacters + "creature.gltf");
  ASSERT_EQ(dae.surface.vertex_count(), gltf.surface.vertex_count());
  ASSERT_EQ(dae.surface.triangle_count(), gltf.surface.triangle_count());
  // Blender's Z-up coordinates (x, y, z) are (x, z, -y) in the glTF file;
  // each vertex at exactly one glTF vertex (to float rounding).
  std::vector<int32_t> to_gltf(dae.surface.vertex_count(), -1);
  for (size_t v = 0; v < dae.surface.vertex_count(); ++v) {
    const double* p = dae.surface.positions.data() + 3 * v;
    const std::array<double, 3> want{p[0], p[2], -p[1]};
    for (size_t u = 0; u < gltf.surface.vertex_count(); ++u) {
      const double* q = gltf.surface.positions.data() + 3 * u;
      if (std::abs(q[0] - want[0]) > 1e-6 || std::abs(q[1] - want[1]) > 1e-6 || std::abs(q[2] - want[2]) > 1e-6)
        continue;
      ASSERT_EQ(to_gltf[v], -1) << "dae vertex " << v << " is at two glTF vertices";
      to_gltf[v] = static_cast<int32_t>(u);
    }
    ASSERT_NE(to_gltf[v], -1) << "dae vertex " << v << " is at no glTF vertex";
  }
  // The exporters split each quad of the mesh along a diagonal of their
  // own, so compare what does not depend on it: each vertex's normal (the
  // area-weighted sum of its triangles' normals, dae turned into glTF
  // axes) points the same way in both; and the quads' sides are edges of
  // both.
  const auto normals = [&](const TriangleSurface& s, const std::vector<int32_t>& index, bool turn) {
    std::vector<std::array<double, 3>> n(gltf.surface.vertex_count(), {0, 0, 0});
    for (size_t t = 0; t < s.triangle_count(); ++t) {
      std::array<std::array<double, 3>, 3> p;
      for (int k = 0; k < 3; ++k) {
        const double* q = s.positions.data() + 3 * s.triangles[3 * t + k];
        p[k] = turn ? std::array<double, 3>{q[0], q[2], -q[1]} : std::array<double, 3>{q[0], q[1], q[2]};
      }
      const std::array<double, 3> u{p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]},
          w{p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
      const std::array<double, 3> c{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
      for (int k = 0; k < 3; ++k)
        for (int d = 0; d < 3; ++d) n[index[s.triangles[3 * t + k]]][d] += c[d];
    }
    return n;
  };
  std::vector<int32_t> identity(gltf.surface.vertex_count());
  for (size_t v = 0; v < identity.size(); ++v) identity[v] = static_cast<int32_t>(v);
  const auto nd = normals(dae.surface, to_gltf, true), ng = normals(gltf.surface, identity, false);
  for (size_t v = 0; v < nd.size(); ++v) {
    const double dot = nd[v][0] * ng[v][0] + nd[v][1] * ng[v][1] + nd[v][2] * ng[v][2];
    const double la = std::sqrt(nd[v][0] * nd[v][0] + nd[v][1] * nd[v][1] + nd[v][2] * nd[v][2]);
    const double lb = std::sqrt(ng[v][0] * ng[v][0] + ng[v][1] * ng[v][1] + ng[v][2] * ng[v][2]);
    EXPECT_GT(dot, 0.9 * la * lb) << "glTF vertex " << v;
  }
  std::set<std::pair<int32_t, int32_t>> gltf_edges;
  for (size_t t = 0; t < gltf.surface.triangle_count(); ++t)
    for (int e = 0; e < 3; ++e) {
      const int32_t a = gltf.surface.triangles[3 * t + e], b = gltf.surface.triangles[3 * t + (e + 1) % 3];
      gltf_edges.insert({std::min(a, b), std::max(a, b)});
    }
  std::set<std::pair<int32_t, int32_t>> common;
  for (size_t t = 0; t < dae.surface.triangle_count(); ++t)
    for (int e = 0; e < 3; ++e) {
      const int32_t a = to_gltf[dae.surface.triangles[3 * t + e]],
                    b = to_gltf[dae.surface.triangles[3 * t + (e + 1) % 3]];
      if (gltf_edges.count({std::min(a, b), std::max(a, b)})) common.insert({std::min(a, b), std::max(a, b)});
    }
  // 528 triangles, 792 edges: the 264 quads' 528 sides at least.
  EXPECT_GE(common.size(), 528u) << common.size();
}

TEST(CharacterCollada, MissingJointFileKeepsItsVerticesAndItsWarning) {
  const Character c = read_character(kCharacters + "missing_joint.dae");
  EXPECT_EQ(c.surface.vertex_count(), 266u);
  EXPECT_EQ(c.surface.triangle_count(), 528u);
  ASSERT_EQ(c.warnings.size(), 1u) << joined(c.warnings);
  EXPECT_NE(c.warnings[0].find("'head'"), std::string::npos) << c.warnings[0];
  EXPECT_NE(c.warnings[0].find("held at their bind pose"), std::string::npos) << c.warnings[0];
}

TEST(CharacterCollada, LoosePointKeepsItsPositionAndTheControllersWeights) {
  // creature.dae with one more <vertices> entry that no triangle uses,
  // weighted to joint 0 (hips) with weight 0 of the weights array (1).
  std::string text = read_text(kCharacters + "creature.dae");
  ASSERT_TRUE(replace_after(text, "body-mesh-positions-array\" count=\"798\"", "count=\"798\"", "count=\"801\""));
  ASSERT_TRUE(
      replace_after(text, "body-mesh-positions-array\" count", "</float_array>", " 0.5 -0.3 0.2</float_array>"));
  ASSERT_TRUE(replace_after(text, "<accessor source=\"#body-mesh-positions-array\"", "count=\"266\"", "count=\"267\""));
  ASSERT_TRUE(replace_after(text, "<vertex_weights", "count=\"266\"", "count=\"267\""));
  ASSERT_TRUE(replace_after(text, "<vertex_weights", "</vcount>", " 1</vcount>"));
  ASSERT_TRUE(replace_after(text, "<vertex_weights", "</v>", " 0 0</v>"));
  const std::string path = (scratch_dir("snh_collada", "loose") / "loose_point.dae").string();
  std::ofstream(path, std::ios::binary) << text;

  const Character c = read_character(path);
  EXPECT_TRUE(c.warnings.empty()) << joined(c.warnings);
  ASSERT_EQ(c.surface.vertex_count(), 267u);
  EXPECT_EQ(c.surface.triangle_count(), 528u);
  EXPECT_EQ(c.surface.positions(266, 0), 0.5);
  EXPECT_EQ(c.surface.positions(266, 1), -0.3);
  EXPECT_EQ(c.surface.positions(266, 2), 0.2);
  ASSERT_EQ(c.weights.offset[267] - c.weights.offset[266], 1);
  EXPECT_EQ(c.joints[c.weights.joint[c.weights.offset[266]]].name, "rig_hips");
  EXPECT_EQ(c.weights.weight[c.weights.offset[266]], 1.0);
}

TEST(CharacterCollada, CornersThatDoNotMatchLeaveTheSurfaceAsItIs) {
  // Three corners of one triangle onto a file whose triangles are other
  // ones: the collapse refuses and changes nothing.
  TriangleSurface s;
  s.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.triangles = {0, 1, 2};
  detail::WeightRows rows(3, {{0, 1.0}});
  const TriangleSurface before = s;
  const std::string why = detail::collapse_collada_corners(
      kCharacters + "creature.dae", {{"body-mesh", 0, 3}}, [](const std::string&) { return 0; }, s, rows);
  EXPECT_NE(why.find("geometry 'body-mesh'"), std::string::npos) << why;
  EXPECT_EQ(s.positions, before.positions);
  EXPECT_EQ(s.triangles, before.triangles);
  EXPECT_EQ(rows.size(), 3u);
  // A geometry the file lacks.
  const std::string none = detail::collapse_collada_corners(
      kCharacters + "creature.dae", {{"no-such-mesh", 0, 3}}, [](const std::string&) { return 0; }, s, rows);
  EXPECT_NE(none.find("no <geometry> with id 'no-such-mesh'"), std::string::npos) << none;
}

}  // namespace snh::test
