// From a closed triangle surface to a hex8 lattice (surface.h): grid cells
// whose centres are inside (and, on request, those the surface passes
// through) become elements, and face-adjacent elements share vertices unless
// the surface passes between their centres, both inside.
//
// Inside and crossing tests share one procedure: for each axis a, every row
// of cell centres parallel to a is a line; the triangles whose projection on
// the plane of the other two axes (b, c) contains the row's point cross it.
// Point-in-projected-triangle uses one orientation predicate per edge,
// evaluated in a fixed vertex order (lower index first), so the two triangles
// of an edge always agree and a line through an edge or vertex crosses the
// surface exactly as often as a nearby line does: ties (the predicate exactly
// 0) are decided as if the point moved by (e, e^2) in (b, c), e -> 0
// (simulation of simplicity). Each crossing carries the sign of the
// triangle's normal along a, so the winding number of a centre is the sum of
// the signs of the crossings beyond it along +a (crossings at exactly the
// centre count as behind it: the centre moved by +a).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "fem/fast_winding_number.h"
#include "fem/shell_orientation.h"
#include "fem/surface_cells.h"
#include "fem/union_find.h"
#include "snh/error.h"
#include "snh/surface.h"

namespace snh {
namespace {

constexpr uint8_t kInside = 1;
// kCut << a: the segment from this cell's centre to its +a neighbour's crosses the surface.
constexpr uint8_t kCut = 2;
// A triangle meets the cell's open cube (VoxelizeOptions::cover_surface).
constexpr uint8_t kCrossed = 16;

struct Grid {
  std::array<double, 3> origin;
  double h;
  std::array<int, 3> dims;
  size_t index(int i, int j, int k) const { return size_t(i) + size_t(dims[0]) * (size_t(j) + size_t(dims[1]) * k); }
  double centre(int axis, int i) const { return origin[axis] + (i + 0.5) * h; }
};

// The sign of orient2d(A, B, p) in the (b, c) plane for p moved by (e, e^2).
int edge_side(const double* A, const double* B, double pb, double pc, int b, int c) {
  const double db = B[b] - A[b], dc = B[c] - A[c];
  const double o = db * (pc - A[c]) - dc * (pb - A[b]);
  if (o != 0.0) return o > 0.0 ? 1 : -1;
  // d/de of the predicate is -dc, then d/d(e^2) is db.
  if (dc != 0.0) return dc > 0.0 ? -1 : 1;
  if (db != 0.0) return db > 0.0 ? 1 : -1;
  return 0;  // the edge projects to a point: its triangle has no area in (b, c)
}

struct Crossing {
  double t;  // coordinate along the axis
  int sign;  // +1 where the surface faces +axis (the line leaves the inside)
};

// Whether the line parallel to `a` through (pb, pc) in the other two axes
// crosses triangle v, and where.
bool crosses(const double* p, const int32_t* v, int a, double pb, double pc, Crossing& crossing) {
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  int side[3];
  for (int e = 0; e < 3; ++e) {
    const int32_t u = v[e], w = v[(e + 1) % 3];
    side[e] = u < w ? edge_side(p + 3 * u, p + 3 * w, pb, pc, b, c) : -edge_side(p + 3 * w, p + 3 * u, pb, pc, b, c);
  }
  if (side[0] == 0 || side[0] != side[1] || side[1] != side[2]) return false;
  // Where the line meets the triangle's plane, kept within the triangle's
  // extent along the axis (it is there in exact arithmetic).
  const double* x0 = p + 3 * v[0];
  const double* x1 = p + 3 * v[1];
  const double* x2 = p + 3 * v[2];
  const double e1[3] = {x1[0] - x0[0], x1[1] - x0[1], x1[2] - x0[2]};
  const double e2[3] = {x2[0] - x0[0], x2[1] - x0[1], x2[2] - x0[2]};
  const double normal_a = e1[b] * e2[c] - e1[c] * e2[b];
  const double normal_b = e1[c] * e2[a] - e1[a] * e2[c];
  const double normal_c = e1[a] * e2[b] - e1[b] * e2[a];
  const double lo = std::min({x0[a], x1[a], x2[a]}), hi = std::max({x0[a], x1[a], x2[a]});
  const double t =
      normal_a != 0.0 ? x0[a] - (normal_b * (pb - x0[b]) + normal_c * (pc - x0[c])) / normal_a : 0.5 * (lo + hi);
  crossing = {std::min(hi, std::max(lo, t)), side[0]};
  return true;
}

// Fills kCut << axis for every row parallel to `axis`, and kInside by the
// crossing count when `count_inside` (axis 0 only). Without `winding` (the
// crossing-count rule), any crossing between two centres cuts; with it (the
// winding number of each centre, rounded), only a run of crossings along
// which the winding number falls below 1/2: a gap, not the wall of a shell
// inside another.
void sweep(const TriangleSurface& surface, const Grid& grid, int axis, bool count_inside,
           const std::vector<int8_t>* winding, std::vector<uint8_t>& flags) {
  const int a = axis, b = (axis + 1) % 3, c = (axis + 2) % 3;
  const int nb = grid.dims[b], nc = grid.dims[c], na = grid.dims[a];
  const double* p = surface.positions.data();
  const int32_t* tri = surface.triangles.data();
  const size_t triangles = surface.triangle_count();

  // Rows whose point may lie in each triangle's (b, c) bounding box (one row
  // of padding against rounding; the predicates decide), as lists per row.
  const auto row_range = [&](size_t t, int d, int n, int& lo, int& hi) {
    double mn = p[3 * tri[3 * t] + d], mx = mn;
    for (int k = 1; k < 3; ++k) {
      mn = std::min(mn, p[3 * tri[3 * t + k] + d]);
      mx = std::max(mx, p[3 * tri[3 * t + k] + d]);
    }
    lo = std::max(0, static_cast<int>(std::floor((mn - grid.origin[d]) / grid.h - 0.5)));
    hi = std::min(n - 1, static_cast<int>(std::ceil((mx - grid.origin[d]) / grid.h - 0.5)));
  };
  std::vector<size_t> offsets(size_t(nb) * nc + 1, 0);
  for (size_t t = 0; t < triangles; ++t) {
    int b0, b1, c0, c1;
    row_range(t, b, nb, b0, b1);
    row_range(t, c, nc, c0, c1);
    for (int jc = c0; jc <= c1; ++jc)
      for (int jb = b0; jb <= b1; ++jb) ++offsets[size_t(jb) + size_t(nb) * jc + 1];
  }
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  std::vector<int32_t> members(offsets.back());
  std::vector<size_t> fill(offsets.begin(), offsets.end() - 1);
  for (size_t t = 0; t < triangles; ++t) {
    int b0, b1, c0, c1;
    row_range(t, b, nb, b0, b1);
    row_range(t, c, nc, c0, c1);
    for (int jc = c0; jc <= c1; ++jc)
      for (int jb = b0; jb <= b1; ++jb) members[fill[size_t(jb) + size_t(nb) * jc]++] = static_cast<int32_t>(t);
  }

  std::vector<Crossing> crossings;
  for (int jc = 0; jc < nc; ++jc)
    for (int jb = 0; jb < nb; ++jb) {
      const size_t row = size_t(jb) + size_t(nb) * jc;
      const double pb = grid.centre(b, jb), pc = grid.centre(c, jc);
      crossings.clear();
      for (size_t m = offsets[row]; m < offsets[row + 1]; ++m) {
        Crossing x;
        if (crosses(p, tri + 3 * members[m], a, pb, pc, x)) crossings.push_back(x);
      }
      std::sort(crossings.begin(), crossings.end(), [](const Crossing& x, const Crossing& y) { return x.t < y.t; });
      int total = 0;
      for (const Crossing& x : crossings) total += x.sign;
      size_t k = 0;
      int behind = 0;  // sum of signs of crossings at or before the current centre
      std::array<int, 3> cell{};
      cell[b] = jb;
      cell[c] = jc;
      for (int i = 0; i < na; ++i) {
        const double here = grid.centre(a, i);
        const size_t k0 = k;
        while (k < crossings.size() && crossings[k].t <= here) behind += crossings[k++].sign;
        cell[a] = i;
        const size_t index = grid.index(cell[0], cell[1], cell[2]);
        if (i > 0 && k > k0) {
          cell[a] = i - 1;
          const size_t previous = grid.index(cell[0], cell[1], cell[2]);
          // A crossing of sign +1 leaves the inside: the winding number drops by 1.
          int running = 0, drop = 0;
          for (size_t x = k0; x < k; ++x) drop = std::max(drop, running += crossings[x].sign);
          if (!winding || (*winding)[previous] - drop <= 0) flags[previous] |= static_cast<uint8_t>(kCut << a);
        }
        if (count_inside && total - behind > 0) flags[index] |= kInside;
      }
    }
}

// Marks kCrossed on every cell whose open cube a triangle meets.
void mark_crossed(const TriangleSurface& surface, const Grid& grid, std::vector<uint8_t>& flags) {
  const std::vector<char> crossed = fem::surface_crossed_cells(surface, grid.origin, grid.h, grid.dims);
  for (size_t i = 0; i < flags.size(); ++i)
    if (crossed[i]) flags[i] |= kCrossed;
}

using fem::UnionFind;

// VTK_HEXAHEDRON order as local corners (bit 0: +x, bit 1: +y, bit 2: +z).
constexpr int kHexCorners[8] = {0, 1, 3, 2, 4, 5, 7, 6};

}  // namespace

Voxelization voxelize(const TriangleSurface& input, double cell, const VoxelizeOptions& options) {
  const std::string& name = options.name;
  if (!(cell > 0.0) || !std::isfinite(cell)) {
    std::ostringstream s;
    s << name << ": voxelize: the cell size must be positive and finite, got " << cell;
    throw Error(s.str());
  }
  if (input.triangles.empty()) throw Error(name + ": the surface has no triangles");
  Voxelization out;
  // Strict: the surface must be closed as it is. Otherwise its defects are
  // counted (after welding) and warned, and the welded surface is the one
  // swept, so that the triangles of a seam share their edge's vertices and
  // the crossing predicates agree along it.
  if (options.strict) validate_closed_surface(input, name);
  out.report = surface_report(input, name, options.weld_tolerance);
  out.warnings = out.report.warnings;
  TriangleSurface surface = options.strict ? input : weld_vertices(input, options.weld_tolerance).surface;
  // Inside-out or mirrored shells count as their outward twins: the winding
  // number of a shell facing inwards is -1 inside it.
  if (!options.strict)
    for (std::string& w : fem::orient_shells(surface, name)) out.warnings.push_back(std::move(w));

  std::array<double, 3> lo, hi;
  for (int d = 0; d < 3; ++d) lo[d] = hi[d] = surface.positions(0, d);
  for (size_t v = 0; v < surface.vertex_count(); ++v)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], surface.positions(v, d));
      hi[d] = std::max(hi[d], surface.positions(v, d));
    }
  Grid grid{};
  grid.h = cell;
  double total = 1.0;
  for (int d = 0; d < 3; ++d) {
    // A grid short of the box by rounding (extent / cell = 12.000000000000002)
    // loses nothing: cells beyond it have their centres outside the box.
    const double n = std::max(1.0, std::ceil((hi[d] - lo[d]) / cell - 1e-9));
    total *= n;
    if (!(n <= double(std::numeric_limits<int32_t>::max())) || !(total <= double(options.max_grid_cells))) {
      std::ostringstream s;
      s << name << ": voxelize: a cell of " << cell << " makes a grid of " << std::ceil((hi[0] - lo[0]) / cell) << " x "
        << std::ceil((hi[1] - lo[1]) / cell) << " x " << std::ceil((hi[2] - lo[2]) / cell)
        << " cells for the bounding box " << hi[0] - lo[0] << " x " << hi[1] - lo[1] << " x " << hi[2] - lo[2]
        << ", more than the limit of " << options.max_grid_cells
        << " (VoxelizeOptions::max_grid_cells); use a larger cell";
      throw Error(s.str());
    }
    grid.dims[d] = static_cast<int>(n);
    grid.origin[d] = lo[d];
  }

  const size_t cells = size_t(grid.dims[0]) * grid.dims[1] * grid.dims[2];
  std::vector<uint8_t> flags(cells, 0);
  std::vector<int8_t> rounded;
  if (!options.strict) {
    // Inside: the generalized winding number of the centre is at least 1/2
    // (evaluated where it can change: fem::winding_at_cell_centres).
    const std::vector<double> winding =
        fem::winding_at_cell_centres(surface, grid.origin, grid.h, grid.dims, options.winding_beta);
    rounded.resize(cells);
    for (size_t index = 0; index < cells; ++index) {
      const double w = winding[index];
      if (w >= 0.5) flags[index] |= kInside;
      rounded[index] = static_cast<int8_t>(std::max(-100.0, std::min(100.0, std::round(w))));
    }
  }
  for (int axis = 0; axis < 3; ++axis)
    sweep(surface, grid, axis, options.strict && axis == 0, options.strict ? nullptr : &rounded, flags);
  if (options.cover_surface) mark_crossed(surface, grid, flags);
  const uint8_t keep = options.cover_surface ? (kInside | kCrossed) : kInside;

  out.cell = cell;
  out.origin = grid.origin;
  out.dims = grid.dims;
  std::vector<int32_t> kept(cells, -1);
  for (int k = 0; k < grid.dims[2]; ++k)
    for (int j = 0; j < grid.dims[1]; ++j)
      for (int i = 0; i < grid.dims[0]; ++i)
        if (flags[grid.index(i, j, k)] & keep) {
          if (out.element_cell.size() >= size_t(std::numeric_limits<int32_t>::max() / 8))
            throw Error(name + ": voxelize: the lattice would have more vertices than 32-bit indices can address");
          kept[grid.index(i, j, k)] = static_cast<int32_t>(out.element_cell.size());
          out.element_cell.push_back({i, j, k});
        }
  const size_t elements = out.element_cell.size();
  if (elements == 0) {
    std::ostringstream s;
    s << name << ": voxelize: no cell centre lies inside the surface (it encloses nothing) with a cell of " << cell
      << " (bounding box " << hi[0] - lo[0] << " x " << hi[1] - lo[1] << " x " << hi[2] - lo[2]
      << "): use a smaller cell, or check that the surface encloses a volume with its normals facing outwards";
    throw Error(s.str());
  }

  // Element corners (8 per element) joined across faces whose centre-to-
  // centre segment does not cross the surface; each class is one vertex.
  UnionFind corners(8 * elements);
  for (size_t e = 0; e < elements; ++e) {
    const std::array<int, 3>& g = out.element_cell[e];
    const uint8_t here = flags[grid.index(g[0], g[1], g[2])];
    for (int a = 0; a < 3; ++a) {
      if (g[a] + 1 >= grid.dims[a]) continue;
      std::array<int, 3> n = g;
      ++n[a];
      const int32_t f = kept[grid.index(n[0], n[1], n[2])];
      if (f < 0) continue;
      // A cut between two centres inside is a gap; a cell kept for the
      // surface crossing it (centre outside) joins its neighbours.
      if ((here & (kCut << a)) && (here & kInside) && (flags[grid.index(n[0], n[1], n[2])] & kInside)) continue;
      for (int corner = 0; corner < 8; ++corner)
        if (corner & (1 << a))
          corners.unite(static_cast<int32_t>(8 * e + corner), static_cast<int32_t>(8 * f + (corner ^ (1 << a))));
    }
  }
  std::vector<int32_t> vertex_of(8 * elements, -1);
  Mesh& lattice = out.lattice;
  lattice.type = ElementType::hex8;
  lattice.elements.resize(8 * elements);
  for (size_t e = 0; e < elements; ++e) {
    const std::array<int, 3>& g = out.element_cell[e];
    int32_t node[8];
    for (int corner = 0; corner < 8; ++corner) {
      int32_t& v = vertex_of[corners.find(static_cast<int32_t>(8 * e + corner))];
      if (v < 0) {
        v = static_cast<int32_t>(lattice.vertex_count());
        Vec3 p;
        for (int d = 0; d < 3; ++d) p[d] = grid.origin[d] + cell * (g[d] + ((corner >> d) & 1));
        lattice.positions.push_back(p);
      }
      node[corner] = v;
    }
    for (int n = 0; n < 8; ++n) lattice.elements[8 * e + n] = node[kHexCorners[n]];
  }

  // Components: elements joined through shared vertices.
  UnionFind pieces(elements);
  std::vector<int32_t> first(lattice.vertex_count(), -1);
  for (size_t e = 0; e < elements; ++e)
    for (int n = 0; n < 8; ++n) {
      int32_t& f = first[lattice.elements[8 * e + n]];
      if (f < 0)
        f = static_cast<int32_t>(e);
      else
        pieces.unite(f, static_cast<int32_t>(e));
    }
  for (size_t e = 0; e < elements; ++e)
    if (pieces.find(static_cast<int32_t>(e)) == static_cast<int32_t>(e)) ++out.components;
  return out;
}

}  // namespace snh
