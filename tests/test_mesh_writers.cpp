// write_mesh: every format read_mesh reads back gives the same vertices
// (bit for bit) and elements (same order, same node order), for a hex8
// lattice and a tet4 mesh, with the groups and arrays each format carries and
// without those it cannot; bad extensions and meshes are errors that name
// the path and leave no file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "snh/error.h"
#include "snh/mesh.h"
#include "snh/mesh_io.h"
#include "support/errors.h"

namespace snh {
namespace {

using test::contains;
using test::error_of;

namespace fs = std::filesystem;

class TempDir {
 public:
  TempDir() {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("snh_write_mesh_" + std::string(test->name()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

// Coordinates no short decimal holds (thirds, sevenths, tiny and huge
// offsets), so that a writer with too few digits shows.
Mesh with_awkward_coordinates(Mesh m) {
  double* x = m.positions.data();
  for (size_t i = 0; i < 3 * m.vertex_count(); ++i)
    x[i] = x[i] / 3.0 + 0.01 * std::sin(1.7 * double(i) + 0.3) + 1e-13 / 7.0 * double(i % 5);
  return m;
}

std::vector<int32_t> vertices_where(const Mesh& m, const std::function<bool(const std::array<double, 3>&)>& keep) {
  std::vector<int32_t> out;
  for (size_t v = 0; v < m.vertex_count(); ++v)
    if (keep(m.vertex(v))) out.push_back(static_cast<int32_t>(v));
  return out;
}

// Groups of every dimension on a mesh of the unit-spaced lattice `rest`
// (selected at rest, before the coordinates are disturbed), sorted by
// dimension then tag as read_mesh lists them; a vertex in two volume groups;
// named and unnamed groups; names with spaces and quotes.
std::vector<MeshGroup> groups_for(const Mesh& rest) {
  std::vector<MeshGroup> groups;
  groups.push_back({"corner", 4, 0, {0}, {}});
  groups.push_back({"front edge", 3, 1, vertices_where(rest, [](auto x) { return x[1] == 0.0 && x[2] == 0.0; }), {}});
  groups.push_back({"", 1, 2, vertices_where(rest, [](auto x) { return x[2] == 0.0; }), {}});
  MeshGroup left{"left \"half\"", 1, 3, {}, {}}, all{"all", 2, 3, {}, {}};
  const int n = nodes_per_element(rest.type);
  for (size_t e = 0; e < rest.element_count(); ++e) {
    double x = 0.0;
    for (int a = 0; a < n; ++a) x += rest.positions(rest.elements[n * e + a], 0) / n;
    if (x < 1.5) left.elements.push_back(static_cast<int32_t>(e));
    all.elements.push_back(static_cast<int32_t>(e));
  }
  for (MeshGroup* g : {&left, &all}) {
    for (int32_t e : g->elements)
      g->vertices.insert(g->vertices.end(), &rest.elements[n * e], &rest.elements[n * e] + n);
    std::sort(g->vertices.begin(), g->vertices.end());
    g->vertices.erase(std::unique(g->vertices.begin(), g->vertices.end()), g->vertices.end());
  }
  groups.push_back(left);
  groups.push_back(all);
  return groups;
}

std::vector<MeshArray> arrays_for(size_t count, bool cells) {
  std::vector<MeshArray> arrays;
  MeshArray scalar{cells ? "phase" : "temperature", 1, {}}, vector{"displacement field", 3, {}};
  MeshArray odd{"a&b <c>%", 2, {}}, wide{"wide", 65, std::vector<double>(65 * count, 0.5)};
  for (size_t i = 0; i < count; ++i) {
    scalar.values.push_back(1.0 / (3.0 + double(i)));
    for (int d = 0; d < 3; ++d) vector.values.push_back(std::exp(-double(i + d)) * (d == 1 ? -1e-300 : 1e300));
    odd.values.insert(odd.values.end(), {double(i), std::sqrt(2.0) * double(i)});
  }
  arrays.push_back(scalar);
  arrays.push_back(vector);
  arrays.push_back(odd);
  arrays.push_back(wide);                                      // more components than the VTK readers take: left out
  arrays.push_back({"", 1, std::vector<double>(count, 1.0)});  // no name: left out
  arrays.push_back({"phase", 1, std::vector<double>(count, 2.0)});  // a second "phase" (cells): left out
  return arrays;
}

// The arrays a VTK reader gets back: named, first of their name, at most 64 components.
std::vector<MeshArray> carried(const std::vector<MeshArray>& arrays) {
  std::vector<MeshArray> out;
  for (const MeshArray& a : arrays)
    if (!a.name.empty() && a.components <= 64 &&
        std::none_of(out.begin(), out.end(), [&](const MeshArray& b) { return b.name == a.name; }))
      out.push_back(a);
  return out;
}

void expect_same_arrays(const std::vector<MeshArray>& got, const std::vector<MeshArray>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].name, want[i].name);
    EXPECT_EQ(got[i].components, want[i].components) << want[i].name;
    EXPECT_EQ(got[i].values, want[i].values) << want[i].name;
  }
}

void expect_same_groups(const std::vector<MeshGroup>& got, const std::vector<MeshGroup>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    SCOPED_TRACE("group " + std::to_string(i) + " '" + want[i].name + "'");
    EXPECT_EQ(got[i].name, want[i].name);
    EXPECT_EQ(got[i].tag, want[i].tag);
    EXPECT_EQ(got[i].dimension, want[i].dimension);
    EXPECT_EQ(got[i].vertices, want[i].vertices);
    EXPECT_EQ(got[i].elements, want[i].elements);
  }
}

// What Medit keeps: reference numbers of curve, surface and volume groups,
// named by their number; not point groups, and not a volume group sharing
// elements with one before it.
std::vector<MeshGroup> medit_groups(const std::vector<MeshGroup>& groups) {
  std::vector<MeshGroup> out;
  for (const MeshGroup& g : groups) {
    if (g.dimension == 0 || g.name == "all") continue;
    out.push_back(g);
    out.back().name = std::to_string(g.tag);
  }
  return out;
}

Mesh with_groups_and_arrays(const Mesh& rest) {
  Mesh m = with_awkward_coordinates(rest);
  m.groups = groups_for(rest);
  m.point_arrays = arrays_for(m.vertex_count(), false);
  m.cell_arrays = arrays_for(m.element_count(), true);
  validate_mesh(m);
  return m;
}

void expect_round_trips(const Mesh& m, const TempDir& dir) {
  std::vector<std::string> names = {"m.msh", "m.vtk", "m.vtu", "m.mesh", "M.MSH"};
  if (m.type == ElementType::tet4) names.insert(names.end(), {"t.node", "u.ele"});
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    const std::string path = dir.file(name);
    write_mesh(path, m);
    const Mesh back = read_mesh(path);
    EXPECT_EQ(back.type, m.type);
    EXPECT_EQ(back.positions, m.positions);  // == on doubles: exact
    EXPECT_EQ(back.elements, m.elements);    // same order, same node order
    const std::string ext = name.substr(name.find('.'));
    if (ext == ".msh" || ext == ".MSH") {
      expect_same_groups(back.groups, m.groups);
    } else if (ext == ".mesh") {
      expect_same_groups(back.groups, medit_groups(m.groups));
    } else {
      EXPECT_TRUE(back.groups.empty());
    }
    if (ext == ".vtk" || ext == ".vtu") {
      expect_same_arrays(back.point_arrays, carried(m.point_arrays));
      expect_same_arrays(back.cell_arrays, carried(m.cell_arrays));
    } else {
      EXPECT_TRUE(back.point_arrays.empty());
      EXPECT_TRUE(back.cell_arrays.empty());
    }
  }
  // Either file of a TetGen pair names both.
  if (m.type == ElementType::tet4) {
    EXPECT_TRUE(fs::exists(dir.file("t.ele")));
    EXPECT_TRUE(fs::exists(dir.file("u.node")));
  }
}

TEST(WriteMesh, EveryFormatGivesBackAHexLattice) {
  TempDir dir;
  expect_round_trips(with_groups_and_arrays(make_box_lattice(3, 2, 2, 1.0)), dir);
  // A generated lattice without groups or arrays reads back without any.
  const Mesh plain = with_awkward_coordinates(make_box_lattice(2, 2, 1, 1.0));
  for (const char* name : {"p.msh", "p.vtk", "p.vtu", "p.mesh"}) {
    write_mesh(dir.file(name), plain);
    const Mesh back = read_mesh(dir.file(name));
    EXPECT_EQ(back.positions, plain.positions) << name;
    EXPECT_EQ(back.elements, plain.elements) << name;
    EXPECT_TRUE(back.groups.empty() && back.point_arrays.empty() && back.cell_arrays.empty()) << name;
  }
}

TEST(WriteMesh, EveryFormatGivesBackATetMesh) {
  TempDir dir;
  // Every tet's node order must survive (a reader turns over only mirrored tets).
  expect_round_trips(with_groups_and_arrays(make_tet_box(3, 2, 2, 1.0)), dir);
}

TEST(WriteMesh, GroupsAFormatCannotKeepAreLeftOut) {
  TempDir dir;
  const Mesh rest = make_box_lattice(2, 1, 1, 1.0);
  Mesh m = rest;
  // Tag 0 (gmsh's and Medit's "no group"); a volume group whose vertices are
  // not its elements'; a surface group with a vertex on no face inside it
  // (two opposite corners of a cube); a repeated (dimension, tag).
  m.groups = {{"opposite corners", 5, 2, {0, 7}, {}},
              {"none", 0, 3, {0, 1, 3, 4, 6, 7, 9, 10}, {0}},
              {"extra vertex", 6, 3, {0, 1, 2, 3, 4, 6, 7, 9, 10}, {0}},
              {"first", 7, 3, {0, 1, 3, 4, 6, 7, 9, 10}, {0}},
              {"again", 7, 3, {1, 2, 4, 5, 7, 8, 10, 11}, {1}}};
  validate_mesh(m);
  write_mesh(dir.file("m.msh"), m);
  expect_same_groups(read_mesh(dir.file("m.msh")).groups, {m.groups[3]});
  write_mesh(dir.file("m.mesh"), m);
  MeshGroup seven = m.groups[3];
  seven.name = "7";
  expect_same_groups(read_mesh(dir.file("m.mesh")).groups, {seven});
}

TEST(WriteMesh, BadExtensionsAndMeshesAreErrorsThatWriteNothing) {
  TempDir dir;
  const Mesh hexes = make_box_lattice(1, 1, 1, 1.0);
  std::string e = error_of([&] { write_mesh(dir.file("lattice.obj"), hexes); });
  EXPECT_TRUE(contains(e, "lattice.obj: unknown mesh format '.obj'")) << e;
  EXPECT_TRUE(contains(e, ".msh, .vtk, .vtu, .mesh")) << e;
  e = error_of([&] { write_mesh(dir.file("lattice"), hexes); });
  EXPECT_TRUE(contains(e, "unknown mesh format (no extension)")) << e;
  e = error_of([&] { write_mesh(dir.file("lattice.node"), hexes); });
  EXPECT_TRUE(contains(e, "lattice.node: TetGen .node/.ele files hold only tetrahedra, and this mesh is hex8")) << e;
  Mesh inverted = hexes;
  std::swap(inverted.elements[0], inverted.elements[1]);
  e = error_of([&] { write_mesh(dir.file("bad.vtk"), inverted); });
  EXPECT_TRUE(contains(e, "write_mesh " + dir.file("bad.vtk") + ": ")) << e;
  Mesh short_array = hexes;
  short_array.point_arrays.push_back({"t", 1, {1.0}});
  e = error_of([&] { write_mesh(dir.file("bad.vtu"), short_array); });
  EXPECT_TRUE(contains(e, "point array 't' has 1 values")) << e;
  e = error_of([&] { write_mesh(dir.file("missing/folder/m.msh"), hexes); });
  EXPECT_TRUE(contains(e, "cannot write")) << e;
  for (const char* name : {"lattice.obj", "lattice", "lattice.node", "lattice.ele", "bad.vtk", "bad.vtu"})
    EXPECT_FALSE(fs::exists(dir.file(name))) << name;
}

}  // namespace
}  // namespace snh
