// Surface readers and write_obj: every format reads (files written here and
// the gmsh/meshio files under data/surfaces), STL corners merge into an
// indexed surface, write_obj round-trips, malformed input is rejected with
// the file and line (or byte), and the closed-surface check names open,
// non-manifold and flipped edges.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "snh/error.h"
#include "snh/surface.h"
#include "support/data_dir.h"
#include "support/errors.h"
#include "support/scratch.h"
#include "support/surface_shapes.h"

namespace snh {
namespace {

using test::error_of;

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) { return test::scratch_dir("snh_surface_io", name); }

fs::path write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// A tetrahedron facing outwards: vertices 0..3, its four triangles.
const std::vector<double> kTetPositions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
const std::vector<int32_t> kTetTriangles = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};

template <class T>
void put(std::string& out, T value, bool big_endian) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (big_endian)
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  out.append(reinterpret_cast<const char*>(bytes), sizeof(T));
}

TEST(SurfaceReaders, ObjCornerFormsNegativeIndicesAndPolygons) {
  const fs::path dir = scratch("obj");
  const TriangleSurface s = read_surface(write_text(dir / "forms.OBJ",
                                                    "# a unit square pyramid\n"
                                                    "mtllib none.mtl\n"
                                                    "o pyramid\n"
                                                    "v 0 0 0\n"
                                                    "v 1 0 0 1.0\n"
                                                    "v 1 1 0\n"
                                                    "v 0 1 0\n"
                                                    "v 0.5 0.5 1 # apex\n"
                                                    "vt 0 0\n"
                                                    "vn 0 0 1\n"
                                                    "g base\n"
                                                    "usemtl skin\n"
                                                    "s off\n"
                                                    "f 1/1/1 4/1/1 3/1/1 2/1/1\n"
                                                    "f 1//1 2//1 5//1\n"
                                                    "f 2/1 3/1 5/1\n"
                                                    "f -3 -2 -1\n"
                                                    "f 4 1 5\r\n")
                                             .string());
  EXPECT_EQ(s.vertex_count(), 5u);
  EXPECT_EQ(s.positions(4, 2), 1.0);
  // The quad fanned from its first corner, then the four sides; -1 is the last vertex.
  const std::vector<int32_t> expected = {0, 3, 2, 0, 2, 1, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};
  EXPECT_EQ(s.triangles, expected);
  validate_closed_surface(s);
  EXPECT_NEAR(enclosed_volume(s), 1.0 / 3.0, 1e-15);
}

TEST(SurfaceReaders, PlyAsciiAndBinaryBothEndians) {
  const fs::path dir = scratch("ply");
  // ASCII with extra properties, a quad split into... the tetrahedron's faces,
  // and an element after the faces that is skipped.
  std::string ascii =
      "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar red\nelement face 4\nproperty list uchar int vertex_indices\n"
      "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  for (int v = 0; v < 4; ++v)
    ascii += std::to_string(kTetPositions[3 * v]) + " " + std::to_string(kTetPositions[3 * v + 1]) + " " +
             std::to_string(kTetPositions[3 * v + 2]) + " 255\n";
  for (int f = 0; f < 4; ++f)
    ascii += "3 " + std::to_string(kTetTriangles[3 * f]) + " " + std::to_string(kTetTriangles[3 * f + 1]) + " " +
             std::to_string(kTetTriangles[3 * f + 2]) + "\n";
  ascii += "0 1\n";
  const TriangleSurface a = read_surface(write_text(dir / "ascii.ply", ascii).string());
  EXPECT_EQ(a.positions.xyz(), kTetPositions);
  EXPECT_EQ(a.triangles, kTetTriangles);

  for (const bool big : {false, true}) {
    // Little endian: float coordinates and a colour between them; big: doubles, ushort counts, uint indices.
    std::string header =
        std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
        " 1.0\nelement vertex 4\n" +
        (big ? "property double x\nproperty double y\nproperty double z\n"
             : "property float x\nproperty uchar red\nproperty float y\nproperty float z\n") +
        "element face 4\n" +
        (big ? "property list ushort uint vertex_indices\n" : "property list uchar int vertex_indices\n") +
        "property float quality\nend_header\n";
    std::string body;
    for (int v = 0; v < 4; ++v) {
      if (big) {
        for (int d = 0; d < 3; ++d) put<double>(body, kTetPositions[3 * v + d], true);
      } else {
        put<float>(body, float(kTetPositions[3 * v]), false);
        put<uint8_t>(body, 7, false);
        put<float>(body, float(kTetPositions[3 * v + 1]), false);
        put<float>(body, float(kTetPositions[3 * v + 2]), false);
      }
    }
    for (int f = 0; f < 4; ++f) {
      if (big)
        put<uint16_t>(body, 3, true);
      else
        put<uint8_t>(body, 3, false);
      for (int c = 0; c < 3; ++c) {
        if (big)
          put<uint32_t>(body, uint32_t(kTetTriangles[3 * f + c]), true);
        else
          put<int32_t>(body, kTetTriangles[3 * f + c], false);
      }
      put<float>(body, 0.5f, big);
    }
    const TriangleSurface b = read_surface(write_text(dir / (big ? "be.ply" : "le.ply"), header + body).string());
    EXPECT_EQ(b.positions.xyz(), kTetPositions) << (big ? "big" : "little");
    EXPECT_EQ(b.triangles, kTetTriangles) << (big ? "big" : "little");

    // Cut short inside the faces: the byte offset is named.
    const std::string cut = header + body.substr(0, body.size() - 5);
    const std::string e = error_of([&] { read_surface(write_text(dir / "cut.ply", cut).string()); });
    EXPECT_NE(e.find("cut.ply (byte "), std::string::npos) << e;
    EXPECT_NE(e.find("truncated"), std::string::npos) << e;
  }
}

