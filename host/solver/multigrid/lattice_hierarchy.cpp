#include "solver/multigrid/lattice_hierarchy.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <string>

#include "fem/union_find.h"
#include "snh/error.h"

namespace snh::solver {

int hex8_node_bit(int a, int d) { return d == 0 ? ((a + 1) >> 1) & 1 : d == 1 ? (a >> 1) & 1 : (a >> 2) & 1; }

// Trilinear weights of the 2x refinement (1D: 1 - |p - c| / 2 with p the
// fine node's and c the coarse corner's position in fine spacings).
double child_weight(int o, int a, int corner) {
  double w = 1.0;
  for (int d = 0; d < 3; ++d) {
    const int distance = std::abs(((o >> d) & 1) + hex8_node_bit(a, d) - 2 * hex8_node_bit(corner, d));
    w *= distance == 0 ? 1.0 : distance == 1 ? 0.5 : 0.0;
  }
  return w;
}

std::vector<double> octant_weights() {
  std::vector<double> w(8 * 64);
  for (int o = 0; o < 8; ++o)
    for (int a = 0; a < 8; ++a)
      for (int corner = 0; corner < 8; ++corner) w[64 * o + 8 * a + corner] = child_weight(o, a, corner);
  return w;
}

namespace {

using fem::UnionFind;

// The coarser level of `fine` (its cells, children, vertices) and the
// prolongation from it into `fine`.
LatticeLevel coarsen(LatticeLevel& fine) {
  const size_t fine_cells = fine.cells.size();
  // Group fine cells by parent, in order of the parent's first child.
  std::map<std::array<int, 3>, std::vector<int>> by_parent;
  std::vector<std::array<int, 3>> parent_order;
  for (size_t c = 0; c < fine_cells; ++c) {
    std::array<int, 3> p;
    for (int d = 0; d < 3; ++d) p[d] = fine.cells[c][d] >> 1;  // cells have non-negative coordinates
    auto [it, inserted] = by_parent.try_emplace(p);
    if (inserted) parent_order.push_back(p);
    it->second.push_back(static_cast<int>(c));
  }
  // One coarse cell per connected group of children (sharing a fine vertex).
  LatticeLevel coarse;
  std::vector<int> parent_of(fine_cells, -1);
  for (const auto& p : parent_order) {
    const std::vector<int>& kids = by_parent[p];
    UnionFind groups(kids.size());
    for (size_t i = 0; i < kids.size(); ++i)
      for (size_t j = i + 1; j < kids.size(); ++j) {
        const int* a = &fine.elements[8 * kids[i]];
        const int* b = &fine.elements[8 * kids[j]];
        bool share = false;
        for (int x = 0; x < 8 && !share; ++x)
          for (int y = 0; y < 8 && !share; ++y) share = a[x] == b[y];
        if (share) groups.unite(static_cast<int>(i), static_cast<int>(j));
      }
    std::map<int, int> cell_of_group;
    for (size_t i = 0; i < kids.size(); ++i) {
      const int g = groups.find(static_cast<int>(i));
      auto [it, inserted] = cell_of_group.try_emplace(g, static_cast<int>(coarse.cells.size()));
      if (inserted) {
        coarse.cells.push_back(p);
        coarse.children.insert(coarse.children.end(), 8, -1);
      }
      const int c = kids[i];
      int octant = 0;
      for (int d = 0; d < 3; ++d) octant |= (fine.cells[c][d] & 1) << d;
      coarse.children[8 * it->second + octant] = c;
      parent_of[c] = it->second;
    }
  }
  // Coarse vertices: corner slots (cell, corner) merged wherever a fine
  // vertex interpolates the same lattice point from two coarse cells.
  const size_t coarse_cells = coarse.cells.size();
  UnionFind slots(8 * coarse_cells);
  std::vector<std::vector<std::pair<int, int>>> users(fine.vertex_count);  // (fine cell, node)
  for (size_t c = 0; c < fine_cells; ++c)
    for (int a = 0; a < 8; ++a) users[fine.elements[8 * c + a]].push_back({static_cast<int>(c), a});
  auto octant_of = [&](int c) {
    int o = 0;
    for (int d = 0; d < 3; ++d) o |= (fine.cells[c][d] & 1) << d;
    return o;
  };
  for (size_t v = 0; v < fine.vertex_count; ++v) {
    std::map<std::array<int, 3>, int> first_slot;  // lattice point -> a slot there
    for (const auto& [c, a] : users[v]) {
      const int cell = parent_of[c], o = octant_of(c);
      for (int corner = 0; corner < 8; ++corner) {
        if (child_weight(o, a, corner) == 0.0) continue;
        std::array<int, 3> point;
        for (int d = 0; d < 3; ++d) point[d] = coarse.cells[cell][d] + hex8_node_bit(corner, d);
        const int slot = 8 * cell + corner;
        auto [it, inserted] = first_slot.try_emplace(point, slot);
        if (!inserted) slots.unite(it->second, slot);
      }
    }
  }
  std::vector<int> vertex_of_root(8 * coarse_cells, -1);
  coarse.elements.resize(8 * coarse_cells);
  for (size_t s = 0; s < 8 * coarse_cells; ++s) {
    const int root = slots.find(static_cast<int>(s));
    if (vertex_of_root[root] < 0) vertex_of_root[root] = static_cast<int>(coarse.vertex_count++);
    coarse.elements[s] = vertex_of_root[root];
  }
  // Prolongation into the fine level, from the first cell using each vertex
  // (every cell using it gives the same weights on the same coarse vertices).
  fine.prolongation_vertices.assign(8 * fine.vertex_count, 0);
  fine.prolongation_weights.assign(8 * fine.vertex_count, 0.0);
  std::vector<std::vector<std::pair<int, double>>> transpose(coarse.vertex_count);
  for (size_t v = 0; v < fine.vertex_count; ++v) {
    if (users[v].empty()) continue;
    const auto [c, a] = users[v].front();
    const int cell = parent_of[c], o = octant_of(c);
    int k = 0;
    for (int corner = 0; corner < 8; ++corner) {
      const double w = child_weight(o, a, corner);
      if (w == 0.0) continue;
      const int cv = coarse.elements[8 * cell + corner];
      fine.prolongation_vertices[8 * v + k] = cv;
      fine.prolongation_weights[8 * v + k] = w;
      ++k;
      transpose[cv].push_back({static_cast<int>(v), w});
    }
  }
  fine.restriction_offsets.assign(coarse.vertex_count + 1, 0);
  fine.restriction_vertices.clear();
  fine.restriction_weights.clear();
  coarse.mask.assign(3 * coarse.vertex_count, 0);
  for (size_t cv = 0; cv < coarse.vertex_count; ++cv) {
    for (const auto& [v, w] : transpose[cv]) {  // increasing v: filled in vertex order
      fine.restriction_vertices.push_back(v);
      fine.restriction_weights.push_back(w);
      for (int d = 0; d < 3; ++d) coarse.mask[3 * cv + d] |= fine.mask[3 * v + d];
    }
    fine.restriction_offsets[cv + 1] = static_cast<int>(fine.restriction_vertices.size());
  }
  return coarse;
}

}  // namespace

bool is_hex8_lattice(const Mesh& mesh) {
  if (mesh.type != ElementType::hex8 || mesh.element_count() == 0) return false;
  const auto p0 = mesh.vertex(mesh.elements[0]), p1 = mesh.vertex(mesh.elements[1]);
  const double h = p1[0] - p0[0];
  if (!(h > 0.0)) return false;
  for (size_t e = 0; e < mesh.element_count(); ++e) {
    const auto base = mesh.vertex(mesh.elements[8 * e]);
    for (int a = 0; a < 8; ++a) {
      const auto x = mesh.vertex(mesh.elements[8 * e + a]);
      for (int d = 0; d < 3; ++d)
        if (std::abs(x[d] - base[d] - h * hex8_node_bit(a, d)) > 1e-6 * h) return false;
    }
  }
  return true;
}

void require_hex8_lattice(const Mesh& mesh) {
  if (mesh.type != ElementType::hex8)
    throw Error("multigrid: needs a hex8 lattice; this mesh is tet4 (use block-jacobi)");
  if (!is_hex8_lattice(mesh))
    throw Error(
        "multigrid: the mesh is not a hex8 lattice (axis-aligned cubes of one edge length, nodes in VTK order); use "
        "block-jacobi");
}

LatticeHierarchy build_lattice_hierarchy(const Mesh& mesh, const std::vector<char>& fine_mask, size_t coarsest_dofs,
                                         int max_levels) {
  require_hex8_lattice(mesh);
  if (fine_mask.size() != 3 * mesh.vertex_count()) throw Error("multigrid: constraint mask has the wrong size");
  LatticeHierarchy hierarchy;
  const auto p0 = mesh.vertex(mesh.elements[0]), p1 = mesh.vertex(mesh.elements[1]);
  hierarchy.spacing = p1[0] - p0[0];
  LatticeLevel fine;
  fine.vertex_count = mesh.vertex_count();
  fine.elements.assign(mesh.elements.begin(), mesh.elements.end());
  fine.mask = fine_mask;
  std::array<double, 3> origin{INFINITY, INFINITY, INFINITY};
  for (size_t e = 0; e < mesh.element_count(); ++e) {
    const auto x = mesh.vertex(mesh.elements[8 * e]);
    for (int d = 0; d < 3; ++d) origin[d] = std::min(origin[d], x[d]);
  }
  fine.cells.resize(mesh.element_count());
  for (size_t e = 0; e < mesh.element_count(); ++e) {
    const auto x = mesh.vertex(mesh.elements[8 * e]);
    for (int d = 0; d < 3; ++d)
      fine.cells[e][d] = static_cast<int>(std::lround((x[d] - origin[d]) / hierarchy.spacing));
  }
  hierarchy.levels.push_back(std::move(fine));
  // At least one coarse level where the lattice can shrink (a level cannot
  // be both finest and coarsest: the coarsest is solved from its matrices).
  while (static_cast<int>(hierarchy.levels.size()) < max_levels &&
         (hierarchy.levels.size() == 1 || 3 * hierarchy.levels.back().vertex_count > coarsest_dofs)) {
    LatticeLevel coarse = coarsen(hierarchy.levels.back());
    if (3 * coarse.cells.size() > 2 * hierarchy.levels.back().cells.size()) {  // fewer than 1.5x fewer cells
      LatticeLevel& last = hierarchy.levels.back();
      last.prolongation_vertices.clear();
      last.prolongation_weights.clear();
      last.restriction_offsets.clear();
      last.restriction_vertices.clear();
      last.restriction_weights.clear();
      break;
    }
    hierarchy.levels.push_back(std::move(coarse));
  }
  return hierarchy;
}

}  // namespace snh::solver
