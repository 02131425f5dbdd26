// Mesh readers and boundary-surface writers: every format reads (files made
// by Debian's gmsh and meshio under data/meshes, and files written here),
// round-trips, has mirrored elements turned over, and rejects bad input with
// a message naming the file, the line (or byte) or element, and the fault.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "snh/error.h"
#include "snh/io.h"
#include "snh/mesh.h"
#include "snh/mesh_io.h"
#include "snh/selection.h"
#include "support/data_dir.h"
#include "support/errors.h"
#include "support/lattices.h"
#include "support/scratch.h"

namespace snh {
namespace {

using test::error_of;

namespace fs = std::filesystem;

const fs::path kData = test::data_dir() / "meshes";

// A fresh folder for the files a test writes.
fs::path scratch(const std::string& name) { return test::scratch_dir("snh_mesh_io", name); }

std::string read_error(const fs::path& path) {
  return error_of([&] { read_mesh(path.string()); });
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream file(path, std::ios::binary);
  file << text;
  ASSERT_TRUE(file.good()) << path;
}

std::string text_of(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream s;
  s << file.rdbuf();
  return s.str();
}

// ---- Writers for the round trips (the library writes .vtu only) ----

template <class T>
void put(std::ostream& out, T value, bool big_endian = false) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  if (big_endian) std::reverse(b, b + sizeof(T));
  out.write(reinterpret_cast<const char*>(b), sizeof(T));
}

std::ofstream open(const fs::path& path) {
  std::ofstream file(path, std::ios::binary);
  file << std::setprecision(17);
  return file;
}

int gmsh_type(const Mesh& m) { return m.type == ElementType::tet4 ? 4 : 5; }
int vtk_type(const Mesh& m) { return m.type == ElementType::tet4 ? 10 : 12; }

void write_msh22(const fs::path& path, const Mesh& m, bool binary) {
  auto f = open(path);
  const int n = nodes_per_element(m.type);
  f << "$MeshFormat\n2.2 " << (binary ? 1 : 0) << " 8\n";
  if (binary) {
    put<int32_t>(f, 1);
    f << "\n";
  }
  f << "$EndMeshFormat\n$Nodes\n" << m.vertex_count() << "\n";
  for (size_t v = 0; v < m.vertex_count(); ++v) {
    if (binary) {
      put<int32_t>(f, static_cast<int32_t>(v + 1));
      for (int d = 0; d < 3; ++d) put<double>(f, m.positions(v, d));
    } else {
      f << v + 1 << " " << m.positions(v, 0) << " " << m.positions(v, 1) << " " << m.positions(v, 2) << "\n";
    }
  }
  if (binary) f << "\n";
  f << "$EndNodes\n$Elements\n" << m.element_count() << "\n";
  if (binary) {
    put<int32_t>(f, gmsh_type(m));
    put<int32_t>(f, static_cast<int32_t>(m.element_count()));
    put<int32_t>(f, 2);
  }
  for (size_t e = 0; e < m.element_count(); ++e) {
    if (binary) {
      put<int32_t>(f, static_cast<int32_t>(e + 1));
      put<int32_t>(f, 1);
      put<int32_t>(f, 1);
      for (int a = 0; a < n; ++a) put<int32_t>(f, m.elements[n * e + a] + 1);
    } else {
      f << e + 1 << " " << gmsh_type(m) << " 2 1 1";
      for (int a = 0; a < n; ++a) f << " " << m.elements[n * e + a] + 1;
      f << "\n";
    }
  }
  if (binary) f << "\n";
  f << "$EndElements\n";
}

void write_msh41(const fs::path& path, const Mesh& m, bool binary) {
  auto f = open(path);
  const int n = nodes_per_element(m.type);
  const uint64_t nv = m.vertex_count(), ne = m.element_count();
  f << "$MeshFormat\n4.1 " << (binary ? 1 : 0) << " 8\n";
  if (binary) {
    put<int32_t>(f, 1);
    f << "\n";
  }
  f << "$EndMeshFormat\n$Nodes\n";
  if (binary) {
    for (uint64_t v : {uint64_t(1), nv, uint64_t(1), nv}) put<uint64_t>(f, v);
    put<int32_t>(f, 3);
    put<int32_t>(f, 1);
    put<int32_t>(f, 0);
    put<uint64_t>(f, nv);
    for (uint64_t v = 0; v < nv; ++v) put<uint64_t>(f, v + 1);
    for (double x : m.positions.xyz()) put<double>(f, x);
    f << "\n";
  } else {
    f << "1 " << nv << " 1 " << nv << "\n3 1 0 " << nv << "\n";
    for (uint64_t v = 0; v < nv; ++v) f << v + 1 << "\n";
    for (uint64_t v = 0; v < nv; ++v)
      f << m.positions(v, 0) << " " << m.positions(v, 1) << " " << m.positions(v, 2) << "\n";
  }
  f << "$EndNodes\n$Elements\n";
  if (binary) {
    for (uint64_t v : {uint64_t(1), ne, uint64_t(1), ne}) put<uint64_t>(f, v);
    put<int32_t>(f, 3);
    put<int32_t>(f, 1);
    put<int32_t>(f, gmsh_type(m));
    put<uint64_t>(f, ne);
    for (uint64_t e = 0; e < ne; ++e) {
      put<uint64_t>(f, e + 1);
      for (int a = 0; a < n; ++a) put<uint64_t>(f, static_cast<uint64_t>(m.elements[n * e + a] + 1));
    }
    f << "\n";
  } else {
    f << "1 " << ne << " 1 " << ne << "\n3 1 " << gmsh_type(m) << " " << ne << "\n";
    for (uint64_t e = 0; e < ne; ++e) {
      f << e + 1;
      for (int a = 0; a < n; ++a) f << " " << m.elements[n * e + a] + 1;
      f << "\n";
    }
  }
  f << "$EndElements\n";
}

// Legacy VTK: version 4.2 (counts in CELLS) or 5.1 (OFFSETS/CONNECTIVITY).
void write_vtk(const fs::path& path, const Mesh& m, bool binary, bool v5) {
  auto f = open(path);
  const int n = nodes_per_element(m.type);
  const size_t nv = m.vertex_count(), ne = m.element_count();
  f << "# vtk DataFile Version " << (v5 ? "5.1" : "4.2") << "\nsnh test\n"
    << (binary ? "BINARY" : "ASCII") << "\nDATASET UNSTRUCTURED_GRID\nPOINTS " << nv << " double\n";
  for (size_t i = 0; i < 3 * nv; ++i) {
    if (binary)
      put<double>(f, m.positions.xyz()[i], true);
    else
      f << m.positions.xyz()[i] << ((i % 3 == 2) ? "\n" : " ");
  }
  if (binary) f << "\n";
  if (v5) {
    f << "CELLS " << ne + 1 << " " << n * ne << "\nOFFSETS vtktypeint64\n";
    for (size_t e = 0; e <= ne; ++e) binary ? put<int64_t>(f, int64_t(n * e), true) : void(f << n * e << "\n");
    f << (binary ? "\n" : "") << "CONNECTIVITY vtktypeint64\n";
    for (int32_t v : m.elements) binary ? put<int64_t>(f, v, true) : void(f << v << "\n");
  } else {
    f << "CELLS " << ne << " " << (n + 1) * ne << "\n";
    for (size_t e = 0; e < ne; ++e) {
      if (binary) {
        put<int32_t>(f, n, true);
        for (int a = 0; a < n; ++a) put<int32_t>(f, m.elements[n * e + a], true);
      } else {
        f << n;
        for (int a = 0; a < n; ++a) f << " " << m.elements[n * e + a];
        f << "\n";
      }
    }
  }
  f << (binary ? "\n" : "") << "CELL_TYPES " << ne << "\n";
  for (size_t e = 0; e < ne; ++e) binary ? put<int32_t>(f, vtk_type(m), true) : void(f << vtk_type(m) << "\n");
  f << (binary ? "\n" : "") << "CELL_DATA " << ne << "\n";
}

// VTK XML with raw appended data (write_vtu writes ascii).
void write_vtu_appended(const fs::path& path, const Mesh& m) {
  const int n = nodes_per_element(m.type);
  const size_t ne = m.element_count();
  std::ostringstream data;
  std::vector<uint64_t> offsets;
  auto block = [&](const void* bytes, size_t size) {
    offsets.push_back(data.str().size());
    put<uint32_t>(data, static_cast<uint32_t>(size));
    data.write(static_cast<const char*>(bytes), static_cast<std::streamsize>(size));
  };
  block(m.positions.data(), m.positions.xyz().size() * sizeof(double));
  std::vector<int64_t> connectivity(m.elements.begin(), m.elements.end()), ends;
  for (size_t e = 1; e <= ne; ++e) ends.push_back(int64_t(n * e));
  std::vector<uint8_t> types(ne, static_cast<uint8_t>(vtk_type(m)));
  block(connectivity.data(), connectivity.size() * 8);
  block(ends.data(), ends.size() * 8);
  block(types.data(), types.size());
  auto f = open(path);
  f << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << m.vertex_count() << "\" NumberOfCells=\"" << ne << "\">\n"
    << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" offset=\"" << offsets[0]
    << "\"/></Points>\n<Cells>\n"
    << "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"appended\" offset=\"" << offsets[1] << "\"/>\n"
    << "<DataArray type=\"Int64\" Name=\"offsets\" format=\"appended\" offset=\"" << offsets[2] << "\"/>\n"
    << "<DataArray type=\"UInt8\" Name=\"types\" format=\"appended\" offset=\"" << offsets[3] << "\"/>\n"
    << "</Cells>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_" << data.str()
    << "\n</AppendedData>\n</VTKFile>\n";
}

void write_medit(const fs::path& path, const Mesh& m) {
  auto f = open(path);
  const int n = nodes_per_element(m.type);
  f << "MeshVersionFormatted 2\nDimension 3\n# written by test_mesh_io\nVertices\n" << m.vertex_count() << "\n";
  for (size_t v = 0; v < m.vertex_count(); ++v)
    f << m.positions(v, 0) << " " << m.positions(v, 1) << " " << m.positions(v, 2) << " 0\n";
  f << (m.type == ElementType::tet4 ? "Tetrahedra\n" : "Hexahedra\n") << m.element_count() << "\n";
  for (size_t e = 0; e < m.element_count(); ++e) {
    for (int a = 0; a < n; ++a) f << m.elements[n * e + a] + 1 << " ";
    f << "1\n";
  }
  f << "End\n";
}

// Points numbered from 1, as TetGen does without -z.
void write_tetgen(const fs::path& node_path, const Mesh& m) {
  auto f = open(node_path);
  f << "# test_mesh_io\n" << m.vertex_count() << " 3 0 0\n";
  for (size_t v = 0; v < m.vertex_count(); ++v)
    f << v + 1 << " " << m.positions(v, 0) << " " << m.positions(v, 1) << " " << m.positions(v, 2) << "\n";
  fs::path ele_path = node_path;
  ele_path.replace_extension(".ele");
  auto g = open(ele_path);
  g << m.element_count() << " 4 0\n";
  for (size_t e = 0; e < m.element_count(); ++e) {
    g << e + 1;
    for (int a = 0; a < 4; ++a) g << " " << m.elements[4 * e + a] + 1;
    g << "\n";
  }
}

struct Format {
  std::string name, extension;
  std::function<void(const fs::path&, const Mesh&)> write;
  bool hexes = true;
};

std::vector<Format> formats() {
  return {
      {"msh22_ascii", ".msh", [](const fs::path& p, const Mesh& m) { write_msh22(p, m, false); }},
      {"msh22_binary", ".msh", [](const fs::path& p, const Mesh& m) { write_msh22(p, m, true); }},
      {"msh41_ascii", ".msh", [](const fs::path& p, const Mesh& m) { write_msh41(p, m, false); }},
      {"msh41_binary", ".msh", [](const fs::path& p, const Mesh& m) { write_msh41(p, m, true); }},
      {"vtk42_ascii", ".vtk", [](const fs::path& p, const Mesh& m) { write_vtk(p, m, false, false); }},
      {"vtk42_binary", ".vtk", [](const fs::path& p, const Mesh& m) { write_vtk(p, m, true, false); }},
      {"vtk51_ascii", ".vtk", [](const fs::path& p, const Mesh& m) { write_vtk(p, m, false, true); }},
      {"vtk51_binary", ".vtk", [](const fs::path& p, const Mesh& m) { write_vtk(p, m, true, true); }},
      {"vtu_ascii", ".vtu", [](const fs::path& p, const Mesh& m) { write_vtu(p.string(), m, m.positions); }},
      {"vtu_appended", ".vtu", write_vtu_appended},
      {"medit", ".mesh", write_medit},
      {"tetgen", ".node", write_tetgen, false},
  };
}

// Irregular positions, so that a swapped coordinate or node shows.
Mesh jiggled(Mesh m) { return test::sine_jiggled(std::move(m), 0.01); }

double total(const Mesh& m) { return mesh_volume(m, m.positions); }

// ---- Files made by gmsh and meshio ----

TEST(MeshIoData, EveryFileReads) {
  struct Expected {
    const char* file;
    ElementType type;
    size_t vertices, elements;
    double volume;
  };
  const double box = 0.125;
  const Expected expected[] = {
      {"box_tet.msh22.msh", ElementType::tet4, 228, 627, box},
      {"box_tet.msh22_binary.msh", ElementType::tet4, 228, 627, box},
      {"box_tet.msh41.msh", ElementType::tet4, 228, 627, box},
      {"box_tet.msh41_binary.msh", ElementType::tet4, 228, 627, box},
      {"box_tet.mesh", ElementType::tet4, 228, 627, box},
      {"box_tet.vtk", ElementType::tet4, 228, 627, box},
      {"box_tet_meshio_binary.vtk", ElementType::tet4, 228, 627, box},
      {"box_tet.vtu", ElementType::tet4, 228, 627, box},
      {"box_tet_base64.vtu", ElementType::tet4, 228, 627, box},
      {"box_tet.node", ElementType::tet4, 228, 627, box},
      {"box_tet.ele", ElementType::tet4, 228, 627, box},
      {"hex_box.msh", ElementType::hex8, 45, 16, box},
      {"hex_box.msh22.msh", ElementType::hex8, 45, 16, box},
      {"hex_box.mesh", ElementType::hex8, 45, 16, box},
      {"hex_box.vtk", ElementType::hex8, 45, 16, box},
      {"hex_box.vtu", ElementType::hex8, 45, 16, box},
  };
  for (const Expected& e : expected) {
    SCOPED_TRACE(e.file);
    const Mesh m = read_mesh((kData / e.file).string());
    EXPECT_EQ(m.type, e.type);
    EXPECT_EQ(m.vertex_count(), e.vertices);
    EXPECT_EQ(m.element_count(), e.elements);
    EXPECT_NEAR(total(m), e.volume, 1e-12);
    EXPECT_TRUE(validate_mesh(m).unused_vertices.empty());
  }
  // A faceted cylinder of radius 0.3 and length 1: a little under pi r^2.
  const Mesh cylinder = read_mesh((kData / "cylinder_tet.msh").string());
  EXPECT_NEAR(total(cylinder), M_PI * 0.09, 0.03 * M_PI * 0.09);
  EXPECT_LT(total(cylinder), M_PI * 0.09);
}

TEST(MeshIoData, FormatsOfTheSameMeshAgree) {
  const Mesh a = read_mesh((kData / "box_tet.msh41.msh").string());
  for (const char* other : {"box_tet.msh22.msh", "box_tet.msh22_binary.msh", "box_tet.msh41_binary.msh", "box_tet.vtk",
                            "box_tet_meshio_binary.vtk", "box_tet_base64.vtu", "box_tet.node"}) {
    SCOPED_TRACE(other);
    const Mesh b = read_mesh((kData / other).string());
    // gmsh's ASCII output rounds to 16 digits; its binary output does not.
    ASSERT_EQ(a.positions.xyz().size(), b.positions.xyz().size());
    for (size_t i = 0; i < a.positions.xyz().size(); ++i)
      EXPECT_NEAR(a.positions.xyz()[i], b.positions.xyz()[i], 1e-15) << i;
    EXPECT_EQ(a.elements, b.elements);
  }
}

// ---- Round trips ----

TEST(MeshIoRoundTrip, EveryFormat) {
  const fs::path dir = scratch("round_trip");
  const Mesh meshes[] = {jiggled(make_box_lattice(3, 2, 2, 0.5, {1.0, -2.0, 0.25})),
                         jiggled(make_tet_box(2, 2, 1, 0.3))};
  for (const Format& format : formats())
    for (const Mesh& mesh : meshes) {
      if (mesh.type == ElementType::hex8 && !format.hexes) continue;
      SCOPED_TRACE(format.name + " " + to_string(mesh.type));
      const fs::path path = dir / (format.name + "_" + to_string(mesh.type) + format.extension);
      format.write(path, mesh);
      const Mesh back = read_mesh(path.string());
      EXPECT_EQ(back.type, mesh.type);
      EXPECT_EQ(back.positions, mesh.positions);
      EXPECT_EQ(back.elements, mesh.elements);
      EXPECT_DOUBLE_EQ(total(back), total(mesh));
    }
}

TEST(MeshIoRoundTrip, VoxelCylinderThroughVtu) {
  const fs::path path = scratch("cylinder") / "cylinder.vtu";
  const Mesh mesh = make_voxel_cylinder(1.0, 2.0, 0.25);
  write_vtu(path.string(), mesh, mesh.positions);
  const Mesh back = read_mesh(path.string());
  EXPECT_EQ(back.positions, mesh.positions);
  EXPECT_EQ(back.elements, mesh.elements);
}

// ---- Orientation ----

TEST(MeshIoOrientation, MirroredElementsAreTurnedOver) {
  const fs::path dir = scratch("orientation");
  Mesh tets = jiggled(make_tet_box(2, 1, 1, 1.0));
  Mesh hexes = jiggled(make_box_lattice(2, 1, 1, 1.0));
  const double tet_volume = total(tets), hex_volume = total(hexes);
  // Every other element mirrored: two tet nodes swapped, the hex's bottom
  // and top faces swapped.
  for (size_t e = 0; e < tets.element_count(); e += 2) std::swap(tets.elements[4 * e + 1], tets.elements[4 * e + 2]);
  for (size_t e = 0; e < hexes.element_count(); e += 2)
    for (int a = 0; a < 4; ++a) std::swap(hexes.elements[8 * e + a], hexes.elements[8 * e + a + 4]);
  for (const Format& format : formats())
    for (const Mesh* mesh : {&tets, &hexes}) {
      if (mesh->type == ElementType::hex8 && !format.hexes) continue;
      SCOPED_TRACE(format.name + " " + to_string(mesh->type));
      const fs::path path = dir / (format.name + "_" + to_string(mesh->type) + format.extension);
      format.write(path, *mesh);
      const Mesh back = read_mesh(path.string());
      EXPECT_NEAR(total(back), mesh == &tets ? tet_volume : hex_volume, 1e-12);
      EXPECT_EQ(back.positions, mesh->positions);
      // Only the mirrored elements changed.
      const int n = nodes_per_element(mesh->type);
      for (size_t e = 0; e < mesh->element_count(); ++e) {
        const bool same = std::equal(back.elements.begin() + n * e, back.elements.begin() + n * (e + 1),
                                     mesh->elements.begin() + n * e);
        EXPECT_EQ(same, e % 2 == 1) << "element " << e;
      }
    }
}

// ---- Bad input: each names the file, the line (or byte) or element, and the fault ----

const char* kTet22 =
    "$MeshFormat\n"        // 1
    "2.2 0 8\n"            // 2
    "$EndMeshFormat\n"     // 3
    "$Nodes\n"             // 4
    "5\n"                  // 5
    "1 0 0 0\n"            // 6
    "2 1 0 0\n"            // 7
    "3 0 1 0\n"            // 8
    "4 0 0 1\n"            // 9
    "5 1 1 1\n"            // 10
    "$EndNodes\n"          // 11
    "$Elements\n"          // 12
    "3\n"                  // 13
    "1 2 2 0 1 1 2 3\n"    // 14 (a triangle: skipped)
    "2 4 2 0 1 1 2 3 4\n"  // 15
    "3 4 2 0 1 2 3 4 5\n"  // 16
    "$EndElements\n";      // 17

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

class MeshIoBadInput : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = scratch(::testing::UnitTest::GetInstance()->current_test_info()->name()); }
  // Writes `text` to `name` and returns read_mesh's message.
  std::string error(const std::string& name, const std::string& text) {
    write_text(dir_ / name, text);
    return read_error(dir_ / name);
  }
  fs::path dir_;
};

