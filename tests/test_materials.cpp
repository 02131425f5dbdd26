// Every material model: derivatives against finite differences, the
// closed-form eigensystem against a numerical one, the projected Hessian
// against the numerical eigen-clamp, rest stability and linear elasticity
// after normalization by (E, nu) (seed 004 Eqs. 3-4, 15), no NaN where the
// model is defined, and the device kernels against the host reference.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "snh/error.h"
#include "snh/probe.h"
#include "snh_test_support.h"

namespace snh::test {
namespace {

struct ModelCase {
  std::string name;
  Material material;
  reference::MaterialSpec spec() const { return reference::spec_of(material); }
};

std::vector<ModelCase> model_cases() {
  std::vector<ModelCase> out;
  for (double nu : {0.3, 0.45}) {
    for (MaterialModel m : {MaterialModel::stable_neo_hookean, MaterialModel::fung, MaterialModel::arruda_boyce,
                            MaterialModel::corotational, MaterialModel::fixed_corotational, MaterialModel::stvk_kikuuwe,
                            MaterialModel::neohookean})
      out.push_back({std::string(to_string(m)) + "/nu" + std::to_string(nu).substr(0, 4),
                     Material::from_youngs_modulus(m, 1.0, nu)});
  }
  return out;
}

bool is_principal_stretch(MaterialModel m) {
  return m == MaterialModel::corotational || m == MaterialModel::fixed_corotational || m == MaterialModel::stvk_kikuuwe;
}

// Smallest sigma_i + sigma_j: co-rotational twists are singular where it is 0.
double min_pair_sum(const Eigen::Matrix3d& f) {
  const auto s = reference::svd_rotation_variant<double>(to_array<double>(f)).sigma;
  return std::min({s[0] + s[1], s[0] + s[2], s[1] + s[2]});
}

Matrix9 fd_hessian(const Eigen::Matrix3d& f, const reference::MaterialSpec& spec, double h) {
  Matrix9 out;
  for (int c = 0; c < 9; ++c) {
    Eigen::Matrix3d plus = f, minus = f;
    plus(c) += h;
    minus(c) -= h;
    const Eigen::Matrix3d dp = to_eigen(reference::material_pk1<double>(to_array<double>(plus), spec)) -
                               to_eigen(reference::material_pk1<double>(to_array<double>(minus), spec));
    out.col(c) = Eigen::Map<const Vector9>(dp.data()) / (2.0 * h);
  }
  return out;
}

Matrix9 closed_form_hessian(const Eigen::Matrix3d& f, const reference::MaterialSpec& spec) {
  const auto e = reference::material_hessian_eigensystem<double>(to_array<double>(f), spec);
  return hessian_from_eigensystem(e);
}

// Deformations where the model is smooth: all of the hard set, except for
// the co-rotational family the points where sigma_i + sigma_j vanishes.
std::vector<NamedDeformation> smooth_deformations(const ModelCase& m) {
  std::vector<NamedDeformation> out;
  for (const NamedDeformation& d : hard_deformations()) {
    const bool corotational =
        m.material.model == MaterialModel::corotational || m.material.model == MaterialModel::fixed_corotational;
    if (corotational && min_pair_sum(d.F) < 1e-2) continue;
    out.push_back(d);
  }
  return out;
}

TEST(Materials, Pk1AndHessianMatchFiniteDifferences) {
  int checked = 0;
  for (const ModelCase& m : model_cases()) {
    for (const NamedDeformation& d : smooth_deformations(m)) {
      SCOPED_TRACE(m.name + " / " + d.name);
      const auto spec = m.spec();
      const Eigen::Matrix3d p = to_eigen(reference::material_pk1<double>(to_array<double>(d.F), spec));
      const Matrix9 h = closed_form_hessian(d.F, spec);
      double best_p = 1e300, best_h = 1e300;
      for (double step : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
        Eigen::Matrix3d fd;
        for (int i = 0; i < 9; ++i) {
          Eigen::Matrix3d plus = d.F, minus = d.F;
          plus(i) += step;
          minus(i) -= step;
          fd(i) = (reference::material_energy<double>(to_array<double>(plus), spec) -
                   reference::material_energy<double>(to_array<double>(minus), spec)) /
                  (2.0 * step);
        }
        best_p = std::min(best_p, (fd - p).norm() / std::max(p.norm(), m.material.mu));
        best_h = std::min(best_h, (fd_hessian(d.F, spec, step) - h).norm() / std::max(h.norm(), m.material.mu));
      }
      EXPECT_LT(best_p, 1e-6);
      EXPECT_LT(best_h, 1e-6);
      ++checked;
    }
  }
  EXPECT_GT(checked, 14 * 30);  // 7 models x 2 nu over (most of) the hard set
}

TEST(Materials, ClosedFormEigensystemAndProjection) {
  for (const ModelCase& m : model_cases()) {
    for (const NamedDeformation& d : smooth_deformations(m)) {
      SCOPED_TRACE(m.name + " / " + d.name);
      const auto spec = m.spec();
      const Matrix9 h = closed_form_hessian(d.F, spec);
      const double scale = std::max(h.norm(), m.material.mu);
      // The closed form is symmetric, its vectors orthonormal, and it equals
      // the Hessian (checked against finite differences above).
      const auto e = reference::material_hessian_eigensystem<double>(to_array<double>(d.F), spec);
      Matrix9 q;
      for (int k = 0; k < 9; ++k) q.col(k) = Eigen::Map<const Vector9>(e.vectors[k].data());
      EXPECT_LE((q.transpose() * q - Matrix9::Identity()).norm(), 1e-12);
      std::array<double, 9> sorted = e.values;
      std::sort(sorted.begin(), sorted.end());
      const Matrix9 fd = fd_hessian(d.F, spec, 1e-6);
      const Eigen::SelfAdjointEigenSolver<Matrix9> numeric(0.5 * (fd + fd.transpose()));
      for (int k = 0; k < 9; ++k) EXPECT_NEAR(sorted[k], numeric.eigenvalues()[k], 1e-6 * scale) << k;
      // Projected action = numerical clamp of the closed-form matrix.
      const Eigen::SelfAdjointEigenSolver<Matrix9> exact(h);
      const Matrix9 clamped =
          exact.eigenvectors() * exact.eigenvalues().cwiseMax(0.0).asDiagonal() * exact.eigenvectors().transpose();
      Matrix9 projected;
      for (int c = 0; c < 9; ++c) {
        reference::Mat3<double> unit{};
        unit[c] = 1.0;
        const auto col = reference::material_projected_action<double>(to_array<double>(d.F), unit, spec);
        for (int r = 0; r < 9; ++r) projected(r, c) = col[r];
      }
      EXPECT_LE((projected - clamped).norm(), 1e-10 * scale);
    }
  }
}

TEST(Materials, RestStableAndLinearElasticityAfterNormalization) {
  for (double nu : {0.2, 0.3, 0.4, 0.49}) {
    const LameParameters target = lame_from_youngs_modulus(2.0, nu);
    for (const ModelCase& m0 : model_cases()) {
      const Material material = Material::from_youngs_modulus(m0.material.model, 2.0, nu);
      const ModelCase m{m0.name, material};
      SCOPED_TRACE(m.name + " at nu " + std::to_string(nu));
      const auto spec = m.spec();
      const auto identity = to_array<double>(Eigen::Matrix3d::Identity());
      EXPECT_NEAR(reference::material_energy<double>(identity, spec), 0.0, 1e-14 * target.lambda);
      EXPECT_LE(to_eigen(reference::material_pk1<double>(identity, spec)).norm(), 1e-13 * target.lambda);
      // Seed 004, Eqs. 3-4: Lame parameters from the second derivatives of
      // psi(sigma) at (1, 1, 1), taken as central differences of its gradient
      // (P11 = dpsi/dsigma_0 for diagonal F): accurate for every model,
      // including the Kikuuwe penalty, cubic on the compressed side.
      auto p11 = [&](double a, double b) {
        return reference::material_pk1<double>(to_array<double>(Eigen::Vector3d(a, b, 1.0).asDiagonal()), spec)[0];
      };
      const double h = 1e-6;
      const double d11 = (p11(1 + h, 1) - p11(1 - h, 1)) / (2 * h);
      const double d12 = (p11(1, 1 + h) - p11(1, 1 - h)) / (2 * h);
      EXPECT_NEAR(d12, target.lambda, 1e-5 * (target.lambda + target.mu));
      EXPECT_NEAR(0.5 * (d11 - d12), target.mu, 1e-5 * (target.lambda + target.mu));
      EXPECT_NEAR(material.lame().mu, target.mu, 1e-12 * target.mu);
      EXPECT_NEAR(material.lame().lambda, target.lambda, 1e-12 * (target.lambda + target.mu));
      // The Hessian at rest is the linear elasticity tensor of (E, nu).
      Matrix9 c = Matrix9::Zero();
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          for (int k = 0; k < 3; ++k)
            for (int l = 0; l < 3; ++l)
              c(3 * j + i, 3 * l + k) =
                  target.lambda * (i == j) * (k == l) + target.mu * ((i == k) * (j == l) + (i == l) * (j == k));
      EXPECT_LE((closed_form_hessian(Eigen::Matrix3d::Identity(), spec) - c).norm(), 1e-12 * c.norm());
    }
  }
}

TEST(Materials, NoNanWhereDefinedAndNeoHookeanWithoutHandlingIsFlagged) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0), exponent(-8.0, 1.0);
  for (const ModelCase& m : model_cases()) {
    SCOPED_TRACE(m.name);
    EXPECT_TRUE(m.material.defined_for_inversion());
    for (int n = 0; n < 300; ++n) {
      Eigen::Matrix3d f;
      const double scale = std::pow(10.0, exponent(rng));
      for (int k = 0; k < 9; ++k) f(k) = scale * u(rng);
      for (int precision = 0; precision < 2; ++precision) {
        const auto spec = m.spec();
        bool finite = true;
        if (precision == 0) {
          finite = finite && std::isfinite(reference::material_energy<double>(to_array<double>(f), spec));
          for (double x : reference::material_pk1<double>(to_array<double>(f), spec))
            finite = finite && std::isfinite(x);
          for (double x : reference::material_hessian_eigensystem<double>(to_array<double>(f), spec).values)
            finite = finite && std::isfinite(x);
        } else {
          finite = finite && std::isfinite(reference::material_energy<float>(to_array<float>(f), spec));
          for (float x : reference::material_pk1<float>(to_array<float>(f), spec)) finite = finite && std::isfinite(x);
        }
        EXPECT_TRUE(finite) << f;
      }
    }
  }
  MaterialOptions none;
  none.neohookean_j0 = 0.0;
  const Material raw = Material::from_youngs_modulus(MaterialModel::neohookean, 1.0, 0.3, none);
  EXPECT_FALSE(raw.defined_for_inversion());
  reference::MaterialSpec spec = reference::spec_of(raw);
  spec.barrier = false;
  const auto inverted = to_array<double>(Eigen::Vector3d(1.0, 1.0, -0.5).asDiagonal());
  EXPECT_FALSE(std::isfinite(reference::material_energy<double>(inverted, spec)));
}

