// The pieces of a voxelized lattice, what holds each, and the rule for the
// ones nothing holds (snh/pieces.h): refuse them, join them to the body with
// a path of cells along the surface, or leave them out.
//
// Joining. The path runs through the grid cells the surface crosses (a thin
// finger joined to the hand along its own skin); only where no such path
// exists is it the straight line of cells. The lattice's vertices are
// classes of element corners joined across shared faces (voxelize). The
// added cells' corners are new nodes; the path's consecutive cells are
// joined across their common face, corner to corner, with a union-find over
// the given vertices and the new corners, so a given vertex keeps its index
// unless the path glues it to another (where two paths meet, or a path turns
// beside a cut), and the added cells share vertices with nothing but their
// neighbours on the path. Two given vertices prescribed by different
// constraint sets are never glued: the corner joins the first of them and
// the sets stay apart (a cut remains there, as the voxelizer leaves one
// between two fingers pressed together).
#include "snh/pieces.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <unordered_map>

#include "fem/surface_cells.h"
#include "fem/union_find.h"
#include "snh/error.h"

namespace snh {
namespace {

using Cell = std::array<int, 3>;
using Point = std::array<double, 3>;

// VTK_HEXAHEDRON order as local corners (bit 0: +x, bit 1: +y, bit 2: +z);
// the permutation is its own inverse, so corner c sits at node kHexCorners[c].
constexpr int kHexCorners[8] = {0, 1, 3, 2, 4, 5, 7, 6};

int64_t grid_index(const std::array<int, 3>& dims, const Cell& c) {
  return c[0] + static_cast<int64_t>(dims[0]) * (c[1] + static_cast<int64_t>(dims[1]) * c[2]);
}

// Signed distance from p to the obstacle placed by its motion at t = 0
// (positive on the free side).
double obstacle_distance(const Obstacle& o, const Point& p) {
  Point point = o.point, direction = o.direction;
  if (o.motion) {
    const RigidTransform m = o.motion(0.0);
    point = m.apply(o.point);
    for (int i = 0; i < 3; ++i)
      direction[i] = m.rotation[3 * i] * o.direction[0] + m.rotation[3 * i + 1] * o.direction[1] +
                     m.rotation[3 * i + 2] * o.direction[2];
  }
  const double n = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
  const Point d{p[0] - point[0], p[1] - point[1], p[2] - point[2]};
  switch (o.type) {
    case ObstacleType::plane:
      return (d[0] * direction[0] + d[1] * direction[1] + d[2] * direction[2]) / n;
    case ObstacleType::sphere:
      return std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - o.radius;
    case ObstacleType::cylinder: {
      const double along = (d[0] * direction[0] + d[1] * direction[1] + d[2] * direction[2]) / n;
      double off2 = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double q = d[k] - along * direction[k] / n;
        off2 += q * q;
      }
      return std::sqrt(off2) - o.radius;
    }
  }
  return HUGE_VAL;
}

// The pair (a in `from`, b in `to`) of cells nearest each other (squared
// distance between the cells' indices), ties to the smallest grid indices.
std::pair<Cell, Cell> nearest_cells(const std::vector<Cell>& from, const std::vector<Cell>& to,
                                    const std::array<int, 3>& dims) {
  Cell lo = from[0], hi = from[0];
  for (const Cell& c : from)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], c[d]);
      hi[d] = std::max(hi[d], c[d]);
    }
  int64_t best = std::numeric_limits<int64_t>::max();
  std::pair<int64_t, int64_t> best_index{0, 0};
  std::pair<Cell, Cell> out{from[0], to[0]};
  for (const Cell& b : to) {
    int64_t box = 0;  // to the box of `from`: a lower bound
    for (int d = 0; d < 3; ++d) {
      const int64_t off = std::max({0, lo[d] - b[d], b[d] - hi[d]});
      box += off * off;
    }
    if (box > best) continue;
    for (const Cell& a : from) {
      int64_t s = 0;
      for (int d = 0; d < 3; ++d) s += int64_t(a[d] - b[d]) * (a[d] - b[d]);
      const std::pair<int64_t, int64_t> index{grid_index(dims, a), grid_index(dims, b)};
      if (s < best || (s == best && index < best_index)) {
        best = s;
        best_index = index;
        out = {a, b};
      }
    }
  }
  return out;
}