TEST_F(MeshIoBadInput, BaselineReads) {
  write_text(dir_ / "good.msh", kTet22);
  const Mesh m = read_mesh((dir_ / "good.msh").string());
  EXPECT_EQ(m.element_count(), 2u);
  EXPECT_NEAR(total(m), 1.0 / 6 + 1.0 / 3, 1e-12);
}

TEST_F(MeshIoBadInput, Malformed) {
  const std::string e = error("bad.msh", replaced(kTet22, "3 0 1 0\n", "3 0 one 0\n"));
  EXPECT_NE(e.find("bad.msh:8: expected a coordinate (a number), found 'one'"), std::string::npos) << e;
  const std::string v = error("bad.vtk", "# vtk DataFile Version 4.2\nx\nASCII\nDATASET POLYDATA\n");
  EXPECT_NE(v.find("bad.vtk:4: expected DATASET UNSTRUCTURED_GRID"), std::string::npos) << v;
  const std::string x = error("bad.vtu", "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\">\n<Piece Numb");
  EXPECT_NE(x.find("bad.vtu:3: malformed XML"), std::string::npos) << x;
  const std::string m = error("bad.mesh", "MeshVersionFormatted 2\nDimension 3\nVertices\n1\n0 0 zero 0\n");
  EXPECT_NE(m.find("bad.mesh:5: expected coordinate z of Vertices entry 1 of 1 (a number), found 'zero'"),
            std::string::npos)
      << m;
  const std::string z = error("zlib.vtu", replaced(text_of(kData / "box_tet_base64.vtu"),
                                                   "byte_order=", "compressor=\"vtkZLibDataCompressor\" byte_order="));
  EXPECT_NE(z.find("zlib.vtu:7: the Points array is compressed (vtkZLibDataCompressor); only uncompressed data is "
                   "supported"),
            std::string::npos)
      << z;
  const std::string n = error("not_a_mesh.msh", "hello\n");
  EXPECT_NE(n.find("not_a_mesh.msh:1: not a Gmsh mesh"), std::string::npos) << n;
}

