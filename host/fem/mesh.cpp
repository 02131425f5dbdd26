// Mesh validation, the lattice generators of the paper's scenes, and the
// deformed volume used by tests and diagnostics.
#include "snh/mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

#include "fem/name_table.h"
#include "fem/rest_state.h"
#include "snh/error.h"
#include "snh/surface.h"

namespace snh {

namespace {

constexpr NameTable<ElementType, 2> kElementTypeNames{{{ElementType::hex8, "hex8"}, {ElementType::tet4, "tet4"}}};

}  // namespace

const char* element_type_name(ElementType type) { return name_of(kElementTypeNames, type, "unknown"); }
ElementType parse_element_type(const std::string& text) { return value_named(kElementTypeNames, text, "element type"); }
const char* to_string(ElementType type) { return element_type_name(type); }

int nodes_per_element(ElementType type) {
  switch (type) {
    case ElementType::hex8:
      return 8;
    case ElementType::tet4:
      return 4;
  }
  throw Error("mesh: unknown element type " + std::to_string(static_cast<int>(type)));
}

int quadrature_points(ElementType type) {
  switch (type) {
    case ElementType::hex8:
      return 8;
    case ElementType::tet4:
      return 1;
  }
  throw Error("mesh: unknown element type " + std::to_string(static_cast<int>(type)));
}

MeshWarnings validate_mesh(const Mesh& mesh) {
  const int n = nodes_per_element(mesh.type);
  if (mesh.positions.xyz().size() % 3 != 0) {
    std::ostringstream s;
    s << "mesh: the position array has " << mesh.positions.xyz().size()
      << " values, not a multiple of 3 (xyz per vertex)";
    throw Error(s.str());
  }
  if (mesh.elements.size() % n != 0) {
    std::ostringstream s;
    s << "mesh: the element array has " << mesh.elements.size() << " indices, not a multiple of " << n << " ("
      << to_string(mesh.type) << " nodes per element)";
    throw Error(s.str());
  }
  if (mesh.vertex_count() == 0) throw Error("mesh: it has no vertices");
  if (mesh.element_count() == 0) throw Error("mesh: it has no elements");
  // Indices are int32 (the device's layout), so larger meshes cannot be addressed.
  if (mesh.vertex_count() > static_cast<size_t>(std::numeric_limits<int32_t>::max())) {
    std::ostringstream s;
    s << "mesh: it has " << mesh.vertex_count() << " vertices, more than 32-bit indices can address";
    throw Error(s.str());
  }

  const size_t vertices = mesh.vertex_count();
  for (size_t v = 0; v < vertices; ++v)
    for (int d = 0; d < 3; ++d)
      if (!std::isfinite(mesh.positions(v, d))) {
        std::ostringstream s;
        s << "mesh: vertex " << v << " has a non-finite coordinate ("
          << "xyz"[d] << " = " << mesh.positions(v, d) << ")";
        throw Error(s.str());
      }

  std::vector<char> used(vertices, 0);
  const size_t elements = mesh.element_count();
  for (size_t e = 0; e < elements; ++e) {
    const int32_t* nodes = mesh.elements.data() + n * e;
    for (int a = 0; a < n; ++a) {
      if (nodes[a] < 0 || static_cast<size_t>(nodes[a]) >= vertices) {
        std::ostringstream s;
        s << "mesh: element " << e << " refers to vertex " << nodes[a] << " (node " << a << "), but the mesh has "
          << vertices << " vertices";
        throw Error(s.str());
      }
      for (int b = 0; b < a; ++b)
        if (nodes[b] == nodes[a]) {
          std::ostringstream s;
          s << "mesh: element " << e << " uses vertex " << nodes[a] << " twice (nodes " << b << " and " << a << ")";
          throw Error(s.str());
        }
      used[nodes[a]] = 1;
    }
  }

  // Zero, negative (inverted) and non-finite rest volumes at any quadrature
  // point; the rest-state code names the element.
  fem::compute_rest_state(mesh);

  for (const MeshGroup& g : mesh.groups) {
    const std::string who = "mesh: group " + (g.name.empty() ? std::string() : "'" + g.name + "' ") + "(tag " +
                            std::to_string(g.tag) + ", dimension " + std::to_string(g.dimension) + ")";
    if (g.dimension < 0 || g.dimension > 3) throw Error(who + " has a dimension outside 0..3");
    if (g.dimension != 3 && !g.elements.empty()) throw Error(who + " holds elements but is not a volume group");
    const auto check = [&](const std::vector<int32_t>& list, size_t limit, const char* noun, const char* nouns) {
      for (size_t i = 0; i < list.size(); ++i) {
        if (list[i] < 0 || static_cast<size_t>(list[i]) >= limit) {
          std::ostringstream s;
          s << who << " holds " << noun << " " << list[i] << ", but the mesh has " << limit << " " << nouns;
          throw Error(s.str());
        }
        if (i > 0 && list[i] <= list[i - 1])
          throw Error(who + ": its " + nouns + " are not sorted ascending without repeats");
      }
    };
    check(g.vertices, vertices, "vertex", "vertices");
    check(g.elements, elements, "element", "elements");
  }
  const auto check_arrays = [](const std::vector<MeshArray>& arrays, size_t count, const char* kind) {
    for (const MeshArray& a : arrays)
      if (a.components < 1 || a.values.size() != count * static_cast<size_t>(a.components)) {
        std::ostringstream s;
        s << "mesh: " << kind << " array '" << a.name << "' has " << a.values.size() << " values for " << a.components
          << " components, but the mesh has " << count << " " << kind << "s";
        throw Error(s.str());
      }
  };
  check_arrays(mesh.point_arrays, vertices, "point");
  check_arrays(mesh.cell_arrays, elements, "cell");

  MeshWarnings warnings;
  for (size_t v = 0; v < vertices; ++v)
    if (!used[v]) warnings.unused_vertices.push_back(static_cast<int32_t>(v));
  return warnings;
}

namespace {

void check_lattice(int nx, int ny, int nz, double h, const std::array<double, 3>& origin, const char* generator) {
  if (nx < 1 || ny < 1 || nz < 1) {
    std::ostringstream s;
    s << generator << ": the lattice needs at least one cell per axis, got " << nx << " x " << ny << " x " << nz;
    throw Error(s.str());
  }
  if (!(h > 0.0) || !std::isfinite(h)) {
    std::ostringstream s;
    s << generator << ": the cell size h must be positive and finite, got " << h;
    throw Error(s.str());
  }
  for (int d = 0; d < 3; ++d)
    if (!std::isfinite(origin[d])) {
      std::ostringstream s;
      s << generator << ": the origin's "
        << "xyz"[d] << " coordinate is not finite (" << origin[d] << ")";
      throw Error(s.str());
    }
  // The voxelizer's grid limit (VoxelizeOptions::max_grid_cells) holds for
  // the generators too: a lattice beyond it (a typo such as a radius of 115
  // for 1.15) is refused before anything is allocated.
  const double cells = double(nx) * double(ny) * double(nz);
  const int64_t max_cells = VoxelizeOptions{}.max_grid_cells;
  if (cells > double(max_cells)) {
    std::ostringstream s;
    s << generator << ": a " << nx << " x " << ny << " x " << nz << " lattice has " << std::llround(cells)
      << " cells, more than the limit of " << max_cells << "; use a larger cell size or a smaller body";
    throw Error(s.str());
  }
  const double vertices = (nx + 1.0) * (ny + 1.0) * (nz + 1.0);
  if (vertices > double(std::numeric_limits<int32_t>::max())) {
    std::ostringstream s;
    s << generator << ": a " << nx << " x " << ny << " x " << nz
      << " lattice has more vertices than 32-bit indices can address";
    throw Error(s.str());
  }
}

// Grid vertices in the order i + (nx+1) (j + (ny+1) k) at origin + h (i, j, k).
std::vector<double> lattice_positions(int nx, int ny, int nz, double h, const std::array<double, 3>& origin) {
  std::vector<double> positions;
  positions.reserve(3 * size_t(nx + 1) * (ny + 1) * (nz + 1));
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        positions.push_back(origin[0] + h * i);
        positions.push_back(origin[1] + h * j);
        positions.push_back(origin[2] + h * k);
      }
  return positions;
}

// Vertex index of local corner c (bit 0: +x, bit 1: +y, bit 2: +z) of cell (i, j, k).
int32_t corner(int nx, int ny, int i, int j, int k, int c) {
  const int64_t x = i + (c & 1), y = j + ((c >> 1) & 1), z = k + ((c >> 2) & 1);
  return static_cast<int32_t>(x + int64_t(nx + 1) * (y + int64_t(ny + 1) * z));
}

// VTK_HEXAHEDRON order as local corners: the bottom face counter-clockwise
// from +z, then the top face (matches fem::kHexNodeSigns).
constexpr int kHexCorners[8] = {0, 1, 3, 2, 4, 5, 7, 6};

void append_hex(std::vector<int32_t>& elements, int nx, int ny, int i, int j, int k) {
  for (int c : kHexCorners) elements.push_back(corner(nx, ny, i, j, k, c));
}

// The six tetrahedra of the Kuhn split of the unit cube, as local corners:
// each walks from corner 0 to corner 7 adding one axis at a time, one per
// permutation of the axes. Every cube shares the 0-7 diagonal direction, so
// the split faces match across neighbouring cubes. Orientation is fixed here
// once, from the exact integer corner coordinates.
struct KuhnTets {
  int tets[6][4];
  KuhnTets() {
    const int axes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int t = 0; t < 6; ++t) {
      const int c1 = 1 << axes[t][0];
      const int c2 = c1 | (1 << axes[t][1]);
      int* tet = tets[t];
      tet[0] = 0;
      tet[1] = c1;
      tet[2] = c2;
      tet[3] = 7;
      auto p = [](int c, int d) { return (c >> d) & 1; };
      int e[3][3];  // edge vectors from corner 0 (which is the origin)
      for (int r = 0; r < 3; ++r)
        for (int d = 0; d < 3; ++d) e[r][d] = p(tet[r + 1], d);
      const int det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                      e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                      e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
      if (det < 0) std::swap(tet[1], tet[2]);
    }
  }
};

}  // namespace

