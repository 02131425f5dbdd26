// Meshes: the lattice generators, validation messages that name the culprit,
// deformed volumes, and the ParaView writers.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "fem/rest_state.h"
#include "snh/error.h"
#include "snh/io.h"
#include "snh/mesh.h"
#include "support/errors.h"
#include "vtu_test_support.h"

namespace snh {
namespace {

using test::contains;
using test::error_of;

namespace fs = std::filesystem;

// The message of the snh::Error `f` throws; fails the test when it throws
// nothing.
// Signed volume of tet `e`, computed directly from its corners.
double tet_volume(const Mesh& mesh, size_t e) {
  const auto p0 = mesh.vertex(mesh.elements[4 * e]), p1 = mesh.vertex(mesh.elements[4 * e + 1]),
             p2 = mesh.vertex(mesh.elements[4 * e + 2]), p3 = mesh.vertex(mesh.elements[4 * e + 3]);
  double a[3], b[3], c[3];
  for (int d = 0; d < 3; ++d) {
    a[d] = p1[d] - p0[d];
    b[d] = p2[d] - p0[d];
    c[d] = p3[d] - p0[d];
  }
  return (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
          a[2] * (b[0] * c[1] - b[1] * c[0])) /
         6.0;
}

Points scaled(const Points& x, double s) {
  std::vector<double> out(x.xyz());
  for (double& v : out) v *= s;
  return Points::from_xyz(std::move(out));
}

// A fresh directory under the system temp directory, removed on exit.
class TempDir {
 public:
  explicit TempDir(const std::string& name) {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("snh_" + name + "_" + test->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

using test::read_array;
using test::read_text;

TEST(Mesh, ElementTypeProperties) {
  EXPECT_STREQ(to_string(ElementType::hex8), "hex8");
  EXPECT_STREQ(to_string(ElementType::tet4), "tet4");
  EXPECT_EQ(nodes_per_element(ElementType::hex8), 8);
  EXPECT_EQ(nodes_per_element(ElementType::tet4), 4);
  EXPECT_EQ(quadrature_points(ElementType::hex8), 8);
  EXPECT_EQ(quadrature_points(ElementType::tet4), 1);
}

TEST(Mesh, BoxLatticeCountsLayoutAndVolume) {
  const int nx = 3, ny = 4, nz = 5;
  const double h = 0.3;
  const std::array<double, 3> origin = {1.0, -2.0, 0.5};
  const Mesh mesh = make_box_lattice(nx, ny, nz, h, origin);
  EXPECT_EQ(mesh.type, ElementType::hex8);
  ASSERT_EQ(mesh.vertex_count(), size_t(4 * 5 * 6));
  ASSERT_EQ(mesh.element_count(), size_t(nx * ny * nz));
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        const auto v = mesh.vertex(i + (nx + 1) * (j + (ny + 1) * k));
        EXPECT_NEAR(v[0], origin[0] + h * i, 1e-14);
        EXPECT_NEAR(v[1], origin[1] + h * j, 1e-14);
        EXPECT_NEAR(v[2], origin[2] + h * k, 1e-14);
      }
  // Element 0's nodes are the first cube's corners in VTK order.
  for (int a = 0; a < 8; ++a) {
    const auto v = mesh.vertex(mesh.elements[a]);
    for (int d = 0; d < 3; ++d)
      EXPECT_NEAR(v[d], origin[d] + 0.5 * h * (1.0 + fem::kHexNodeSigns[a][d]), 1e-14) << "node " << a;
  }
  EXPECT_TRUE(validate_mesh(mesh).unused_vertices.empty());
  const double expected = nx * ny * nz * h * h * h;
  EXPECT_NEAR(mesh_volume(mesh, mesh.positions), expected, 1e-12 * expected);
  EXPECT_NEAR(fem::compute_rest_state(mesh).rest_volume, expected, 1e-12 * expected);
}

TEST(Mesh, LatticeRestStateIsUniformUntilAVertexMoves) {
  Mesh mesh = make_box_lattice(3, 3, 3, 0.1);
  EXPECT_TRUE(fem::compute_rest_state(mesh).uniform);
  EXPECT_FALSE(fem::compute_rest_state(make_tet_box(2, 2, 2, 0.1)).uniform)
      << "the six Kuhn tets of a cube differ in shape";
  // An interior vertex, shared by eight cubes.
  mesh.positions(1 + 4 * (1 + 4 * 1), 0) += 0.01;
  const fem::RestState moved = fem::compute_rest_state(mesh);
  EXPECT_FALSE(moved.uniform);
  EXPECT_NEAR(moved.rest_volume, 27e-3, 1e-15);
}

TEST(Mesh, TetBoxIsPositiveExactAndConforming) {
  const int nx = 2, ny = 3, nz = 4;
  const double h = 0.5;
  const Mesh mesh = make_tet_box(nx, ny, nz, h, {-1.0, 0.0, 2.0});
  EXPECT_EQ(mesh.type, ElementType::tet4);
  ASSERT_EQ(mesh.vertex_count(), size_t(3 * 4 * 5));
  ASSERT_EQ(mesh.element_count(), size_t(6 * nx * ny * nz));
  const double cell = h * h * h;
  for (size_t e = 0; e < mesh.element_count(); ++e) EXPECT_NEAR(tet_volume(mesh, e), cell / 6.0, 1e-14) << e;
  EXPECT_TRUE(validate_mesh(mesh).unused_vertices.empty());
  EXPECT_NEAR(mesh_volume(mesh, mesh.positions), nx * ny * nz * cell, 1e-12 * nx * ny * nz * cell);

  // Conforming: every face is shared by two tets except the boundary's, two
  // triangles per boundary square.
  std::map<std::set<int32_t>, int> faces;
  for (size_t e = 0; e < mesh.element_count(); ++e)
    for (int skip = 0; skip < 4; ++skip) {
      std::set<int32_t> face;
      for (int a = 0; a < 4; ++a)
        if (a != skip) face.insert(mesh.elements[4 * e + a]);
      ++faces[face];
    }
  int boundary = 0;
  for (const auto& [face, count] : faces) {
    EXPECT_LE(count, 2);
    boundary += count == 1;
  }
  EXPECT_EQ(boundary, 2 * 2 * (nx * ny + ny * nz + nz * nx));
}

TEST(Mesh, VoxelCylinderKeepsCellsWithinTheRadius) {
  const double radius = 1.0, length = 2.0, h = 0.25;
  const Mesh mesh = make_voxel_cylinder(radius, length, h);
  // 8 x 8 cells across; per quadrant, centre offsets {1, 3, 5, 7} h/2 keep
  // 4 + 4 + 3 + 2 columns; 8 layers.
  ASSERT_EQ(mesh.element_count(), size_t(4 * 13 * 8));
  EXPECT_TRUE(validate_mesh(mesh).unused_vertices.empty());
  const double expected = mesh.element_count() * h * h * h;
  EXPECT_NEAR(mesh_volume(mesh, mesh.positions), expected, 1e-12 * expected);

  // Every kept cell's centre lies within the radius of the z axis.
  for (size_t e = 0; e < mesh.element_count(); ++e) {
    double c[3] = {0, 0, 0};
    for (int a = 0; a < 8; ++a)
      for (int d = 0; d < 3; ++d) c[d] += mesh.vertex(mesh.elements[8 * e + a])[d] / 8.0;
    EXPECT_LE(std::hypot(c[0], c[1]), radius) << "element " << e;
  }

  // Mirror-symmetric about the axis, and spanning z in [0, length].
  std::set<std::array<double, 3>> vertices;
  double zmin = 1e9, zmax = -1e9, rmax = 0.0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const auto p = mesh.vertex(v);
    vertices.insert(p);
    zmin = std::min(zmin, p[2]);
    zmax = std::max(zmax, p[2]);
    rmax = std::max({rmax, std::abs(p[0]), std::abs(p[1])});
  }
  EXPECT_EQ(vertices.size(), mesh.vertex_count()) << "duplicate vertices";
  for (const auto& p : vertices) {
    EXPECT_TRUE(vertices.count({-p[0], p[1], p[2]})) << p[0] << " " << p[1] << " " << p[2];
    EXPECT_TRUE(vertices.count({p[0], -p[1], p[2]})) << p[0] << " " << p[1] << " " << p[2];
    EXPECT_TRUE(vertices.count({p[1], p[0], p[2]})) << p[0] << " " << p[1] << " " << p[2];
  }
  EXPECT_EQ(zmin, 0.0);
  EXPECT_NEAR(zmax, length, 1e-14);
  EXPECT_NEAR(rmax, 1.0, 1e-14);
}

TEST(Mesh, VoxelCylinderWithOddCellCountAndShortLength) {
  // 2 r / h = 4.5 -> 5 cells across, centred on the axis; length < h -> one layer.
  const double h = 0.4;
  const Mesh mesh = make_voxel_cylinder(0.9, 0.1, h);
  // Offsets {0, 1, 2} h: columns with i^2 + j^2 <= (0.9 / 0.4)^2 = 5.06.
  int columns = 0;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j) columns += i * i + j * j <= 5;
  ASSERT_EQ(mesh.element_count(), size_t(columns));
  EXPECT_TRUE(validate_mesh(mesh).unused_vertices.empty());
  EXPECT_NEAR(mesh_volume(mesh, mesh.positions), columns * h * h * h, 1e-12);
  double zmax = 0.0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) zmax = std::max(zmax, mesh.vertex(v)[2]);
  EXPECT_NEAR(zmax, h, 1e-15);
}

TEST(Mesh, DeformedVolume) {
  for (const Mesh& mesh : {make_box_lattice(2, 3, 2, 0.5), make_tet_box(2, 3, 2, 0.5)}) {
    SCOPED_TRACE(to_string(mesh.type));
    const double rest = mesh_volume(mesh, mesh.positions);
    EXPECT_NEAR(rest, 1.5, 1e-12);
    EXPECT_NEAR(mesh_volume(mesh, scaled(mesh.positions, 2.0)), 8.0 * rest, 1e-12 * rest);
    // A rotation about z by 90 degrees plus a translation keeps the volume.
    Points rotated(mesh.vertex_count());
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
      rotated(v, 0) = -mesh.positions(v, 1) + 3.0;
      rotated(v, 1) = mesh.positions(v, 0);
      rotated(v, 2) = mesh.positions(v, 2) - 1.0;
    }
    EXPECT_NEAR(mesh_volume(mesh, rotated), rest, 1e-12 * rest);
    // A mirror image is inside out.
    Points mirrored(mesh.positions);
    for (size_t v = 0; v < mesh.vertex_count(); ++v) mirrored(v, 0) = -mirrored(v, 0);
    EXPECT_NEAR(mesh_volume(mesh, mirrored), -rest, 1e-12 * rest);
  }
  const Mesh box = make_box_lattice(1, 1, 1, 1.0);
  EXPECT_THROW(mesh_volume(box, Points(1)), Error);
}

