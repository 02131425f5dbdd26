// Self-contact by the incremental-potential barrier (Li et al. 2020,
// "Incremental Potential Contact"): the host side, and the reference the
// device's terms (solver/contact/barrier_terms.h) are tested against. The simulated
// surface (the mesh's boundary faces, hex8 quads as two triangles) as points,
// edges and triangles; a deterministic uniform-grid broad phase; the pairs within dhat
// at x (point-triangle and edge-edge, those sharing a vertex excluded); the
// barrier's energy kappa sum b, gradient and PSD-projected Hessian as 3x3
// vertex blocks in a fixed order; and the largest step along x + alpha p that
// continuous collision detection clears (kernels/contact/ccd.h). The per-pair
// math is kernels/contact/ipc_*.h, ccd.h and psd_jacobi.h, written once for
// the host and the device (kernels/contact/barrier_pairs.cl). Internal to
// the library.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "snh/mesh.h"
#include "snh/regions.h"
#include "snh/surface.h"

namespace snh::solver {

// The default dhat as a fraction of the mean rest surface edge length h:
// small enough that no pair of a lattice's rest surface is active (the
// closest non-adjacent rest features, the quad diagonals of two faces
// meeting at an edge, are h / sqrt(3) apart) and that a face compressed to 5% of its height
// (rows 0.05 h apart, the squash of docs/validation.md) keeps its
// non-adjacent features out of range; IPC's own default, 1e-3 of the
// bounding box diagonal, is the same on a 6^3 lattice.
inline constexpr double kDefaultSelfDistance = 0.01;
// The default kappa, E h^2 / dhat^3 with E the largest Young's modulus over
// the materials: at d = dhat / 2 a pair then pushes back with about
// 4 E h^2 (the force of a 100% strain on a face of area h^2), so faces
// pressed together stop near dhat / 2 under the pressures of a squash.
double default_barrier_stiffness(const MaterialMap& materials, double edge, double dhat);

// The edge-edge mollifier's threshold factor (IPC sec. 4.3): ex = 1e-3
// |A|^2 |B|^2 of the rest edges.
inline constexpr double kMollifierFactor = 1e-3;

// Projects a symmetric n x n matrix (row-major) to its nearest PSD matrix:
// negative eigenvalues clamped to 0 (IPC sec. 4.2), by Eigen's
// SelfAdjointEigenSolver. The tests' reference: the pair Hessians are
// projected by the cyclic Jacobi method of kernels/contact/psd_jacobi.h,
// on the host (project_psd_pair) as on the device.
void project_psd(double* matrix, int n);
// A 12 x 12 pair Hessian projected by kernels/contact/psd_jacobi.h.
void project_psd_pair(double* matrix);

// One pair within dhat: kind 0 point-triangle (vertex = p, t0, t1, t2), 1
// edge-edge (a0, a1, b0, b1); mesh vertex indices. ex: the edge-edge
// mollifier's threshold from the rest edges (ipc_barrier.h).
struct BarrierPair {
  int kind = 0;
  std::array<int, 4> vertex{0, 0, 0, 0};
  double ex = 0.0;
  bool operator==(const BarrierPair& o) const { return kind == o.kind && vertex == o.vertex; }
};

// The barrier's Hessian as 3x3 blocks per vertex row (block CSR):
// row v's blocks offsets[v] .. offsets[v + 1], at columns `columns`,
// 9 values each row-major. Rows and columns ascend: assembled in a fixed
// order, so bitwise deterministic.
struct BarrierHessian {
  std::vector<int> offsets, columns;
  std::vector<double> blocks;
};

class BarrierContact {
 public:
  // The surface of a hex8 or tet4 mesh and its rest edge lengths.
  explicit BarrierContact(const Mesh& mesh);
  // A surface carried by the cells of a hex8 lattice: surface vertex s sits
  // at sum_k w_sk x(v_sk) over its cell's 8 corners (snh/surface.h embed).
  // Pairs, distances and CCD act on those positions (the map is linear, so
  // a step x + t p moves them along W x + t W p); gradients and Hessians go
  // back to the lattice as W^T g and W^T H W (PSD where H is). Throws
  // snh::Error for an embedding that does not match the surface or mesh.
  BarrierContact(const Mesh& lattice, const TriangleSurface& surface, const Embedding& embedding);

  // dhat (> 0): the distance below which a pair is active.
  void set_distance(double dhat) { dhat_ = dhat; }
  double distance() const { return dhat_; }
  // The length the default dhat is a fraction of (ContactOptions::
  // self_distance): the cell size for an embedded surface, else the mean
  // rest length of the surface edges (the cell size on a lattice).
  double length_scale() const { return mean_edge_; }
  // Leaves out, from now on, the pairs closer than dhat at the lattice
  // positions `rest` (seams, surfaces touching or crossing at rest: a
  // barrier on them would push the rest shape apart or be infinite there).
  // Returns how many.
  size_t exclude_pairs_near(const std::vector<double>& rest);

