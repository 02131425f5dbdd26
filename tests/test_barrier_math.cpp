// The barrier's per-pair math (kernels/contact/ipc_*.h, ccd.h): squared
// distances of every distance type with gradients and Hessians against
// central differences, the barrier and mollifier derivatives, the PSD
// projection (Eigen's reference and the shared cyclic Jacobi one), and the
// conservative CCD on crossing motions (generic, glancing and parallel).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "solver/contact/barrier_contact.h"

namespace snh::test {
namespace ipc {
#define SNH_DOUBLE 1
#include "contact/ccd.h"
#include "contact/ipc_barrier.h"
#include "contact/psd_jacobi.h"
}  // namespace ipc
namespace {

using Config = std::array<double, 12>;

Config random_config(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Config x;
  for (double& v : x) v = u(rng);
  return x;
}

// Best relative error of a central difference of f over steps 1e-4 .. 1e-9
// (the sweep HOBAK's derivative tests use): each entry of `analytic` is
// d f_k / d x_i for the output k.
double best_difference_error(const std::function<void(const Config&, std::vector<double>&)>& f, const Config& x,
                             const std::vector<double>& analytic, int outputs) {
  double best = HUGE_VAL;
  double scale = 1.0;
  for (double a : analytic) scale = std::max(scale, std::abs(a));
  for (double h = 1e-4; h >= 1e-9; h /= 10.0) {
    double worst = 0.0;
    std::vector<double> plus(outputs), minus(outputs);
    for (int i = 0; i < 12; ++i) {
      Config xp = x, xm = x;
      xp[i] += h;
      xm[i] -= h;
      f(xp, plus);
      f(xm, minus);
      for (int k = 0; k < outputs; ++k) {
        const double numeric = (plus[k] - minus[k]) / (2.0 * h);
        worst = std::max(worst, std::abs(numeric - analytic[k * 12 + i]) / scale);
      }
    }
    best = std::min(best, worst);
  }
  return best;
}

// A form of a fixed type (no reclassification under the differences).
void check_form(int m, const int* c, int form, const Config& x, const char* what) {
  double g[12], h[144];
  ipc::ipc_form_distance(m, c, form, x.data(), g, h);
  const std::vector<double> grad(g, g + 12), hess(h, h + 144);
  const double e1 = best_difference_error(
      [&](const Config& y, std::vector<double>& out) { out[0] = ipc::ipc_form_distance(m, c, form, y.data(), 0, 0); },
      x, grad, 1);
  const double e2 = best_difference_error(
      [&](const Config& y, std::vector<double>& out) {
        double gy[12], hy[144];
        ipc::ipc_form_distance(m, c, form, y.data(), gy, hy);
        out.assign(gy, gy + 12);
      },
      x, hess, 12);
  EXPECT_LT(e1, 1e-6) << what << " gradient";
  EXPECT_LT(e2, 1e-6) << what << " Hessian";
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) ASSERT_EQ(h[12 * i + j], h[12 * j + i]) << what << " Hessian not symmetric";
}

TEST(BarrierMath, PointTriangleDistancesOfEveryTypeMatchDifferences) {
  std::mt19937_64 rng(7);
  int seen[7] = {0};
  for (int trial = 0; trial < 4000; ++trial) {
    Config x = random_config(rng);
    for (int i = 0; i < 3; ++i) x[i] *= 2.0;  // the point beyond the triangle more often
    int type;
    const double d = ipc::ipc_pt_distance(x.data(), &type, nullptr, nullptr);
    ASSERT_GE(type, 0);
    ASSERT_LE(type, IPC_PT_T);
    if (seen[type] >= 30) continue;
    ++seen[type];
    // The classified distance is the true one: no closer point on a dense
    // sample of the triangle.
    double sampled = HUGE_VAL;
    for (int a = 0; a <= 60; ++a)
      for (int b = 0; a + b <= 60; ++b) {
        double s = 0.0;
        for (int k = 0; k < 3; ++k) {
          const double q = x[3 + k] + (a / 60.0) * (x[6 + k] - x[3 + k]) + (b / 60.0) * (x[9 + k] - x[3 + k]);
          s += (x[k] - q) * (x[k] - q);
        }
        sampled = std::min(sampled, s);
      }
    EXPECT_LE(d, sampled + 1e-12) << "type " << type;
    EXPECT_GE(std::sqrt(d), std::sqrt(sampled) - 0.05) << "type " << type;
    int c[12], m, form;
    ipc::ipc_pt_form(type, c, &m, &form);
    check_form(m, c, form, x, "point-triangle");
  }
  for (int t = 0; t < 7; ++t) EXPECT_GE(seen[t], 10) << "point-triangle type " << t << " rarely drawn";
}

TEST(BarrierMath, EdgeEdgeDistancesOfEveryTypeMatchDifferences) {
  std::mt19937_64 rng(11);
  int seen[9] = {0};
  for (int trial = 0; trial < 20000; ++trial) {
    Config x = random_config(rng);
    if (trial % 2) {  // short edges far apart: endpoint types more often
      for (int i = 3; i < 6; ++i) x[i] = x[i - 3] + 0.3 * x[i];
      for (int i = 9; i < 12; ++i) x[i] = x[i - 3] + 0.3 * x[i];
    }
    int type;
    const double d = ipc::ipc_ee_distance(x.data(), &type, nullptr, nullptr);
    if (seen[type] >= 30) continue;
    ++seen[type];
    double sampled = HUGE_VAL;
    for (int a = 0; a <= 200; ++a)
      for (int b = 0; b <= 200; ++b) {
        double s = 0.0;
        for (int k = 0; k < 3; ++k) {
          const double p = x[k] + (a / 200.0) * (x[3 + k] - x[k]), q = x[6 + k] + (b / 200.0) * (x[9 + k] - x[6 + k]);
          s += (p - q) * (p - q);
        }
        sampled = std::min(sampled, s);
      }
    EXPECT_LE(d, sampled + 1e-12) << "type " << type;
    EXPECT_GE(std::sqrt(d), std::sqrt(sampled) - 0.02) << "type " << type;
    int c[12], m, form;
    ipc::ipc_ee_form(type, c, &m, &form);
    check_form(m, c, form, x, "edge-edge");
  }
  for (int t = 0; t < 9; ++t) EXPECT_GE(seen[t], 10) << "edge-edge type " << t << " rarely drawn";
}

TEST(BarrierMath, ParallelEdgesAreClassifiedByTheirClosestEndpoint) {
  // b parallel to a, offset by 0.5 in y: the distance is 0.5 (overlapping
  // spans) or the endpoint gap.
  Config x = {0, 0, 0, 1, 0, 0, 0.25, 0.5, 0, 2, 0.5, 0};
  int type;
  EXPECT_NEAR(std::sqrt(ipc::ipc_ee_distance(x.data(), &type, nullptr, nullptr)), 0.5, 1e-12);
  Config y = {0, 0, 0, 1, 0, 0, 2, 0.5, 0, 3, 0.5, 0};
  EXPECT_NEAR(ipc::ipc_ee_distance(y.data(), &type, nullptr, nullptr), 1.0 + 0.25, 1e-12);
  EXPECT_EQ(type, IPC_EE_A1B0);
}

TEST(BarrierMath, BarrierAndMollifierDerivativesMatchDifferences) {
  const double sh = 0.09;
  for (double s = 1e-4; s < sh; s *= 1.7) {
    const double h = 1e-7 * s;
    const double d1 = (ipc::ipc_barrier(s + h, sh) - ipc::ipc_barrier(s - h, sh)) / (2 * h);
    const double d2 = (ipc::ipc_barrier_first(s + h, sh) - ipc::ipc_barrier_first(s - h, sh)) / (2 * h);
    EXPECT_NEAR(d1, ipc::ipc_barrier_first(s, sh), 1e-6 * std::max(1.0, std::abs(d1))) << s;
    EXPECT_NEAR(d2, ipc::ipc_barrier_second(s, sh), 1e-5 * std::max(1.0, std::abs(d2))) << s;
    EXPECT_GT(ipc::ipc_barrier(s, sh), 0.0);
    EXPECT_LT(ipc::ipc_barrier_first(s, sh), 0.0);  // repulsive
  }
  // C^1 at dhat, and zero beyond it.
  EXPECT_EQ(ipc::ipc_barrier(sh, sh), 0.0);
  EXPECT_NEAR(ipc::ipc_barrier(sh * (1 - 1e-6), sh), 0.0, 1e-15);
  EXPECT_NEAR(ipc::ipc_barrier_first(sh * (1 - 1e-6), sh), 0.0, 1e-9);
  EXPECT_EQ(ipc::ipc_barrier_first(2 * sh, sh), 0.0);
  const double ex = 0.3;
  for (double c = 0.01; c < 0.5; c += 0.037) {
    const double h = 1e-7;
    EXPECT_NEAR((ipc::ipc_mollifier(c + h, ex) - ipc::ipc_mollifier(c - h, ex)) / (2 * h),
                ipc::ipc_mollifier_first(c, ex), 1e-6);
    EXPECT_NEAR((ipc::ipc_mollifier_first(c + h, ex) - ipc::ipc_mollifier_first(c - h, ex)) / (2 * h),
                ipc::ipc_mollifier_second(c, ex), 1e-5);
  }
  EXPECT_NEAR(ipc::ipc_mollifier(ex, ex), 1.0, 1e-15);
  EXPECT_EQ(ipc::ipc_mollifier(0.0, ex), 0.0);
}

TEST(BarrierMath, PairPotentialsMatchDifferences) {
  std::mt19937_64 rng(5);
  int checked[2] = {0, 0};
  for (int trial = 0; trial < 400; ++trial) {
    const Config x = random_config(rng);
    for (int kind = 0; kind < 2; ++kind) {
      int type;
      const double s =
          kind == 0 ? ipc::ipc_pt_distance(x.data(), &type, 0, 0) : ipc::ipc_ee_distance(x.data(), &type, 0, 0);
      const double sh = 1.5 * s;
      double ex = 0.0;
      if (kind == 1)
        ex = 2.0 * ipc::ipc_edge_cross_squared(x.data(), 0, 0) * (trial % 2 ? 1.0 : 0.25);  // mollified or not
      auto potential = [&](const Config& y, double* g, double* h) {
        double d;
        return kind == 0 ? ipc::ipc_pt_potential(y.data(), sh, &d, g, h)
                         : ipc::ipc_ee_potential(y.data(), sh, ex, &d, g, h);
      };
      double g[12], h[144];
      potential(x, g, h);
      // Reclassification under the differences would mix two forms: skip
      // configurations within a step of a type boundary.
      bool stable = true;
      for (int i = 0; i < 12 && stable; ++i)
        for (double sign : {-1.0, 1.0}) {
          Config y = x;
          y[i] += sign * 1e-4;
          int t2;
          if ((kind == 0 ? (ipc::ipc_pt_distance(y.data(), &t2, 0, 0), t2)
                         : (ipc::ipc_ee_distance(y.data(), &t2, 0, 0), t2)) != type)
            stable = false;
        }
      if (!stable) continue;
      const double e1 = best_difference_error(
          [&](const Config& y, std::vector<double>& out) { out[0] = potential(y, nullptr, nullptr); }, x,
          std::vector<double>(g, g + 12), 1);
      const double e2 = best_difference_error(
          [&](const Config& y, std::vector<double>& out) {
            double gy[12], hy[144];
            potential(y, gy, hy);
            out.assign(gy, gy + 12);
          },
          x, std::vector<double>(h, h + 144), 12);
      EXPECT_LT(e1, 1e-6) << "kind " << kind << " type " << type;
      EXPECT_LT(e2, 1e-5) << "kind " << kind << " type " << type;
      ++checked[kind];
    }
  }
  EXPECT_GE(checked[0], 100);
  EXPECT_GE(checked[1], 100);
}

TEST(BarrierMath, PsdProjectionClampsNegativeEigenvaluesAndKeepsPsdMatrices) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::Matrix<double, 12, 12, Eigen::RowMajor> a;
    for (int i = 0; i < 144; ++i) a.data()[i] = n(rng);
    Eigen::Matrix<double, 12, 12, Eigen::RowMajor> sym = a + a.transpose();
    Eigen::Matrix<double, 12, 12, Eigen::RowMajor> projected = sym;
    solver::project_psd(projected.data(), 12);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> before(sym), after(projected);
    const double scale = before.eigenvalues().cwiseAbs().maxCoeff();
    EXPECT_GE(after.eigenvalues().minCoeff(), -1e-12 * scale);
    // The positive part is kept: eigenvalues max(lambda, 0).
    Eigen::VectorXd expected = before.eigenvalues().cwiseMax(0.0);
    std::sort(expected.data(), expected.data() + 12);
    for (int i = 0; i < 12; ++i) EXPECT_NEAR(after.eigenvalues()[i], expected[i], 1e-12 * scale);
    EXPECT_LT((projected - projected.transpose()).norm(), 1e-12 * scale);
    // Already PSD: unchanged bit for bit.
    Eigen::Matrix<double, 12, 12, Eigen::RowMajor> psd = a * a.transpose();
    psd.diagonal().array() += 1e-3;  // away from a zero eigenvalue's rounding
    Eigen::Matrix<double, 12, 12, Eigen::RowMajor> kept = psd;
    solver::project_psd(kept.data(), 12);
    EXPECT_EQ(kept, psd);
  }
}

