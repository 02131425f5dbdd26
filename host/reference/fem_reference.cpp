#include "reference/fem_reference.h"

#include <string>

#include "material/element_reference.h"
#include "snh/error.h"

namespace snh::reference {

namespace {

void check_sizes(const Mesh& mesh, const fem::RestState& rest, const MaterialMap& materials,
                 const std::vector<double>& x) {
  validate_material_map(mesh, materials);
  if (x.size() != 3 * mesh.vertex_count())
    throw Error("fem reference: positions have " + std::to_string(x.size()) + " entries, expected " +
                std::to_string(3 * mesh.vertex_count()));
  if (rest.type != mesh.type || rest.nodes != nodes_per_element(mesh.type))
    throw Error("fem reference: the rest state belongs to another element type");
}

// The material of each map entry, in the element reference's terms.
std::vector<MaterialSpec> specs(const MaterialMap& materials) {
  std::vector<MaterialSpec> out;
  for (const Material& m : materials.materials) out.push_back(spec_of(m));
  return out;
}

Mat3<double> deformation_gradient(const Mesh& mesh, const fem::RestState& rest, const std::vector<double>& x, size_t e,
                                  int q) {
  Mat3<double> f;
  fem::deformation_gradient(mesh, rest, x.data(), e, q, f.data());
  return f;
}

}  // namespace

double assembled_energy(const Mesh& mesh, const fem::RestState& rest, const MaterialMap& materials,
                        const std::vector<double>& x) {
  check_sizes(mesh, rest, materials, x);
  const std::vector<MaterialSpec> spec = specs(materials);
  double total = 0.0;
  for (size_t e = 0; e < mesh.element_count(); ++e) {
    const MaterialSpec& m = spec[materials.element_material[e]];
    double sum = 0.0;
    for (int q = 0; q < rest.quadrature; ++q)
      sum += rest.weight(e, q) * material_energy<double>(deformation_gradient(mesh, rest, x, e, q), m);
    total += sum;
  }
  return total;
}

std::vector<double> assembled_forces(const Mesh& mesh, const fem::RestState& rest, const MaterialMap& materials,
                                     const std::vector<double>& x) {
  check_sizes(mesh, rest, materials, x);
  const std::vector<MaterialSpec> spec = specs(materials);
  std::vector<double> forces(x.size(), 0.0);
  for (size_t e = 0; e < mesh.element_count(); ++e) {
    const MaterialSpec& m = spec[materials.element_material[e]];
    const int32_t* nodes = mesh.elements.data() + static_cast<size_t>(rest.nodes) * e;
    for (int q = 0; q < rest.quadrature; ++q) {
      const Mat3<double> pk1 = material_pk1<double>(deformation_gradient(mesh, rest, x, e, q), m);
      const double w = rest.weight(e, q);
      for (int a = 0; a < rest.nodes; ++a) {
        const double* g = rest.gradient(e, q, a);
        for (int i = 0; i < 3; ++i)
          forces[3 * nodes[a] + i] -= w * (pk1[i] * g[0] + pk1[3 + i] * g[1] + pk1[6 + i] * g[2]);
      }
    }
  }
  return forces;
}

Eigen::SparseMatrix<double> assembled_projected_stiffness(const Mesh& mesh, const fem::RestState& rest,
                                                          const MaterialMap& materials, const std::vector<double>& x) {
  check_sizes(mesh, rest, materials, x);
  const std::vector<MaterialSpec> spec = specs(materials);
  const int n = rest.nodes, size = 3 * n;
  const Eigen::Index dofs = static_cast<Eigen::Index>(x.size());
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(mesh.element_count() * static_cast<size_t>(size) * size);
  Eigen::MatrixXd ke(size, size);
  for (size_t e = 0; e < mesh.element_count(); ++e) {
    const MaterialSpec& m = spec[materials.element_material[e]];
    const int32_t* nodes = mesh.elements.data() + static_cast<size_t>(n) * e;
    ke.setZero();
    for (int q = 0; q < rest.quadrature; ++q) {
      // One SVD per point; the action from it is bitwise the same as
      // material_projected_action(F, dF), which would redo the SVD per column.
      const Svd<double> svd = svd_rotation_variant<double>(deformation_gradient(mesh, rest, x, e, q));
      const double w = rest.weight(e, q);
      for (int b = 0; b < n; ++b) {
        const double* gb = rest.gradient(e, q, b);
        for (int d = 0; d < 3; ++d) {
          Mat3<double> df{};
          for (int c = 0; c < 3; ++c) df[3 * c + d] = gb[c];
          const Mat3<double> dp = material_projected_action_from_svd<double>(svd, df, m);
          double* column = ke.col(3 * b + d).data();
          for (int a = 0; a < n; ++a) {
            const double* ga = rest.gradient(e, q, a);
            for (int i = 0; i < 3; ++i)
              column[3 * a + i] += w * (dp[i] * ga[0] + dp[3 + i] * ga[1] + dp[6 + i] * ga[2]);
          }
        }
      }
    }
    for (int b = 0; b < n; ++b)
      for (int d = 0; d < 3; ++d)
        for (int a = 0; a < n; ++a)
          for (int i = 0; i < 3; ++i)
            triplets.emplace_back(3 * nodes[a] + i, 3 * nodes[b] + d, ke(3 * a + i, 3 * b + d));
  }
  Eigen::SparseMatrix<double> k(dofs, dofs);
  k.setFromTriplets(triplets.begin(), triplets.end());
  return k;
}

double assembled_energy(const Mesh& mesh, const fem::RestState& rest, const StableNeoHookean& material,
                        const std::vector<double>& x) {
  return assembled_energy(mesh, rest, uniform_material(mesh, material), x);
}

std::vector<double> assembled_forces(const Mesh& mesh, const fem::RestState& rest, const StableNeoHookean& material,
                                     const std::vector<double>& x) {
  return assembled_forces(mesh, rest, uniform_material(mesh, material), x);
}

Eigen::SparseMatrix<double> assembled_projected_stiffness(const Mesh& mesh, const fem::RestState& rest,
                                                          const StableNeoHookean& material,
                                                          const std::vector<double>& x) {
  return assembled_projected_stiffness(mesh, rest, uniform_material(mesh, material), x);
}

}  // namespace snh::reference
