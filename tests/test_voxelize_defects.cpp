// voxelize on imperfect surfaces: on watertight ones the winding-number
// rule keeps the same cells as crossing counts (VoxelizeOptions::strict);
// a surface opened along a seam and punctured keeps its closed original's
// cells up to the layer along the surface; separate and intersecting shells,
// edges shared by four triangles and flipped triangles; the warnings name
// the file, and what cannot be voxelized is an error naming it.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "snh/error.h"
#include "snh/scene.h"
#include "snh/surface.h"
#include "support/errors.h"
#include "support/surface_shapes.h"

namespace snh {
namespace {

using test::error_of;
namespace fs = std::filesystem;
using Cells = std::set<std::array<int, 3>>;

Cells cells_of(const Voxelization& v) { return Cells(v.element_cell.begin(), v.element_cell.end()); }

std::array<double, 3> centre(const Voxelization& v, const std::array<int, 3>& g) {
  return {v.origin[0] + (g[0] + 0.5) * v.cell, v.origin[1] + (g[1] + 0.5) * v.cell,
          v.origin[2] + (g[2] + 0.5) * v.cell};
}

// A torus about the z axis (radii R, r), n x m quads split in two.
TriangleSurface torus(double R, double r, int n, int m) {
  TriangleSurface s;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      s.positions.push_back(
          {(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
    }
  const auto at = [&](int i, int j) { return ((i % n) * m + j % m); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      s.triangles.insert(s.triangles.end(), {a, b, c, a, c, d});
    }
  return s;
}

TriangleSurface joined(const TriangleSurface& a, const TriangleSurface& b) {
  TriangleSurface s = a;
  for (size_t v = 0; v < b.vertex_count(); ++v)
    s.positions.push_back({b.positions(v, 0), b.positions(v, 1), b.positions(v, 2)});
  for (int32_t v : b.triangles) s.triangles.push_back(v + static_cast<int32_t>(a.vertex_count()));
  return s;
}

// Watertight surfaces: the same cells by winding numbers as by crossing
// counts. A centre exactly on the surface would be a tie (crossing counts
// decide it as if moved along +x, the winding number is 1/2 there); none of
// these grids has one, which the exact winding number confirms.
TEST(VoxelizeDefects, WatertightSurfacesKeepTheCrossingCountCells) {
  const fs::path data = fs::path(SNH_DATA_DIR) / "surfaces";
  const struct {
    std::string name;
    TriangleSurface surface;
    double cell;
  } cases[] = {{"sphere.obj", read_surface((data / "sphere.obj").string()), 0.05},
               {"sphere.ply", read_surface((data / "sphere.ply").string()), 0.03},
               {"sphere.stl", read_surface((data / "sphere.stl").string()), 0.07},
               {"sphere_binary.stl", read_surface((data / "sphere_binary.stl").string()), 0.04},
               {"slit_box.stl", read_surface((data / "slit_box.stl").string()), 0.05},
               {"icosphere", test::icosphere(4, 1.0), 0.1},
               {"torus", torus(1.0, 0.35, 48, 24), 0.07},
               {"box of whole cells", test::box_surface({0, 0, 0}, {1, 1, 1}), 0.25},
               {"octahedron, centres on its vertices", test::octahedron(1.0), 0.4},
               {"slit box (code)", test::slit_box(0.04, 0.5, 0.6), 0.1}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    VoxelizeOptions strict;
    strict.strict = true;
    const Voxelization crossing = voxelize(c.surface, c.cell, strict);
    const Voxelization winding = voxelize(c.surface, c.cell);
    EXPECT_TRUE(winding.warnings.empty()) << winding.warnings.front();
    EXPECT_EQ(cells_of(winding), cells_of(crossing));
    // Same cells, same gluing across gaps: the same lattice.
    EXPECT_EQ(winding.lattice.elements, crossing.lattice.elements);
    EXPECT_EQ(winding.lattice.positions, crossing.lattice.positions);
    EXPECT_EQ(winding.components, crossing.components);
  }
}

// The icosphere cut along a seam (the triangles above z = 0.3 get their own
// copies of the vertices they share with the rest) and punctured (the
// triangles whose centroid lies within 0.12 of (1, 0, 0) removed): the
// seam is welded, and the hole changes only cells along the surface.
TEST(VoxelizeDefects, OpenedSphereKeepsItsCellsUpToTheSurfaceLayer) {
  const TriangleSurface closed = test::icosphere(4, 1.0);
  TriangleSurface opened = closed;
  std::vector<int32_t> copy(closed.vertex_count(), -1);
  std::vector<char> below(closed.vertex_count(), 0);
  const auto centroid = [&](size_t t, int d) {
    double x = 0.0;
    for (int k = 0; k < 3; ++k) x += closed.positions(closed.triangles[3 * t + k], d) / 3.0;
    return x;
  };
  for (size_t t = 0; t < closed.triangle_count(); ++t)
    if (centroid(t, 2) <= 0.3)
      for (int k = 0; k < 3; ++k) below[closed.triangles[3 * t + k]] = 1;
  opened.triangles.clear();
  size_t removed = 0;
  for (size_t t = 0; t < closed.triangle_count(); ++t) {
    const double dx = centroid(t, 0) - 1.0, dy = centroid(t, 1), dz = centroid(t, 2);
    if (dx * dx + dy * dy + dz * dz < 0.12 * 0.12) {
      ++removed;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      int32_t v = closed.triangles[3 * t + k];
      if (centroid(t, 2) > 0.3 && below[v]) {
        if (copy[v] < 0) {
          copy[v] = static_cast<int32_t>(opened.vertex_count());
          opened.positions.push_back({closed.positions(v, 0), closed.positions(v, 1), closed.positions(v, 2)});
        }
        v = copy[v];
      }
      opened.triangles.push_back(v);
    }
  }
  const size_t seam = opened.vertex_count() - closed.vertex_count();
  ASSERT_GT(seam, 20u);
  ASSERT_GT(removed, 2u);
  EXPECT_THROW(validate_closed_surface(opened), Error);

  const double h = 0.1;
  const Voxelization a = voxelize(closed, h);
  VoxelizeOptions named;
  named.name = "opened.obj";
  const Voxelization b = voxelize(opened, h, named);
  EXPECT_EQ(b.report.welded_vertices, seam);
  EXPECT_GT(b.report.open_edges, 0u);
  EXPECT_EQ(b.report.non_manifold_edges + b.report.inconsistent_edges + b.report.degenerate_triangles, 0u);
  EXPECT_EQ(b.report.shells, 1u);
  ASSERT_EQ(b.warnings.size(), 2u);
  EXPECT_EQ(b.warnings[0], "opened.obj: " + std::to_string(seam) + " vertices welded to a coincident vertex (seams)");
  EXPECT_EQ(b.warnings[1].rfind("opened.obj: " + std::to_string(b.report.open_edges) + " open edges", 0), 0u);
  const Cells ca = cells_of(a), cb = cells_of(b);
  std::vector<std::array<int, 3>> differ;
  for (const auto& c : ca)
    if (!cb.count(c)) differ.push_back(c);
  for (const auto& c : cb)
    if (!ca.count(c)) differ.push_back(c);
  std::printf("opened sphere, cell %.2f: %zu cells closed, %zu opened, %zu differ\n", h, ca.size(), cb.size(),
              differ.size());
  EXPECT_LE(differ.size(), 6u);
  for (const auto& c : differ) {
    // Within the layer of cells the surface passes through: the centre is
    // at most half a cell diagonal from the sphere (the polyhedron lies
    // within 0.003 of it), and next to the hole.
    const auto p = centre(a, c);
    const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    EXPECT_LT(std::abs(r - 1.0), 0.5 * std::sqrt(3.0) * h + 0.003) << c[0] << " " << c[1] << " " << c[2];
    EXPECT_LT(std::hypot(p[0] - 1.0, p[1], p[2]), 0.12 + std::sqrt(3.0) * h);
  }
  // The embedding maps the file's vertices, seam copies included.
  const Embedding e = embed(b, opened);
  EXPECT_EQ(e.element.size(), opened.vertex_count());
  const Points x = embedded_positions(e, b.lattice, b.lattice.positions);
  for (size_t i = 0; i < x.xyz().size(); ++i) ASSERT_NEAR(x.xyz()[i], opened.positions.xyz()[i], 1e-12);
}

TEST(VoxelizeDefects, SeparateShellsAreSeparateComponents) {
  const TriangleSurface a = test::box_surface({0, 0, 0}, {1, 1, 1}), b = test::box_surface({2, 0, 0}, {3, 1, 1});
  VoxelizeOptions named;
  named.name = "two.stl";
  const Voxelization v = voxelize(joined(a, b), 0.25, named);
  EXPECT_EQ(v.components, 2);
  EXPECT_EQ(v.report.shells, 2u);
  EXPECT_EQ(v.element_cell.size(), 2u * 64u);
  ASSERT_EQ(v.warnings.size(), 1u);
  EXPECT_EQ(v.warnings[0], "two.stl: 2 shells (separate pieces); overlapping ones are united");
}

TEST(VoxelizeDefects, IntersectingShellsGiveTheirUnion) {
  // A box through a box: winding number 2 where they overlap.
  const TriangleSurface a = test::box_surface({0, 0, 0}, {1, 1, 1});
  const TriangleSurface b = test::box_surface({0.5, 0.25, 0.25}, {1.5, 0.75, 1.75});
  const double h = 0.125;
  const Voxelization v = voxelize(joined(a, b), h);
  Cells expected;
  for (int k = 0; k < v.dims[2]; ++k)
    for (int j = 0; j < v.dims[1]; ++j)
      for (int i = 0; i < v.dims[0]; ++i) {
        const auto p = centre(v, {i, j, k});
        const bool in_a = p[0] < 1 && p[1] < 1 && p[2] < 1;
        const bool in_b = p[0] > 0.5 && p[1] > 0.25 && p[1] < 0.75 && p[2] > 0.25;
        if (in_a || in_b) expected.insert({i, j, k});
      }
  EXPECT_EQ(cells_of(v), expected);
  EXPECT_EQ(v.components, 1);
  EXPECT_EQ(v.report.shells, 2u);
}

TEST(VoxelizeDefects, NonManifoldEdgeAndFlippedTriangle) {
  // Two boxes sharing an edge: the edge has four triangles; the boxes touch
  // only along it, so the lattice has two components.
  const TriangleSurface pair = joined(test::box_surface({0, 0, 0}, {1, 1, 1}), test::box_surface({1, 1, 0}, {2, 2, 1}));
  const Voxelization v = voxelize(pair, 0.25);
  EXPECT_EQ(v.report.non_manifold_edges, 1u);
  EXPECT_EQ(v.element_cell.size(), 128u);
  EXPECT_EQ(v.components, 2);
  // A flipped triangle (half of the bottom face of a box of 4 x 4 x 4
  // cells) subtracts twice its solid angle: only cells of the bottom layer
  // above it can fall out.
  TriangleSurface flipped = test::box_surface({0, 0, 0}, {1, 1, 1});
  std::swap(flipped.triangles[4], flipped.triangles[5]);  // triangle 1: half of the z = 0 face
  const Voxelization f = voxelize(flipped, 0.25);
  EXPECT_EQ(f.report.inconsistent_edges, 3u);
  ASSERT_EQ(f.warnings.size(), 1u);
  EXPECT_NE(f.warnings[0].find("flipped triangles"), std::string::npos);
  EXPECT_LT(f.element_cell.size(), 64u);
  EXPECT_GE(f.element_cell.size(), 64u - 16u);
  for (int k = 1; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) EXPECT_TRUE(cells_of(f).count({i, j, k})) << i << " " << j << " " << k;
}

TEST(VoxelizeDefects, StrictRefusesWhatTheDefaultWarnsAbout) {
  TriangleSurface open = test::box_surface({0, 0, 0}, {1, 1, 1});
  open.triangles.resize(3 * 11);
  VoxelizeOptions strict;
  strict.strict = true;
  strict.name = "open.obj";
  const std::string e = error_of([&] { voxelize(open, 0.25, strict); });
  EXPECT_EQ(e.rfind("open.obj: it is not closed", 0), 0u) << e;
  // The default voxelizes it: a missing half face leaves w ~ 1/2 beneath it.
  EXPECT_GE(voxelize(open, 0.25).element_cell.size(), 48u);
}

TEST(VoxelizeDefects, WhatCannotBeVoxelizedIsAnErrorNamingTheFile) {
  VoxelizeOptions named;
  named.name = "bad.obj";
  const std::string none = error_of([&] { voxelize(TriangleSurface{}, 0.1, named); });
  EXPECT_EQ(none, "bad.obj: the surface has no triangles");
  TriangleSurface box = test::box_surface({0, 0, 0}, {1, 1, 1});
  box.positions(2, 1) = HUGE_VAL;
  const std::string inf = error_of([&] { voxelize(box, 0.1, named); });
  EXPECT_EQ(inf.rfind("bad.obj: vertex 2 has a non-finite coordinate (y = inf)", 0), 0u) << inf;
  // A lone triangle encloses nothing. A box facing inwards is an inside-out
  // skin: voxelized as its outward twin, with a warning naming the shell;
  // strict keeps refusing it.
  TriangleSurface sheet;
  sheet.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  sheet.triangles = {0, 1, 2};
  const std::string empty = error_of([&] { voxelize(sheet, 0.1, named); });
  EXPECT_EQ(empty.rfind("bad.obj: voxelize: no cell centre lies inside the surface", 0), 0u) << empty;
  TriangleSurface inwards = test::box_surface({0, 0, 0}, {1, 1, 1});
  for (size_t t = 0; t < inwards.triangle_count(); ++t)
    std::swap(inwards.triangles[3 * t], inwards.triangles[3 * t + 1]);
  const Voxelization turned = voxelize(inwards, 0.25, named);
  EXPECT_EQ(turned.element_cell, voxelize(test::box_surface({0, 0, 0}, {1, 1, 1}), 0.25, named).element_cell);
  ASSERT_FALSE(turned.warnings.empty());
  EXPECT_EQ(turned.warnings.back().rfind("bad.obj: shell 0 (from triangle 0, 12 triangles) faces inwards", 0), 0u)
      << turned.warnings.back();
  VoxelizeOptions strict = named;
  strict.strict = true;
  EXPECT_FALSE(error_of([&] { voxelize(inwards, 0.25, strict); }).empty());
}

TEST(VoxelizeDefects, SceneKeyStrictSurfaceAndTheFileInMessages) {
  const fs::path dir = fs::temp_directory_path() / "snh_voxelize_defects";
  fs::remove_all(dir);
  fs::create_directories(dir);
  // An open box (one triangle missing) as OBJ.
  TriangleSurface open = test::box_surface({0, 0, 0}, {1, 1, 1});
  open.triangles.resize(3 * 11);
  write_obj((dir / "open.obj").string(), open);
  const fs::path scene = dir / "s.json";
  std::ofstream(scene) << R"({"embed": {"surface": "open.obj", "cell": 0.25}})";
  const SceneFile loaded = load_scene(scene.string());
  ASSERT_TRUE(loaded.embedded);
  ASSERT_EQ(loaded.embedded->voxels.warnings.size(), 1u);
  EXPECT_EQ(loaded.embedded->voxels.warnings[0].rfind((dir / "open.obj").string() + ": 3 open edges", 0), 0u)
      << loaded.embedded->voxels.warnings[0];
  std::ofstream(scene) << R"({"embed": {"surface": "open.obj", "cell": 0.25, "strict_surface": true}})";
  const std::string e = error_of([&] { load_scene(scene.string()); });
  EXPECT_NE(e.find("embed.surface: " + (dir / "open.obj").string() + ": it is not closed"), std::string::npos) << e;
  std::ofstream(scene) << R"({"embed": {"surface": "open.obj", "cell": 0.25, "strict_surface": 1}})";
  EXPECT_NE(error_of([&] { load_scene(scene.string()); }).find("embed.strict_surface: expected true or false"),
            std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace snh
