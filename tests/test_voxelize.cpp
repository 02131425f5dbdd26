// voxelize: which grid cells become elements (centres inside, checked
// against exact shapes and an independent winding number, ties on edges and
// vertices included), how the lattice's volume converges to the surface's,
// that material on the two sides of a slit thinner than a cell is not glued,
// and `snh-gpu-bench voxelize` writing a lattice read_mesh reads back, in
// every format write_mesh writes.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "snh/error.h"
#include "snh/mesh.h"
#include "snh/mesh_io.h"
#include "snh/scene.h"
#include "snh/surface.h"
#include "support/errors.h"
#include "support/surface_shapes.h"

namespace snh {
namespace {

using test::error_of;

namespace fs = std::filesystem;

std::array<double, 3> centre(const Voxelization& v, const std::array<int, 3>& g) {
  return {v.origin[0] + (g[0] + 0.5) * v.cell, v.origin[1] + (g[1] + 0.5) * v.cell,
          v.origin[2] + (g[2] + 0.5) * v.cell};
}

// The lattice is a valid hex8 mesh of cubes of side `cell` at their grid cells.
void expect_consistent(const Voxelization& v) {
  const Mesh& m = v.lattice;
  EXPECT_TRUE(validate_mesh(m).unused_vertices.empty());
  ASSERT_EQ(v.element_cell.size(), m.element_count());
  // VTK order: bottom face counter-clockwise from +z (corners 0, 1, 3, 2 of the cube), then the top.
  const int corner[8] = {0, 1, 3, 2, 4, 5, 7, 6};
  for (size_t e = 0; e < m.element_count(); ++e)
    for (int n = 0; n < 8; ++n)
      for (int d = 0; d < 3; ++d)
        ASSERT_DOUBLE_EQ(m.positions(m.elements[8 * e + n], d),
                         v.origin[d] + v.cell * (v.element_cell[e][d] + ((corner[n] >> d) & 1)))
            << "element " << e << " node " << n;
  EXPECT_NEAR(mesh_volume(m, m.positions), m.element_count() * std::pow(v.cell, 3), 1e-9 * m.element_count());
}

// Pieces of the elements for which `keep` holds, joined through shared vertices.
int pieces(const Mesh& m, const std::function<bool(size_t)>& keep) {
  std::vector<size_t> parent(m.element_count());
  std::iota(parent.begin(), parent.end(), 0);
  const std::function<size_t(size_t)> find = [&](size_t x) { return parent[x] == x ? x : parent[x] = find(parent[x]); };
  std::map<int32_t, size_t> first;
  for (size_t e = 0; e < m.element_count(); ++e) {
    if (!keep(e)) continue;
    for (int n = 0; n < 8; ++n) {
      const auto [it, added] = first.emplace(m.elements[8 * e + n], e);
      if (!added) parent[find(e)] = find(it->second);
    }
  }
  int count = 0;
  for (size_t e = 0; e < m.element_count(); ++e)
    if (keep(e) && find(e) == e) ++count;
  return count;
}

TEST(Voxelize, BoxWithSidesOfWholeCellsIsFilledExactly) {
  const Voxelization v = voxelize(test::box_surface({0.5, -1, 2}, {1.5, -0.5, 2.75}), 0.25);
  EXPECT_EQ(v.dims, (std::array<int, 3>{4, 2, 3}));
  EXPECT_EQ(v.origin, (std::array<double, 3>{0.5, -1, 2}));
  EXPECT_EQ(v.lattice.element_count(), 24u);
  EXPECT_EQ(v.lattice.vertex_count(), 5u * 3u * 4u);
  EXPECT_EQ(v.components, 1);
  expect_consistent(v);
  // The same cubes, in the same order, as the box generator.
  const Mesh box = make_box_lattice(4, 2, 3, 0.25, {0.5, -1, 2});
  for (size_t e = 0; e < 24; ++e)
    for (int n = 0; n < 8; ++n)
      EXPECT_EQ(v.lattice.vertex(v.lattice.elements[8 * e + n]), box.vertex(box.elements[8 * e + n]));
}

TEST(Voxelize, RaysThroughEdgesAndVerticesCountOnce) {
  // Cell centres at 1/6, 1/2, 5/6: every row of centres along an axis runs
  // through the diagonal edges of two box faces.
  const Voxelization box = voxelize(test::box_surface({0, 0, 0}, {1, 1, 1}), 1.0 / 3.0);
  EXPECT_EQ(box.lattice.element_count(), 27u);
  EXPECT_EQ(box.lattice.vertex_count(), 64u);
  expect_consistent(box);

  // Centres at -0.8, -0.4, 0, 0.4, 0.8: rows through the octahedron's
  // vertices (1, 0, 0) ... and along its edges in the coordinate planes;
  // no centre on its faces (|x| + |y| + |z| is a multiple of 0.4).
  const Voxelization oct = voxelize(test::octahedron(1.0), 0.4);
  ASSERT_EQ(oct.dims, (std::array<int, 3>{5, 5, 5}));
  std::set<std::array<int, 3>> expected, kept(oct.element_cell.begin(), oct.element_cell.end());
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) {
        const auto c = centre(oct, {i, j, k});
        if (std::abs(c[0]) + std::abs(c[1]) + std::abs(c[2]) < 1.0) expected.insert({i, j, k});
      }
  EXPECT_EQ(kept, expected);
  EXPECT_EQ(kept.size(), 25u);  // 1 + 6 (distance 0.4) + 12 (0.8 along two axes) + 6 (0.8 along one)
  expect_consistent(oct);
}

TEST(Voxelize, SphereVolumeErrorIsBoundedByAreaTimesCell) {
  const TriangleSurface sphere = test::icosphere(4, 1.0);
  const double volume = enclosed_volume(sphere), area = surface_area(sphere);
  // |V_lattice - V| <= C A h. A layer of cells of thickness h/2 along the
  // surface bounds it with C = 1/2; cells inside and outside cancel to much
  // less: measured C = 0.094, 0.035, 0.023, 0.010 for h = R/5 ... R/40.
  double first = 0.0, last = 0.0;
  for (const double h : {0.2, 0.1, 0.05, 0.025}) {
    const Voxelization v = voxelize(sphere, h);
    const double error = std::abs(v.lattice.element_count() * h * h * h - volume);
    std::printf("h %.3f: %zu cells, |V_lattice - V| = %.3e = %.4f A h\n", h, v.lattice.element_count(), error,
                error / (area * h));
    EXPECT_LE(error, 0.12 * area * h) << "h = " << h;
    EXPECT_EQ(v.components, 1);
    if (h == 0.2) first = error;
    last = error;
  }
  EXPECT_LT(last, first / 8);
}

TEST(Voxelize, ElementCentresAreInsideAndDeepPointsAreCovered) {
  const TriangleSurface sphere = test::icosphere(3, 1.0);
  // Face planes of the convex polyhedron: inside is n . p < d for all faces.
  std::vector<std::array<double, 4>> planes;
  for (size_t t = 0; t < sphere.triangle_count(); ++t) {
    const double* a = sphere.positions.data() + 3 * sphere.triangles[3 * t];
    const double* b = sphere.positions.data() + 3 * sphere.triangles[3 * t + 1];
    const double* c = sphere.positions.data() + 3 * sphere.triangles[3 * t + 2];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& x : n) x /= len;
    planes.push_back({n[0], n[1], n[2], n[0] * a[0] + n[1] * a[1] + n[2] * a[2]});
  }
  const auto depth = [&](const std::array<double, 3>& p) {  // distance to the surface, positive inside
    double d = 1e300;
    for (const auto& f : planes) d = std::min(d, f[3] - (f[0] * p[0] + f[1] * p[1] + f[2] * p[2]));
    return d;
  };
  for (const double h : {0.1, 0.07}) {
    const Voxelization v = voxelize(sphere, h);
    expect_consistent(v);
    for (const auto& g : v.element_cell) ASSERT_GT(depth(centre(v, g)), 0.0) << g[0] << " " << g[1] << " " << g[2];
    // A point deeper than half a cell's diagonal has its cell's centre inside.
    const std::set<std::array<int, 3>> kept(v.element_cell.begin(), v.element_cell.end());
    std::mt19937 random(12);
    std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
    int deep = 0;
    for (int n = 0; n < 20000; ++n) {
      const std::array<double, 3> p = {coordinate(random), coordinate(random), coordinate(random)};
      if (depth(p) <= std::sqrt(3.0) * h / 2) continue;
      ++deep;
      std::array<int, 3> g;
      for (int d = 0; d < 3; ++d) g[d] = static_cast<int>(std::floor((p[d] - v.origin[d]) / h));
      ASSERT_TRUE(kept.count(g)) << "point " << p[0] << " " << p[1] << " " << p[2] << " lies in no element";
    }
    EXPECT_GT(deep, 5000);
  }
}

