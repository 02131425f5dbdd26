// The bones as triangles, to be seen beside the lattice (snh/rig.h):
// capsules tessellated, surface bones as they are, each placed by its frame's
// transform, written as a .vtu with the bone of each triangle.
#include <cmath>
#include <fstream>
#include <sstream>

#include "snh/animation.h"
#include "snh/error.h"
#include "snh/rig.h"

namespace snh {
namespace {

using Point = std::array<double, 3>;

Point cross(const Point& a, const Point& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

Point normalized(const Point& a) {
  const double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  return {a[0] / n, a[1] / n, a[2] / n};
}

// A closed capsule: a pole, rings of `segments` vertices (round end at a,
// the straight part, round end at b), a pole; outward by construction.
void add_capsule(const Capsule& c, int segments, TriangleSurface& s) {
  Point axis{c.b[0] - c.a[0], c.b[1] - c.a[1], c.b[2] - c.a[2]};
  const double length = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  axis = length > 0.0 ? Point{axis[0] / length, axis[1] / length, axis[2] / length} : Point{0, 0, 1};
  const Point helper = std::abs(axis[0]) < 0.9 ? Point{1, 0, 0} : Point{0, 1, 0};
  const Point u = normalized(cross(axis, helper)), v = cross(axis, u);
  const int quarter = std::max(1, segments / 4);  // rings per round end, the equator included
  const double pi = std::acos(-1.0);
  const int32_t base = static_cast<int32_t>(s.vertex_count());
  const auto add = [&](const Point& p) { s.positions.push_back(p); };
  add({c.a[0] - c.radius * axis[0], c.a[1] - c.radius * axis[1], c.a[2] - c.radius * axis[2]});
  // Ring k of 2 * quarter: latitude from -90 degrees (exclusive) to 0 at a, then 0 to 90 (exclusive) at b.
  int rings = 0;
  for (int end = 0; end < 2; ++end)
    for (int k = 0; k < quarter; ++k, ++rings) {
      const double latitude = end == 0 ? -pi / 2 + (k + 1) * (pi / 2) / quarter : k * (pi / 2) / quarter;
      const Point& centre = end == 0 ? c.a : c.b;
      const double along = c.radius * std::sin(latitude), r = c.radius * std::cos(latitude);
      for (int j = 0; j < segments; ++j) {
        const double phi = 2 * pi * j / segments, cu = std::cos(phi) * r, cv = std::sin(phi) * r;
        add({centre[0] + along * axis[0] + cu * u[0] + cv * v[0], centre[1] + along * axis[1] + cu * u[1] + cv * v[1],
             centre[2] + along * axis[2] + cu * u[2] + cv * v[2]});
      }
    }
  add({c.b[0] + c.radius * axis[0], c.b[1] + c.radius * axis[1], c.b[2] + c.radius * axis[2]});
  const int32_t south = base, north = base + 1 + rings * segments;
  const auto ring = [&](int k, int j) { return base + 1 + k * segments + (j % segments); };
  // (u, v, axis) is right-handed: counter-clockwise about +axis is increasing phi.
  for (int j = 0; j < segments; ++j) s.triangles.insert(s.triangles.end(), {south, ring(0, j + 1), ring(0, j)});
  for (int k = 0; k + 1 < rings; ++k)
    for (int j = 0; j < segments; ++j)
      s.triangles.insert(s.triangles.end(), {ring(k, j), ring(k, j + 1), ring(k + 1, j + 1), ring(k, j),
                                             ring(k + 1, j + 1), ring(k + 1, j)});
  for (int j = 0; j < segments; ++j)
    s.triangles.insert(s.triangles.end(), {north, ring(rings - 1, j), ring(rings - 1, j + 1)});
}

}  // namespace

BoneMesh bone_mesh(const std::vector<Bone>& bones, const std::vector<Matrix4>& transforms, int segments) {
  if (!transforms.empty() && transforms.size() != bones.size())
    throw Error("bone_mesh: " + std::to_string(transforms.size()) + " transforms for " + std::to_string(bones.size()) +
                " bones");
  if (segments < 3) throw Error("bone_mesh: segments must be >= 3, got " + std::to_string(segments));
  BoneMesh out;
  TriangleSurface& s = out.surface;
  for (size_t b = 0; b < bones.size(); ++b) {
    const size_t first_vertex = s.vertex_count();
    if (const Capsule* c = std::get_if<Capsule>(&bones[b].shape)) {
      add_capsule(*c, segments, s);
    } else {
      const TriangleSurface& t = std::get<TriangleSurface>(bones[b].shape);
      for (size_t i = 0; i < t.vertex_count(); ++i)
        s.positions.push_back({t.positions(i, 0), t.positions(i, 1), t.positions(i, 2)});
      for (int32_t i : t.triangles) s.triangles.push_back(static_cast<int32_t>(first_vertex) + i);
    }
    out.vertex_bone.resize(s.vertex_count(), static_cast<int32_t>(b));
    out.triangle_bone.resize(s.triangle_count(), static_cast<int32_t>(b));
    if (transforms.empty()) continue;
    const Matrix4& m = transforms[b];
    for (size_t v = first_vertex; v < s.vertex_count(); ++v) {
      const Point p{s.positions(v, 0), s.positions(v, 1), s.positions(v, 2)};
      for (int r = 0; r < 3; ++r)
        s.positions(v, r) = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
    }
  }
  return out;
}

void write_bone_mesh_vtu(const std::string& path, const BoneMesh& mesh) {
  const TriangleSurface& s = mesh.surface;
  if (mesh.triangle_bone.size() != s.triangle_count())
    throw Error("write_bone_mesh_vtu " + path + ": " + std::to_string(mesh.triangle_bone.size()) +
                " bone indices for " + std::to_string(s.triangle_count()) + " triangles");
  std::ofstream out(path);
  if (!out) throw Error("write_bone_mesh_vtu: cannot write " + path);
  out.precision(17);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <UnstructuredGrid>\n"
      << "    <Piece NumberOfPoints=\"" << s.vertex_count() << "\" NumberOfCells=\"" << s.triangle_count() << "\">\n"
      << "      <Points>\n        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (size_t v = 0; v < s.vertex_count(); ++v)
    out << "          " << s.positions(v, 0) << ' ' << s.positions(v, 1) << ' ' << s.positions(v, 2) << '\n';
  out << "        </DataArray>\n      </Points>\n      <Cells>\n"
      << "        <DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n";
  for (size_t t = 0; t < s.triangle_count(); ++t)
    out << "          " << s.triangles[3 * t] << ' ' << s.triangles[3 * t + 1] << ' ' << s.triangles[3 * t + 2] << '\n';
  out << "        </DataArray>\n        <DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n";
  for (size_t t = 0; t < s.triangle_count(); ++t) out << "          " << 3 * (t + 1) << '\n';
  out << "        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (size_t t = 0; t < s.triangle_count(); ++t) out << "          5\n";  // VTK_TRIANGLE
  out << "        </DataArray>\n      </Cells>\n      <CellData Scalars=\"bone\">\n"
      << "        <DataArray type=\"Int32\" Name=\"bone\" format=\"ascii\">\n";
  for (int32_t b : mesh.triangle_bone) out << "          " << b << '\n';
  out << "        </DataArray>\n      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  if (!out) throw Error("write_bone_mesh_vtu: cannot write " + path);
}

std::vector<Matrix4> bone_transforms_at(const std::vector<Bone>& bones, const Animation& animation, size_t frame) {
  std::vector<Matrix4> out(bones.size(), identity_matrix4());
  if (frame >= animation.frame_count()) return out;
  for (size_t k = 0; k < animation.bones.size(); ++k)
    for (size_t b = 0; b < bones.size(); ++b)
      if (bones[b].name == animation.bones[k]) out[b] = animation.transforms[frame][k];
  return out;
}

}  // namespace snh