// The face-connected cells of the segment from a's centre to b's, a and b
// included (3D DDA: step the axis whose next cell boundary the segment meets
// first, the lower axis on a tie).
std::vector<Cell> cell_line(const Cell& a, const Cell& b) {
  std::vector<Cell> line{a};
  Cell c = a;
  int steps[3] = {0, 0, 0}, length[3], sign[3];
  for (int d = 0; d < 3; ++d) {
    length[d] = std::abs(b[d] - a[d]);
    sign[d] = b[d] > a[d] ? 1 : -1;
  }
  while (c != b) {
    int axis = -1;
    double first = HUGE_VAL;
    for (int d = 0; d < 3; ++d)
      if (steps[d] < length[d]) {
        const double t = (steps[d] + 0.5) / length[d];
        if (t < first) first = t, axis = d;
      }
    ++steps[axis];
    c[axis] += sign[axis];
    line.push_back(c);
  }
  return line;
}

// The fewest face-connected cells from a cell of `from` to a cell marked in
// `target` through cells marked in `passable`, both ends included: a
// breadth-first search whose layers are taken in ascending grid index, each
// cell reached from the lowest-index cell of the layer before, the lowest-
// index target of the first layer that holds one; empty when none is reached.
std::vector<Cell> shortest_cell_path(const std::vector<Cell>& from, const std::vector<char>& passable,
                                     const std::vector<char>& target, const std::array<int, 3>& dims) {
  std::vector<int64_t> parent(passable.size(), -2);  // -2: not reached; -1: a source
  std::vector<int64_t> layer;
  for (const Cell& c : from) layer.push_back(grid_index(dims, c));
  std::sort(layer.begin(), layer.end());
  for (int64_t c : layer) parent[c] = -1;
  const int64_t stride[3] = {1, dims[0], int64_t(dims[0]) * dims[1]};
  std::vector<int64_t> next;
  while (!layer.empty()) {
    next.clear();
    for (int64_t c : layer) {
      const int64_t at[3] = {c % dims[0], (c / dims[0]) % dims[1], c / stride[2]};
      for (int d = 0; d < 3; ++d)
        for (int step : {-1, 1}) {
          if (at[d] + step < 0 || at[d] + step >= dims[d]) continue;
          const int64_t n = c + step * stride[d];
          if (parent[n] != -2 || !(passable[n] || target[n])) continue;
          parent[n] = c;
          next.push_back(n);
        }
    }
    std::sort(next.begin(), next.end());
    for (int64_t n : next) {
      if (!target[n]) continue;
      std::vector<Cell> path;
      for (int64_t c = n; c >= 0; c = parent[c])
        path.push_back({int(c % dims[0]), int((c / dims[0]) % dims[1]), int(c / stride[2])});
      std::reverse(path.begin(), path.end());
      return path;
    }
    // Targets end a path; they are not passed through.
    next.erase(std::remove_if(next.begin(), next.end(), [&](int64_t n) { return target[n] != 0; }), next.end());
    layer.swap(next);
  }
  return {};
}