TEST(Voxelize, CellsMatchAnIndependentWindingNumber) {
  const fs::path data = fs::path(SNH_DATA_DIR) / "surfaces";
  const struct {
    const char* name;
    TriangleSurface surface;
    double cell;
  } cases[] = {{"slit box (code)", test::slit_box(0.04, 0.5, 0.6), 0.1},
               {"slit_box.stl", read_surface((data / "slit_box.stl").string()), 0.05},
               {"sphere.ply", read_surface((data / "sphere.ply").string()), 0.06},
               {"icosphere, coarse cells", test::icosphere(2, 1.0), 0.3}};
  for (const auto& c : cases) {
    const Voxelization v = voxelize(c.surface, c.cell);
    expect_consistent(v);
    const std::set<std::array<int, 3>> kept(v.element_cell.begin(), v.element_cell.end());
    for (int k = 0; k < v.dims[2]; ++k)
      for (int j = 0; j < v.dims[1]; ++j)
        for (int i = 0; i < v.dims[0]; ++i) {
          const double w = test::winding_number(c.surface, centre(v, {i, j, k}));
          ASSERT_LT(std::abs(w - std::round(w)), 1e-6) << c.name << ": a centre on the surface";
          EXPECT_EQ(kept.count({i, j, k}) == 1, w > 0.5) << c.name << ": cell " << i << " " << j << " " << k;
        }
  }
}