TEST(Mesh, GeneratorArgumentsAreChecked) {
  EXPECT_THROW(make_box_lattice(0, 1, 1, 1.0), Error);
  EXPECT_THROW(make_box_lattice(1, -1, 1, 1.0), Error);
  EXPECT_THROW(make_box_lattice(1, 1, 1, 0.0), Error);
  EXPECT_THROW(make_box_lattice(1, 1, 1, std::nan("")), Error);
  EXPECT_THROW(make_box_lattice(1, 1, 1, 1.0, {0.0, std::numeric_limits<double>::infinity(), 0.0}), Error);
  EXPECT_THROW(make_box_lattice(5000, 5000, 5000, 1.0), Error);
  EXPECT_THROW(make_tet_box(1, 1, 0, 1.0), Error);
  EXPECT_THROW(make_tet_box(1, 1, 1, -1.0), Error);
  EXPECT_THROW(make_voxel_cylinder(0.0, 1.0, 0.1), Error);
  EXPECT_THROW(make_voxel_cylinder(1.0, -1.0, 0.1), Error);
  EXPECT_THROW(make_voxel_cylinder(1.0, 1.0, 0.0), Error);
  EXPECT_THROW(make_voxel_cylinder(1.0, std::nan(""), 0.1), Error);
}

TEST(MeshValidation, IndexOutOfRange) {
  Mesh mesh = make_box_lattice(2, 1, 1, 1.0);  // 12 vertices
  mesh.elements[8 + 3] = 99;
  const std::string message = error_of([&] { validate_mesh(mesh); });
  EXPECT_TRUE(contains(message, "element 1 ")) << message;
  EXPECT_TRUE(contains(message, "vertex 99")) << message;
  EXPECT_TRUE(contains(message, "12 vertices")) << message;
  mesh.elements[8 + 3] = -1;
  EXPECT_TRUE(contains(error_of([&] { validate_mesh(mesh); }), "vertex -1"));
}