std::array<double, 8> trilinear_weights(const double local[3]) {
  constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                 {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  std::array<double, 8> w{};
  for (int a = 0; a < 8; ++a) {
    w[a] = 1.0;
    for (int d = 0; d < 3; ++d) w[a] *= kCorner[a][d] ? local[d] : 1.0 - local[d];
  }
  return w;
}

std::string point_text(const Point& p) {
  std::ostringstream s;
  s << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return s.str();
}

// The lattice with `added` cells appended, joined along each line.
struct Joined {
  Voxelization voxels;
  std::vector<int32_t> vertex_map, element_source;
};

// set_of[v]: the constraint set prescribing given vertex v, or -1.
Joined join_lines(const Voxelization& given, const std::vector<std::vector<Cell>>& lines,
                  const std::vector<int32_t>& set_of) {
  const Mesh& old = given.lattice;
  const size_t vertices = old.vertex_count(), elements = old.element_count();
  std::unordered_map<int64_t, int32_t> element_of;
  for (size_t e = 0; e < elements; ++e) element_of.emplace(grid_index(given.dims, given.element_cell[e]), int32_t(e));
  Joined out;
  out.voxels = given;
  out.element_source.resize(elements);
  for (size_t e = 0; e < elements; ++e) out.element_source[e] = static_cast<int32_t>(e);
  // Element of each line cell, the added ones numbered after the given ones.
  std::vector<std::vector<int32_t>> line_elements;
  for (const std::vector<Cell>& line : lines) {
    std::vector<int32_t> ids;
    for (const Cell& c : line) {
      auto [it, added] = element_of.emplace(grid_index(given.dims, c), int32_t(out.voxels.element_cell.size()));
      if (added) {
        out.voxels.element_cell.push_back(c);
        out.element_source.push_back(ids.empty() ? it->second : out.element_source[ids.back()]);
      }
      ids.push_back(it->second);
    }
    line_elements.push_back(std::move(ids));
  }
  const size_t total = out.voxels.element_cell.size();
  const auto node = [&](size_t e, int corner) -> int32_t {
    return e < elements ? old.elements[8 * e + kHexCorners[corner]]
                        : static_cast<int32_t>(vertices + 8 * (e - elements) + corner);
  };
  fem::UnionFind classes(vertices + 8 * (total - elements));
  std::vector<int32_t> class_set(classes.parent.size(), -1);  // per representative
  for (size_t v = 0; v < vertices; ++v) class_set[v] = set_of[v];
  const auto unite = [&](int32_t x, int32_t y) {
    x = classes.find(x);
    y = classes.find(y);
    if (x == y || (class_set[x] >= 0 && class_set[y] >= 0 && class_set[x] != class_set[y])) return;
    classes.unite(x, y);
    class_set[std::min(x, y)] = std::max(class_set[x], class_set[y]);
  };
  for (const std::vector<int32_t>& ids : line_elements)
    for (size_t k = 0; k + 1 < ids.size(); ++k) {
      size_t p = ids[k], q = ids[k + 1];
      const Cell &cp = out.voxels.element_cell[p], &cq = out.voxels.element_cell[q];
      int axis = 0;
      while (cp[axis] == cq[axis]) ++axis;
      if (cq[axis] < cp[axis]) std::swap(p, q);  // p below q along the axis
      for (int corner = 0; corner < 8; ++corner)
        if (corner & (1 << axis)) unite(node(p, corner), node(q, corner ^ (1 << axis)));
    }
  std::vector<int32_t> id(classes.parent.size(), -1);
  Mesh& lattice = out.voxels.lattice;
  lattice.positions.clear();
  for (size_t k = 0; k < classes.parent.size(); ++k) {
    if (classes.find(static_cast<int32_t>(k)) != static_cast<int32_t>(k)) continue;
    id[k] = static_cast<int32_t>(lattice.positions.size());
    if (k < vertices) {
      lattice.positions.push_back({old.positions(k, 0), old.positions(k, 1), old.positions(k, 2)});
    } else {
      const size_t e = elements + (k - vertices) / 8;
      const int corner = static_cast<int>((k - vertices) % 8);
      Vec3 p;
      for (int d = 0; d < 3; ++d)
        p[d] = given.origin[d] + given.cell * (out.voxels.element_cell[e][d] + ((corner >> d) & 1));
      lattice.positions.push_back(p);
    }
  }
  out.vertex_map.resize(vertices);
  for (size_t v = 0; v < vertices; ++v) out.vertex_map[v] = id[classes.find(static_cast<int32_t>(v))];
  lattice.elements.resize(8 * total);
  for (size_t e = 0; e < total; ++e)
    for (int n = 0; n < 8; ++n) lattice.elements[8 * e + n] = id[classes.find(node(e, kHexCorners[n]))];
  return out;
}

// The pieces of the given lattice into out.pieces, each with its vertex
// count and bounding box; returns the piece of each vertex (-1: in none).
std::vector<int32_t> find_pieces(const Mesh& lattice, PiecedLattice& out) {
  const std::vector<std::vector<int32_t>> elements_of = mesh_pieces(lattice);
  std::vector<int32_t> piece_of_vertex(lattice.vertex_count(), -1);
  for (size_t p = 0; p < elements_of.size(); ++p) {
    LatticePiece piece;
    piece.elements = elements_of[p];
    piece.lo = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
    piece.hi = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int32_t e : piece.elements)
      for (int n = 0; n < 8; ++n) {
        const int32_t v = lattice.elements[8 * e + n];
        if (piece_of_vertex[v] >= 0) continue;
        piece_of_vertex[v] = static_cast<int32_t>(p);
        ++piece.vertices;
        for (int d = 0; d < 3; ++d) {
          piece.lo[d] = std::min(piece.lo[d], lattice.positions(v, d));
          piece.hi[d] = std::max(piece.hi[d], lattice.positions(v, d));
        }
      }
    out.pieces.push_back(std::move(piece));
  }
  return piece_of_vertex;
}

