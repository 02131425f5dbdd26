// Explicitly assembled host reference of the finite-element operators, in
// double: the elastic energy, the elastic forces and the PSD-projected
// stiffness as a sparse matrix. Built from the rest state and the element
// reference functions, independently of the kernels' gathers; the tests
// compare the device's matrix-free operators with it, and benchmarks use it
// as the CPU baseline. Every element uses its material of the map (any
// model, through reference::material_*); the StableNeoHookean overloads are
// the uniform map of that material.
#pragma once

#include <Eigen/Sparse>
#include <vector>

#include "fem/rest_state.h"
#include "snh/material.h"
#include "snh/mesh.h"
#include "snh/regions.h"

namespace snh::reference {

// Elastic energy at positions x (xyz per vertex): the sum over elements and
// quadrature points of weight * psi(F), summed per element, then in element
// order.
double assembled_energy(const Mesh& mesh, const fem::RestState& rest, const MaterialMap& materials,
                        const std::vector<double>& x);
double assembled_energy(const Mesh& mesh, const fem::RestState& rest, const StableNeoHookean& material,
                        const std::vector<double>& x);

// Elastic forces -dE/dx, xyz per vertex.
std::vector<double> assembled_forces(const Mesh& mesh, const fem::RestState& rest, const MaterialMap& materials,
                                     const std::vector<double>& x);
std::vector<double> assembled_forces(const Mesh& mesh, const fem::RestState& rest, const StableNeoHookean& material,
                                     const std::vector<double>& x);

// The PSD-projected stiffness at x, 3n x 3n (DOF 3 v + i), column-major
// sparse. Each element matrix is built column by column: for node b and
// direction d, dF = e_d (dN_b/dX)^T and dP = H_projected : dF, whose column
// entry for node a, component i is sum_q w_q sum_j dP_ij dN_a/dX_j. Element
// matrices are assembled with triplets in element order (deterministic).
Eigen::SparseMatrix<double> assembled_projected_stiffness(const Mesh& mesh, const fem::RestState& rest,
                                                          const MaterialMap& materials, const std::vector<double>& x);
Eigen::SparseMatrix<double> assembled_projected_stiffness(const Mesh& mesh, const fem::RestState& rest,
                                                          const StableNeoHookean& material,
                                                          const std::vector<double>& x);

}  // namespace snh::reference