Mesh make_box_lattice(int nx, int ny, int nz, double h, std::array<double, 3> origin) {
  check_lattice(nx, ny, nz, h, origin, "make_box_lattice");
  Mesh mesh;
  mesh.type = ElementType::hex8;
  mesh.positions = Points::from_xyz(lattice_positions(nx, ny, nz, h, origin));
  mesh.elements.reserve(8 * size_t(nx) * ny * nz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) append_hex(mesh.elements, nx, ny, i, j, k);
  return mesh;
}

Mesh make_voxel_cylinder(double radius, double length, double h) {
  if (!(radius > 0.0) || !std::isfinite(radius) || !(length > 0.0) || !std::isfinite(length) || !(h > 0.0) ||
      !std::isfinite(h)) {
    std::ostringstream s;
    s << "make_voxel_cylinder: radius, length and cell size must be positive and finite, got radius " << radius
      << ", length " << length << ", h " << h;
    throw Error(s.str());
  }
  const double cells_across = std::ceil(2.0 * radius / h);
  const double cells_along = std::max(1.0, std::round(length / h));
  if (cells_across > 1e6 || cells_along > 1e6) {
    std::ostringstream s;
    s << "make_voxel_cylinder: radius " << radius << " and length " << length << " need too many cells of size " << h;
    throw Error(s.str());
  }
  const int n = static_cast<int>(cells_across), nz = static_cast<int>(cells_along);
  const std::array<double, 3> origin = {-0.5 * n * h, -0.5 * n * h, 0.0};
  check_lattice(n, n, nz, h, origin, "make_voxel_cylinder");

  // Centre offsets (i + 1/2 - n/2) h are exact mirrors across the axis, so
  // the kept set is symmetric even where a centre lies on the radius.
  std::vector<char> keep_column(size_t(n) * n, 0);
  bool any = false;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double cx = (i + 0.5 - 0.5 * n) * h, cy = (j + 0.5 - 0.5 * n) * h;
      keep_column[size_t(j) * n + i] = std::sqrt(cx * cx + cy * cy) <= radius;
      any = any || keep_column[size_t(j) * n + i];
    }
  if (!any) {
    std::ostringstream s;
    s << "make_voxel_cylinder: no cell of size " << h << " has its centre within radius " << radius;
    throw Error(s.str());
  }

  const std::vector<double> positions = lattice_positions(n, n, nz, h, origin);
  std::vector<int32_t> elements;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (keep_column[size_t(j) * n + i]) append_hex(elements, n, n, i, j, k);

  // Renumber the used vertices in their lattice order.
  std::vector<int32_t> index(positions.size() / 3, -1);
  for (int32_t v : elements) index[v] = 0;
  Mesh mesh;
  mesh.type = ElementType::hex8;
  int32_t next = 0;
  for (size_t v = 0; v < index.size(); ++v)
    if (index[v] == 0) {
      index[v] = next++;
      mesh.positions.push_back({positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]});
    }
  mesh.elements.reserve(elements.size());
  for (int32_t v : elements) mesh.elements.push_back(index[v]);
  return mesh;
}