  // The pairs closer than dhat at x (xyz per vertex): point-triangle pairs
  // in point then triangle order, then edge-edge pairs in edge order.
  std::vector<BarrierPair> near_pairs(const std::vector<double>& x) const;
  // sum over pairs of b (without kappa), in pair order; *min_distance gets
  // the smallest distance (not squared) over the pairs (dhat when none).
  double energy(const std::vector<double>& x, const std::vector<BarrierPair>& pairs, double* min_distance) const;
  // g += kappa d(sum b)/dx (xyz per vertex).
  void add_gradient(const std::vector<double>& x, const std::vector<BarrierPair>& pairs, double kappa,
                    std::vector<double>& g) const;
  // kappa times the pairs' PSD-projected Hessians, assembled.
  BarrierHessian hessian(const std::vector<double>& x, const std::vector<BarrierPair>& pairs, double kappa) const;
  // The candidate pairs at x (p null) or along x + t p, t in [0, 1]: those
  // whose boxes (swept with p), inflated by dhat, overlap; point-triangle
  // pairs in point then triangle order, then edge-edge pairs in edge order.
  // near_pairs() is those of them closer than dhat at x.
  std::vector<BarrierPair> candidate_pairs(const std::vector<double>& x, const std::vector<double>* p) const;
  // The largest alpha in [0, 1] such that x + t p, t in [0, alpha], has no
  // pair in contact: the smallest additive-CCD time of impact over the pairs
  // whose swept boxes (inflated by dhat) overlap, each run over [0, 1] (so
  // the minimum does not depend on the pairs' order, as on the device);
  // 1 when none hits.
  double step_bound(const std::vector<double>& x, const std::vector<double>& p) const;
  // The smallest distance between any two non-adjacent surface primitives
  // within `reach` of each other (reach when none).
  double min_distance(const std::vector<double>& x, double reach) const;

  size_t point_count() const { return points_.size(); }
  size_t edge_count() const { return edges_.size() / 2; }
  size_t triangle_count() const { return triangles_.size() / 3; }
  const std::vector<int>& triangles() const { return triangles_; }
  // The surface's points (vertex indices, ascending), edges (2 each,
  // ascending pairs, sorted) and their rest lengths squared: the primitive
  // indices of the pairs' keys.
  const std::vector<int>& points() const { return points_; }
  const std::vector<int>& edges() const { return edges_; }
  const std::vector<double>& edge_rest_squared() const { return edge_rest_squared_; }
  // The pairs left out (exclude_pairs_near), sorted keys kind << 62 | a <<
  // 31 | b of point or edge a and triangle or edge b.
  const std::vector<uint64_t>& exclusion_keys() const { return excluded_; }
  // The positions the pairs' vertex indices refer to: the surface's
  // vertices with an embedding, else the mesh's.
  size_t surface_vertex_count() const { return carrier_.empty() ? 0 : weight_.size() / 8; }
  // The embedding: 8 lattice vertices and weights per surface vertex (both
  // empty without one).
  const std::vector<int>& carriers() const { return carrier_; }
  const std::vector<double>& weights() const { return weight_; }

 private:
  // Candidate pairs whose boxes overlap: point-triangle (point, triangle)
  // then edge-edge (edge a < edge b), no shared vertex. A primitive's box
  // spans x and, with p, x + p, inflated by `inflate`.
  void candidates(const std::vector<double>& x, const std::vector<double>* p, double inflate,
                  std::vector<std::array<int, 2>>& point_triangle, std::vector<std::array<int, 2>>& edge_edge) const;
  BarrierPair make_pair(int kind, int a, int b) const;
  // The surface positions W x (x itself without an embedding).
  const std::vector<double>& lift(const std::vector<double>& x, std::vector<double>& storage) const;
  // The surface edges and their rest lengths from triangles_ and positions.
  void build_edges(const std::vector<double>& rest);

  std::vector<int> points_;     // surface vertices (mesh indices, ascending)
  std::vector<int> edges_;      // 2 per edge, ascending pairs, sorted
  std::vector<int> triangles_;  // 3 per triangle
  std::vector<double> edge_rest_squared_;
  double mean_edge_ = 1.0;
  double dhat_ = 0.0;
  // The embedding (empty: surface vertices are mesh vertices): 8 lattice
  // vertices and weights per surface vertex, and the lattice's vertex count.
  bool excluded(int kind, int a, int b) const;
  std::vector<uint64_t> excluded_;  // kind, a, b of the left-out pairs, sorted
  std::vector<int> carrier_;
  std::vector<double> weight_;
  size_t lattice_vertices_ = 0;
};

}  // namespace snh::solver