TEST(Materials, DeviceMatchesHostReferenceForEveryModel) {
  std::vector<Matrix3> fs;
  std::vector<std::string> names;
  for (const NamedDeformation& d : hard_deformations()) {
    fs.push_back(to_array<double>(d.F));
    names.push_back(d.name);
  }
  for (const ModelCase& m : model_cases()) {
    if (m.name.find("nu0.45") == std::string::npos) continue;  // one kernel build per model
    MaterialProbe probe(m.material, Precision::double_);
    const auto results = probe.evaluate(fs);
    for (size_t n = 0; n < fs.size(); ++n) {
      SCOPED_TRACE(m.name + " / " + names[n]);
      const auto spec = m.spec();
      const auto p = reference::material_pk1<double>(fs[n], spec);
      double diff = 0.0, norm = 0.0;
      for (int i = 0; i < 9; ++i) {
        diff += (results[n].P[i] - p[i]) * (results[n].P[i] - p[i]);
        norm += p[i] * p[i];
      }
      EXPECT_LE(std::sqrt(diff),
                1e-12 * std::max(std::sqrt(norm), m.material.mu) * (1.0 + m.material.lambda / m.material.mu));
      const double psi = reference::material_energy<double>(fs[n], spec);
      EXPECT_LE(std::abs(results[n].psi - psi),
                1e-12 * std::max(std::abs(psi), m.material.mu) * (1.0 + m.material.lambda / m.material.mu));
    }
  }
}

TEST(Materials, NamesAndOutOfRangeOptions) {
  for (const char* name :
       {"snh", "fung", "arruda-boyce", "corotational", "fixed-corotational", "stvk-kikuuwe", "neohookean"})
    EXPECT_EQ(to_string(parse_material_model(name)), std::string(name));
  EXPECT_THROW(parse_material_model("mooney"), Error);
  MaterialOptions bad;
  bad.fung_gamma = 2.0;  // gamma mu1 >= 1: no positive linear part left
  EXPECT_THROW(Material::from_youngs_modulus(MaterialModel::fung, 1.0, 0.3, bad), Error);
  EXPECT_THROW(Material::from_youngs_modulus(MaterialModel::corotational, -1.0, 0.3), Error);
  EXPECT_THROW(Material::from_youngs_modulus(MaterialModel::stvk_kikuuwe, 1.0, 0.5), Error);
}

}  // namespace
}  // namespace snh::test
