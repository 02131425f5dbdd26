// The embedding of a surface in its voxelization (snh/surface.h): each
// surface vertex follows the trilinear interpolation of one lattice cell.
//
// Which cell. The grid (Voxelization::origin, cell) gives each vertex its
// local coordinates u = (p - origin) / cell. Its cell is the kept cell (an
// element of the lattice) nearest to it, the distance being that from p to
// the closed cube, with distances below 1e-9 cells counted as 0; among
// equally near cells the one with the smallest grid index
// i + dims[0] (j + dims[1] k) wins. So a vertex inside a kept cell goes to
// it, and a vertex on a face, edge or corner shared by kept cells goes to
// the first of them in grid order, whatever the rounding of its position.
//
// Vertices outside every kept cell. The voxelization keeps a cell when its
// centre is inside the surface, so the surface passes through dropped cells
// and some of its vertices lie outside the lattice, by up to about half a
// cell. Such a vertex goes to the nearest kept cell by the rule above, and
// its weights are that cell's trilinear functions at its (unclamped) local
// coordinates: it is extrapolated, not snapped onto the cell. Its weights
// still sum to 1, and the surface is reproduced exactly at rest and under
// every affine map of the lattice; clamping would flatten the surface onto
// the lattice's faces already at rest. A vertex farther than one cell from
// every kept cell is not the surface this lattice was made from: snh::Error
// naming it.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <unordered_map>

#include "snh/error.h"
#include "snh/surface.h"