std::string stl_ascii(const std::vector<double>& p, const std::vector<int32_t>& t) {
  std::string s = "solid tet\n";
  for (size_t f = 0; f < t.size() / 3; ++f) {
    s += "  facet normal 0 0 0\n    outer loop\n";
    for (int c = 0; c < 3; ++c)
      s += "      vertex " + std::to_string(p[3 * t[3 * f + c]]) + " " + std::to_string(p[3 * t[3 * f + c] + 1]) + " " +
           std::to_string(p[3 * t[3 * f + c] + 2]) + "\n";
    s += "    endloop\n  endfacet\n";
  }
  return s + "endsolid tet\n";
}

std::string stl_binary(const std::vector<double>& p, const std::vector<int32_t>& t) {
  std::string s = "solid but binary";  // binary files may start like ASCII ones
  s.resize(80, ' ');
  put<uint32_t>(s, uint32_t(t.size() / 3), false);
  for (size_t f = 0; f < t.size() / 3; ++f) {
    for (int k = 0; k < 3; ++k) put<float>(s, 0.0f, false);
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d) put<float>(s, float(p[3 * t[3 * f + c] + d]), false);
    put<uint16_t>(s, 0, false);
  }
  return s;
}

TEST(SurfaceReaders, StlAsciiAndBinaryMergeCoincidentCorners) {
  const fs::path dir = scratch("stl");
  for (const std::string& text : {stl_ascii(kTetPositions, kTetTriangles), stl_binary(kTetPositions, kTetTriangles)}) {
    const TriangleSurface s = read_surface(write_text(dir / "tet.stl", text).string());
    // 12 corners by value become the 4 vertices, in the order first met.
    EXPECT_EQ(s.vertex_count(), 4u);
    EXPECT_EQ(s.triangle_count(), 4u);
    validate_closed_surface(s);
    EXPECT_NEAR(enclosed_volume(s), 1.0 / 6.0, 1e-7);
  }
  // -0 and +0 are the same corner.
  std::string signed_zero = stl_ascii(kTetPositions, kTetTriangles);
  signed_zero.replace(signed_zero.find("vertex 0.000000 0.000000 0.000000"), 33, "vertex -0 0 -0.0");
  EXPECT_EQ(read_surface(write_text(dir / "zero.stl", signed_zero).string()).vertex_count(), 4u);
}

