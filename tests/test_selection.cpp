// Selections (snh/selection.h) on lattices with known counts, groups and
// arrays; body-force lumping (snh/loads.h) against the rest volume and its
// first moment computed here with a finer rule; and the scene-file
// selectors (host/scene/scene_selectors.h) with errors naming the key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/scene_selectors.h"
#include "snh/error.h"
#include "snh/loads.h"
#include "snh/mesh.h"
#include "snh/mesh_io.h"
#include "snh/scene.h"
#include "snh/selection.h"
#include "support/errors.h"
#include "support/lattices.h"

namespace snh {
namespace {

using test::contains;
using test::error_of;

const std::string kMeshes = std::string(SNH_DATA_DIR) + "/meshes/";

bool sorted_unique(const std::vector<int32_t>& v) {
  for (size_t i = 1; i < v.size(); ++i)
    if (v[i] <= v[i - 1]) return false;
  return true;
}

// The lattice vertex index of grid point (i, j, k) of make_box_lattice(n, n, n, h).
int32_t lattice_vertex(int n, int i, int j, int k) { return i + (n + 1) * (j + (n + 1) * k); }

// A 4 x 4 x 4 lattice of h = 0.25 with two groups and two arrays.
Mesh lattice_with_groups() {
  Mesh m = make_box_lattice(4, 4, 4, 0.25);
  MeshGroup bottom{"bottom", 1, 2, {}, {}};
  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= 4; ++i) bottom.vertices.push_back(lattice_vertex(4, i, j, 0));
  std::sort(bottom.vertices.begin(), bottom.vertices.end());
  MeshGroup first{"first_layer", 1, 3, {}, {}};
  for (int32_t e = 0; e < 16; ++e) first.elements.push_back(e);  // k = 0 cells
  for (int32_t v = 0; v < 50; ++v) first.vertices.push_back(v);
  MeshGroup unnamed{"", 9, 3, {}, {63}};
  for (int a = 0; a < 8; ++a) unnamed.vertices.push_back(m.elements[8 * 63 + a]);
  std::sort(unnamed.vertices.begin(), unnamed.vertices.end());
  m.groups = {bottom, first, unnamed};
  MeshArray x{"x", 1, {}}, all{"position", 3, m.positions.xyz()};
  for (size_t v = 0; v < m.vertex_count(); ++v) x.values.push_back(m.positions(v, 0));
  MeshArray layer{"layer", 1, {}};
  for (size_t e = 0; e < m.element_count(); ++e) layer.values.push_back(double(e / 16));
  m.point_arrays = {x, all};
  m.cell_arrays = {layer};
  validate_mesh(m);
  return m;
}

// ---- Vertices ----

TEST(Selection, VerticesOnPlanesOfALattice) {
  const Mesh m = make_box_lattice(4, 4, 4, 0.25);
  const auto bottom = vertices_on_plane(m, {0, 0, 0}, {0, 0, 1});
  EXPECT_EQ(bottom.size(), 25u);
  EXPECT_TRUE(sorted_unique(bottom));
  for (int32_t v : bottom) EXPECT_EQ(m.positions(v, 2), 0.0);
  // The normal's length does not matter; the top face.
  EXPECT_EQ(vertices_on_plane(m, {0.3, 0.1, 1.0}, {0, 0, -7}).size(), 25u);
  // x + y = 0.5: grid points with i + j = 2, in each of 5 layers.
  const auto diagonal = vertices_on_plane(m, {0.5, 0, 0}, {1, 1, 0});
  EXPECT_EQ(diagonal.size(), 15u);
  for (int32_t v : diagonal) EXPECT_NEAR(m.positions(v, 0) + m.positions(v, 1), 0.5, 1e-12);
  // Between grid planes: nothing, unless the tolerance reaches them.
  EXPECT_TRUE(vertices_on_plane(m, {0, 0, 0.1}, {0, 0, 1}).empty());
  EXPECT_EQ(vertices_on_plane(m, {0, 0, 0.1}, {0, 0, 1}, 0.16).size(), 50u);
}

TEST(Selection, VerticesInBoxesAndSpheres) {
  const Mesh m = make_box_lattice(4, 4, 4, 0.25);
  EXPECT_EQ(vertices_in_box(m, {0, 0, 0}, {0.5, 0.5, 0.5}).size(), 27u);  // faces included
  EXPECT_EQ(vertices_in_box(m, {0.1, 0.1, 0.1}, {0.4, 0.4, 0.4}).size(), 1u);
  EXPECT_EQ(vertices_in_box(m, {-1, -1, 0.9}, {2, 2, 2}), vertices_on_plane(m, {0, 0, 1}, {0, 0, 1}));
  // Centre, its 6 neighbours at h, then 12 more at h sqrt 2.
  const auto one = vertices_in_sphere(m, {0.5, 0.5, 0.5}, 0.25 + 1e-9);
  EXPECT_EQ(one.size(), 7u);
  EXPECT_TRUE(std::binary_search(one.begin(), one.end(), lattice_vertex(4, 2, 2, 2)));
  EXPECT_EQ(vertices_in_sphere(m, {0.5, 0.5, 0.5}, 0.25 * std::sqrt(2.0) + 1e-9).size(), 19u);
  EXPECT_EQ(vertices_in_sphere(m, {0.5, 0.5, 0.5}, 0.0).size(), 1u);
  EXPECT_TRUE(vertices_in_sphere(m, {5, 5, 5}, 1.0).empty());
}

TEST(Selection, BadGeometryIsAnError) {
  const Mesh m = make_box_lattice(2, 2, 2, 0.5);
  EXPECT_TRUE(contains(error_of([&] { vertices_in_box(m, {0, 1, 0}, {1, 0, 1}); }), "y range"));
  EXPECT_TRUE(contains(error_of([&] { elements_in_box(m, {0, 0, 0}, {1, 1, NAN}); }), "z range"));
  EXPECT_TRUE(contains(error_of([&] { vertices_on_plane(m, {0, 0, 0}, {0, 0, 0}); }), "normal"));
  EXPECT_TRUE(contains(error_of([&] { vertices_on_plane(m, {0, 0, 0}, {0, 0, 1}, -1.0); }), "tolerance"));
  EXPECT_TRUE(contains(error_of([&] { vertices_in_sphere(m, {0, 0, 0}, -1.0); }), "radius"));
  EXPECT_TRUE(contains(error_of([&] { elements_in_sphere(m, {0, 0, 0}, NAN); }), "radius"));
}

// ---- Elements ----

TEST(Selection, ElementsByCentroid) {
  const Mesh m = make_box_lattice(4, 4, 4, 0.25);
  const auto corner = elements_in_box(m, {0, 0, 0}, {0.5, 0.5, 0.5});
  EXPECT_EQ(corner.size(), 8u);
  EXPECT_TRUE(sorted_unique(corner));
  EXPECT_EQ(corner.front(), 0);
  // The 8 cells around the centre have centroids h sqrt(3) / 2 from it.
  EXPECT_EQ(elements_in_sphere(m, {0.5, 0.5, 0.5}, 0.25 * std::sqrt(3.0) / 2 + 1e-9).size(), 8u);
  EXPECT_TRUE(elements_in_sphere(m, {0.5, 0.5, 0.5}, 0.2).empty());
  // Each cube of a tet box is six tets; their centroids stay in the cube.
  const Mesh tets = make_tet_box(4, 4, 4, 0.25);
  EXPECT_EQ(elements_in_box(tets, {0, 0, 0}, {0.5, 0.5, 0.5}).size(), 48u);
  EXPECT_EQ(elements_in_box(tets, {0, 0, 0}, {1, 1, 1}).size(), tets.element_count());
}

// ---- Groups ----

TEST(Selection, GroupsByNameAndTag) {
  const Mesh m = lattice_with_groups();
  EXPECT_EQ(vertices_in_group(m, "bottom"), vertices_on_plane(m, {0, 0, 0}, {0, 0, 1}));
  EXPECT_EQ(vertices_in_group(m, "first_layer").size(), 50u);
  EXPECT_EQ(vertices_in_group(m, 1, 2), vertices_in_group(m, "bottom"));
  EXPECT_EQ(vertices_in_group(m, 1, 3), vertices_in_group(m, "first_layer"));
  EXPECT_EQ(elements_in_group(m, "first_layer"), elements_in_box(m, {0, 0, 0}, {1, 1, 0.25}));
  EXPECT_EQ(elements_in_group(m, 1), elements_in_group(m, "first_layer"));  // the volume group of tag 1
  EXPECT_EQ(elements_in_group(m, 9), std::vector<int32_t>{63});
  EXPECT_EQ(vertices_in_group(m, 9).size(), 8u);
  EXPECT_EQ(vertices_in_group(m, "").size(), 8u);  // the unnamed group, the only one without a name
}

TEST(Selection, MissingOrAmbiguousGroupsNameWhatTheMeshHas) {
  const Mesh m = lattice_with_groups();
  const std::string missing = error_of([&] { vertices_in_group(m, "top"); });
  EXPECT_TRUE(contains(missing, "vertices_in_group: the mesh has no group 'top'")) << missing;
  EXPECT_TRUE(contains(missing, "'bottom' (surface, tag 1)")) << missing;
  EXPECT_TRUE(contains(missing, "'first_layer' (volume, tag 1)")) << missing;
  EXPECT_TRUE(contains(missing, "unnamed (volume, tag 9)")) << missing;
  const std::string ambiguous = error_of([&] { vertices_in_group(m, 1); });
  EXPECT_TRUE(contains(ambiguous, "2 groups match with tag 1")) << ambiguous;
  EXPECT_TRUE(contains(ambiguous, "give the dimension")) << ambiguous;
  const std::string surface = error_of([&] { elements_in_group(m, "bottom"); });
  EXPECT_TRUE(contains(surface, "not a volume group")) << surface;
  EXPECT_TRUE(contains(surface, "'first_layer' (volume, tag 1)")) << surface;
  EXPECT_TRUE(contains(error_of([&] { vertices_in_group(m, "bottom", 3); }), "of dimension 3"));
  const std::string none = error_of([&] { elements_in_group(make_box_lattice(1, 1, 1, 1.0), 3); });
  EXPECT_TRUE(contains(none, "its groups: none")) << none;
}

// ---- Arrays ----

TEST(Selection, ByArrayValue) {
  const Mesh m = lattice_with_groups();
  EXPECT_EQ(vertices_with_value(m, "x", 0.0), vertices_on_plane(m, {0, 0, 0}, {1, 0, 0}));
  EXPECT_EQ(vertices_with_value_in(m, "x", 0.2, 0.3), vertices_on_plane(m, {0.25, 0, 0}, {1, 0, 0}));
  EXPECT_EQ(vertices_with_value_in(m, "x", 0.0, 1.0).size(), m.vertex_count());
  EXPECT_TRUE(vertices_with_value(m, "x", 0.1).empty());
  EXPECT_EQ(elements_with_value(m, "layer", 3.0), elements_in_box(m, {0, 0, 0.75}, {1, 1, 1}));
  EXPECT_EQ(elements_with_value_in(m, "layer", 1.0, 2.0).size(), 32u);
  const std::string missing = error_of([&] { vertices_with_value(m, "temperature", 1.0); });
  EXPECT_TRUE(contains(missing, "no point array 'temperature'")) << missing;
  EXPECT_TRUE(contains(missing, "'x' (1 component), 'position' (3 components)")) << missing;
  EXPECT_TRUE(contains(error_of([&] { vertices_with_value(m, "position", 1.0); }), "3 components"));
  EXPECT_TRUE(contains(error_of([&] { elements_with_value(m, "x", 1.0); }), "cell arrays: 'layer'"));
  EXPECT_TRUE(contains(error_of([&] { elements_with_value_in(m, "layer", 2.0, 1.0); }), "empty"));
}

TEST(Selection, ValidateMeshChecksGroupsAndArrays) {
  Mesh m = lattice_with_groups();
  m.groups[0].vertices.push_back(1000);
  EXPECT_TRUE(contains(error_of([&] { validate_mesh(m); }), "holds vertex 1000"));
  m = lattice_with_groups();
  std::swap(m.groups[1].elements[0], m.groups[1].elements[1]);
  EXPECT_TRUE(contains(error_of([&] { validate_mesh(m); }), "not sorted"));
  m = lattice_with_groups();
  m.groups[0].elements.push_back(0);
  EXPECT_TRUE(contains(error_of([&] { validate_mesh(m); }), "not a volume group"));
  m = lattice_with_groups();
  m.cell_arrays[0].values.pop_back();
  EXPECT_TRUE(contains(error_of([&] { validate_mesh(m); }), "cell array 'layer' has 63 values"));
}

TEST(Selection, SplitHexesCarriesGroupsAndArrays) {
  const Mesh hexes = lattice_with_groups();
  const Mesh tets = split_hexes_into_tets(hexes);
  validate_mesh(tets);
  ASSERT_EQ(tets.groups.size(), hexes.groups.size());
  EXPECT_EQ(tets.groups[0].vertices, hexes.groups[0].vertices);
  EXPECT_EQ(elements_in_group(tets, "first_layer").size(), 6 * 16u);
  // The split tets of the first layer are the tets with centroids in it.
  EXPECT_EQ(elements_in_group(tets, "first_layer"), elements_in_box(tets, {0, 0, 0}, {1, 1, 0.25}));
  EXPECT_EQ(elements_in_group(tets, 9), (std::vector<int32_t>{378, 379, 380, 381, 382, 383}));
  EXPECT_EQ(tets.point_arrays[1].values, hexes.positions.xyz());
  EXPECT_EQ(elements_with_value(tets, "layer", 3.0), elements_in_box(tets, {0, 0, 0.75}, {1, 1, 1}));
}

// ---- Body force ----

// Rest volume and first moment (integral of x) by a 4 x 4 x 4 Gauss rule on
// each hex (exact for trilinear hexes) or exactly for tets.
void volume_and_moment(const Mesh& m, double& volume, std::array<double, 3>& moment) {
  volume = 0.0;
  moment = {0, 0, 0};
  const int n = nodes_per_element(m.type);
  for (size_t e = 0; e < m.element_count(); ++e) {
    const int32_t* v = m.elements.data() + n * e;
    if (m.type == ElementType::tet4) {
      double d[3][3];
      for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) d[r][k] = m.positions(v[r + 1], k) - m.positions(v[0], k);
      const double vol =
          (d[0][0] * (d[1][1] * d[2][2] - d[1][2] * d[2][1]) - d[0][1] * (d[1][0] * d[2][2] - d[1][2] * d[2][0]) +
           d[0][2] * (d[1][0] * d[2][1] - d[1][1] * d[2][0])) /
          6.0;
      volume += vol;
      for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 4; ++a) moment[k] += vol / 4 * m.positions(v[a], k);
      continue;
    }
    static const double kSigns[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                        {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    const double p[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
    const double w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        for (int k = 0; k < 4; ++k) {
          const double xi[3] = {p[i], p[j], p[k]};
          double jac[3][3] = {}, x[3] = {};
          for (int a = 0; a < 8; ++a) {
            const double* s = kSigns[a];
            const double f[3] = {1 + s[0] * xi[0], 1 + s[1] * xi[1], 1 + s[2] * xi[2]};
            const double dn[3] = {0.125 * s[0] * f[1] * f[2], 0.125 * f[0] * s[1] * f[2], 0.125 * f[0] * f[1] * s[2]};
            const double shape = 0.125 * f[0] * f[1] * f[2];
            for (int d = 0; d < 3; ++d) {
              x[d] += shape * m.positions(v[a], d);
              for (int r = 0; r < 3; ++r) jac[r][d] += dn[r] * m.positions(v[a], d);
            }
          }
          const double det = jac[0][0] * (jac[1][1] * jac[2][2] - jac[1][2] * jac[2][1]) -
                             jac[0][1] * (jac[1][0] * jac[2][2] - jac[1][2] * jac[2][0]) +
                             jac[0][2] * (jac[1][0] * jac[2][1] - jac[1][1] * jac[2][0]);
          const double weight = w[i] * w[j] * w[k] * det;
          volume += weight;
          for (int d = 0; d < 3; ++d) moment[d] += weight * x[d];
        }
  }
}

TEST(Selection, BodyForceSumsToForceTimesVolumeWithTheRightMoment) {
  const std::array<double, 3> b{0.5, -2.0, -9.81};
  const std::vector<Mesh> meshes = {make_box_lattice(3, 2, 4, 0.2),
                                    test::sine_jiggled(make_box_lattice(3, 2, 4, 0.2), 0.03),
                                    make_tet_box(2, 3, 2, 0.3),
                                    test::sine_jiggled(make_tet_box(2, 3, 2, 0.3), 0.04),
                                    read_mesh(kMeshes + "box_tet.msh41.msh"),
                                    read_mesh(kMeshes + "hex_box.msh")};
  for (size_t i = 0; i < meshes.size(); ++i) {
    SCOPED_TRACE(i);
    const Mesh& m = meshes[i];
    const Points f = lump_body_force(m, b);
    ASSERT_EQ(f.size(), m.vertex_count());
    double volume = 0.0;
    std::array<double, 3> moment;
    volume_and_moment(m, volume, moment);
    EXPECT_NEAR(volume, mesh_volume(m, m.positions), 1e-13);
    // sum_a f_a = b V, and sum_a f_a (x_a . e) = b (integral of x . e): the
    // shape functions at the Gauss points, not V / 8 per node, give the
    // second on non-affine hexes.
    for (int d = 0; d < 3; ++d) {
      double sum = 0.0;
      for (size_t v = 0; v < m.vertex_count(); ++v) sum += f(v, d);
      EXPECT_NEAR(sum, b[d] * volume, 1e-13 * std::abs(b[d]) + 1e-15);
      for (int k = 0; k < 3; ++k) {
        double first = 0.0;
        for (size_t v = 0; v < m.vertex_count(); ++v) first += f(v, d) * m.positions(v, k);
        EXPECT_NEAR(first, b[d] * moment[k], 1e-13 * std::abs(b[d]) + 1e-15) << d << " " << k;
      }
    }
  }
}

TEST(Selection, BodyForceOfALatticeInteriorVertexIsBH3) {
  const double h = 0.25;
  const Mesh m = make_box_lattice(4, 4, 4, h);
  const Points f = lump_body_force(m, {0, 0, -8.0});
  const int32_t centre = lattice_vertex(4, 2, 2, 2), corner = lattice_vertex(4, 0, 0, 0),
                edge = lattice_vertex(4, 2, 0, 0), face = lattice_vertex(4, 2, 2, 0);
  EXPECT_NEAR(f(centre, 2), -8.0 * h * h * h, 1e-15);
  EXPECT_NEAR(f(face, 2), -8.0 * h * h * h / 2, 1e-15);
  EXPECT_NEAR(f(edge, 2), -8.0 * h * h * h / 4, 1e-15);
  EXPECT_NEAR(f(corner, 2), -8.0 * h * h * h / 8, 1e-15);
  EXPECT_EQ(f(centre, 0), 0.0);
  // Tets of a Kuhn-split lattice carry V / 4 per node: the same interior load.
  const Points t = lump_body_force(make_tet_box(4, 4, 4, h), {0, 0, -8.0});
  EXPECT_NEAR(t(centre, 2), -8.0 * h * h * h, 1e-15);
}

// ---- Scene files ----

using nlohmann::json;

std::vector<int32_t> scene_vertices(const Mesh& m, const std::string& selector) {
  return scene_io::parse_vertex_selection(scene_io::SceneJson{"test.json"}, json::parse(selector), "select", m);
}
std::vector<int32_t> scene_elements(const Mesh& m, const std::string& selector) {
  return scene_io::parse_element_selection(scene_io::SceneJson{"test.json"}, json::parse(selector), "region", m);
}
std::string scene_vertices_error(const Mesh& m, const std::string& selector) {
  return error_of([&] { scene_vertices(m, selector); });
}
std::string scene_elements_error(const Mesh& m, const std::string& selector) {
  return error_of([&] { scene_elements(m, selector); });
}

TEST(SelectionSceneFile, VertexSelectorsMatchTheLibrary) {
  const Mesh m = lattice_with_groups();
  EXPECT_EQ(scene_vertices(m, R"({"ids": [7, 3, 7]})"), (std::vector<int32_t>{3, 7}));
  EXPECT_EQ(scene_vertices(m, R"({"box": {"min": [0, 0, 0], "max": [0.5, 0.5, 0.5]}})").size(), 27u);
  EXPECT_EQ(scene_vertices(m, R"({"plane": {"axis": "z", "value": 0}})").size(), 25u);
  EXPECT_EQ(scene_vertices(m, R"({"plane": {"point": [0.5, 0, 0], "normal": [1, 1, 0]}})").size(), 15u);
  EXPECT_EQ(scene_vertices(m, R"({"sphere": {"center": [0.5, 0.5, 0.5], "radius": 0.26}})").size(), 7u);
  EXPECT_EQ(scene_vertices(m, R"({"group": "bottom"})"), vertices_in_group(m, "bottom"));
  EXPECT_EQ(scene_vertices(m, R"({"group": 1, "dimension": 3})"), vertices_in_group(m, "first_layer"));
  EXPECT_EQ(scene_vertices(m, R"({"point_array": {"name": "x", "value": 1}})").size(), 25u);
  EXPECT_EQ(scene_vertices(m, R"({"point_array": {"name": "x", "min": 0.7, "max": 2}})").size(), 50u);
  EXPECT_TRUE(scene_vertices(m, R"({"sphere": {"center": [9, 9, 9], "radius": 1}})").empty());
}

TEST(SelectionSceneFile, ElementSelectorsMatchTheLibrary) {
  const Mesh m = lattice_with_groups();
  EXPECT_EQ(scene_elements(m, R"({"ids": [5, 1]})"), (std::vector<int32_t>{1, 5}));
  EXPECT_EQ(scene_elements(m, R"({"box": {"min": [0, 0, 0], "max": [0.5, 0.5, 0.5]}})").size(), 8u);
  EXPECT_EQ(scene_elements(m, R"({"sphere": {"center": [0.5, 0.5, 0.5], "radius": 0.22}})").size(), 8u);
  EXPECT_EQ(scene_elements(m, R"({"group": "first_layer"})").size(), 16u);
  EXPECT_EQ(scene_elements(m, R"({"group": 9})"), std::vector<int32_t>{63});
  EXPECT_EQ(scene_elements(m, R"({"cell_array": {"name": "layer", "value": 2}})").size(), 16u);
  EXPECT_EQ(scene_elements(m, R"({"cell_array": {"name": "layer", "min": 2, "max": 3}})").size(), 32u);
}

TEST(SelectionSceneFile, ErrorsNameTheKey) {
  const Mesh m = lattice_with_groups();
  std::string e = scene_vertices_error(m, R"({"group": "top"})");
  EXPECT_TRUE(contains(e, "test.json: select.group: vertices_in_group: the mesh has no group 'top'")) << e;
  EXPECT_TRUE(contains(e, "'bottom' (surface, tag 1)")) << e;
  e = scene_vertices_error(m, R"({"group": 1})");
  EXPECT_TRUE(contains(e, "select.group:") && contains(e, "give the dimension")) << e;
  e = scene_vertices_error(m, R"({"box": {"min": [0, 0, 0], "max": [1, 1, 1]}, "plane": {}})");
  EXPECT_TRUE(contains(e, "select: give one selector, found both box and plane")) << e;
  e = scene_vertices_error(m, R"({"cylinder": {}})");
  EXPECT_TRUE(contains(e, "select.cylinder: unknown key")) << e;
  e = scene_vertices_error(m, R"({"sphere": {"center": [0, 0, 0]}})");
  EXPECT_TRUE(contains(e, "select.sphere.radius: missing")) << e;
  e = scene_vertices_error(m, R"({"sphere": {"center": [0, 0, 0], "radius": -1}})");
  EXPECT_TRUE(contains(e, "select.sphere: vertices_in_sphere:")) << e;
  e = scene_vertices_error(m, R"({"plane": {"axis": "z", "normal": [0, 0, 1], "point": [0, 0, 0]}})");
  EXPECT_TRUE(contains(e, "select.plane: give axis and value, or point and normal")) << e;
  e = scene_vertices_error(m, R"({"point_array": {"name": "temperature", "value": 1}})");
  EXPECT_TRUE(contains(e, "select.point_array: vertices_with_value: the mesh has no point array 'temperature'")) << e;
  e = scene_vertices_error(m, R"({"point_array": {"name": "x", "value": 1, "min": 0}})");
  EXPECT_TRUE(contains(e, "select.point_array: give either value, or min and max")) << e;
  e = scene_vertices_error(m, R"({"ids": [0], "dimension": 2})");
  EXPECT_TRUE(contains(e, "select.dimension: only a group selector")) << e;
  e = scene_vertices_error(m, R"({"group": 1.5})");
  EXPECT_TRUE(contains(e, "select.group: expected a group name")) << e;
  e = scene_elements_error(m, R"({"group": "bottom"})");
  EXPECT_TRUE(contains(e, "region.group: elements_in_group: group 'bottom' is not a volume group")) << e;
  e = scene_elements_error(m, R"({"ids": [64]})");
  EXPECT_TRUE(contains(e, "region.ids: element 64 is out of range (the mesh has 64 elements)")) << e;
  e = scene_elements_error(m, R"({"plane": {}})");
  EXPECT_TRUE(contains(e, "region.plane: unknown key")) << e;
}

TEST(SelectionSceneFile, ConstraintsFromAGmshGroup) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "snh_group_scene.json";
  std::ofstream(path) << R"({"mesh": {"file": ")" << kMeshes << R"(box_groups.msh41.msh"},
    "constraints": [{"name": "wall", "select": {"group": "fixed"}},
                    {"name": "end", "select": {"group": 7, "dimension": 2}}],
    "body_force": [0, 0, -1]})";
  const SceneFile f = load_scene(path.string());
  ASSERT_EQ(f.scene.constraints.size(), 2u);
  const Mesh& m = f.scene.mesh;
  EXPECT_EQ(f.scene.constraints[0].vertices, vertices_on_plane(m, {0, 0, 0}, {1, 0, 0}));
  EXPECT_EQ(f.scene.constraints[1].vertices, vertices_on_plane(m, {1, 0, 0}, {1, 0, 0}));
  EXPECT_EQ(f.scene.options.external_force, lump_body_force(m, {0, 0, -1}));
  std::ofstream(path) << R"({"mesh": {"file": ")" << kMeshes << R"(box_groups.msh41.msh"},
    "constraints": [{"select": {"group": "wall"}}]})";
  const std::string e = error_of([&] { load_scene(path.string()); });
  EXPECT_TRUE(contains(e, "constraints[0].select.group: vertices_in_group: the mesh has no group 'wall'")) << e;
  EXPECT_TRUE(contains(e, "'fixed' (surface, tag 1)")) << e;
}

}  // namespace
}  // namespace snh