// A piece with a vertex in a set that prescribes a component is held by the
// first such set.
void hold_by_constraints(const std::vector<ConstraintSet>& constraints, const std::vector<int32_t>& piece_of_vertex,
                         PiecedLattice& out) {
  for (const ConstraintSet& set : constraints) {
    if (!set.components[0] && !set.components[1] && !set.components[2]) continue;
    for (int32_t v : set.vertices) {
      if (v < 0 || static_cast<size_t>(v) >= piece_of_vertex.size() || piece_of_vertex[v] < 0) continue;
      LatticePiece& piece = out.pieces[piece_of_vertex[v]];
      if (piece.hold != PieceHold::none) continue;
      piece.hold = PieceHold::constraint;
      piece.held_by = set.name;
    }
  }
}

// A piece nothing else holds, with a vertex in an obstacle's contact layer at
// rest, is held by the first such obstacle.
void hold_by_obstacles(const Mesh& lattice, const std::vector<int32_t>& piece_of_vertex, const PieceOptions& options,
                       PiecedLattice& out) {
  for (size_t v = 0; v < piece_of_vertex.size() && !options.obstacles.empty(); ++v) {
    if (piece_of_vertex[v] < 0 || out.pieces[piece_of_vertex[v]].hold != PieceHold::none) continue;
    for (size_t k = 0; k < options.obstacles.size(); ++k)
      if (obstacle_distance(options.obstacles[k], lattice.vertex(v)) <= options.contact_thickness) {
        out.pieces[piece_of_vertex[v]].hold = PieceHold::obstacle;
        out.pieces[piece_of_vertex[v]].held_by = "obstacles[" + std::to_string(k) + "]";
        break;
      }
  }
}

// When nothing holds any piece, the largest (the first of them) stands for
// the body.
void hold_largest_if_none_held(PiecedLattice& out) {
  if (std::none_of(out.pieces.begin(), out.pieces.end(),
                   [](const LatticePiece& p) { return p.hold != PieceHold::none; })) {
    size_t largest = 0;
    for (size_t p = 1; p < out.pieces.size(); ++p)
      if (out.pieces[p].elements.size() > out.pieces[largest].elements.size()) largest = p;
    out.pieces[largest].hold = PieceHold::largest;
  }
}