Mesh make_tet_box(int nx, int ny, int nz, double h, std::array<double, 3> origin) {
  check_lattice(nx, ny, nz, h, origin, "make_tet_box");
  static const KuhnTets kuhn;
  Mesh mesh;
  mesh.type = ElementType::tet4;
  mesh.positions = Points::from_xyz(lattice_positions(nx, ny, nz, h, origin));
  mesh.elements.reserve(24 * size_t(nx) * ny * nz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& tet : kuhn.tets)
          for (int c : tet) mesh.elements.push_back(corner(nx, ny, i, j, k, c));
  return mesh;
}

Mesh split_hexes_into_tets(const Mesh& hexes) {
  if (hexes.type != ElementType::hex8) throw Error("split_hexes_into_tets: the mesh is not hex8");
  static const KuhnTets kuhn;
  // Kuhn corners are bit masks (bit 0: x, 1: y, 2: z); VTK hex node order.
  static const int kVtkNode[8] = {0, 1, 3, 2, 4, 5, 7, 6};
  Mesh mesh;
  mesh.type = ElementType::tet4;
  mesh.positions = hexes.positions;
  mesh.elements.reserve(3 * hexes.elements.size());
  for (size_t e = 0; e < hexes.element_count(); ++e)
    for (const auto& tet : kuhn.tets) {
      int32_t v[4];
      for (int c = 0; c < 4; ++c) v[c] = hexes.elements[8 * e + kVtkNode[tet[c]]];
      double d[3][3];
      for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) d[r][k] = hexes.positions(v[r + 1], k) - hexes.positions(v[0], k);
      const double det = d[0][0] * (d[1][1] * d[2][2] - d[1][2] * d[2][1]) -
                         d[0][1] * (d[1][0] * d[2][2] - d[1][2] * d[2][0]) +
                         d[0][2] * (d[1][0] * d[2][1] - d[1][1] * d[2][0]);
      if (det < 0.0) std::swap(v[1], v[2]);
      mesh.elements.insert(mesh.elements.end(), v, v + 4);
    }
  constexpr int32_t kTetsPerHex = 6;
  static_assert(sizeof(KuhnTets::tets) / sizeof(KuhnTets::tets[0]) == kTetsPerHex, "six tets per hex");
  mesh.point_arrays = hexes.point_arrays;
  mesh.groups = hexes.groups;
  for (MeshGroup& g : mesh.groups) {
    std::vector<int32_t> tets;
    tets.reserve(kTetsPerHex * g.elements.size());
    for (int32_t e : g.elements)
      for (int32_t t = 0; t < kTetsPerHex; ++t) tets.push_back(kTetsPerHex * e + t);
    g.elements = std::move(tets);
  }
  for (const MeshArray& a : hexes.cell_arrays) {
    MeshArray split{a.name, a.components, {}};
    split.values.reserve(kTetsPerHex * a.values.size());
    for (size_t e = 0; e < hexes.element_count(); ++e)
      for (int t = 0; t < kTetsPerHex; ++t)
        split.values.insert(split.values.end(), a.values.begin() + static_cast<std::ptrdiff_t>(a.components * e),
                            a.values.begin() + static_cast<std::ptrdiff_t>(a.components * (e + 1)));
    mesh.cell_arrays.push_back(std::move(split));
  }
  return mesh;
}

