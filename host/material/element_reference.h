// Host reference of the element math: the very headers under kernels/,
// compiled as C++ once per precision. Tests compare the OpenCL kernels with
// these functions, and the functions with Eigen and finite differences.
// 3x3 matrices are column-major arrays (index 3 * column + row, the paper's vec).
#pragma once

#include <array>
#include <vector>

#include "snh/material.h"

namespace snh::reference {

template <typename Real>
using Mat3 = std::array<Real, 9>;

template <typename Real>
struct Svd {
  Mat3<Real> u, v;
  std::array<Real, 3> sigma;
};

template <typename Real>
struct SymmetricEigen {
  std::array<Real, 3> values;  // ascending
  Mat3<Real> vectors;          // unit eigenvectors as columns
};

// Nine eigenpairs of the unprojected 9x9 Hessian, in the paper's order: the
// block's three (ascending), the twists, then the flips (Eqs. 45-48).
template <typename Real>
struct HessianEigensystem {
  std::array<Real, 9> values;
  std::array<Mat3<Real>, 9> vectors;
};

struct SnhParameters {
  double mu = 0.0;
  double lambda = 0.0;
  bool barrier = true;
};

template <typename Real>
Svd<Real> svd_rotation_variant(const Mat3<Real>& f);

template <typename Real>
SymmetricEigen<Real> symmetric_eigen(const std::array<Real, 6>& packed);  // a00 a01 a02 a11 a12 a22

// snh_portable.h's snh_pow2_inverse: 2^-floor(log2 m), for normal m > 0.
template <typename Real>
Real pow2_inverse(Real m);

template <typename Real>
Real snh_energy(const Mat3<Real>& f, const SnhParameters& p);

template <typename Real>
Mat3<Real> snh_pk1(const Mat3<Real>& f, const SnhParameters& p);

template <typename Real>
HessianEigensystem<Real> snh_hessian_eigensystem(const Mat3<Real>& f, const SnhParameters& p);

// dP = H_projected : dF, the closed-form PSD projection applied to dF.
template <typename Real>
Mat3<Real> snh_projected_action(const Mat3<Real>& f, const Mat3<Real>& df, const SnhParameters& p);

// The same from a given factorization F = U diag(sigma) V^T (any sign
// convention), to check that the Hessian does not depend on it.
template <typename Real>
Mat3<Real> snh_projected_action_from_svd(const Svd<Real>& svd, const Mat3<Real>& df, const SnhParameters& p);

// Any material model (ids of snh::MaterialModel), parameters as in
// snh::Material: the same kernels/materials/material.h the device runs.
struct MaterialSpec {
  int model = 0;
  bool barrier = true;
  double mu = 0.0, lambda = 0.0, c0 = 0.0, c1 = 0.0;
  // Alpha/mixing path (see snh::Material): lambda part's model (-1: model) and
  // parameter, nonlinearity of each part.
  int lambda_model = -1;
  double lambda_c0 = 0.0, alpha_lambda = 1.0, alpha_mu = 1.0;
};

MaterialSpec spec_of(const Material& material);

template <typename Real>
Real material_energy(const Mat3<Real>& f, const MaterialSpec& m);

template <typename Real>
Mat3<Real> material_pk1(const Mat3<Real>& f, const MaterialSpec& m);

template <typename Real>
HessianEigensystem<Real> material_hessian_eigensystem(const Mat3<Real>& f, const MaterialSpec& m);

template <typename Real>
Mat3<Real> material_projected_action(const Mat3<Real>& f, const Mat3<Real>& df, const MaterialSpec& m);

// The same from a given factorization F = U diag(sigma) V^T (one SVD per
// point for all columns of an element matrix).
template <typename Real>
Mat3<Real> material_projected_action_from_svd(const Svd<Real>& svd, const Mat3<Real>& df, const MaterialSpec& m);

// Contact penalty of one vertex at x against `count` obstacle records
// (kernels/contact/obstacle.h, the records of solver/contact/obstacles.h): returns
// the energy, writes the force -dE/dx, the Gauss-Newton Hessian (column-
// major) and the deepest g = thickness - phi (0 when none).
template <typename Real>
struct ObstacleContact {
  Real energy = 0;
  std::array<Real, 3> force{};
  std::array<Real, 9> hessian{};
  Real depth = 0;
};
template <typename Real>
ObstacleContact<Real> obstacle_contact(const std::vector<Real>& records, Real stiffness, Real thickness,
                                       const std::array<Real, 3>& x);
// The lagged friction potential of kernels/contact/obstacle.h
// (obstacle_friction) at x from start position x0 and anchors (xyz per
// obstacle): energy, force and Hessian (depth 0).
template <typename Real>
ObstacleContact<Real> obstacle_friction(const std::vector<Real>& start_records,
                                        const std::vector<Real>& friction_records, Real stiffness, Real thickness,
                                        Real slip, const std::array<Real, 3>& x0, const std::vector<Real>& anchors,
                                        const std::array<Real, 3>& x);
// The anchor kept for the next step against one obstacle (its start record,
// friction record and record at the step's end; obstacle_friction_anchor).
template <typename Real>
std::array<Real, 3> obstacle_friction_anchor(const std::vector<Real>& start_record,
                                             const std::vector<Real>& friction_record,
                                             const std::vector<Real>& end_record, Real thickness, Real slip,
                                             const std::array<Real, 3>& x0, const std::array<Real, 3>& anchor,
                                             const std::array<Real, 3>& x);

}  // namespace snh::reference