// The slot's two sides (cell centres at x < 0.5 and x > 0.5) share lattice
// vertices only at or below the slot's bottom (z = 0.5, a cell face): the
// cells whose bottom is above it are two pieces, joined through the material
// below (and the vertices at the slot's bottom) into one lattice.
void expect_slit_cut(const TriangleSurface& slit, const TriangleSurface& solid, double h) {
  const Voxelization v = voxelize(slit, h), w = voxelize(solid, h);
  expect_consistent(v);
  // The slot is thinner than a cell and holds no centre: the same cells.
  EXPECT_EQ(v.element_cell, w.element_cell);
  EXPECT_GT(v.lattice.vertex_count(), w.lattice.vertex_count());
  const auto x_of = [&](const Voxelization& l, size_t e) { return centre(l, l.element_cell[e])[0]; };
  const auto z_of = [&](const Voxelization& l, size_t e) { return centre(l, l.element_cell[e])[2]; };
  std::vector<int> side(v.lattice.vertex_count(), 0);  // bit 0: a left element uses it, bit 1: a right one
  for (size_t e = 0; e < v.lattice.element_count(); ++e)
    for (int n = 0; n < 8; ++n) side[v.lattice.elements[8 * e + n]] |= x_of(v, e) < 0.5 ? 1 : 2;
  int shared = 0;
  for (size_t p = 0; p < side.size(); ++p)
    if (side[p] == 3) {
      ++shared;
      EXPECT_LE(v.lattice.positions(p, 2), 0.5 + 1e-9) << "vertex " << p << " glues the slot's sides";
    }
  EXPECT_GT(shared, 0);
  EXPECT_EQ(v.components, 1);
  EXPECT_EQ(pieces(v.lattice, [&](size_t e) { return z_of(v, e) > 0.5 + h; }), 2);
  // Without the slot, the same cells are one piece.
  EXPECT_EQ(w.components, 1);
  EXPECT_EQ(pieces(w.lattice, [&](size_t e) { return z_of(w, e) > 0.5 + h; }), 1);
}