TEST_F(MeshIoBadInput, Truncated) {
  const std::string text = kTet22;
  const std::string e = error("cut.msh", text.substr(0, text.find("3 4 2 0 1 2 3 4 5")));
  EXPECT_NE(e.find("cut.msh:16: the file ends where element 3 of 3 was expected"), std::string::npos) << e;

  // Binary data cut short is reported by byte offset.
  const Mesh mesh = make_tet_box(1, 1, 1, 1.0);
  write_msh41(dir_ / "full.msh", mesh, true);
  const std::string bytes = text_of(dir_ / "full.msh");
  const std::string b = error("cut_binary.msh", bytes.substr(0, bytes.size() - 60));
  EXPECT_NE(b.find("cut_binary.msh (byte "), std::string::npos) << b;
  EXPECT_NE(b.find("the file is truncated"), std::string::npos) << b;

  write_vtu_appended(dir_ / "full.vtu", mesh);
  const std::string vtu = text_of(dir_ / "full.vtu");
  const std::string u = error("cut.vtu", vtu.substr(0, vtu.find("\n_") + 41));
  EXPECT_NE(u.find("cut.vtu (byte "), std::string::npos) << u;
  EXPECT_NE(u.find("the Points array announces 192 bytes, but only"), std::string::npos) << u;
}