TEST(MeshValidation, RepeatedVertex) {
  Mesh mesh = make_box_lattice(2, 1, 1, 1.0);
  mesh.elements[8 + 5] = mesh.elements[8 + 0];
  const std::string message = error_of([&] { validate_mesh(mesh); });
  EXPECT_TRUE(contains(message, "element 1 ")) << message;
  EXPECT_TRUE(contains(message, "twice")) << message;
}

TEST(MeshValidation, NonFiniteCoordinate) {
  Mesh mesh = make_box_lattice(2, 1, 1, 1.0);
  mesh.positions(7, 1) = std::nan("");
  const std::string message = error_of([&] { validate_mesh(mesh); });
  EXPECT_TRUE(contains(message, "vertex 7 ")) << message;
  EXPECT_TRUE(contains(message, "non-finite")) << message;
  mesh.positions(7, 1) = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(contains(error_of([&] { validate_mesh(mesh); }), "vertex 7 "));
}

TEST(MeshValidation, InvertedHex) {
  for (int inverted = 0; inverted < 2; ++inverted) {
    Mesh mesh = make_box_lattice(2, 1, 1, 1.0);
    // Top and bottom faces swapped: a mirror image of the cube.
    for (int a = 0; a < 4; ++a) std::swap(mesh.elements[8 * inverted + a], mesh.elements[8 * inverted + a + 4]);
    const std::string message = error_of([&] { validate_mesh(mesh); });
    EXPECT_TRUE(contains(message, "element " + std::to_string(inverted) + " ")) << message;
    EXPECT_TRUE(contains(message, "negative")) << message;
    EXPECT_TRUE(contains(message, "inverted")) << message;
  }
}