TEST(Voxelize, SlitThinnerThanACellIsNotGlued) {
  expect_slit_cut(test::slit_box(0.04, 0.5, 0.6), test::box_surface({0, 0, 0}, {1, 0.6, 1}), 0.1);
  // gmsh's slit box, 0.04 wide from z = 0.5 up, in floats.
  const fs::path data = fs::path(SNH_DATA_DIR) / "surfaces";
  expect_slit_cut(read_surface((data / "slit_box.stl").string()), test::box_surface({0, 0, 0}, {1, 0.6, 1}), 0.05);
}

// cover_surface: the centre-inside cells plus exactly the cells the surface
// passes through, so that the lattice covers the solid and every surface
// vertex lies in its element (no extrapolation); one connected piece.
TEST(Voxelize, CoverSurfaceAddsTheCellsTheSurfaceCrosses) {
  const TriangleSurface sphere = test::icosphere(3, 1.0);
  std::vector<std::array<double, 4>> planes;  // the convex polyhedron's faces: inside is n . p < d
  for (size_t t = 0; t < sphere.triangle_count(); ++t) {
    const double* a = sphere.positions.data() + 3 * sphere.triangles[3 * t];
    const double* b = sphere.positions.data() + 3 * sphere.triangles[3 * t + 1];
    const double* c = sphere.positions.data() + 3 * sphere.triangles[3 * t + 2];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& x : n) x /= len;
    planes.push_back({n[0], n[1], n[2], n[0] * a[0] + n[1] * a[1] + n[2] * a[2]});
  }
  const auto depth = [&](const std::array<double, 3>& p) {  // > 0 inside; outside, -depth <= the distance
    double d = 1e300;
    for (const auto& f : planes) d = std::min(d, f[3] - (f[0] * p[0] + f[1] * p[1] + f[2] * p[2]));
    return d;
  };
  VoxelizeOptions cover;
  cover.cover_surface = true;
  for (const double h : {0.1, 0.07}) {
    SCOPED_TRACE(h);
    const Voxelization centres = voxelize(sphere, h), v = voxelize(sphere, h, cover);
    expect_consistent(v);
    EXPECT_EQ(v.components, 1);
    const std::set<std::array<int, 3>> kept(v.element_cell.begin(), v.element_cell.end());
    for (const auto& g : centres.element_cell) EXPECT_TRUE(kept.count(g)) << g[0] << " " << g[1] << " " << g[2];
    EXPECT_GT(v.element_cell.size(), centres.element_cell.size());
    // Kept cells reach the solid (centre within half a diagonal of it);
    // dropped cells near it hold none of its points (3 x 3 x 3 samples of
    // the cube: corners, edge and face midpoints, centre).
    const double reach = std::sqrt(3.0) * h / 2;
    for (int k = 0; k < v.dims[2]; ++k)
      for (int j = 0; j < v.dims[1]; ++j)
        for (int i = 0; i < v.dims[0]; ++i) {
          const std::array<double, 3> c = centre(v, {i, j, k});
          const double dc = depth(c);
          if (kept.count({i, j, k})) {
            ASSERT_GE(dc, -reach - 1e-12) << i << " " << j << " " << k;
            continue;
          }
          if (dc < -reach) continue;  // farther than half a diagonal: the cube is outside
          for (int s = 0; s < 27; ++s) {
            const std::array<double, 3> p = {c[0] + h * ((s % 3) / 2.0 - 0.5), c[1] + h * ((s / 3 % 3) / 2.0 - 0.5),
                                             c[2] + h * ((s / 9) / 2.0 - 0.5)};
            ASSERT_LE(depth(p), 1e-12) << "cell " << i << " " << j << " " << k << " dropped with a point inside";
          }
        }
    EXPECT_GE(mesh_volume(v.lattice, v.lattice.positions), enclosed_volume(sphere));
    // Every surface vertex lies in its element's cube: weights in [0, 1].
    const Embedding e = embed(v, sphere);
    for (size_t i = 0; i < sphere.vertex_count(); ++i) {
      const auto& g = v.element_cell[e.element[i]];
      for (int d = 0; d < 3; ++d) {
        const double u = (sphere.positions(i, d) - v.origin[d]) / h - g[d];
        EXPECT_GE(u, -1e-9) << "vertex " << i;
        EXPECT_LE(u, 1 + 1e-9) << "vertex " << i;
      }
      for (int a = 0; a < 8; ++a) EXPECT_GE(e.weights[8 * i + a], -1e-9) << "vertex " << i;
    }
  }
  // A slit between cell centres stays open; one holding a column of centres
  // (x = 0.5 at h = 0.2) is glued through those cells, which the surface
  // crosses; without cover_surface they are dropped and the slit is open.
  const TriangleSurface slit = test::slit_box(0.04, 0.5, 0.6);
  const auto pieces_above = [](const Voxelization& l, double z) {
    return pieces(l.lattice, [&](size_t e) { return centre(l, l.element_cell[e])[2] > z; });
  };
  EXPECT_EQ(pieces_above(voxelize(slit, 0.1, cover), 0.6), 2);
  EXPECT_EQ(pieces_above(voxelize(slit, 0.2, cover), 0.7), 1);
  EXPECT_EQ(pieces_above(voxelize(slit, 0.2), 0.7), 2);
}