TEST_F(MeshIoBadInput, WrongCounts) {
  const std::string more = error("more.msh", replaced(kTet22, "$Nodes\n5\n", "$Nodes\n6\n"));
  EXPECT_NE(more.find("more.msh:11: node line 6 of 6 has 1 values, expected 4"), std::string::npos) << more;
  const std::string fewer = error("fewer.msh", replaced(kTet22, "$Elements\n3\n", "$Elements\n2\n"));
  EXPECT_NE(fewer.find("fewer.msh:16: expected $EndElements after the elements (does the element count match?), "
                       "found '3'"),
            std::string::npos)
      << fewer;
  const std::string vtk = error("count.vtk",
                                "# vtk DataFile Version 4.2\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
                                "0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 2\n10 10\n");
  EXPECT_NE(vtk.find("count.vtk:10: CELL_TYPES has 2 entries, but CELLS has 1 cells"), std::string::npos) << vtk;
  write_text(dir_ / "count.ele", "1 4 0\n1 1 2 3 4\n");
  const std::string tet = error("count.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n");
  EXPECT_NE(tet.find("count.node:5: the file ends where point 4 of 4 was expected"), std::string::npos) << tet;
}

TEST_F(MeshIoBadInput, OutOfRangeIndices) {
  const std::string e = error("range.msh", replaced(kTet22, "3 4 2 0 1 2 3 4 5", "3 4 2 0 1 2 3 4 99"));
  EXPECT_NE(e.find("range.msh:16: element 3 refers to node 99, which the $Nodes section does not define"),
            std::string::npos)
      << e;
  const std::string v = error("range.vtk",
                              "# vtk DataFile Version 4.2\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
                              "0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 4\nCELL_TYPES 1\n10\n");
  EXPECT_NE(v.find("range.vtk:8: cell 0 refers to point 4, but the file has 4 points"), std::string::npos) << v;
  const std::string m = error("range.mesh",
                              "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n"
                              "Tetrahedra\n1\n1 2 3 0 0\nEnd\n");
  EXPECT_NE(m.find("range.mesh:11: tetrahedron 1 refers to vertex 0, but the file has 4 Vertices (numbered from 1)"),
            std::string::npos)
      << m;
  write_text(dir_ / "range.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n");
  const std::string t = error("range.ele", "1 4 0\n1 1 2 3 5\n");
  EXPECT_NE(t.find("range.ele:2: tetrahedron 1 refers to point 5, which"), std::string::npos) << t;
  const Mesh mesh = make_tet_box(1, 1, 1, 1.0);
  // write_vtu checks indices, so a good file is written and edited.
  write_vtu((dir_ / "range.vtu").string(), mesh, mesh.positions);
  std::string vtu = text_of(dir_ / "range.vtu");
  const size_t c = vtu.find("Name=\"connectivity\"");
  const size_t first = vtu.find("\n", c) + 1;
  const size_t line_end = vtu.find("\n", first);
  vtu.replace(first, line_end - first, "          0 108 3 7");
  const std::string u = error("range.vtu", vtu);
  EXPECT_NE(u.find("range.vtu:"), std::string::npos) << u;
  EXPECT_NE(u.find("cell 0 refers to point 108, but the file has 8 points"), std::string::npos) << u;
}

TEST_F(MeshIoBadInput, UnsupportedElementTypes) {
  const std::string e = error("prism.msh", replaced(kTet22, "3 4 2 0 1 2 3 4 5", "3 6 2 0 1 1 2 3 4 5 5"));
  EXPECT_NE(e.find("prism.msh:16: element 3 has unsupported type 6 (6-node prism); only 4-node tetrahedra (type "
                   "4) and 8-node hexahedra (type 5) are supported"),
            std::string::npos)
      << e;
  const std::string q = error("tet10.msh", replaced(kTet22, "3 4 2 0 1 2 3 4 5", "3 11 2 0 1 1 2 3 4 5 1 2 3 4 5"));
  EXPECT_NE(q.find("tet10.msh:16: element 3 has unsupported type 11 (10-node tetrahedron)"), std::string::npos) << q;
  const std::string u = error("unknown.msh", replaced(kTet22, "3 4 2 0 1 2 3 4 5", "3 999 2 0 1 2 3 4 5"));
  EXPECT_NE(u.find("unknown.msh:16: element 3 has unknown element type 999"), std::string::npos) << u;
  const std::string v = error("wedge.vtk",
                              "# vtk DataFile Version 4.2\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 6 double\n"
                              "0 0 0 1 0 0 0 1 0 0 0 1 1 0 1 0 1 1\nCELLS 1 7\n6 0 1 2 3 4 5\nCELL_TYPES 1\n13\n");
  EXPECT_NE(v.find("wedge.vtk:8: cell 0 has unsupported VTK cell type 13 (wedge)"), std::string::npos) << v;
  const std::string m =
      error("prisms.mesh", "MeshVersionFormatted 2\nDimension 3\nVertices\n1\n0 0 0 0\nPrisms\n1\n1 1 1 1 1 1 0\n");
  EXPECT_NE(m.find("prisms.mesh:6: the file has 1 Prisms, an unsupported element type"), std::string::npos) << m;
  write_text(dir_ / "tet10.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n");
  const std::string t = error("tet10.ele", "1 10 0\n1 1 2 3 4 1 1 1 1 1 1\n");
  EXPECT_NE(t.find("tet10.ele:1: 10 nodes per tetrahedron are not supported"), std::string::npos) << t;
  const std::string mixed = error("mixed.msh", replaced(kTet22, "3 4 2 0 1 2 3 4 5", "3 5 2 0 1 1 2 3 4 5 1 2 3"));
  EXPECT_NE(mixed.find("mixed.msh:16: element 3 is a hexahedron, but element 2 (line 15) is a tetrahedron"),
            std::string::npos)
      << mixed;
  const std::string surface = error("surface.msh", replaced(replaced(kTet22, "2 4 2 0 1 1 2 3 4", "2 2 2 0 1 1 2 4"),
                                                            "3 4 2 0 1 2 3 4 5", "3 2 2 0 1 2 3 4"));
  EXPECT_NE(surface.find("surface.msh: the file holds no tetrahedra or 8-node hexahedra"), std::string::npos)
      << surface;
  const std::string ext = read_error(dir_ / "mesh.stl");
  EXPECT_NE(ext.find("mesh.stl: unknown mesh format '.stl'"), std::string::npos) << ext;
  const std::string missing = read_error(dir_ / "missing.msh");
  EXPECT_NE(missing.find("cannot read"), std::string::npos) << missing;
  EXPECT_NE(missing.find("missing.msh"), std::string::npos) << missing;
}

