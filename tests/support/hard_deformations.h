// The hard deformation gradients every element test runs over: identity,
// rotations, F = 0, plane/line/point degeneracies, single and double
// reflections, repeated singular values, 1e-6 compressions, 10x stretches
// and random F.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <random>
#include <string>
#include <vector>

namespace snh::test {

struct NamedDeformation {
  std::string name;
  Eigen::Matrix3d F;
};

inline Eigen::Matrix3d random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return q.toRotationMatrix();
}

inline std::vector<NamedDeformation> hard_deformations() {
  std::mt19937_64 rng(20180301);
  std::vector<NamedDeformation> out;
  const Eigen::Matrix3d r1 = random_rotation(rng), r2 = random_rotation(rng);
  auto svd_form = [&](const std::string& name, double a, double b, double c) {
    out.push_back({name, r1 * Eigen::Vector3d(a, b, c).asDiagonal() * r2.transpose()});
  };
  out.push_back({"identity", Eigen::Matrix3d::Identity()});
  out.push_back({"rotation", r1});
  out.push_back({"rotation_pi", Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix()});
  out.push_back({"zero", Eigen::Matrix3d::Zero()});
  svd_form("plane", 1.2, 0.7, 0.0);
  svd_form("line", 1.5, 0.0, 0.0);
  svd_form("point_1e-8", 1e-8, 1e-8, 1e-8);
  out.push_back({"single_reflection", Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal()});
  svd_form("single_reflection_rotated", 1.3, 0.9, -0.6);
  out.push_back({"double_reflection", Eigen::Vector3d(-1.0, -1.0, 1.0).asDiagonal()});
  out.push_back({"triple_reflection", -Eigen::Matrix3d::Identity()});
  svd_form("repeated_2_2_0.5", 2.0, 2.0, 0.5);
  svd_form("repeated_1.5_0.7_0.7", 1.5, 0.7, 0.7);
  svd_form("repeated_inverted", 0.8, 0.8, -0.8);
  svd_form("uniform_scale_0.5", 0.5, 0.5, 0.5);
  svd_form("compress_1e-6_axis", 1.0, 1.0, 1e-6);
  svd_form("compress_1e-6_all", 1e-6, 1e-6, 1e-6);
  svd_form("stretch_10x", 10.0, 1.0, 1.0);
  svd_form("stretch_10x_volume_preserving", 10.0, 1.0 / std::sqrt(10.0), 1.0 / std::sqrt(10.0));
  svd_form("near_alpha", 1.1, 1.0, 1.0);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (int i = 0; i < 12; ++i) {
    Eigen::Matrix3d f;
    for (int k = 0; k < 9; ++k) f(k) = u(rng);
    out.push_back({"random_" + std::to_string(i), f});
  }
  for (int i = 0; i < 4; ++i) {
    Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
    for (int k = 0; k < 9; ++k) f(k) += 0.2 * u(rng);
    out.push_back({"near_rest_" + std::to_string(i), f});
  }
  return out;
}

// Column-major array <-> Eigen (Eigen is column-major too: the same index).
template <typename Real>
std::array<Real, 9> to_array(const Eigen::Matrix3d& m) {
  std::array<Real, 9> a;
  for (int i = 0; i < 9; ++i) a[i] = static_cast<Real>(m(i));
  return a;
}

template <typename Real>
Eigen::Matrix3d to_eigen(const std::array<Real, 9>& a) {
  Eigen::Matrix3d m;
  for (int i = 0; i < 9; ++i) m(i) = static_cast<double>(a[i]);
  return m;
}

// Row-major array (the public API's order: snh::Matrix3, ProbeResult::P)
// <-> Eigen.
inline std::array<double, 9> to_row_major(const Eigen::Matrix3d& m) {
  std::array<double, 9> a;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a[3 * r + c] = m(r, c);
  return a;
}

inline Eigen::Matrix3d from_row_major(const std::array<double, 9>& a) {
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = a[3 * r + c];
  return m;
}

// A 9x9 Hessian over the column-major vec(F), h(i, k) = d vec(P)_i /
// d vec(F)_k, as ProbeResult::H: H[9 a + b] = d P_a / d F_b over the
// row-major indices a, b.
template <typename Matrix>
std::array<double, 81> hessian_row_major(const Matrix& h) {
  auto vec_index = [](int a) { return 3 * (a % 3) + a / 3; };
  std::array<double, 81> out;
  for (int a = 0; a < 9; ++a)
    for (int b = 0; b < 9; ++b) out[9 * a + b] = h(vec_index(a), vec_index(b));
  return out;
}

}  // namespace snh::test