// The slit lattice keeps two copies of the vertices on the slit's plane, at
// the same positions: every format write_mesh writes gives it back when
// coincident vertices are allowed (by default a reader refuses them and
// names the option), and a scene file reads it with
// mesh.allow_coincident_vertices.
TEST(Voxelize, SlitLatticeReadsBackWithCoincidentVerticesAllowed) {
  const Voxelization v = voxelize(test::slit_box(0.04, 0.5, 0.6), 0.1);
  const fs::path dir = fs::temp_directory_path() / ("snh_slit_lattice_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  MeshReadOptions allow;
  allow.allow_coincident_vertices = true;
  for (const char* name : {"slit.msh", "slit.vtk", "slit.vtu", "slit.mesh"}) {
    SCOPED_TRACE(name);
    const std::string path = (dir / name).string();
    write_mesh(path, v.lattice);
    const std::string refused = error_of([&] { read_mesh(path); });
    EXPECT_NE(refused.find("duplicates vertex"), std::string::npos) << refused;
    EXPECT_NE(refused.find("MeshReadOptions::allow_coincident_vertices"), std::string::npos) << refused;
    const Mesh back = read_mesh(path, allow);
    EXPECT_EQ(back.positions, v.lattice.positions);
    EXPECT_EQ(back.elements, v.lattice.elements);
  }
  const auto scene = [&](const std::string& extra) {
    const fs::path file = dir / "slit_scene.json";
    std::ofstream(file) << R"({"mesh": {"file": "slit.vtu")" << extra << "}}";
    return file.string();
  };
  EXPECT_EQ(load_scene(scene(R"(, "allow_coincident_vertices": true)")).scene.mesh.elements, v.lattice.elements);
  EXPECT_NE(error_of([&] { load_scene(scene("")); }).find("duplicates vertex"), std::string::npos);
  EXPECT_NE(error_of([&] {
              load_scene(scene(R"(, "allow_coincident_vertices": 1)"));
            }).find("mesh.allow_coincident_vertices: expected true or false"),
            std::string::npos);
  fs::remove_all(dir);
}

TEST(Voxelize, BadCellSizesAndAbsurdGridsAreErrors) {
  const TriangleSurface sphere = test::icosphere(1, 1.0);
  for (const double h : {0.0, -0.1, std::nan(""), HUGE_VAL}) {
    const std::string e = error_of([&] { voxelize(sphere, h); });
    EXPECT_NE(e.find("cell size must be positive and finite"), std::string::npos) << e;
  }
  const std::string big = error_of([&] { voxelize(sphere, 1e-6); });
  EXPECT_NE(big.find("more than the limit of"), std::string::npos) << big;
  EXPECT_NE(big.find("use a larger cell"), std::string::npos) << big;
  VoxelizeOptions small;
  small.max_grid_cells = 100;
  const std::string limit = error_of([&] { voxelize(sphere, 0.2, small); });
  EXPECT_NE(limit.find("10 x 10 x 10"), std::string::npos) << limit;
  EXPECT_NE(limit.find("limit of 100"), std::string::npos) << limit;
  EXPECT_EQ(voxelize(sphere, 0.5, small).dims, (std::array<int, 3>{4, 4, 4}));
  // One cell of side 10 from the corner (-1, -1, -1): its centre (4, 4, 4) is outside.
  const std::string empty = error_of([&] { voxelize(test::octahedron(1.0), 10.0); });
  EXPECT_NE(empty.find("no cell centre lies inside"), std::string::npos) << empty;
}

#ifdef SNH_BENCH_BINARY
TEST(VoxelizeCommand, WritesALatticeThatReadMeshReadsBack) {
  const fs::path dir = fs::temp_directory_path() / ("snh_voxelize_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path surface = fs::path(SNH_DATA_DIR) / "surfaces" / "sphere.stl";
  const auto run = [](const std::string& arguments, std::string& text) {
    FILE* pipe = popen((std::string(SNH_BENCH_BINARY) + " " + arguments + " 2>&1").c_str(), "r");
    if (!pipe) return -1;
    char buffer[4096];
    size_t n;
    while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) text.append(buffer, n);
    const int status = pclose(pipe);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  };
  std::string text;
  ASSERT_EQ(run("voxelize " + surface.string() + " --cell 0.1 --out " + (dir / "sphere.vtu").string(), text), 0)
      << text;
  std::map<std::string, double> value;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    const size_t colon = line.find(": ");
    if (colon != std::string::npos) value[line.substr(0, colon)] = std::atof(line.c_str() + colon + 2);
  }
  const Mesh back = read_mesh((dir / "sphere.vtu").string());
  const Voxelization v = voxelize(read_surface(surface.string()), 0.1);
  EXPECT_EQ(back.element_count(), v.lattice.element_count());
  EXPECT_EQ(value["cells"], double(back.element_count())) << text;
  EXPECT_EQ(value["vertices"], double(back.vertex_count())) << text;
  EXPECT_EQ(value["components"], 1.0) << text;
  EXPECT_EQ(value["coincident vertices"], 0.0) << text;
  EXPECT_NEAR(value["lattice volume"], mesh_volume(back, back.positions), 1e-5) << text;
  EXPECT_NEAR(value["enclosed volume"], enclosed_volume(read_surface(surface.string())), 1e-5) << text;
  ASSERT_EQ(back.cell_arrays.size(), 1u);
  EXPECT_EQ(back.cell_arrays[0].name, "grid_cell");
  for (size_t e = 0; e < v.element_cell.size(); ++e)
    for (int d = 0; d < 3; ++d) EXPECT_EQ(back.cell_arrays[0].values[3 * e + d], v.element_cell[e][d]);

  // The other formats by their extension: the same lattice exactly (the
  // grid_cell array where the format carries arrays).
  for (const char* name : {"sphere.msh", "sphere.vtk", "sphere.mesh", "sphere.VTU"}) {
    SCOPED_TRACE(name);
    std::string out;
    ASSERT_EQ(run("voxelize " + surface.string() + " --cell 0.1 --out " + (dir / name).string(), out), 0) << out;
    const Mesh other = read_mesh((dir / name).string());
    EXPECT_EQ(other.positions, v.lattice.positions);
    EXPECT_EQ(other.elements, v.lattice.elements);
    const bool arrays = std::string(name) != "sphere.msh" && std::string(name) != "sphere.mesh";
    ASSERT_EQ(other.cell_arrays.size(), arrays ? 1u : 0u);
    if (arrays) {
      EXPECT_EQ(other.cell_arrays[0].values, back.cell_arrays[0].values);
    }
  }
  // gmsh's slit box at h = 0.05: the vertices on the slit's plane above its
  // bottom come twice, as the library's lattice has them.
  std::string slit;
  const fs::path slit_surface = fs::path(SNH_DATA_DIR) / "surfaces" / "slit_box.stl";
  ASSERT_EQ(run("voxelize " + slit_surface.string() + " --cell 0.05 --out " + (dir / "slit.msh").string(), slit), 0)
      << slit;
  MeshReadOptions allow;
  allow.allow_coincident_vertices = true;
  const Mesh slit_back = read_mesh((dir / "slit.msh").string(), allow);
  EXPECT_EQ(slit_back.positions, voxelize(read_surface(slit_surface.string()), 0.05).lattice.positions);
  std::map<std::array<double, 3>, int> at;
  for (size_t i = 0; i < slit_back.vertex_count(); ++i) ++at[slit_back.vertex(i)];
  int coincident = 0;
  for (const auto& [position, count] : at) coincident += count > 1 ? count : 0;
  EXPECT_GT(coincident, 0);
  EXPECT_NE(slit.find("coincident vertices: " + std::to_string(coincident) +
                      " (read the lattice back with MeshReadOptions::allow_coincident_vertices"),
            std::string::npos)
      << slit;

  std::string covered;
  ASSERT_EQ(run("voxelize " + surface.string() + " --cell 0.1 --cover-surface --out " + (dir / "cover.vtu").string(),
                covered),
            0)
      << covered;
  VoxelizeOptions cover;
  cover.cover_surface = true;
  EXPECT_EQ(read_mesh((dir / "cover.vtu").string()).elements,
            voxelize(read_surface(surface.string()), 0.1, cover).lattice.elements);
  EXPECT_GT(read_mesh((dir / "cover.vtu").string()).element_count(), back.element_count());

  std::string bad;
  EXPECT_NE(run("voxelize " + surface.string() + " --cell 0.1 --out " + (dir / "sphere.obj").string(), bad), 0);
  EXPECT_NE(bad.find("unknown mesh format '.obj'"), std::string::npos) << bad;
  std::string tets;
  EXPECT_NE(run("voxelize " + surface.string() + " --cell 0.1 --out " + (dir / "sphere.node").string(), tets), 0);
  EXPECT_NE(tets.find("TetGen .node/.ele files hold only tetrahedra, and this mesh is hex8"), std::string::npos)
      << tets;
  EXPECT_FALSE(fs::exists(dir / "sphere.node"));
  std::string open;
  const fs::path hole = dir / "hole.obj";
  TriangleSurface box = test::box_surface({0, 0, 0}, {1, 1, 1});
  box.triangles.resize(box.triangles.size() - 3);
  write_obj(hole.string(), box);
  // By default the hole is tolerated with a warning naming the file;
  // --strict refuses it.
  EXPECT_EQ(run("voxelize " + hole.string() + " --cell 0.1 --out " + (dir / "hole.vtu").string(), open), 0) << open;
  EXPECT_NE(open.find("open edges"), std::string::npos) << open;
  EXPECT_NE(open.find("hole.obj"), std::string::npos) << open;
  EXPECT_TRUE(fs::exists(dir / "hole.vtu"));
  std::string strict;
  EXPECT_NE(run("voxelize " + hole.string() + " --cell 0.1 --strict --out " + (dir / "strict.vtu").string(), strict),
            0);
  EXPECT_NE(strict.find("open edges"), std::string::npos) << strict;
  EXPECT_FALSE(fs::exists(dir / "strict.vtu"));
  fs::remove_all(dir);
}
#endif

}  // namespace
}  // namespace snh