// The pieces nothing holds, ascending.
std::vector<size_t> find_free_pieces(const PiecedLattice& out) {
  std::vector<size_t> free_pieces;
  for (size_t p = 0; p < out.pieces.size(); ++p)
    if (out.pieces[p].hold == PieceHold::none) free_pieces.push_back(p);
  return free_pieces;
}

// Each free piece's nearest bone (the first of the nearest) and its distance.
void find_nearest_bones(const Mesh& lattice, const std::vector<Bone>& bones, const std::vector<size_t>& free_pieces,
                        PiecedLattice& out) {
  for (size_t p : free_pieces) {
    LatticePiece& piece = out.pieces[p];
    double best = HUGE_VAL;
    for (const Bone& bone : bones) {
      double d = HUGE_VAL;
      for (int32_t e : piece.elements)
        for (int n = 0; n < 8 && d > 0.0; ++n)
          d = std::min(d, bone_distance(bone, lattice.vertex(lattice.elements[8 * e + n])));
      if (d < best) best = d, piece.nearest_bone = bone.name, piece.nearest_bone_distance = d;
    }
  }
}

std::string describe_piece(const PiecedLattice& out, size_t p) {
  const LatticePiece& piece = out.pieces[p];
  std::ostringstream s;
  s << "piece " << p + 1 << ": " << piece.elements.size() << " cells, bounding box " << point_text(piece.lo) << " to "
    << point_text(piece.hi);
  if (!piece.nearest_bone.empty())
    s << ", nearest bone '" << piece.nearest_bone << "' at " << piece.nearest_bone_distance;
  return s.str();
}

// The error rule: in a dynamic scene the free pieces are held by their
// inertia (a warning for each under a load); otherwise an snh::Error names
// them and the remedies.
void hold_by_inertia_or_refuse(const std::vector<size_t>& free_pieces, const PieceOptions& options,
                               PiecedLattice& out) {
  if (options.dynamic) {
    for (size_t p : free_pieces) {
      out.pieces[p].hold = PieceHold::inertia;
      if (options.loaded)
        out.warnings.push_back("embed: " + describe_piece(out, p) + " of " + std::to_string(out.pieces.size()) +
                               " is held by nothing but its inertia: under the load it moves on its own (falls)");
    }
    return;
  }
  std::ostringstream s;
  s << "the lattice falls into " << out.pieces.size() << " pieces, and nothing holds " << free_pieces.size()
    << " of them (no vertex in a constraint set or a bone, none in an obstacle's contact layer): a quasistatic "
       "solve leaves such a piece at rest while the body moves, stretching the surface embedded in it, and finds "
       "no equilibrium under a load";
  for (size_t p : free_pieces) s << "\n  " << describe_piece(out, p);
  s << "\nremedies: a bone that reaches into each piece; " << options.rule_name
    << " \"attach\" (join each to its nearest held piece through the cells its surface crosses) or \"drop\" (leave "
       "it out; its "
       "surface follows the nearest kept cell); or another cell size (a larger cell bridges the gap, a smaller "
       "one resolves the thin part)";
  throw Error(s.str());
}

// Grid cells of the held pieces (the targets) and of each free one.
std::vector<Cell> held_cells_of(const Voxelization& voxels, const std::vector<size_t>& free_pieces,
                                const PiecedLattice& out) {
  std::vector<Cell> held_cells;
  std::vector<char> free(out.pieces.size(), 0);
  for (size_t p : free_pieces) free[p] = 1;
  for (size_t p = 0; p < out.pieces.size(); ++p)
    if (!free[p])
      for (int32_t e : out.pieces[p].elements) held_cells.push_back(voxels.element_cell[e]);
  return held_cells;
}

std::vector<Cell> cells_of(const Voxelization& voxels, const LatticePiece& piece) {
  std::vector<Cell> cells;
  for (int32_t e : piece.elements) cells.push_back(voxels.element_cell[e]);
  return cells;
}

