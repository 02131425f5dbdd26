// Self-collision by the reference-map penalty (Smith et al. 2018 sec. 6;
// Hirota et al. 2001, Irving et al. 2004): a surface sample whose deformed
// position lies in a deformed element not adjacent to it is mapped to rest
// space through that element, the closest rest-surface point Y is found,
// and a spring pulls the sample to Y's deformed position,
//   E_c = k/2 |x_s - sum_j w_j x_j|^2,
// w the barycentric weights of Y on its rest triangle, frozen for a Newton
// iteration (docs/design.md). With a = [1, -w0, -w1, -w2] over
// (s, j0, j1, j2): dE/dx_i = k a_i d, d = sum_i a_i x_i, and the Hessian
// k (a a^T) (x) I3 is PSD. E_c is C^1 across activation: a sample entering
// an element through the surface has X on that surface, so Y = X and d = 0.
//
// Detection runs on the host, deterministically (no order-dependent steps):
// a uniform grid over the deformed elements' bounding boxes built by count,
// prefix sum and fill in element order; samples located by barycentric
// coordinates in tets, and in hexes through their six-tet (Kuhn) split as the
// paper does ("a tetrahedralization of the hexahedral mesh"): linear, so one
// 3x3 solve per tet, exact and defined for inverted elements, where
// inverting the trilinear map needs Newton iterations that may fail.
// Only tets (hex pieces) that keep their rest orientation locate a sample:
// an inverted piece has no reference map.
// Excluded for sample s: every element that shares a vertex with an element
// of s (the one-ring of s's elements, not only the elements of s; on tet4
// meshes one ring more, self_contact.cpp), and every rest triangle with a
// vertex in those elements. At a crease compressed
// elements overlap their immediate neighbours (and a hex's Kuhn tets no
// longer cover the trilinear hex exactly), so a sample would otherwise be
// found in the element next to its own and pulled toward a surface point
// beside itself; one ring further out the overlap of a well-resolved fold is
// a genuine contact. The price: contact closer than about two elements to a
// sample, topologically, goes undetected (at the very apex of a fold).
// Internal to the library.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "snh/mesh.h"

namespace snh::solver {

// One active self-contact: sample vertex s, the rest triangle (j0, j1, j2)
// holding its closest rest-surface point and that point's barycentric
// weights, and the element the sample was found in.
struct SelfContactPair {
  int sample = 0;
  std::array<int, 3> vertex{0, 0, 0};
  std::array<double, 3> weight{0, 0, 0};
  int element = 0;
  bool operator==(const SelfContactPair& o) const {
    return sample == o.sample && vertex == o.vertex && weight == o.weight && element == o.element;
  }
};

class SelfContactDetector {
 public:
  // The rest surface (faces of exactly one element; hex quads as two
  // triangles), the samples (its vertices), the exclusions and a rest-space
  // grid over the surface triangles, built once. hex8 or tet4.
  explicit SelfContactDetector(const Mesh& mesh);

  // The active contacts at positions x (xyz per vertex), in sample order.
  std::vector<SelfContactPair> detect(const std::vector<double>& x) const;

  const std::vector<int>& samples() const { return samples_; }
  size_t triangle_count() const { return triangles_.size() / 3; }
  // Seconds the last detect() spent building the deformed grid and
  // locating the samples (with their closest rest points).
  double last_grid_seconds() const { return last_grid_seconds_; }
  double last_location_seconds() const { return last_location_seconds_; }

  // The closest point of the rest surface to X, skipping triangles with a
  // vertex excluded for `sample` (-1: none skipped): its triangle's vertices
  // and barycentric weights. false when no triangle qualifies.
  bool closest_rest_point(const std::array<double, 3>& X, int sample, std::array<int, 3>& vertex,
                          std::array<double, 3>& weight) const;
  // Whether element e is excluded for sample s (shares a vertex with an
  // element of s).
  bool excluded(int sample, int element) const;

 private:
  // Rest position through element e's barycentric map when x lies in its
  // deformed shape (a hex: in one of its six Kuhn tets).
  bool locate(int element, const double* p, const std::vector<double>& x, std::array<double, 3>& X) const;
  bool near_sample(int sample, int vertex) const;

  ElementType type_;
  int nodes_;
  std::vector<int32_t> elements_;
  std::vector<double> rest_;
  double cell_ = 1.0;  // grid cell width, the mean element extent at rest
  std::vector<int> samples_;
  // Per sample (CSR): the sorted vertices of its elements (its "near" set).
  std::vector<int> near_offsets_, near_;
  std::vector<int> sample_of_vertex_;  // -1 for interior vertices
  std::vector<int> triangles_;         // 3 vertices each
  // Rest-space grid over the triangles (CSR over cells, in triangle order).
  std::array<double, 3> rest_origin_{0, 0, 0};
  std::array<int, 3> rest_dims_{1, 1, 1};
  std::vector<int> rest_offsets_, rest_cells_;
  mutable double last_grid_seconds_ = 0.0, last_location_seconds_ = 0.0;
};

// Host reference of the penalty over a frozen contact list (tests and the
// energy sum): energy k/2 sum |d_c|^2 summed in list order in double;
// gradient dE/dx added into g (xyz per vertex).
double self_contact_energy(const std::vector<SelfContactPair>& contacts, double stiffness,
                           const std::vector<double>& x);
void self_contact_gradient(const std::vector<SelfContactPair>& contacts, double stiffness, const std::vector<double>& x,
                           std::vector<double>& g);
// |x_s - sum_j w_j x_j|: the spring's length, the penetration the penalty sees.
double self_contact_length(const SelfContactPair& c, const std::vector<double>& x);

}  // namespace snh::solver