TEST_F(MeshIoBadInput, NonFiniteCoordinates) {
  const std::string e = error("nan.msh", replaced(kTet22, "4 0 0 1\n", "4 0 nan 1\n"));
  EXPECT_NE(e.find("nan.msh:9: vertex 4 has a non-finite coordinate (y = nan)"), std::string::npos) << e;
  const std::string i = error("inf.msh", replaced(kTet22, "4 0 0 1\n", "4 0 0 1e999\n"));
  EXPECT_NE(i.find("inf.msh:9: vertex 4 has a non-finite coordinate (z = inf)"), std::string::npos) << i;
  const std::string m = error("inf.mesh", "MeshVersionFormatted 2\nDimension 3\nVertices\n2\n0 0 0 0\n-inf 0 0 0\n");
  EXPECT_NE(m.find("inf.mesh:6: vertex 2 has a non-finite coordinate (x = -inf)"), std::string::npos) << m;
  // Binary: the byte offset of the node.
  Mesh mesh = make_tet_box(1, 1, 1, 1.0);
  mesh.positions(2, 1) = std::numeric_limits<double>::quiet_NaN();
  write_msh22(dir_ / "nan_binary.msh", mesh, true);
  const std::string b = read_error(dir_ / "nan_binary.msh");
  EXPECT_NE(b.find("nan_binary.msh (byte "), std::string::npos) << b;
  EXPECT_NE(b.find("vertex 3 has a non-finite coordinate (y = nan)"), std::string::npos) << b;
}

TEST_F(MeshIoBadInput, DuplicateVertices) {
  const std::string e = error("dup.msh", replaced(kTet22, "5 1 1 1\n", "5 0 1 0\n"));
  EXPECT_NE(e.find("dup.msh:10: vertex 5 duplicates vertex 3 (line 8): both are at (0, 1, 0)"), std::string::npos) << e;
  write_text(dir_ / "dup.node", "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 -0 0\n");
  const std::string t = error("dup.ele", "1 4 0\n0 0 1 2 3\n");
  EXPECT_NE(t.find("dup.node:5: vertex 3 duplicates vertex 0 (line 2): both are at (0, 0, 0)"), std::string::npos) << t;
  const std::string twice = error("twice.msh", replaced(kTet22, "3 4 2 0 1 2 3 4 5", "3 4 2 0 1 2 3 4 2"));
  EXPECT_NE(twice.find("twice.msh:16: element 3 uses vertex 2 twice (nodes 0 and 3)"), std::string::npos) << twice;
  const std::string tag = error("tag.msh", replaced(kTet22, "5 1 1 1\n", "4 1 1 1\n"));
  EXPECT_NE(tag.find("tag.msh:10: node 4 is defined twice"), std::string::npos) << tag;
}

TEST_F(MeshIoBadInput, DegenerateAndTangledElements) {
  const std::string e = error("flat.msh", replaced(kTet22, "5 1 1 1\n", "5 0.5 0.5 0\n"));
  EXPECT_NE(e.find("flat.msh:16: element 3 (tetrahedron) has zero volume: its four vertices are coplanar"),
            std::string::npos)
      << e;
  // A hex with two nodes exchanged across a face diagonal: tangled.
  Mesh hex = make_box_lattice(1, 1, 1, 1.0);
  std::swap(hex.elements[0], hex.elements[2]);
  write_medit(dir_ / "tangled.mesh", hex);
  const std::string t = read_error(dir_ / "tangled.mesh");
  EXPECT_NE(t.find("tangled.mesh:16: element 1 (hexahedron) is degenerate or tangled"), std::string::npos) << t;
  // A hex squashed flat.
  Mesh flat = make_box_lattice(1, 1, 1, 1.0);
  for (size_t v = 0; v < flat.vertex_count(); ++v) flat.positions(v, 2) *= 1e-20;
  write_vtk(dir_ / "flat.vtk", flat, true, false);
  const std::string f = read_error(dir_ / "flat.vtk");
  EXPECT_NE(f.find("flat.vtk (byte "), std::string::npos) << f;
  EXPECT_NE(f.find("cell 0 (hexahedron) has zero volume"), std::string::npos) << f;
}

// Inputs that once crashed a fuzzed reader: each must now be rejected with an
// snh::Error.
TEST(MeshIoFuzzRegressions, EachIsRejectedCleanly) {
  const fs::path root = fs::path(SNH_DATA_DIR).parent_path() / "tests" / "fuzz_regressions";
  int count = 0;
  if (fs::exists(root))
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
      // The mesh formats' inputs; the surfaces', animations' and scenes' are FuzzRegressions'.
      const std::string ext = entry.path().extension().string();
      if (!entry.is_regular_file() ||
          (ext != ".msh" && ext != ".vtk" && ext != ".vtu" && ext != ".mesh" && ext != ".node"))
        continue;
      SCOPED_TRACE(entry.path().string());
      const std::string message = read_error(entry.path());
      EXPECT_NE(message.find(entry.path().stem().string()), std::string::npos) << message;
      ++count;
    }
  if (count == 0) GTEST_SKIP() << "no regression inputs under " << root;
}

// ---- snh-mesh-info ----

#ifdef SNH_MESH_INFO_BINARY
TEST(MeshIoTool, ReportsAndFailsWithNonZeroExit) {
  const fs::path dir = scratch("tool");
  const std::string ok = "\"" SNH_MESH_INFO_BINARY "\" \"" + (kData / "hex_box.msh").string() + "\" > \"" +
                         (dir / "out.json").string() + "\"";
  ASSERT_EQ(std::system(ok.c_str()), 0);
  const std::string json = text_of(dir / "out.json");
  EXPECT_NE(json.find("\"vertices\": 45"), std::string::npos) << json;
  EXPECT_NE(json.find("\"type\": \"hex8\""), std::string::npos) << json;
  write_text(dir / "bad.msh", replaced(kTet22, "3 4 2 0 1 2 3 4 5", "3 4 2 0 1 2 3 4 99"));
  const std::string bad =
      "\"" SNH_MESH_INFO_BINARY "\" \"" + (dir / "bad.msh").string() + "\" 2> \"" + (dir / "err.txt").string() + "\"";
  EXPECT_NE(std::system(bad.c_str()), 0);
  EXPECT_NE(text_of(dir / "err.txt").find("bad.msh:16: element 3 refers to node 99"), std::string::npos);
}
#endif