// The attach rule: each free piece joined to the held cells by a path of
// cells, the lattice rebuilt with the paths and the surface embedded again.
void attach_pieces(const Voxelization& voxels, const TriangleSurface& surface,
                   const std::vector<ConstraintSet>& constraints, const std::vector<size_t>& free_pieces,
                   const std::vector<Cell>& held_cells, PiecedLattice& out) {
  const Mesh& lattice = voxels.lattice;
  std::vector<std::vector<Cell>> lines;
  std::unordered_map<int64_t, char> occupied;
  for (const Cell& c : voxels.element_cell) occupied.emplace(grid_index(voxels.dims, c), 1);
  // Passable: cells the surface crosses that no element occupies.
  std::vector<char> passable = fem::surface_crossed_cells(surface, voxels.origin, voxels.cell, voxels.dims);
  std::vector<char> target(passable.size(), 0);
  for (const Cell& c : voxels.element_cell) passable[grid_index(voxels.dims, c)] = 0;
  for (const Cell& c : held_cells) target[grid_index(voxels.dims, c)] = 1;
  for (size_t p : free_pieces) {
    std::vector<Cell> path = shortest_cell_path(cells_of(voxels, out.pieces[p]), passable, target, voxels.dims);
    out.pieces[p].joined_through = "surface";
    if (path.empty()) {
      const auto [a, b] = nearest_cells(cells_of(voxels, out.pieces[p]), held_cells, voxels.dims);
      path = cell_line(a, b);
      out.pieces[p].joined_through = "straight line";
    }
    lines.push_back(std::move(path));
    out.pieces[p].outcome = "attached";
    for (const Cell& c : lines.back())
      out.pieces[p].added_cells += occupied.emplace(grid_index(voxels.dims, c), 1).second;
  }
  std::vector<int32_t> set_of(lattice.vertex_count(), -1);
  for (size_t k = 0; k < constraints.size(); ++k)
    if (constraints[k].components[0] || constraints[k].components[1] || constraints[k].components[2])
      for (int32_t v : constraints[k].vertices)
        if (v >= 0 && static_cast<size_t>(v) < set_of.size() && set_of[v] < 0) set_of[v] = static_cast<int32_t>(k);
  Joined joined = join_lines(voxels, lines, set_of);
  out.voxels = std::move(joined.voxels);
  out.vertex_map = std::move(joined.vertex_map);
  out.element_source = std::move(joined.element_source);
  // The surface as the caller embedded it: vertices beyond a cell of the
  // lattice (a character's open sheets) are carried, not refused.
  out.embedding = embed_carrying_all(out.voxels, surface).embedding;
}

