#include "solver/contact/barrier_contact.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <map>
#include <utility>

#include "fem/boundary_faces.h"
#include "snh/error.h"

namespace snh::solver {

namespace kernel {
#define SNH_DOUBLE 1
#include "contact/ccd.h"
#include "contact/ipc_barrier.h"
#include "contact/psd_jacobi.h"
}  // namespace kernel

namespace {

struct Box {
  double lo[3], hi[3];
  bool overlaps(const Box& o) const {
    for (int d = 0; d < 3; ++d)
      if (lo[d] > o.hi[d] || o.lo[d] > hi[d]) return false;
    return true;
  }
};

// A uniform grid over boxes: per cell the boxes overlapping it, built by
// count, prefix sum and fill in box order (deterministic).
class Grid {
 public:
  explicit Grid(const std::vector<Box>& boxes) : boxes_(boxes) {
    if (boxes.empty()) return;
    double extent = 0.0;
    for (int d = 0; d < 3; ++d) {
      origin_[d] = boxes[0].lo[d];
      top_[d] = boxes[0].hi[d];
    }
    for (const Box& b : boxes)
      for (int d = 0; d < 3; ++d) {
        origin_[d] = std::min(origin_[d], b.lo[d]);
        top_[d] = std::max(top_[d], b.hi[d]);
        extent += b.hi[d] - b.lo[d];
      }
    cell_ = extent / (3.0 * static_cast<double>(boxes.size()));
    double span = 0.0;
    for (int d = 0; d < 3; ++d) span = std::max(span, top_[d] - origin_[d]);
    // At most 8 cells per box (and a floor for tiny spans): memory bounded
    // by the surface, whatever the motion.
    const double cells_cap = std::max(64.0, 8.0 * static_cast<double>(boxes.size()));
    if (!(cell_ > 0.0)) cell_ = span > 0.0 ? span : 1.0;
    for (;;) {
      double cells = 1.0;
      for (int d = 0; d < 3; ++d) cells *= std::floor((top_[d] - origin_[d]) / cell_) + 1.0;
      if (cells <= cells_cap) break;
      cell_ *= 1.5;
    }
    for (int d = 0; d < 3; ++d) dims_[d] = static_cast<int>(std::floor((top_[d] - origin_[d]) / cell_)) + 1;
    offsets_.assign(static_cast<size_t>(dims_[0]) * dims_[1] * dims_[2] + 1, 0);
    for (const Box& b : boxes) visit(b, [&](size_t c) { ++offsets_[c + 1]; });
    for (size_t c = 1; c < offsets_.size(); ++c) offsets_[c] += offsets_[c - 1];
    entries_.resize(offsets_.back());
    std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
    for (size_t i = 0; i < boxes.size(); ++i) visit(boxes[i], [&](size_t c) { entries_[fill[c]++] = int(i); });
  }

  // The boxes overlapping `b`, ascending, each once.
  void query(const Box& b, std::vector<int>& out) const {
    out.clear();
    if (boxes_.empty()) return;
    visit(b, [&](size_t c) {
      for (int k = offsets_[c]; k < offsets_[c + 1]; ++k)
        if (boxes_[entries_[k]].overlaps(b)) out.push_back(entries_[k]);
    });
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }

 private:
  template <typename F>
  void visit(const Box& b, F&& f) const {
    int lo[3], hi[3];
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::clamp(static_cast<int>(std::floor((b.lo[d] - origin_[d]) / cell_)), 0, dims_[d] - 1);
      hi[d] = std::clamp(static_cast<int>(std::floor((b.hi[d] - origin_[d]) / cell_)), 0, dims_[d] - 1);
      if (b.hi[d] < origin_[d] || b.lo[d] > top_[d]) return;
    }
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) f((static_cast<size_t>(k) * dims_[1] + j) * dims_[0] + i);
  }

  const std::vector<Box>& boxes_;
  double origin_[3] = {0, 0, 0}, top_[3] = {0, 0, 0}, cell_ = 1.0;
  int dims_[3] = {1, 1, 1};
  std::vector<int> offsets_, entries_;
};

// The box of vertices `v` (count n) at x and, with p, at x + p, inflated.
Box box_of(const int* v, int n, const std::vector<double>& x, const std::vector<double>* p, double inflate) {
  Box b;
  for (int d = 0; d < 3; ++d) {
    b.lo[d] = b.hi[d] = x[3 * v[0] + d];
    for (int i = 0; i < n; ++i) {
      const double a = x[3 * v[i] + d];
      b.lo[d] = std::min(b.lo[d], a);
      b.hi[d] = std::max(b.hi[d], a);
      if (p) {
        const double e = a + (*p)[3 * v[i] + d];
        b.lo[d] = std::min(b.lo[d], e);
        b.hi[d] = std::max(b.hi[d], e);
      }
    }
    b.lo[d] -= inflate;
    b.hi[d] += inflate;
  }
  return b;
}