// ---- Boundary surfaces ----

struct Surface {
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::vector<int>> faces;  // 0-based
};

Surface read_obj(const fs::path& path) {
  Surface s;
  std::ifstream file(path);
  std::string line;
  while (std::getline(file, line)) {
    std::istringstream in(line);
    std::string key;
    in >> key;
    if (key == "v") {
      std::array<double, 3> v;
      in >> v[0] >> v[1] >> v[2];
      s.vertices.push_back(v);
    } else if (key == "f") {
      std::vector<int> f;
      int i;
      while (in >> i) f.push_back(i - 1);
      s.faces.push_back(f);
    }
  }
  return s;
}

Surface read_ply(const fs::path& path) {
  Surface s;
  std::ifstream file(path);
  std::string line;
  size_t vertices = 0, faces = 0;
  while (std::getline(file, line) && line != "end_header") {
    std::istringstream in(line);
    std::string a, b;
    size_t n = 0;
    in >> a >> b >> n;
    if (a == "element" && b == "vertex") vertices = n;
    if (a == "element" && b == "face") faces = n;
  }
  for (size_t i = 0; i < vertices; ++i) {
    std::array<double, 3> v;
    file >> v[0] >> v[1] >> v[2];
    s.vertices.push_back(v);
  }
  for (size_t i = 0; i < faces; ++i) {
    int n;
    file >> n;
    std::vector<int> f(n);
    for (int& v : f) file >> v;
    s.faces.push_back(f);
  }
  return s;
}

// Closed (every directed edge matched by its reverse exactly once), and
// every face's normal points away from the centroid of a convex body.
void expect_closed_and_outward(const Surface& s, const std::array<double, 3>& centre) {
  std::map<std::pair<int, int>, int> edges;
  for (const auto& f : s.faces)
    for (size_t c = 0; c < f.size(); ++c) ++edges[{f[c], f[(c + 1) % f.size()]}];
  for (const auto& [edge, count] : edges) {
    EXPECT_EQ(count, 1) << edge.first << "-" << edge.second;
    const auto reverse = edges.find({edge.second, edge.first});
    EXPECT_TRUE(reverse != edges.end() && reverse->second == 1) << edge.first << "-" << edge.second;
  }
  for (const auto& f : s.faces) {
    std::array<double, 3> normal{}, mid{};
    for (size_t c = 0; c < f.size(); ++c) {
      const auto& p = s.vertices[f[c]];
      const auto& q = s.vertices[f[(c + 1) % f.size()]];
      normal[0] += (p[1] - q[1]) * (p[2] + q[2]);  // Newell's method
      normal[1] += (p[2] - q[2]) * (p[0] + q[0]);
      normal[2] += (p[0] - q[0]) * (p[1] + q[1]);
      for (int d = 0; d < 3; ++d) mid[d] += p[d] / double(f.size());
    }
    double dot = 0.0;
    for (int d = 0; d < 3; ++d) dot += normal[d] * (mid[d] - centre[d]);
    EXPECT_GT(dot, 0.0);
  }
}

TEST(MeshIoSurface, BoxLatticeIsClosedAndOutward) {
  const fs::path dir = scratch("surface");
  const int nx = 3, ny = 2, nz = 4;
  const double h = 0.5;
  const size_t quads = 2 * (nx * ny + ny * nz + nx * nz);
  const size_t boundary_vertices = (nx + 1) * (ny + 1) * (nz + 1) - (nx - 1) * (ny - 1) * (nz - 1);
  const std::array<double, 3> centre = {nx * h / 2, ny * h / 2, nz * h / 2};
  for (const Mesh& mesh : {make_box_lattice(nx, ny, nz, h), make_tet_box(nx, ny, nz, h)}) {
    SCOPED_TRACE(to_string(mesh.type));
    const bool hex = mesh.type == ElementType::hex8;
    write_obj_surface((dir / "box.obj").string(), mesh);
    write_ply_surface((dir / "box.ply").string(), mesh);
    for (const Surface& s : {read_obj(dir / "box.obj"), read_ply(dir / "box.ply")}) {
      EXPECT_EQ(s.faces.size(), hex ? quads : 2 * quads);
      EXPECT_EQ(s.vertices.size(), boundary_vertices);
      for (const auto& f : s.faces) EXPECT_EQ(f.size(), hex ? 4u : 3u);
      expect_closed_and_outward(s, centre);
    }
  }
}

TEST(MeshIoSurface, DeformedPositionsAndReadMeshes) {
  const fs::path dir = scratch("surface_deformed");
  const Mesh mesh = read_mesh((kData / "box_tet.msh41.msh").string());
  std::vector<double> x = mesh.positions.xyz();
  for (double& v : x) v *= 2.0;
  write_obj_surface((dir / "box.obj").string(), mesh, Points::from_xyz(std::move(x)));
  const Surface s = read_obj(dir / "box.obj");
  expect_closed_and_outward(s, {1.0, 0.5, 0.25});
  for (const auto& v : s.vertices)
    EXPECT_TRUE(v[0] == 0.0 || v[0] == 2.0 || v[1] == 0.0 || v[1] == 1.0 || v[2] == 0.0 || v[2] == 0.5);
  const Mesh hexes = read_mesh((kData / "hex_box.mesh").string());
  write_ply_surface((dir / "hex.ply").string(), hexes);
  const Surface h = read_ply(dir / "hex.ply");
  EXPECT_EQ(h.faces.size(), 2u * (4 * 2 + 2 * 2 + 4 * 2));
  expect_closed_and_outward(h, {0.5, 0.25, 0.125});
}

TEST(MeshIoSurface, BadArguments) {
  const fs::path dir = scratch("surface_bad");
  const Mesh mesh = make_box_lattice(1, 1, 1, 1.0);
  const std::string e = error_of([&] { write_obj_surface((dir / "a.obj").string(), mesh, Points(2)); });
  EXPECT_NE(e.find("write_obj_surface"), std::string::npos) << e;
  EXPECT_NE(e.find("the positions have 6 values, but the mesh has 8 vertices"), std::string::npos) << e;
  const std::string d = error_of([&] { write_ply_surface((dir / "no" / "such" / "a.ply").string(), mesh); });
  EXPECT_NE(d.find("cannot be opened"), std::string::npos) << d;
}

// ---- Groups and arrays ----

std::array<double, 3> centroid(const Mesh& m, size_t e) {
  const int n = nodes_per_element(m.type);
  std::array<double, 3> c{0, 0, 0};
  for (int a = 0; a < n; ++a)
    for (int d = 0; d < 3; ++d) c[d] += m.positions(m.elements[n * e + a], d) / n;
  return c;
}