namespace snh {
namespace {

// Distances to a cell up to this many cells count as inside it.
constexpr double kOnBoundary = 1e-9;
// Farther than this many cells from every kept cell: not embeddable.
constexpr double kMaxDistance = 1.0;

// Grid index of cell (i, j, k).
int64_t grid_index(const std::array<int, 3>& dims, int i, int j, int k) {
  return i + static_cast<int64_t>(dims[0]) * (j + static_cast<int64_t>(dims[1]) * k);
}

// The trilinear shape functions of a hex8 in VTK node order at local
// coordinates (s, t, r) in [0, 1]^3 for points inside the cube.
std::array<double, 8> trilinear_weights(double s, double t, double r) {
  // VTK_HEXAHEDRON corners: (0,0,0) (1,0,0) (1,1,0) (0,1,0), then z = 1.
  constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                 {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const double local[3] = {s, t, r};
  std::array<double, 8> w{};
  for (int a = 0; a < 8; ++a) {
    w[a] = 1.0;
    for (int d = 0; d < 3; ++d) w[a] *= kCorner[a][d] ? local[d] : 1.0 - local[d];
  }
  return w;
}

// The trilinear functions extended to first order from the point q of the
// cube nearest to local coordinates u: N_a(q) + grad N_a(q) . (u - q). They
// sum to 1, reproduce affine maps exactly and grow linearly with the
// distance, where the unclamped functions grow quadratically.
std::array<double, 8> first_order_weights(const double u[3]) {
  constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                 {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  double q[3], delta[3];
  for (int d = 0; d < 3; ++d) {
    q[d] = std::clamp(u[d], 0.0, 1.0);
    delta[d] = u[d] - q[d];
  }
  std::array<double, 8> w{};
  for (int a = 0; a < 8; ++a) {
    double f[3], df[3];
    for (int d = 0; d < 3; ++d) {
      f[d] = kCorner[a][d] ? q[d] : 1.0 - q[d];
      df[d] = kCorner[a][d] ? 1.0 : -1.0;
    }
    w[a] = f[0] * f[1] * f[2] + df[0] * f[1] * f[2] * delta[0] + f[0] * df[1] * f[2] * delta[1] +
           f[0] * f[1] * df[2] * delta[2];
  }
  return w;
}

void check_voxelization(const Voxelization& voxels) {
  const Mesh& lattice = voxels.lattice;
  if (lattice.type != ElementType::hex8) throw Error("embed: the voxelization's lattice is not hex8");
  if (!(voxels.cell > 0.0) || !std::isfinite(voxels.cell)) {
    std::ostringstream s;
    s << "embed: the voxelization's cell size " << voxels.cell << " is not positive";
    throw Error(s.str());
  }
  if (voxels.element_cell.size() != lattice.element_count()) {
    std::ostringstream s;
    s << "embed: the voxelization has " << voxels.element_cell.size() << " element cells for "
      << lattice.element_count() << " elements";
    throw Error(s.str());
  }
  for (size_t e = 0; e < voxels.element_cell.size(); ++e)
    for (int d = 0; d < 3; ++d)
      if (voxels.element_cell[e][d] < 0 || voxels.element_cell[e][d] >= voxels.dims[d]) {
        std::ostringstream s;
        s << "embed: element " << e << "'s grid cell (" << voxels.element_cell[e][0] << ", "
          << voxels.element_cell[e][1] << ", " << voxels.element_cell[e][2] << ") is outside the grid of "
          << voxels.dims[0] << " x " << voxels.dims[1] << " x " << voxels.dims[2] << " cells";
        throw Error(s.str());
      }
}

Embedding embed_impl(const Voxelization& voxels, const TriangleSurface& surface, std::vector<double>* far) {
  check_voxelization(voxels);
  if (surface.positions.xyz().size() % 3 != 0) throw Error("embed: the surface's positions are not xyz triples");
  std::unordered_map<int64_t, int32_t> element_of_cell;
  element_of_cell.reserve(voxels.element_cell.size());
  for (size_t e = 0; e < voxels.element_cell.size(); ++e) {
    const auto& c = voxels.element_cell[e];
    if (!element_of_cell.emplace(grid_index(voxels.dims, c[0], c[1], c[2]), static_cast<int32_t>(e)).second) {
      std::ostringstream s;
      s << "embed: elements " << element_of_cell[grid_index(voxels.dims, c[0], c[1], c[2])] << " and " << e
        << " share grid cell (" << c[0] << ", " << c[1] << ", " << c[2] << ")";
      throw Error(s.str());
    }
  }

  Embedding out;
  const size_t n = surface.vertex_count();
  out.element.resize(n);
  out.weights.resize(8 * n);
  for (size_t v = 0; v < n; ++v) {
    double u[3];
    for (int d = 0; d < 3; ++d) u[d] = (surface.positions(v, d) - voxels.origin[d]) / voxels.cell;
    if (!std::isfinite(u[0]) || !std::isfinite(u[1]) || !std::isfinite(u[2])) {
      std::ostringstream s;
      s << "embed: surface vertex " << v << " has a non-finite position";
      throw Error(s.str());
    }
    // The nearest kept cell lies among the 27 around the one holding u: a
    // cell farther than that is more than kMaxDistance away.
    const int base[3] = {static_cast<int>(std::floor(u[0])), static_cast<int>(std::floor(u[1])),
                         static_cast<int>(std::floor(u[2]))};
    double best_distance = std::numeric_limits<double>::infinity();
    int64_t best_index = std::numeric_limits<int64_t>::max();
    std::array<int, 3> best_cell{};
    int32_t best_element = -1;
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int c[3] = {base[0] + di, base[1] + dj, base[2] + dk};
          if (c[0] < 0 || c[1] < 0 || c[2] < 0 || c[0] >= voxels.dims[0] || c[1] >= voxels.dims[1] ||
              c[2] >= voxels.dims[2])
            continue;
          const int64_t index = grid_index(voxels.dims, c[0], c[1], c[2]);
          const auto found = element_of_cell.find(index);
          if (found == element_of_cell.end()) continue;
          double squared = 0.0;
          for (int d = 0; d < 3; ++d) {
            const double outside = std::max({0.0, c[d] - u[d], u[d] - (c[d] + 1)});
            squared += outside * outside;
          }
          double distance = std::sqrt(squared);
          if (distance <= kOnBoundary) distance = 0.0;
          if (distance < best_distance || (distance == best_distance && index < best_index)) {
            best_distance = distance;
            best_index = index;
            best_cell = {c[0], c[1], c[2]};
            best_element = found->second;
          }
        }
    if ((best_element < 0 || best_distance > kMaxDistance) && far) {
      // Rings of grid cells outwards from the vertex's (clamped) cell until
      // no nearer cell can remain.
      int c0[3];
      for (int d = 0; d < 3; ++d) c0[d] = std::clamp(base[d], 0, voxels.dims[d] - 1);
      const int rings = std::max({voxels.dims[0], voxels.dims[1], voxels.dims[2]});
      double outside0 = 0.0;  // how far the vertex is from the grid's box, in cells
      for (int d = 0; d < 3; ++d) {
        const double o = std::max({0.0, -u[d], u[d] - voxels.dims[d]});
        outside0 += o * o;
      }
      outside0 = std::sqrt(outside0);
      for (int r = 0; r <= rings; ++r) {
        if (best_element >= 0 && std::max(outside0, r - 1.0) > best_distance) break;
        for (int k = c0[2] - r; k <= c0[2] + r; ++k)
          for (int j = c0[1] - r; j <= c0[1] + r; ++j)
            for (int i = c0[0] - r; i <= c0[0] + r; ++i) {
              if (std::max({std::abs(i - c0[0]), std::abs(j - c0[1]), std::abs(k - c0[2])}) != r) continue;
              if (i < 0 || j < 0 || k < 0 || i >= voxels.dims[0] || j >= voxels.dims[1] || k >= voxels.dims[2])
                continue;
              const int64_t index = grid_index(voxels.dims, i, j, k);
              const auto found = element_of_cell.find(index);
              if (found == element_of_cell.end()) continue;
              const int c[3] = {i, j, k};
              double squared = 0.0;
              for (int d = 0; d < 3; ++d) {
                const double outside = std::max({0.0, c[d] - u[d], u[d] - (c[d] + 1)});
                squared += outside * outside;
              }
              const double distance = std::sqrt(squared);
              if (distance < best_distance || (distance == best_distance && index < best_index)) {
                best_distance = distance;
                best_index = index;
                best_cell = {i, j, k};
                best_element = found->second;
              }
            }
      }
      out.element[v] = best_element;
      const double local[3] = {u[0] - best_cell[0], u[1] - best_cell[1], u[2] - best_cell[2]};
      const auto w = first_order_weights(local);
      std::copy(w.begin(), w.end(), out.weights.begin() + 8 * v);
      (*far)[v] = best_distance * voxels.cell;
      continue;
    }
    if (best_element < 0 || best_distance > kMaxDistance) {
      std::ostringstream s;
      s << "embed: surface vertex " << v << " at (" << surface.positions(v, 0) << ", " << surface.positions(v, 1)
        << ", " << surface.positions(v, 2) << ") lies in no element and more than one cell (" << voxels.cell
        << ") from every element: is this the surface the lattice was voxelized from?";
      throw Error(s.str());
    }
    out.element[v] = best_element;
    const auto w = trilinear_weights(u[0] - best_cell[0], u[1] - best_cell[1], u[2] - best_cell[2]);
    std::copy(w.begin(), w.end(), out.weights.begin() + 8 * v);
    if (far) (*far)[v] = best_distance * voxels.cell;
  }
  return out;
}

}  // namespace

Embedding embed(const Voxelization& voxels, const TriangleSurface& surface) {
  return embed_impl(voxels, surface, nullptr);
}

CarriedEmbedding embed_carrying_all(const Voxelization& voxels, const TriangleSurface& surface) {
  CarriedEmbedding out;
  out.distance.assign(surface.vertex_count(), 0.0);
  out.embedding = embed_impl(voxels, surface, &out.distance);
  return out;
}

Points embedded_positions(const Embedding& embedding, const Mesh& lattice, const Points& x) {
  if (lattice.type != ElementType::hex8) throw Error("embedded_positions: the lattice is not hex8");
  if (x.size() != lattice.vertex_count()) {
    std::ostringstream s;
    s << "embedded_positions: the positions have " << x.xyz().size() << " values, but the lattice has "
      << lattice.vertex_count() << " vertices (" << lattice.positions.xyz().size() << " values expected)";
    throw Error(s.str());
  }
  const size_t n = embedding.element.size();
  if (embedding.weights.size() != 8 * n) {
    std::ostringstream s;
    s << "embedded_positions: the embedding has " << embedding.weights.size() << " weights for " << n
      << " vertices (8 per vertex expected)";
    throw Error(s.str());
  }
  const size_t elements = lattice.element_count();
  Points out(n);
  const double* px = x.data();
  double* po = out.data();
  for (size_t v = 0; v < n; ++v) {
    const int32_t e = embedding.element[v];
    if (e < 0 || static_cast<size_t>(e) >= elements) {
      std::ostringstream s;
      s << "embedded_positions: surface vertex " << v << " refers to element " << e << ", but the lattice has "
        << elements << " elements";
      throw Error(s.str());
    }
    for (int a = 0; a < 8; ++a) {
      const size_t node = static_cast<size_t>(lattice.elements[8 * static_cast<size_t>(e) + a]);
      const double w = embedding.weights[8 * v + a];
      for (int d = 0; d < 3; ++d) po[3 * v + d] += w * px[3 * node + d];
    }
  }
  return out;
}

}  // namespace snh