// The pair's barrier b (kind 0: point-triangle, 1: edge-edge with its
// mollifier), its squared distance in *s, and with g and h its gradient (12)
// and Hessian (144) at the gathered positions q.
double pair_potential(const BarrierPair& pair, const double* q, double sh, double* s, double* g, double* h) {
  return pair.kind == 0 ? kernel::ipc_pt_potential(q, sh, s, g, h) : kernel::ipc_ee_potential(q, sh, pair.ex, s, g, h);
}

void gather(const BarrierPair& pair, const std::vector<double>& x, double* out) {
  for (int v = 0; v < 4; ++v)
    for (int d = 0; d < 3; ++d) out[3 * v + d] = x[3 * pair.vertex[v] + d];
}

}  // namespace

double default_barrier_stiffness(const MaterialMap& materials, double edge, double dhat) {
  double youngs = 0.0;
  for (const Material& m : materials.materials)
    youngs = std::max(youngs, m.mu * (3.0 * m.lambda + 2.0 * m.mu) / (m.lambda + m.mu));
  return youngs * edge * edge / (dhat * dhat * dhat);
}

void project_psd(double* matrix, int n) {
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> m(matrix, n, n);
  const Eigen::MatrixXd symmetric = 0.5 * (m + m.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(symmetric);
  if (eigen.info() != Eigen::Success) throw Error("barrier contact: eigen-decomposition of a pair Hessian failed");
  if (eigen.eigenvalues().minCoeff() >= 0.0) return;  // already PSD: unchanged
  const Eigen::VectorXd clamped = eigen.eigenvalues().cwiseMax(0.0);
  m = eigen.eigenvectors() * clamped.asDiagonal() * eigen.eigenvectors().transpose();
}

void project_psd_pair(double* matrix) { kernel::psd_project12(matrix); }

BarrierContact::BarrierContact(const Mesh& mesh) {
  const fem::BoundaryFaces faces = fem::boundary_faces(mesh, "barrier contact");
  // Hex quads (counter-clockwise from outside) as triangles (0 1 2), (0 2 3).
  const size_t count = faces.faces.size() / faces.corners;
  for (size_t f = 0; f < count; ++f) {
    const int32_t* c = faces.faces.data() + faces.corners * f;
    auto add = [&](int a, int b, int d) {
      triangles_.push_back(faces.vertices[c[a]]);
      triangles_.push_back(faces.vertices[c[b]]);
      triangles_.push_back(faces.vertices[c[d]]);
    };
    add(0, 1, 2);
    if (faces.corners == 4) add(0, 2, 3);
  }
  points_.assign(faces.vertices.begin(), faces.vertices.end());
  build_edges(mesh.positions.xyz());
}

BarrierContact::BarrierContact(const Mesh& lattice, const TriangleSurface& surface, const Embedding& embedding) {
  const size_t n = surface.vertex_count();
  if (lattice.type != ElementType::hex8)
    throw Error("barrier contact: an embedded self-contact surface needs a hex8 lattice");
  if (surface.positions.xyz().size() != 3 * n || embedding.element.size() != n || embedding.weights.size() != 8 * n)
    throw Error("barrier contact: the self-contact surface has " + std::to_string(n) +
                " vertices but its embedding has " + std::to_string(embedding.element.size()) + " elements and " +
                std::to_string(embedding.weights.size()) + " weights (8 per vertex)");
  for (int32_t v : surface.triangles)
    if (v < 0 || static_cast<size_t>(v) >= n)
      throw Error("barrier contact: self-contact surface triangle vertex " + std::to_string(v) + " out of range");
  lattice_vertices_ = lattice.vertex_count();
  carrier_.resize(8 * n);
  weight_ = embedding.weights;
  for (size_t v = 0; v < n; ++v) {
    const int32_t e = embedding.element[v];
    if (e < 0 || static_cast<size_t>(e) >= lattice.element_count())
      throw Error("barrier contact: self-contact surface vertex " + std::to_string(v) + " embedded in element " +
                  std::to_string(e) + ", not in the lattice");
    for (int k = 0; k < 8; ++k) carrier_[8 * v + k] = lattice.elements[8 * static_cast<size_t>(e) + k];
  }
  triangles_.assign(surface.triangles.begin(), surface.triangles.end());
  std::vector<char> used(n, 0);
  for (int v : triangles_) used[v] = 1;
  for (size_t v = 0; v < n; ++v)
    if (used[v]) points_.push_back(static_cast<int>(v));
  build_edges(surface.positions.xyz());
  // The cell size: the mean length of the lattice cells' first edges.
  double sum = 0.0;
  for (size_t e = 0; e < lattice.element_count(); ++e) {
    double l2 = 0.0;
    for (int d = 0; d < 3; ++d) {
      const double a =
          lattice.positions(lattice.elements[8 * e + 1], d) - lattice.positions(lattice.elements[8 * e], d);
      l2 += a * a;
    }
    sum += std::sqrt(l2);
  }
  if (lattice.element_count() > 0) mean_edge_ = sum / static_cast<double>(lattice.element_count());
}

namespace {
uint64_t pair_key(int kind, int a, int b) {
  return (static_cast<uint64_t>(kind) << 62) | (static_cast<uint64_t>(a) << 31) | static_cast<uint64_t>(b);
}
}  // namespace

bool BarrierContact::excluded(int kind, int a, int b) const {
  return !excluded_.empty() && std::binary_search(excluded_.begin(), excluded_.end(), pair_key(kind, a, b));
}

size_t BarrierContact::exclude_pairs_near(const std::vector<double>& rest) {
  excluded_.clear();
  std::vector<double> storage;
  const std::vector<double>& x = lift(rest, storage);
  std::vector<std::array<int, 2>> pt, ee;
  candidates(x, nullptr, dhat_, pt, ee);
  const double sh = dhat_ * dhat_;
  double q[12];
  int type;
  for (int kind = 0; kind < 2; ++kind)
    for (const auto& c : kind == 0 ? pt : ee) {
      gather(make_pair(kind, c[0], c[1]), x, q);
      const double d2 = kind == 0 ? kernel::ipc_pt_distance(q, &type, nullptr, nullptr)
                                  : kernel::ipc_ee_distance(q, &type, nullptr, nullptr);
      if (!(d2 >= sh)) excluded_.push_back(pair_key(kind, c[0], c[1]));
    }
  std::sort(excluded_.begin(), excluded_.end());
  return excluded_.size();
}

void BarrierContact::build_edges(const std::vector<double>& rest) {
  std::vector<std::pair<int, int>> edges;
  for (size_t t = 0; t < triangles_.size() / 3; ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles_[3 * t + k], b = triangles_[3 * t + (k + 1) % 3];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  double sum = 0.0;
  for (const auto& [a, b] : edges) {
    edges_.push_back(a);
    edges_.push_back(b);
    double l2 = 0.0;
    for (int d = 0; d < 3; ++d) {
      const double e = rest[3 * b + d] - rest[3 * a + d];
      l2 += e * e;
    }
    edge_rest_squared_.push_back(l2);
    sum += std::sqrt(l2);
  }
  if (!edges.empty()) mean_edge_ = sum / static_cast<double>(edges.size());
}

const std::vector<double>& BarrierContact::lift(const std::vector<double>& x, std::vector<double>& storage) const {
  if (carrier_.empty()) return x;
  const size_t n = weight_.size() / 8;
  storage.assign(3 * n, 0.0);
  for (size_t v = 0; v < n; ++v)
    for (int k = 0; k < 8; ++k) {
      const double w = weight_[8 * v + k];
      const size_t c = static_cast<size_t>(carrier_[8 * v + k]);
      for (int d = 0; d < 3; ++d) storage[3 * v + d] += w * x[3 * c + d];
    }
  return storage;
}

void BarrierContact::candidates(const std::vector<double>& x, const std::vector<double>* p, double inflate,
                                std::vector<std::array<int, 2>>& point_triangle,
                                std::vector<std::array<int, 2>>& edge_edge) const {
  point_triangle.clear();
  edge_edge.clear();
  std::vector<int> found;
  {
    std::vector<Box> boxes(triangle_count());
    for (size_t t = 0; t < boxes.size(); ++t) boxes[t] = box_of(&triangles_[3 * t], 3, x, p, inflate);
    const Grid grid(boxes);
    for (size_t i = 0; i < points_.size(); ++i) {
      grid.query(box_of(&points_[i], 1, x, p, 0.0), found);
      for (int t : found) {
        const int* tv = &triangles_[3 * t];
        if (tv[0] == points_[i] || tv[1] == points_[i] || tv[2] == points_[i]) continue;
        point_triangle.push_back({static_cast<int>(i), t});
      }
    }
  }
  std::vector<Box> boxes(edge_count());
  for (size_t e = 0; e < boxes.size(); ++e) boxes[e] = box_of(&edges_[2 * e], 2, x, p, inflate);
  const Grid grid(boxes);
  for (size_t a = 0; a < boxes.size(); ++a) {
    grid.query(box_of(&edges_[2 * a], 2, x, p, 0.0), found);
    for (int b : found) {
      if (b <= static_cast<int>(a)) continue;
      const int a0 = edges_[2 * a], a1 = edges_[2 * a + 1], b0 = edges_[2 * b], b1 = edges_[2 * b + 1];
      if (a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1) continue;
      edge_edge.push_back({static_cast<int>(a), b});
    }
  }
}

BarrierPair BarrierContact::make_pair(int kind, int a, int b) const {
  BarrierPair pair;
  pair.kind = kind;
  if (kind == 0) {
    pair.vertex = {points_[a], triangles_[3 * b], triangles_[3 * b + 1], triangles_[3 * b + 2]};
  } else {
    pair.vertex = {edges_[2 * a], edges_[2 * a + 1], edges_[2 * b], edges_[2 * b + 1]};
    pair.ex = kMollifierFactor * edge_rest_squared_[a] * edge_rest_squared_[b];
  }
  return pair;
}

std::vector<BarrierPair> BarrierContact::candidate_pairs(const std::vector<double>& lattice_x,
                                                         const std::vector<double>* lattice_p) const {
  std::vector<double> x_storage, p_storage;
  const std::vector<double>& x = lift(lattice_x, x_storage);
  std::vector<std::array<int, 2>> pt, ee;
  candidates(x, lattice_p ? &lift(*lattice_p, p_storage) : nullptr, dhat_, pt, ee);
  std::vector<BarrierPair> pairs;
  pairs.reserve(pt.size() + ee.size());
  for (const auto& c : pt)
    if (!excluded(0, c[0], c[1])) pairs.push_back(make_pair(0, c[0], c[1]));
  for (const auto& c : ee)
    if (!excluded(1, c[0], c[1])) pairs.push_back(make_pair(1, c[0], c[1]));
  return pairs;
}

std::vector<BarrierPair> BarrierContact::near_pairs(const std::vector<double>& lattice_x) const {
  std::vector<double> storage;
  const std::vector<double>& x = lift(lattice_x, storage);
  std::vector<std::array<int, 2>> pt, ee;
  candidates(x, nullptr, dhat_, pt, ee);
  std::vector<BarrierPair> pairs;
  const double sh = dhat_ * dhat_;
  double q[12];
  int type;
  for (const auto& c : pt) {
    if (excluded(0, c[0], c[1])) continue;
    const BarrierPair pair = make_pair(0, c[0], c[1]);
    gather(pair, x, q);
    if (kernel::ipc_pt_distance(q, &type, nullptr, nullptr) < sh) pairs.push_back(pair);
  }
  for (const auto& c : ee) {
    if (excluded(1, c[0], c[1])) continue;
    const BarrierPair pair = make_pair(1, c[0], c[1]);
    gather(pair, x, q);
    if (kernel::ipc_ee_distance(q, &type, nullptr, nullptr) < sh) pairs.push_back(pair);
  }
  return pairs;
}

double BarrierContact::energy(const std::vector<double>& lattice_x, const std::vector<BarrierPair>& pairs,
                              double* min_distance) const {
  std::vector<double> storage;
  const std::vector<double>& x = lift(lattice_x, storage);
  const double sh = dhat_ * dhat_;
  double sum = 0.0, smallest = sh;
  double q[12];
  for (const BarrierPair& pair : pairs) {
    gather(pair, x, q);
    double s = 0.0;
    sum += pair_potential(pair, q, sh, &s, nullptr, nullptr);
    smallest = std::min(smallest, s);
  }
  if (min_distance) *min_distance = std::sqrt(smallest);
  return sum;
}

void BarrierContact::add_gradient(const std::vector<double>& lattice_x, const std::vector<BarrierPair>& pairs,
                                  double kappa, std::vector<double>& g) const {
  std::vector<double> storage;
  const std::vector<double>& x = lift(lattice_x, storage);
  const double sh = dhat_ * dhat_;
  double q[12], pg[12], ph[144], s;
  for (const BarrierPair& pair : pairs) {
    gather(pair, x, q);
    pair_potential(pair, q, sh, &s, pg, ph);
    for (int v = 0; v < 4; ++v) {
      if (carrier_.empty()) {
        for (int d = 0; d < 3; ++d) g[3 * pair.vertex[v] + d] += kappa * pg[3 * v + d];
        continue;
      }
      for (int k = 0; k < 8; ++k) {  // W^T: to the carrying cell's corners
        const size_t at = 8 * static_cast<size_t>(pair.vertex[v]) + k;
        for (int d = 0; d < 3; ++d) g[3 * carrier_[at] + d] += kappa * weight_[at] * pg[3 * v + d];
      }
    }
  }
}

BarrierHessian BarrierContact::hessian(const std::vector<double>& lattice_x, const std::vector<BarrierPair>& pairs,
                                       double kappa) const {
  std::vector<double> storage;
  const std::vector<double>& x = lift(lattice_x, storage);
  const double sh = dhat_ * dhat_;
  // Summed in pair order into blocks kept sorted by (row, column).
  std::map<std::pair<int, int>, std::array<double, 9>> blocks;
  double q[12], pg[12], ph[144], s;
  for (const BarrierPair& pair : pairs) {
    gather(pair, x, q);
    pair_potential(pair, q, sh, &s, pg, ph);
    project_psd_pair(ph);
    auto add = [&](int row, int column, int v, int w, double scale) {
      auto [it, fresh] = blocks.try_emplace({row, column});
      if (fresh) it->second.fill(0.0);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) it->second[3 * i + j] += scale * ph[12 * (3 * v + i) + 3 * w + j];
    };
    for (int v = 0; v < 4; ++v)
      for (int w = 0; w < 4; ++w) {
        if (carrier_.empty()) {
          add(pair.vertex[v], pair.vertex[w], v, w, kappa);
          continue;
        }
        for (int k = 0; k < 8; ++k)  // W^T H W
          for (int l = 0; l < 8; ++l) {
            const size_t a = 8 * static_cast<size_t>(pair.vertex[v]) + k,
                         b = 8 * static_cast<size_t>(pair.vertex[w]) + l;
            add(carrier_[a], carrier_[b], v, w, kappa * weight_[a] * weight_[b]);
          }
      }
  }
  BarrierHessian h;
  const int vertices = static_cast<int>(lattice_x.size() / 3);
  h.offsets.assign(vertices + 1, 0);
  for (const auto& [key, block] : blocks) {
    ++h.offsets[key.first + 1];
    h.columns.push_back(key.second);
    h.blocks.insert(h.blocks.end(), block.begin(), block.end());
  }
  for (int v = 0; v < vertices; ++v) h.offsets[v + 1] += h.offsets[v];
  return h;
}

double BarrierContact::step_bound(const std::vector<double>& lattice_x, const std::vector<double>& lattice_p) const {
  std::vector<double> x_storage, p_storage;
  const std::vector<double>& x = lift(lattice_x, x_storage);
  const std::vector<double>& p = lift(lattice_p, p_storage);  // linear: W p moves W x
  std::vector<std::array<int, 2>> pt, ee;
  candidates(x, &p, dhat_, pt, ee);
  double bound = 1.0;
  double q[12], dq[12];
  for (int kind = 0; kind < 2; ++kind)
    for (const auto& c : kind == 0 ? pt : ee) {
      if (excluded(kind, c[0], c[1])) continue;
      const BarrierPair pair = make_pair(kind, c[0], c[1]);
      gather(pair, x, q);
      gather(pair, p, dq);
      const double toi = kind == 0 ? kernel::ccd_point_triangle(q, dq, 1.0) : kernel::ccd_edge_edge(q, dq, 1.0);
      bound = std::min(bound, toi);
    }
  return bound;
}

double BarrierContact::min_distance(const std::vector<double>& lattice_x, double reach) const {
  std::vector<double> storage;
  const std::vector<double>& x = lift(lattice_x, storage);
  std::vector<std::array<int, 2>> pt, ee;
  candidates(x, nullptr, reach, pt, ee);
  double smallest = reach * reach;
  double q[12];
  int type;
  for (int kind = 0; kind < 2; ++kind)
    for (const auto& c : kind == 0 ? pt : ee) {
      if (excluded(kind, c[0], c[1])) continue;
      gather(make_pair(kind, c[0], c[1]), x, q);
      smallest = std::min(smallest, kind == 0 ? kernel::ipc_pt_distance(q, &type, nullptr, nullptr)
                                              : kernel::ipc_ee_distance(q, &type, nullptr, nullptr));
    }
  return std::sqrt(smallest);
}

}  // namespace snh::solver