// The cyclic Jacobi projection (contact/psd_jacobi.h, what host and device
// run) against Eigen's: random symmetric matrices, repeated and zero
// eigenvalues, rank-one barrier-like Hessians of large dynamic range, the
// pair Hessians themselves; eigenvalues clamped, PSD input left bit for bit.
TEST(BarrierMath, JacobiProjectionMatchesEigensAndKeepsPsdMatrices) {
  using M = Eigen::Matrix<double, 12, 12, Eigen::RowMajor>;
  std::mt19937_64 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  auto expect_same = [](const M& h, const char* what, int trial) {
    M reference = h, jacobi = h;
    solver::project_psd(reference.data(), 12);
    solver::project_psd_pair(jacobi.data());
    const double scale = std::max(h.norm(), DBL_MIN);
    EXPECT_LT((jacobi - reference).norm(), 1e-12 * scale) << what << " " << trial;
    EXPECT_EQ(jacobi, jacobi.transpose()) << what << " " << trial;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> after(jacobi);
    EXPECT_GE(after.eigenvalues().minCoeff(), -1e-12 * scale) << what << " " << trial;
  };
  for (int trial = 0; trial < 200; ++trial) {
    M a;
    for (int i = 0; i < 144; ++i) a.data()[i] = n(rng);
    expect_same(a + a.transpose(), "random", trial);
    // Repeated eigenvalues: Q diag(-1, -1, -1, 2, 2, 0, ...) Q^T.
    const Eigen::MatrixXd square = a;
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(square);
    const Eigen::MatrixXd q = qr.householderQ();
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(12);
    lambda.head(5) << -1, -1, -1, 2, 2;
    expect_same(M(q * lambda.asDiagonal() * q.transpose()), "repeated", trial);
    // A barrier-like Hessian: b'' g g^T + b' H_d with b'' >> b'.
    Eigen::Matrix<double, 12, 1> g;
    for (int i = 0; i < 12; ++i) g[i] = n(rng);
    const M sym = a + a.transpose();
    expect_same(M(1e8 * g * g.transpose() - 1e-2 * sym), "rank one", trial);
    // PSD: unchanged bit for bit.
    M psd = a * a.transpose();
    psd.diagonal().array() += 1e-3;
    M kept = psd;
    solver::project_psd_pair(kept.data());
    EXPECT_EQ(kept, psd) << trial;
    // The pair Hessians within dhat.
    const Config x = random_config(rng);
    for (int kind = 0; kind < 2; ++kind) {
      int type;
      const double s =
          kind == 0 ? ipc::ipc_pt_distance(x.data(), &type, 0, 0) : ipc::ipc_ee_distance(x.data(), &type, 0, 0);
      const double ex = kind == 1 ? 0.5 * ipc::ipc_edge_cross_squared(x.data(), 0, 0) : 0.0;
      double d, gp[12];
      M h;
      if (kind == 0)
        ipc::ipc_pt_potential(x.data(), 1.2 * s, &d, gp, h.data());
      else
        ipc::ipc_ee_potential(x.data(), 1.2 * s, ex, &d, gp, h.data());
      expect_same(h, kind == 0 ? "point-triangle" : "edge-edge", trial);
    }
  }
  M zero = M::Zero();
  solver::project_psd_pair(zero.data());
  EXPECT_EQ(zero, M::Zero());
}