TEST(MeshValidation, DegenerateAndInvertedTets) {
  Mesh flat;
  flat.type = ElementType::tet4;
  flat.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};  // coplanar
  flat.elements = {0, 1, 2, 3};
  std::string message = error_of([&] { validate_mesh(flat); });
  EXPECT_TRUE(contains(message, "element 0 ")) << message;
  EXPECT_TRUE(contains(message, "zero")) << message;

  Mesh tets = make_tet_box(1, 1, 1, 1.0);
  std::swap(tets.elements[4 * 4 + 1], tets.elements[4 * 4 + 2]);
  message = error_of([&] { validate_mesh(tets); });
  EXPECT_TRUE(contains(message, "element 4 ")) << message;
  EXPECT_TRUE(contains(message, "negative")) << message;
}

TEST(MeshValidation, MalformedArrays) {
  Mesh mesh = make_box_lattice(1, 1, 1, 1.0);
  mesh.elements.push_back(0);
  std::string message = error_of([&] { validate_mesh(mesh); });
  EXPECT_TRUE(contains(message, "9 indices")) << message;
  EXPECT_TRUE(contains(message, "multiple of 8")) << message;

  // Positions not three per vertex cannot make a Mesh: Points rejects them.
  mesh = make_box_lattice(1, 1, 1, 1.0);
  std::vector<double> xyz = mesh.positions.xyz();
  xyz.push_back(0.0);
  message = error_of([&] { mesh.positions = Points::from_xyz(xyz); });
  EXPECT_TRUE(contains(message, "not three per point")) << message;

  mesh = make_box_lattice(1, 1, 1, 1.0);
  mesh.elements.clear();
  EXPECT_TRUE(contains(error_of([&] { validate_mesh(mesh); }), "no elements"));
  EXPECT_TRUE(contains(error_of([] { validate_mesh(Mesh{}); }), "no vertices"));
}