TEST(SurfaceReaders, DataFilesFromGmshAndMeshioAgree) {
  const fs::path data = test::data_dir() / "surfaces";
  const TriangleSurface ascii = read_surface((data / "sphere.stl").string());
  EXPECT_EQ(ascii.vertex_count(), 192u);
  EXPECT_EQ(ascii.triangle_count(), 380u);
  validate_closed_surface(ascii);
  const double volume = enclosed_volume(ascii);
  // gmsh's triangles inscribed in the sphere of radius 0.5.
  EXPECT_LT(volume, 4.0 / 3.0 * M_PI * 0.125);
  EXPECT_GT(volume, 0.95 * 4.0 / 3.0 * M_PI * 0.125);
  for (const char* name : {"sphere_binary.stl", "sphere.ply", "sphere.obj"}) {
    const TriangleSurface s = read_surface((data / name).string());
    EXPECT_EQ(s.vertex_count(), 192u) << name;
    EXPECT_EQ(s.triangle_count(), 380u) << name;
    validate_closed_surface(s);
    // ASCII STL keeps 6 digits; the others hold gmsh's floats.
    EXPECT_NEAR(enclosed_volume(s), volume, 1e-5) << name;
  }
  const TriangleSurface slit = read_surface((data / "slit_box.stl").string());
  validate_closed_surface(slit);
  EXPECT_NEAR(enclosed_volume(slit), 0.6 * (1.0 - 0.04 * 0.5), 1e-6);
}

TEST(SurfaceReaders, WriteObjRoundTripsExactly) {
  const fs::path dir = scratch("round_trip");
  const TriangleSurface s = test::icosphere(2, 0.7);
  write_obj((dir / "sphere.obj").string(), s);
  const TriangleSurface back = read_surface((dir / "sphere.obj").string());
  EXPECT_EQ(back.positions, s.positions);
  EXPECT_EQ(back.triangles, s.triangles);

  std::vector<double> moved = s.positions.xyz();
  for (double& x : moved) x = 2.0 * x + 0.1;
  write_obj((dir / "moved.obj").string(), s, Points::from_xyz(moved));
  EXPECT_EQ(read_surface((dir / "moved.obj").string()).positions.xyz(), moved);

  const std::string e = error_of([&] { write_obj((dir / "bad.obj").string(), s, Points(2)); });
  EXPECT_NE(e.find("bad.obj"), std::string::npos) << e;
}