// The drop rule: the free pieces' elements and the vertices only they use
// left out, the rest renumbered in order.
void drop_pieces(const Voxelization& voxels, const Embedding& embedding, const TriangleSurface& surface,
                 const std::vector<size_t>& free_pieces, const std::vector<Cell>& held_cells, PiecedLattice& out) {
  const Mesh& lattice = voxels.lattice;
  std::vector<char> drop_element(lattice.element_count(), 0);
  for (size_t p : free_pieces) {
    out.pieces[p].outcome = "dropped";
    for (int32_t e : out.pieces[p].elements) drop_element[e] = 1;
  }
  Voxelization& kept = out.voxels;
  kept.lattice.elements.clear();
  kept.lattice.positions.clear();
  kept.element_cell.clear();
  out.element_source.clear();
  std::vector<int32_t> new_element(lattice.element_count(), -1);
  std::vector<char> used(lattice.vertex_count(), 0);
  for (size_t e = 0; e < lattice.element_count(); ++e)
    if (!drop_element[e])
      for (int n = 0; n < 8; ++n) used[lattice.elements[8 * e + n]] = 1;
  int32_t next = 0;
  for (size_t v = 0; v < used.size(); ++v) {
    out.vertex_map[v] = used[v] ? next++ : -1;
    if (used[v])
      kept.lattice.positions.push_back({lattice.positions(v, 0), lattice.positions(v, 1), lattice.positions(v, 2)});
  }
  for (size_t e = 0; e < lattice.element_count(); ++e) {
    if (drop_element[e]) continue;
    new_element[e] = static_cast<int32_t>(kept.element_cell.size());
    kept.element_cell.push_back(voxels.element_cell[e]);
    out.element_source.push_back(static_cast<int32_t>(e));
    for (int n = 0; n < 8; ++n) kept.lattice.elements.push_back(out.vertex_map[lattice.elements[8 * e + n]]);
  }
  // Each dropped piece's surface follows the kept cell nearest to it.
  std::unordered_map<int64_t, int32_t> kept_element;
  for (size_t e = 0; e < kept.element_cell.size(); ++e)
    kept_element.emplace(grid_index(voxels.dims, kept.element_cell[e]), static_cast<int32_t>(e));
  std::vector<Cell> anchor(out.pieces.size());
  for (size_t p : free_pieces)
    anchor[p] = nearest_cells(cells_of(voxels, out.pieces[p]), held_cells, voxels.dims).second;
  std::vector<int32_t> piece_of_element(lattice.element_count(), -1);
  for (size_t p = 0; p < out.pieces.size(); ++p)
    for (int32_t e : out.pieces[p].elements) piece_of_element[e] = static_cast<int32_t>(p);
  for (size_t v = 0; v < out.embedding.element.size(); ++v) {
    const int32_t e = embedding.element[v];
    if (!drop_element[e]) {
      out.embedding.element[v] = new_element[e];
      continue;
    }
    const Cell& c = anchor[piece_of_element[e]];
    double local[3];
    for (int d = 0; d < 3; ++d) local[d] = (surface.positions(v, d) - voxels.origin[d]) / voxels.cell - c[d];
    out.embedding.element[v] = kept_element.at(grid_index(voxels.dims, c));
    const auto w = trilinear_weights(local);
    std::copy(w.begin(), w.end(), out.embedding.weights.begin() + 8 * v);
  }
}

// The constraint sets renumbered to the new lattice (out.vertex_map), in
// place.
void renumber_constraints(std::vector<ConstraintSet>& constraints, const PieceOptions& options,
                          const PiecedLattice& out) {
  for (ConstraintSet& set : constraints) {
    std::vector<int32_t> vertices;
    for (int32_t v : set.vertices)
      if (v >= 0 && static_cast<size_t>(v) < out.vertex_map.size() && out.vertex_map[v] >= 0)
        vertices.push_back(out.vertex_map[v]);
    // Two given vertices glued into one stay one entry (the first).
    std::vector<int32_t> seen = vertices;
    std::sort(seen.begin(), seen.end());
    if (std::adjacent_find(seen.begin(), seen.end()) != seen.end()) {
      std::vector<char> taken(out.voxels.lattice.vertex_count(), 0);
      std::vector<int32_t> unique;
      for (int32_t v : vertices)
        if (!taken[v]) taken[v] = 1, unique.push_back(v);
      vertices = std::move(unique);
    }
    // Only a set that prescribes nothing can lie wholly in dropped pieces
    // (a prescribed vertex holds its piece); emptied, it would select no
    // vertex: refused here, where the cause is known.
    if (vertices.empty() && !set.vertices.empty())
      throw Error("constraint set '" + set.name + "': all its " + std::to_string(set.vertices.size()) +
                  " vertices are in dropped pieces (it prescribes no component, so it holds none of them); with " +
                  options.rule_name +
                  " \"drop\" it would select no vertex: give it a component, or select "
                  "vertices of a kept piece");
    set.vertices = std::move(vertices);
  }
}

}  // namespace

const char* to_string(PieceRule rule) {
  switch (rule) {
    case PieceRule::error:
      return "error";
    case PieceRule::attach:
      return "attach";
    case PieceRule::drop:
      return "drop";
  }
  return "?";
}