double mesh_volume(const Mesh& mesh, const Points& x) {
  if (x.size() != mesh.vertex_count()) {
    std::ostringstream s;
    s << "mesh_volume: the configuration has " << x.xyz().size() << " values, but the mesh has " << mesh.vertex_count()
      << " vertices (" << mesh.positions.xyz().size() << " values expected)";
    throw Error(s.str());
  }
  // The rest-state code trusts the indices, so the mesh is checked first.
  validate_mesh(mesh);
  const fem::RestState rest = fem::compute_rest_state(mesh);
  double volume = 0.0;
  const size_t elements = mesh.element_count();
  for (size_t e = 0; e < elements; ++e)
    for (int q = 0; q < rest.quadrature; ++q) {
      double f[9];
      fem::deformation_gradient(mesh, rest, x.data(), e, q, f);
      const double det = fem::determinant(f);
      volume += det * rest.weight(e, q);
    }
  return volume;
}

double vertex_spacing(const Mesh& mesh) {
  std::vector<char> used(mesh.vertex_count(), 0);
  for (int32_t v : mesh.elements) used[v] = 1;
  const double n = static_cast<double>(std::count(used.begin(), used.end(), 1));
  return std::cbrt(mesh_volume(mesh, mesh.positions) / n);
}

}  // namespace snh