TEST(SurfaceReaders, MalformedFilesNameTheLineOrByte) {
  const fs::path dir = scratch("malformed");
  const struct {
    const char* name;
    std::string text;
    const char* where;  // expected in the message
    const char* what;
  } cases[] = {
      {"coordinate.obj", "v 0 0 0\nv 1 0 0\nv 0 x 0\n", "coordinate.obj:3", "'x'"},
      {"short_vertex.obj", "v 0 0 0\nv 1 0\n", "short_vertex.obj:2", "3 coordinates"},
      {"range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n", "range.obj:5", "refers to vertex 4"},
      {"relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", "relative.obj:4", "refers to vertex -4"},
      {"zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "zero.obj:4", "face corner"},
      {"two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", "two.obj:3", "at least 3 corners"},
      {"repeat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 1\n", "repeat.obj:4", "twice"},
      {"nan.obj", "v 0 0 0\nv nan 0 0\n", "nan.obj:2", "non-finite"},
      {"empty.obj", "# nothing\nv 0 0 0\n", "empty.obj", "no faces"},
      {"no_end.ply", "ply\nformat ascii 1.0\nelement vertex 0\n", "no_end.ply:4", "end_header"},
      {"not.ply", "plyx\n", "not.ply:1", "not a PLY"},
      {"format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n", "format.ply:2", "binary_middle_endian"},
      {"face_text.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 one 2\n",
       "face_text.ply:13", "'one'"},
      {"no_z.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n",
       "no_z.ply:3", "'z'"},
      {"loop.stl",
       "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendfacet\nendsolid\n",
       "loop.stl:7", "'endfacet'"},
      {"number.stl", "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 zero\n", "number.stl:4", "'zero'"},
      {"unended.stl",
       "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
       "endfacet\n",
       "unended.stl:9", "endsolid"},
      {"short.stl", std::string("binary junk"), "short.stl", "not an STL file"},
      {"size.stl", std::string(80, 'x') + std::string("\x02\0\0\0", 4) + std::string(60, '\0'), "size.stl (byte 80)",
       "must be 184 bytes"},
      {"surface.vtk", "# vtk DataFile\n", "surface.vtk", "unknown surface format"},
  };
  for (const auto& c : cases) {
    const fs::path path = write_text(dir / c.name, c.text);
    const std::string e = error_of([&] { read_surface(path.string()); });
    EXPECT_NE(e.find(c.where), std::string::npos) << c.name << ": " << e;
    EXPECT_NE(e.find(c.what), std::string::npos) << c.name << ": " << e;
  }
  const std::string missing = error_of([&] { read_surface((dir / "missing.stl").string()); });
  EXPECT_NE(missing.find("missing.stl"), std::string::npos) << missing;
}

TEST(SurfaceClosed, MissingTriangleNamesItsOpenEdges) {
  TriangleSurface s = test::box_surface({0, 0, 0}, {1, 2, 3});
  validate_closed_surface(s);
  EXPECT_NEAR(enclosed_volume(s), 6.0, 1e-14);
  EXPECT_NEAR(surface_area(s), 22.0, 1e-14);
  // Triangle 0 is (0, 2, 3) of the bottom face: its three edges open up.
  s.triangles.erase(s.triangles.begin(), s.triangles.begin() + 3);
  const std::string e = error_of([&] { validate_closed_surface(s); });
  EXPECT_NE(e.find("3 open edges"), std::string::npos) << e;
  EXPECT_NE(e.find("0 (0, 0, 0) - 2 (0, 2, 0)"), std::string::npos) << e;
  EXPECT_NE(e.find("2 (0, 2, 0) - 3 (1, 2, 0)"), std::string::npos) << e;
  EXPECT_NE(e.find("0 (0, 0, 0) - 3 (1, 2, 0)"), std::string::npos) << e;
  // voxelize with VoxelizeOptions::strict checks first.
  VoxelizeOptions strict;
  strict.strict = true;
  const std::string v = error_of([&] { voxelize(s, 0.5, strict); });
  EXPECT_NE(v.find("3 open edges"), std::string::npos) << v;
}

TEST(SurfaceClosed, FlippedTriangleIsAnOrientationError) {
  TriangleSurface s = test::box_surface({0, 0, 0}, {1, 1, 1});
  std::swap(s.triangles[3 * 5 + 1], s.triangles[3 * 5 + 2]);
  const std::string e = error_of([&] { validate_closed_surface(s); });
  EXPECT_NE(e.find("3 edges traversed in the same direction"), std::string::npos) << e;
  EXPECT_NE(e.find("flipped"), std::string::npos) << e;
  EXPECT_NE(e.find("triangles 4 and 5"), std::string::npos) << e;
  EXPECT_EQ(e.find("open edges"), std::string::npos) << e;

  // All of them flipped: closed and consistent, but facing inwards.
  TriangleSurface inwards = test::box_surface({0, 0, 0}, {1, 1, 1});
  for (size_t t = 0; t < inwards.triangle_count(); ++t)
    std::swap(inwards.triangles[3 * t + 1], inwards.triangles[3 * t + 2]);
  VoxelizeOptions strict;
  strict.strict = true;
  const std::string i = error_of([&] { voxelize(inwards, 0.25, strict); });
  EXPECT_NE(i.find("face inwards"), std::string::npos) << i;
  // By default it is turned outwards before its winding number (-1 inside
  // as it is) decides, and warned of.
  const Voxelization d = voxelize(inwards, 0.25);
  EXPECT_EQ(d.element_cell.size(), 64u);
  EXPECT_NE(d.warnings.back().find("faces inwards"), std::string::npos) << d.warnings.back();
}

TEST(SurfaceClosed, EdgeOfFourTrianglesIsNonManifold) {
  // Two tetrahedra sharing the edge 0-1 only.
  TriangleSurface s;
  s.positions = Points::from_xyz(kTetPositions);
  s.triangles = kTetTriangles;
  // Vertices 4, 5: the first tetrahedron turned half a turn about x (2 -> 4, 3 -> 5).
  s.positions.push_back({0, -1, 0});
  s.positions.push_back({0, 0, -1});
  const std::vector<int32_t> second = {0, 4, 1, 0, 1, 5, 1, 4, 5, 0, 5, 4};
  s.triangles.insert(s.triangles.end(), second.begin(), second.end());
  const std::string e = error_of([&] { validate_closed_surface(s); });
  EXPECT_NE(e.find("1 non-manifold edges"), std::string::npos) << e;
  EXPECT_NE(e.find("0 (0, 0, 0) - 1 (1, 0, 0) shared by 4 triangles"), std::string::npos) << e;
}

}  // namespace
}  // namespace snh