TEST(MeshValidation, UnusedVerticesAreOnlyReported) {
  Mesh mesh = make_box_lattice(1, 1, 1, 1.0);
  std::vector<double> xyz = mesh.positions.release();
  xyz.insert(xyz.begin(), {5.0, 5.0, 5.0});
  for (int32_t& v : mesh.elements) ++v;
  xyz.insert(xyz.end(), {6.0, 6.0, 6.0});
  mesh.positions = Points::from_xyz(std::move(xyz));
  MeshWarnings warnings;
  ASSERT_NO_THROW(warnings = validate_mesh(mesh));
  EXPECT_EQ(warnings.unused_vertices, (std::vector<int32_t>{0, 9}));
  EXPECT_NEAR(mesh_volume(mesh, mesh.positions), 1.0, 1e-14);
}

TEST(VtuWriter, WritesAndReadsBack) {
  TempDir dir("vtu");
  const Mesh mesh = make_box_lattice(2, 1, 1, 0.1);
  Points x = mesh.positions;
  x(1, 2) += 1.0 / 3.0;  // a value that needs all 17 digits
  VtuPointField displacement{"displacement", 3, {}};
  for (size_t i = 0; i < x.xyz().size(); ++i) displacement.values.push_back(x.xyz()[i] - mesh.positions.xyz()[i]);
  VtuPointField marker{"marker", 1, std::vector<double>(mesh.vertex_count(), 2.5)};
  VtuCellField energy{"energy", {1e-300, -7.25}};
  const fs::path path = dir.path() / "box.vtu";
  write_vtu(path.string(), mesh, x, {displacement, marker}, {energy});

  const std::string vtu = read_text(path);
  EXPECT_TRUE(contains(vtu, "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">"));
  EXPECT_TRUE(contains(vtu, "NumberOfPoints=\"12\" NumberOfCells=\"2\"")) << vtu;
  EXPECT_TRUE(contains(vtu, "Name=\"displacement\" NumberOfComponents=\"3\"")) << vtu;
  EXPECT_TRUE(contains(vtu, "</VTKFile>"));
  EXPECT_EQ(read_array(vtu, "Points"), x.xyz());
  EXPECT_EQ(read_array(vtu, "displacement"), displacement.values);
  EXPECT_EQ(read_array(vtu, "marker"), marker.values);
  EXPECT_EQ(read_array(vtu, "energy"), energy.values);
  const std::vector<double> connectivity = read_array(vtu, "connectivity");
  ASSERT_EQ(connectivity.size(), mesh.elements.size());
  for (size_t i = 0; i < connectivity.size(); ++i) EXPECT_EQ(connectivity[i], mesh.elements[i]);
  EXPECT_EQ(read_array(vtu, "offsets"), (std::vector<double>{8, 16}));
  EXPECT_EQ(read_array(vtu, "types"), (std::vector<double>{12, 12}));

  const Mesh tets = make_tet_box(1, 1, 1, 1.0);
  write_vtu(path.string(), tets, tets.positions);
  const std::string tet_vtu = read_text(path);
  EXPECT_TRUE(contains(tet_vtu, "NumberOfPoints=\"8\" NumberOfCells=\"6\""));
  EXPECT_EQ(read_array(tet_vtu, "types"), std::vector<double>(6, 10));
  EXPECT_EQ(read_array(tet_vtu, "offsets"), (std::vector<double>{4, 8, 12, 16, 20, 24}));
}

TEST(VtuWriter, SizeErrorsNameTheField) {
  TempDir dir("vtu");
  const Mesh mesh = make_box_lattice(1, 1, 1, 1.0);
  const std::string path = (dir.path() / "bad.vtu").string();
  std::string message = error_of([&] {
    write_vtu(path, mesh, mesh.positions, {{"velocity", 3, std::vector<double>(23)}});
  });
  EXPECT_TRUE(contains(message, "\"velocity\"")) << message;
  EXPECT_TRUE(contains(message, path)) << message;
  message = error_of([&] { write_vtu(path, mesh, mesh.positions, {}, {{"energy", std::vector<double>(2)}}); });
  EXPECT_TRUE(contains(message, "\"energy\"")) << message;
  message = error_of([&] { write_vtu(path, mesh, mesh.positions, {{"tensor", 9, std::vector<double>(72)}}); });
  EXPECT_TRUE(contains(message, "\"tensor\"")) << message;
  message = error_of([&] { write_vtu(path, mesh, Points(7)); });
  EXPECT_TRUE(contains(message, "positions")) << message;
  EXPECT_FALSE(fs::exists(path)) << "nothing is written when the input is rejected";

  const std::string unwritable = (dir.path() / "missing" / "out.vtu").string();
  message = error_of([&] { write_vtu(unwritable, mesh, mesh.positions); });
  EXPECT_TRUE(contains(message, "cannot write " + unwritable)) << message;
}

TEST(VtuWriter, CellVectorsAndTensorsCarryTheirComponents) {
  TempDir dir("vtu");
  const Mesh mesh = make_box_lattice(2, 1, 1, 0.1);
  const fs::path path = dir.path() / "cells.vtu";
  std::vector<double> tensor(18), vector(6);
  for (size_t i = 0; i < tensor.size(); ++i) tensor[i] = 0.5 + static_cast<double>(i);
  for (size_t i = 0; i < vector.size(); ++i) vector[i] = -1.0 / (1.0 + static_cast<double>(i));
  write_vtu(path.string(), mesh, mesh.positions, {}, {{"stress", tensor, 9}, {"traction", vector, 3}, {"J", {1, 2}}});
  const std::string vtu = read_text(path);
  EXPECT_TRUE(contains(vtu, "Name=\"stress\" NumberOfComponents=\"9\"")) << vtu;
  EXPECT_TRUE(contains(vtu, "Name=\"traction\" NumberOfComponents=\"3\"")) << vtu;
  EXPECT_TRUE(contains(vtu, "Name=\"J\" format=\"ascii\"")) << vtu;  // scalars as before
  EXPECT_EQ(read_array(vtu, "stress"), tensor);
  EXPECT_EQ(read_array(vtu, "traction"), vector);

  const std::string bad = (dir.path() / "bad.vtu").string();
  std::string message = error_of([&] { write_vtu(bad, mesh, mesh.positions, {}, {{"F", std::vector<double>(9), 9}}); });
  EXPECT_TRUE(contains(message, "\"F\" has 9 values, but 2 elements x 9 components need 18")) << message;
  message = error_of([&] { write_vtu(bad, mesh, mesh.positions, {}, {{"q", std::vector<double>(8), 4}}); });
  EXPECT_TRUE(contains(message, "\"q\" has 4 components; 1, 3 or 9")) << message;
  EXPECT_FALSE(fs::exists(bad));
}

TEST(VtuWriter, FieldNamesAreEscaped) {
  TempDir dir("vtu");
  const Mesh mesh = make_box_lattice(1, 1, 1, 1.0);
  const fs::path path = dir.path() / "escaped.vtu";
  write_vtu(path.string(), mesh, mesh.positions, {}, {{"a<b & \"c\"", {1.0}}});
  EXPECT_TRUE(contains(read_text(path), "Name=\"a&lt;b &amp; &quot;c&quot;\""));
}

TEST(PvdWriter, ListsTheSteps) {
  TempDir dir("pvd");
  const fs::path path = dir.path() / "run.pvd";
  write_pvd(path.string(), {{0.0, "step_0000.vtu"}, {0.5, "step_0001.vtu"}, {1.0, "frames/step_0002.vtu"}});
  const std::string pvd = read_text(path);
  EXPECT_TRUE(contains(pvd, "<VTKFile type=\"Collection\""));
  EXPECT_TRUE(contains(pvd, "<DataSet timestep=\"0\" group=\"\" part=\"0\" file=\"step_0000.vtu\"/>")) << pvd;
  EXPECT_TRUE(contains(pvd, "timestep=\"0.5\" group=\"\" part=\"0\" file=\"step_0001.vtu\"")) << pvd;
  EXPECT_TRUE(contains(pvd, "timestep=\"1\" group=\"\" part=\"0\" file=\"frames/step_0002.vtu\"")) << pvd;
  EXPECT_TRUE(contains(pvd, "</Collection>"));

  const std::string unwritable = (dir.path() / "missing" / "run.pvd").string();
  EXPECT_TRUE(contains(error_of([&] { write_pvd(unwritable, {}); }), "cannot write " + unwritable));
  EXPECT_THROW(write_pvd(path.string(), {{std::nan(""), "a.vtu"}}), Error);
}

TEST(PvdWriter, PartsOfOneStepShareItsTime) {
  TempDir dir("pvd");
  const fs::path path = dir.path() / "frames.pvd";
  write_pvd_parts(path.string(),
                  {{0.0, "lattice_0000.vtu", 0}, {0.0, "surface_0000.vtu", 1}, {1.0, "lattice_0001.vtu", 0}});
  const std::string pvd = read_text(path);
  EXPECT_TRUE(contains(pvd, "<DataSet timestep=\"0\" group=\"\" part=\"0\" file=\"lattice_0000.vtu\"/>")) << pvd;
  EXPECT_TRUE(contains(pvd, "<DataSet timestep=\"0\" group=\"\" part=\"1\" file=\"surface_0000.vtu\"/>")) << pvd;
  EXPECT_TRUE(contains(error_of([&] { write_pvd_parts(path.string(), {{0.0, "a.vtu", -1}}); }), "part -1"));
}

TEST(VtuWriter, WritesATriangleSurface) {
  TempDir dir("vtu");
  const fs::path path = dir.path() / "surface.vtu";
  // A tetrahedron's boundary, moved by x.
  TriangleSurface s;
  s.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  s.triangles = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
  Points x = s.positions;
  x(3, 2) = 2.0;
  write_surface_vtu(path.string(), s, x, {{"lift", 1, {0, 0, 0, 1}}});
  const std::string vtu = read_text(path);
  EXPECT_TRUE(contains(vtu, "NumberOfPoints=\"4\" NumberOfCells=\"4\""));
  EXPECT_EQ(read_array(vtu, "Points"), x.xyz());
  EXPECT_EQ(read_array(vtu, "connectivity"), std::vector<double>(s.triangles.begin(), s.triangles.end()));
  EXPECT_EQ(read_array(vtu, "offsets"), (std::vector<double>{3, 6, 9, 12}));
  EXPECT_EQ(read_array(vtu, "types"), (std::vector<double>{5, 5, 5, 5}));  // VTK_TRIANGLE
  EXPECT_EQ(read_array(vtu, "lift"), (std::vector<double>{0, 0, 0, 1}));
  write_surface_vtu(path.string(), s);  // at its own positions
  EXPECT_EQ(read_array(read_text(path), "Points"), s.positions.xyz());

  EXPECT_TRUE(contains(error_of([&] { write_surface_vtu(path.string(), s, Points(1)); }), "write_surface_vtu"));
  TriangleSurface bad = s;
  bad.triangles[4] = 9;
  EXPECT_TRUE(contains(error_of([&] { write_surface_vtu(path.string(), bad); }), "triangle 1 refers to vertex 9"));
  EXPECT_THROW(write_surface_vtu(path.string(), s, {}, {{"short", 1, {0, 1}}}), Error);
}

}  // namespace
}  // namespace snh
