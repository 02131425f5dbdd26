// The boundary of a volume mesh as data: a box's boundary is closed, faces
// outwards and encloses the mesh's volume, for hex8 and tet4, at rest and
// deformed.
#include <gtest/gtest.h>

#include <cmath>

#include "snh/error.h"
#include "snh/surface.h"

namespace snh::test {
namespace {

void expect_box_boundary(const Mesh& mesh, int nx, int ny, int nz, double h, const std::string& what) {
  const MeshBoundary b = boundary_surface(mesh);
  // Two triangles per boundary square of the box.
  EXPECT_EQ(b.surface.triangle_count(), static_cast<size_t>(4 * (nx * ny + ny * nz + nx * nz))) << what;
  // Every lattice vertex but the interior ones.
  EXPECT_EQ(b.vertices.size(), mesh.vertex_count() - static_cast<size_t>((nx - 1) * (ny - 1) * (nz - 1))) << what;
  for (size_t i = 0; i < b.vertices.size(); ++i)
    for (int d = 0; d < 3; ++d) EXPECT_EQ(b.surface.positions(i, d), mesh.positions(b.vertices[i], d));
  EXPECT_NO_THROW(validate_closed_surface(b.surface)) << what;
  const double volume = nx * ny * nz * h * h * h;
  EXPECT_NEAR(enclosed_volume(b.surface), volume, 1e-12 * volume) << what;
  // Outward: each triangle's normal points away from the box's centre.
  const double centre[3] = {nx * h / 2, ny * h / 2, nz * h / 2};
  for (size_t t = 0; t < b.surface.triangle_count(); ++t) {
    const double* p[3];
    for (int c = 0; c < 3; ++c) p[c] = b.surface.positions.data() + 3 * b.surface.triangles[3 * t + c];
    const double u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const double v[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    double outward = 0.0;
    for (int d = 0; d < 3; ++d) outward += n[d] * ((p[0][d] + p[1][d] + p[2][d]) / 3 - centre[d]);
    EXPECT_GT(outward, 0.0) << what << " triangle " << t;
  }
}

TEST(BoundarySurface, BoxLatticeIsClosedOutwardAndEnclosesItsVolume) {
  expect_box_boundary(make_box_lattice(3, 2, 4, 0.1), 3, 2, 4, 0.1, "hex8");
  expect_box_boundary(make_tet_box(3, 2, 4, 0.1), 3, 2, 4, 0.1, "tet4");
}

TEST(BoundarySurface, FollowsThePositionsGiven) {
  const Mesh mesh = make_box_lattice(2, 2, 2, 0.5);
  Points x = mesh.positions;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) x(v, 2) *= 2.0;  // stretched along z
  const MeshBoundary b = boundary_surface(mesh, x);
  EXPECT_NEAR(enclosed_volume(b.surface), 2.0, 1e-12);
  EXPECT_THROW(boundary_surface(mesh, Points(1)), Error);
}

}  // namespace
}  // namespace snh::test