TEST(MeshIoGroups, GmshPhysicalGroupsInEveryVersion) {
  struct Expected {
    const char* name;
    int tag, dimension;
    size_t vertices, elements;
  };
  // As gmsh wrote them (and meshio reads them: tests/meshio_crosscheck.py).
  const Expected expected[] = {{"fixed", 1, 2, 28, 0},
                               {"", 7, 2, 28, 0},
                               {"left", 1, 3, 153, 398},
                               {"right", 2, 3, 154, 405},
                               {"all", 3, 3, 279, 803}};
  const Mesh first = read_mesh((kData / "box_groups.msh41.msh").string());
  for (const char* file :
       {"box_groups.msh22.msh", "box_groups.msh22_binary.msh", "box_groups.msh41.msh", "box_groups.msh41_binary.msh"}) {
    SCOPED_TRACE(file);
    const Mesh m = read_mesh((kData / file).string());
    // 2.2 writes each tet twice (its side's group and "all"): one element each.
    EXPECT_EQ(m.element_count(), 803u);
    ASSERT_EQ(m.groups.size(), 5u);
    for (size_t i = 0; i < 5; ++i) {
      const MeshGroup& g = m.groups[i];
      EXPECT_EQ(g.name, expected[i].name) << i;
      EXPECT_EQ(g.tag, expected[i].tag) << i;
      EXPECT_EQ(g.dimension, expected[i].dimension) << i;
      EXPECT_EQ(g.vertices.size(), expected[i].vertices) << i;
      EXPECT_EQ(g.elements.size(), expected[i].elements) << i;
      EXPECT_EQ(g.vertices, first.groups[i].vertices) << i;
      EXPECT_EQ(g.elements, first.groups[i].elements) << i;
    }
    // The surfaces hold the mesh's vertices on their faces.
    EXPECT_EQ(vertices_in_group(m, "fixed"), vertices_on_plane(m, {0, 0, 0}, {1, 0, 0}));
    EXPECT_EQ(vertices_in_group(m, 7), vertices_on_plane(m, {1, 0, 0}, {1, 0, 0}));
    // The volumes split the box at x = 0.5.
    EXPECT_EQ(elements_in_group(m, "left"), elements_in_box(m, {0, 0, 0}, {0.5, 1, 1}));
    EXPECT_EQ(elements_in_group(m, "right"), elements_in_box(m, {0.5, 0, 0}, {1, 1, 1}));
    for (int32_t e : elements_in_group(m, 1)) EXPECT_LT(centroid(m, e)[0], 0.5);
    EXPECT_EQ(elements_in_group(m, "all").size(), m.element_count());
    EXPECT_EQ(m.elements, first.elements);
  }
  // The old files without physical groups have none.
  EXPECT_TRUE(read_mesh((kData / "box_tet.msh41.msh").string()).groups.empty());
  EXPECT_TRUE(read_mesh((kData / "box_tet.msh22.msh").string()).groups.empty());
}

TEST(MeshIoGroups, MeditReferencesBecomeGroupsNamedByTheirNumber) {
  const Mesh m = read_mesh((kData / "box_tet.mesh").string());
  // gmsh writes the elementary entity tags: volume 1, surfaces 1..6 (x = 0,
  // x = 1, y = 0, y = 1, z = 0, z = 1 for an OpenCASCADE box), curves 1..12.
  EXPECT_EQ(elements_in_group(m, "1").size(), 627u);
  EXPECT_EQ(vertices_in_group(m, "1", 2), vertices_on_plane(m, {0, 0, 0}, {1, 0, 0}));
  EXPECT_EQ(vertices_in_group(m, 6, 2), vertices_on_plane(m, {0, 0, 0.25}, {0, 0, 1}));
}

TEST(MeshIoArrays, VtkAndVtuArraysMatchTheirDefinitions) {
  const Mesh groups = read_mesh((kData / "box_groups.msh41.msh").string());
  for (const char* file : {"box_groups_arrays.vtu", "box_groups_arrays_base64.vtu", "box_groups_arrays.vtk",
                           "box_groups_arrays_binary.vtk"}) {
    SCOPED_TRACE(file);
    const Mesh m = read_mesh((kData / file).string());
    ASSERT_EQ(m.point_arrays.size(), 2u);
    ASSERT_EQ(m.cell_arrays.size(), 2u);
    const MeshArray &t = m.point_arrays[0], &u = m.point_arrays[1];
    EXPECT_EQ(t.name, "temperature");
    EXPECT_EQ(t.components, 1);
    EXPECT_EQ(u.name, "displacement");
    EXPECT_EQ(u.components, 3);
    for (size_t v = 0; v < m.vertex_count(); ++v) {
      // meshio writes ASCII data with 12 significant digits.
      EXPECT_NEAR(t.values[v], m.positions(v, 0) + 2 * m.positions(v, 1), 1e-11) << v;
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(u.values[3 * v + d], 0.1 * m.positions(v, d), 1e-11) << v;
    }
    const MeshArray &material = m.cell_arrays[0], &stiffness = m.cell_arrays[1];
    EXPECT_EQ(material.name, "material");
    EXPECT_EQ(stiffness.name, "stiffness");
    for (size_t e = 0; e < m.element_count(); ++e) {
      EXPECT_EQ(material.values[e], centroid(m, e)[0] < 0.5 ? 1.0 : 2.0) << e;
      EXPECT_NEAR(stiffness.values[e], 1 + centroid(m, e)[0], 1e-11) << e;
    }
    EXPECT_EQ(m.elements, groups.elements);
    EXPECT_EQ(elements_with_value(m, "material", 1), elements_in_group(groups, "left"));
    // x + 2y = 0 on the edge x = y = 0 only.
    EXPECT_EQ(vertices_with_value(m, "temperature", 0.0), vertices_in_box(m, {0, 0, 0}, {0, 0, 1}));
    EXPECT_GT(vertices_with_value(m, "temperature", 0.0).size(), 2u);
  }
}