// Positions at t = 1 of linearly moving vertices that are at `at` when
// t = t_star, with velocities v: x0 = at - t_star v.
void start_from(const Config& at, const Config& v, double t_star, Config& x0) {
  for (int i = 0; i < 12; ++i) x0[i] = at[i] - t_star * v[i];
}

double distance_at(const Config& x0, const Config& v, double t, bool edge_edge) {
  Config x;
  for (int i = 0; i < 12; ++i) x[i] = x0[i] + t * v[i];
  int type;
  return std::sqrt(edge_edge ? ipc::ipc_ee_distance(x.data(), &type, 0, 0)
                             : ipc::ipc_pt_distance(x.data(), &type, 0, 0));
}

TEST(BarrierMath, CcdNeverMissesACrossingNorReportsAnImpactAfterIt) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0), t_of(0.05, 0.95);
  int cases = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const bool edge_edge = trial % 2;
    const int flavour = (trial / 2) % 3;  // 0 generic, 1 glancing (edge, vertex, tangent motion), 2 parallel
    Config at = random_config(rng), v = random_config(rng);
    const double t_star = t_of(rng);
    if (!edge_edge) {
      // The point on the triangle at t_star: inside, or (glancing) on an
      // edge or at a vertex, moving nearly in the triangle's plane.
      double a = unit(rng), b = unit(rng) * (1 - a);
      if (flavour == 1) b = trial % 4 == 1 ? 0.0 : 1.0 - a;
      if (flavour == 2) a = 1.0, b = 0.0;
      for (int k = 0; k < 3; ++k) at[k] = at[3 + k] + a * (at[6 + k] - at[3 + k]) + b * (at[9 + k] - at[3 + k]);
      if (flavour >= 1) {
        double e0[3], e1[3], n[3];
        ipc::ipc_sub3(&at[6], &at[3], e0);
        ipc::ipc_sub3(&at[9], &at[3], e1);
        ipc::ipc_cross3(e0, e1, n);
        const double nn = ipc::ipc_dot3(n, n);
        const double along = (ipc::ipc_dot3(v.data(), n) - ipc::ipc_dot3(&v[3], n)) / nn;
        for (int k = 0; k < 3; ++k) v[k] -= (1.0 - 1e-3) * along * n[k];  // relative motion almost tangent
      }
    } else {
      // Edge b through a point of edge a at t_star; parallel: b along a.
      const double s = flavour == 1 ? 0.0 : unit(rng), u = flavour == 1 ? 1.0 : unit(rng);
      double q[3], dir[3];
      for (int k = 0; k < 3; ++k) {
        q[k] = at[k] + s * (at[3 + k] - at[k]);
        dir[k] = flavour == 2 ? (at[3 + k] - at[k]) * (0.5 + unit(rng)) : at[9 + k];
      }
      if (flavour == 2)
        for (int k = 0; k < 3; ++k) dir[k] = (at[3 + k] - at[k]) * 0.7;
      for (int k = 0; k < 3; ++k) {
        at[6 + k] = q[k] - u * dir[k];
        at[9 + k] = q[k] + (1 - u) * dir[k];
      }
    }
    Config x0;
    start_from(at, v, t_star, x0);
    const double d0 = distance_at(x0, v, 0.0, edge_edge);
    if (!(d0 > 1e-6)) continue;
    ++cases;
    const double toi =
        edge_edge ? ipc::ccd_edge_edge(x0.data(), v.data(), 1.0) : ipc::ccd_point_triangle(x0.data(), v.data(), 1.0);
    ASSERT_LT(toi, 1.0) << "missed crossing, trial " << trial << " flavour " << flavour;
    ASSERT_LE(toi, t_star) << "impact reported after the crossing, trial " << trial;
    ASSERT_GE(toi, 0.0);
    // No contact before toi, and some separation left at it.
    for (int k = 0; k <= 50; ++k) EXPECT_GT(distance_at(x0, v, toi * k / 50.0, edge_edge), 0.0);
    EXPECT_GE(distance_at(x0, v, toi, edge_edge), 0.0999 * d0 - 1e-12);
  }
  EXPECT_GE(cases, 2500);
}

TEST(BarrierMath, CcdClearsMotionsThatStayApart) {
  // A point above a triangle moving parallel to it, and two edges moving
  // apart: no hit, the full step.
  const Config pt = {0.2, 0.2, 0.5, 0, 0, 0, 1, 0, 0, 0, 1, 0};
  const Config slide = {0.5, 0.3, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  EXPECT_EQ(ipc::ccd_point_triangle(pt.data(), slide.data(), 1.0), 1.0);
  const Config ee = {0, 0, 0, 1, 0, 0, 0.5, -0.5, 0.3, 0.5, 0.5, 0.3};
  const Config apart = {0, 0, -1, 0, 0, -1, 0, 0, 1, 0, 0, 1};
  EXPECT_EQ(ipc::ccd_edge_edge(ee.data(), apart.data(), 1.0), 1.0);
  // Head on: impact at t = 0.3 / 2 for the edges closing at 2 per unit time.
  Config closing = apart;
  for (double& c : closing) c = -c;
  const double toi = ipc::ccd_edge_edge(ee.data(), closing.data(), 1.0);
  EXPECT_LT(toi, 0.15);
  EXPECT_GT(toi, 0.1);
}

}  // namespace
}  // namespace snh::test