PieceRule parse_piece_rule(const std::string& name) {
  for (PieceRule r : {PieceRule::error, PieceRule::attach, PieceRule::drop})
    if (name == to_string(r)) return r;
  throw Error("expected error, attach or drop, got '" + name + "'");
}

const char* to_string(PieceHold hold) {
  switch (hold) {
    case PieceHold::none:
      return "none";
    case PieceHold::constraint:
      return "constraint";
    case PieceHold::obstacle:
      return "obstacle";
    case PieceHold::inertia:
      return "inertia";
    case PieceHold::largest:
      return "largest";
  }
  return "?";
}

std::vector<std::vector<int32_t>> mesh_pieces(const Mesh& mesh) {
  const size_t elements = mesh.element_count();
  const int nodes = nodes_per_element(mesh.type);
  fem::UnionFind joined(elements);
  std::vector<int32_t> first(mesh.vertex_count(), -1);
  for (size_t e = 0; e < elements; ++e)
    for (int n = 0; n < nodes; ++n) {
      const int32_t v = mesh.elements[nodes * e + n];
      if (v < 0 || static_cast<size_t>(v) >= first.size()) continue;  // validate_mesh names it
      if (first[v] < 0)
        first[v] = static_cast<int32_t>(e);
      else
        joined.unite(first[v], static_cast<int32_t>(e));
    }
  std::vector<int32_t> piece_of(elements, -1);
  std::vector<std::vector<int32_t>> out;
  for (size_t e = 0; e < elements; ++e) {
    const int32_t root = joined.find(static_cast<int32_t>(e));  // the piece's first element
    if (piece_of[root] < 0) {
      piece_of[root] = static_cast<int32_t>(out.size());
      out.emplace_back();
    }
    out[piece_of[root]].push_back(static_cast<int32_t>(e));
  }
  return out;
}

PiecedLattice resolve_pieces(const Voxelization& voxels, const Embedding& embedding, const TriangleSurface& surface,
                             std::vector<ConstraintSet>& constraints, const std::vector<Bone>& bones,
                             const PieceOptions& options) {
  const Mesh& lattice = voxels.lattice;
  if (lattice.type != ElementType::hex8 || voxels.element_cell.size() != lattice.element_count())
    throw Error("resolve_pieces: the voxelization's lattice is not hex8 with one grid cell per element");
  PiecedLattice out;
  out.voxels = voxels;
  out.embedding = embedding;
  out.vertex_map.resize(lattice.vertex_count());
  for (size_t v = 0; v < out.vertex_map.size(); ++v) out.vertex_map[v] = static_cast<int32_t>(v);
  out.element_source.resize(lattice.element_count());
  for (size_t e = 0; e < out.element_source.size(); ++e) out.element_source[e] = static_cast<int32_t>(e);

  const std::vector<int32_t> piece_of_vertex = find_pieces(lattice, out);
  hold_by_constraints(constraints, piece_of_vertex, out);
  hold_by_obstacles(lattice, piece_of_vertex, options, out);
  if (out.pieces.size() < 2) return out;  // the whole body: the solver's rigid-motion check
  hold_largest_if_none_held(out);
  const std::vector<size_t> free_pieces = find_free_pieces(out);
  if (free_pieces.empty()) return out;
  find_nearest_bones(lattice, bones, free_pieces, out);

  if (options.rule == PieceRule::error) {
    hold_by_inertia_or_refuse(free_pieces, options, out);
    return out;
  }

  const std::vector<Cell> held_cells = held_cells_of(voxels, free_pieces, out);
  out.changed = true;

  if (options.rule == PieceRule::attach)
    attach_pieces(voxels, surface, constraints, free_pieces, held_cells, out);
  else
    drop_pieces(voxels, embedding, surface, free_pieces, held_cells, out);
  out.voxels.components = static_cast<int>(mesh_pieces(out.voxels.lattice).size());

  renumber_constraints(constraints, options, out);
  return out;
}

}  // namespace snh