TEST_F(MeshIoBadInput, CellArraysFollowTheKeptVolumeCells) {
  // A triangle, a line and a vertex among two tets (the second mirrored):
  // cell arrays keep the entries of the tets, in order.
  const std::string points =
      "POINTS 5 double\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n"
      "CELLS 5 19\n3 0 1 2\n4 0 1 2 3\n2 3 4\n4 1 2 4 3\n1 4\nCELL_TYPES 5\n5\n10\n3\n10\n1\n";
  const std::string text = "# vtk DataFile Version 4.2\narrays\nASCII\nDATASET UNSTRUCTURED_GRID\n" + points +
                           "CELL_DATA 5\nSCALARS id int 1\nLOOKUP_TABLE default\n10 20 30 40 50\n"
                           "VECTORS v float\n0 0 0 1 2 3 0 0 0 4 5 6 0 0 0\n"
                           "POINT_DATA 5\nSCALARS t double\nLOOKUP_TABLE default\n0 1 2 3 4\n"
                           "NORMALS my%20normals float\n1 0 0 0 1 0 0 0 1 1 0 0 0 1 0\n"
                           "LOOKUP_TABLE colours 1\n0 0 0 1\n"
                           "FIELD FieldData 1\nw 2 5 double\n0 1 2 3 4 5 6 7 8 9\n";
  write_text(dir_ / "arrays.vtk", text);
  const Mesh m = read_mesh((dir_ / "arrays.vtk").string());
  ASSERT_EQ(m.element_count(), 2u);
  ASSERT_EQ(m.cell_arrays.size(), 2u);
  EXPECT_EQ(m.cell_arrays[0].values, (std::vector<double>{20, 40}));
  EXPECT_EQ(m.cell_arrays[1].values, (std::vector<double>{1, 2, 3, 4, 5, 6}));
  ASSERT_EQ(m.point_arrays.size(), 3u);
  EXPECT_EQ(m.point_arrays[0].values, (std::vector<double>{0, 1, 2, 3, 4}));
  EXPECT_EQ(m.point_arrays[1].name, "my normals");
  EXPECT_EQ(m.point_arrays[1].components, 3);
  EXPECT_EQ(m.point_arrays[2].name, "w");
  EXPECT_EQ(m.point_arrays[2].components, 2);
  EXPECT_EQ(m.point_arrays[2].values[9], 9.0);
  // Split into tets, the arrays and (none here) groups go along.
  EXPECT_EQ(elements_with_value(m, "id", 40), std::vector<int32_t>{1});

  // The same in VTU: CellData of the volume cells only.
  const std::string vtu =
      "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n"
      "<Piece NumberOfPoints=\"5\" NumberOfCells=\"4\">\n"
      "<PointData><DataArray type=\"Float32\" Name=\"t\" format=\"ascii\">0 1 2 3 4</DataArray></PointData>\n"
      "<CellData><DataArray type=\"Int32\" Name=\"id\" format=\"ascii\">10 20 30 40</DataArray>\n"
      "<DataArray type=\"Float64\" Name=\"v\" NumberOfComponents=\"2\" format=\"ascii\">0 0 1 2 0 0 3 4"
      "</DataArray></CellData>\n"
      "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">"
      "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1</DataArray></Points>\n<Cells>\n"
      "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2 0 1 2 3 3 4 1 2 4 3</DataArray>\n"
      "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">3 7 9 13</DataArray>\n"
      "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">5 10 3 10</DataArray>\n"
      "</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  write_text(dir_ / "arrays.vtu", vtu);
  const Mesh x = read_mesh((dir_ / "arrays.vtu").string());
  ASSERT_EQ(x.cell_arrays.size(), 2u);
  EXPECT_EQ(x.cell_arrays[0].values, (std::vector<double>{20, 40}));
  EXPECT_EQ(x.cell_arrays[1].values, (std::vector<double>{1, 2, 3, 4}));
  EXPECT_EQ(x.point_arrays[0].values, (std::vector<double>{0, 1, 2, 3, 4}));
}

TEST_F(MeshIoBadInput, BinaryScalarsStartingWithASpaceByte) {
  const Mesh m = make_tet_box(1, 1, 1, 1.0);
  write_vtk(dir_ / "binary.vtk", m, true, false);
  // 0x20 is ' ': the reader must not skip it as whitespace.
  double first = 0.0;
  const uint64_t bits = 0x2000000000000001ull;
  std::memcpy(&first, &bits, 8);
  {
    std::ofstream f(dir_ / "binary.vtk", std::ios::binary | std::ios::app);
    f << "SCALARS s double 1\nLOOKUP_TABLE default\n";
    for (size_t e = 0; e < m.element_count(); ++e) put<double>(f, e == 0 ? first : double(e), true);
    f << "\n";
  }
  const Mesh r = read_mesh((dir_ / "binary.vtk").string());
  ASSERT_EQ(r.cell_arrays.size(), 1u);
  EXPECT_EQ(r.cell_arrays[0].values[0], first);
  EXPECT_EQ(r.cell_arrays[0].values[5], 5.0);
}

TEST_F(MeshIoBadInput, MalformedGroupsAndArrays) {
  const std::string msh22 = text_of(kData / "box_groups.msh22.msh");
  std::string m = error("count.msh", replaced(msh22, "$PhysicalNames\n4\n", "$PhysicalNames\n5\n"));
  EXPECT_NE(m.find("count.msh:10: physical name 5 of 5 should read"), std::string::npos) << m;
  m = error("unknown.msh", replaced(msh22, "3 3 \"all\"", "3 9 \"all\""));
  EXPECT_NE(m.find("unknown.msh:9: $PhysicalNames names physical volume 9 'all', but no element belongs to it"),
            std::string::npos)
      << m;
  m = error("twice.msh", replaced(msh22, "3 3 \"all\"", "3 2 \"all\""));
  EXPECT_NE(m.find("twice.msh:9: physical volume 2 is named twice (first 'right', line 8)"), std::string::npos) << m;
  m = error("quotes.msh", replaced(msh22, "3 3 \"all\"", "3 3 all"));
  EXPECT_NE(m.find("quotes.msh:9: the name of physical group 3 is not in double quotes"), std::string::npos) << m;
  m = error("dimension.msh", replaced(msh22, "3 3 \"all\"", "4 3 \"all\""));
  EXPECT_NE(m.find("dimension.msh:9: physical group 3 has dimension 4"), std::string::npos) << m;
  const std::string msh41 = text_of(kData / "box_groups.msh41.msh");
  m = error("entity.msh", replaced(msh41, "\n3 1 4 398\n", "\n3 5 4 398\n"));
  EXPECT_NE(m.find("entity.msh:745: an element block belongs to entity 5 of dimension 3, which the $Entities "
                   "section does not define"),
            std::string::npos)
      << m;
  m = error("entities.msh", replaced(msh41, "$Entities\n12 20 11 2\n", "$Entities\n12 20 11 3\n"));
  EXPECT_NE(m.find("entities.msh:"), std::string::npos) << m;

  const std::string vtk = text_of(kData / "box_groups_arrays.vtk");
  m = error("points.vtk", replaced(vtk, "POINT_DATA 279", "POINT_DATA 278"));
  EXPECT_NE(m.find("POINT_DATA is for 278 points, but the file has 279"), std::string::npos) << m;
  m = error("tuples.vtk", replaced(vtk, "temperature 1 279 double", "temperature 1 278 double"));
  EXPECT_NE(m.find("FIELD array 'temperature' has 278 tuples, but its POINT_DATA section is for 279 points"),
            std::string::npos)
      << m;
  m = error("keyword.vtk", replaced(vtk, "CELL_DATA 803\nFIELD", "CELL_DATA 803\nFILED"));
  EXPECT_NE(m.find("unexpected keyword 'FILED' in CELL_DATA"), std::string::npos) << m;
  m = error("short.vtk", vtk.substr(0, vtk.size() - 2000));
  EXPECT_NE(m.find("short.vtk:"), std::string::npos) << m;
  m = error("before.vtk", replaced(vtk, "POINTS 279", "POINT_DATA 279\nPOINTS 279"));
  EXPECT_NE(m.find("POINT_DATA comes before POINTS"), std::string::npos) << m;

  const std::string vtu = text_of(kData / "box_groups_arrays.vtu");
  m = error("components.vtu", replaced(vtu, "Name=\"displacement\" NumberOfComponents=\"3\"",
                                       "Name=\"displacement\" NumberOfComponents=\"1\""));
  EXPECT_NE(m.find("PointData array 'displacement' holds 837 values, but 279 tuples of 1 components need 279"),
            std::string::npos)
      << m;
  m = error("twice.vtu", replaced(vtu, "Name=\"stiffness\"", "Name=\"material\""));
  EXPECT_NE(m.find("a second cell array named 'material'"), std::string::npos) << m;
}

}  // namespace
}  // namespace snh
