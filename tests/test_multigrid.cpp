// The multigrid preconditioner (solver/multigrid/lattice_hierarchy.h, solver/multigrid/multigrid.h):
// the hierarchy on boxes, partly filled and non-box lattices and across a
// slit; the coarse operators against the assembled Galerkin product
// P^T D K D P; the V-cycle's symmetry, positivity and exact zeros on
// constrained DOFs; and whole solves (an affine patch test, the same
// answer as block-Jacobi, bitwise repeatability, clear errors).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include "device/opencl_context.h"
#include "device/viennacl_binding.h"
#include "fem/rest_state.h"
#include "fem/vertex_slots.h"
#include "snh/error.h"
#include "snh/material.h"
#include "snh/mesh.h"
#include "snh/regions.h"
#include "snh/simulation.h"
#include "solver/contact/obstacles.h"
#include "solver/linear/chebyshev.h"
#include "solver/model/block_stencil.h"
#include "solver/model/elastic_model.h"
#include "solver/multigrid/lattice_hierarchy.h"
#include "solver/multigrid/multigrid.h"
#include "solver/newton/device_problem.h"
#include "support/device_test_support.h"
#include "vector_compare.h"
#include "viennacl/vector.hpp"

namespace snh::test {
namespace {

constexpr double kH = 0.25;

// The lattice's cells kept by `keep(i, j, k)`, vertices renumbered densely
// in the order of first use.
template <typename Keep>
Mesh lattice_subset(int nx, int ny, int nz, Keep keep) {
  const Mesh box = make_box_lattice(nx, ny, nz, kH);
  Mesh out;
  out.type = ElementType::hex8;
  std::vector<int> renumber(box.vertex_count(), -1);
  for (size_t e = 0; e < box.element_count(); ++e) {
    const auto x = box.vertex(box.elements[8 * e]);
    const int i = static_cast<int>(std::lround(x[0] / kH)), j = static_cast<int>(std::lround(x[1] / kH)),
              k = static_cast<int>(std::lround(x[2] / kH));
    if (!keep(i, j, k)) continue;
    for (int a = 0; a < 8; ++a) {
      int& v = renumber[box.elements[8 * e + a]];
      if (v < 0) {
        v = static_cast<int>(out.vertex_count());
        out.positions.push_back(box.vertex(box.elements[8 * e + a]));
      }
      out.elements.push_back(v);
    }
  }
  return out;
}

std::vector<char> all_free(const Mesh& mesh) { return std::vector<char>(3 * mesh.vertex_count(), 1); }

// Positions of a level's vertices in units of the finest spacing, from its
// cells (corner offsets of VTK order).
std::vector<Eigen::Vector3d> level_positions(const solver::LatticeLevel& level, int level_index) {
  static const int bits[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                 {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const double scale = std::pow(2.0, level_index);
  std::vector<Eigen::Vector3d> out(level.vertex_count, Eigen::Vector3d::Constant(NAN));
  for (size_t c = 0; c < level.cells.size(); ++c)
    for (int a = 0; a < 8; ++a)
      for (int d = 0; d < 3; ++d) out[level.elements[8 * c + a]][d] = scale * (level.cells[c][d] + bits[a][d]);
  return out;
}

// Prolongation of an affine field from level l + 1 reproduces it on level l.
void expect_affine_prolongation(const solver::LatticeHierarchy& h) {
  const Eigen::Vector3d g(0.3, -1.7, 2.2);
  for (size_t l = 0; l + 1 < h.levels.size(); ++l) {
    const auto fine = level_positions(h.levels[l], static_cast<int>(l));
    const auto coarse = level_positions(h.levels[l + 1], static_cast<int>(l + 1));
    for (size_t v = 0; v < h.levels[l].vertex_count; ++v) {
      double value = 0.0, weight = 0.0;
      for (int k = 0; k < 8; ++k) {
        const double w = h.levels[l].prolongation_weights[8 * v + k];
        value += w * (0.5 + g.dot(coarse[h.levels[l].prolongation_vertices[8 * v + k]]));
        weight += w;
      }
      ASSERT_NEAR(weight, 1.0, 1e-15) << "level " << l << " vertex " << v;
      ASSERT_NEAR(value, 0.5 + g.dot(fine[v]), 1e-12) << "level " << l << " vertex " << v;
    }
  }
}

// solver/linear/chebyshev.h: the steps' residual factors p(t) are the polynomials
// each kind is defined by, checked on a fine sampling of the spectrum
// (lambda = 2: upper = 2.2, lower = 0.2).
double sampled_max(const solver::ChebyshevSteps& steps, double from, double to, bool weighted, double upper) {
  double worst = 0.0;
  constexpr int kSamples = 200000;
  for (int i = 0; i <= kSamples; ++i) {
    const double t = from + (to - from) * i / kSamples;
    const double p = std::abs(solver::chebyshev_residual_factor(steps, t));
    worst = std::max(worst, weighted ? std::sqrt(t / upper) * p : p);
  }
  return worst;
}

TEST(Chebyshev, FirstKindIsTheMinimaxPolynomialOnItsInterval) {
  const double lambda = 2.0, upper = 2.2, lower = 0.2;
  for (int degree = 1; degree <= 6; ++degree) {
    const solver::ChebyshevSteps steps = solver::chebyshev_steps(ChebyshevKind::first, degree, lambda);
    EXPECT_EQ(solver::chebyshev_residual_factor(steps, 0.0), 1.0);
    // max |p| on [lower, upper] = 1 / T_k((upper + lower) / (upper - lower)).
    const double bound = 1.0 / std::cosh(degree * std::acosh((upper + lower) / (upper - lower)));
    EXPECT_NEAR(sampled_max(steps, lower, upper, false, upper), bound, 1e-9 * bound) << "degree " << degree;
    for (double beta : steps.beta) EXPECT_EQ(beta, 1.0);
  }
}

// The coarsest level's polynomial solve (coarse_solve_on_device): the first
// kind on a wide interval [upper / 60, upper], the minimax factor there, and
// 0 < p(t) < 1 on (0, lower), so the solve is positive on every eigenvalue
// up to upper.
TEST(Chebyshev, IntervalStepsAreTheMinimaxPolynomialAndPositiveBelow) {
  const double upper = 2.2, lower = upper / 60.0;
  for (int degree : {1, 4, 8, 12}) {
    const solver::ChebyshevSteps steps = solver::chebyshev_interval_steps(degree, lower, upper);
    EXPECT_EQ(solver::chebyshev_residual_factor(steps, 0.0), 1.0);
    const double bound = 1.0 / std::cosh(degree * std::acosh((upper + lower) / (upper - lower)));
    EXPECT_NEAR(sampled_max(steps, lower, upper, false, upper), bound, 1e-8 * bound) << "degree " << degree;
    for (int i = 1; i <= 1000; ++i) {
      const double t = lower * i / 1000.0, p = solver::chebyshev_residual_factor(steps, t);
      EXPECT_GT(p, 0.0) << "degree " << degree << " t " << t;
      EXPECT_LT(p, 1.0) << "degree " << degree << " t " << t;
    }
  }
  // The first kind's smoothing steps are these on [0.1, 1.1] lambda.
  const solver::ChebyshevSteps a = solver::chebyshev_steps(ChebyshevKind::first, 3, 2.0);
  const solver::ChebyshevSteps b = solver::chebyshev_interval_steps(3, 0.1 * 2.0, 1.1 * 2.0);
  EXPECT_EQ(a.c_d, b.c_d);
  EXPECT_EQ(a.c_z, b.c_z);
  EXPECT_THROW(solver::chebyshev_interval_steps(0, 0.1, 1.0), Error);
  EXPECT_THROW(solver::chebyshev_interval_steps(2, 0.0, 1.0), Error);
  EXPECT_THROW(solver::chebyshev_interval_steps(2, 1.0, 1.0), Error);
}

TEST(Chebyshev, FourthKindReachesLottesBoundWithoutALowerBound) {
  const double lambda = 2.0, upper = 2.2;
  for (int degree = 1; degree <= 6; ++degree) {
    const solver::ChebyshevSteps steps = solver::chebyshev_steps(ChebyshevKind::fourth, degree, lambda);
    EXPECT_EQ(solver::chebyshev_residual_factor(steps, 0.0), 1.0);
    // max over (0, upper] of sqrt(t / upper) |p(t)| = 1 / (2 degree + 1).
    EXPECT_NEAR(sampled_max(steps, 0.0, upper, true, upper), 1.0 / (2 * degree + 1), 1e-7) << "degree " << degree;
    EXPECT_LE(sampled_max(steps, 0.0, upper, false, upper), 1.0 + 1e-12);
  }
}

TEST(Chebyshev, OptimizedFourthKindNeverAmplifiesUpToItsBound) {
  const double lambda = 2.0, upper = 2.2;
  for (int degree = 1; degree <= 4; ++degree) {
    const solver::ChebyshevSteps steps = solver::chebyshev_steps(ChebyshevKind::optimized_fourth, degree, lambda);
    EXPECT_EQ(solver::chebyshev_residual_factor(steps, 0.0), 1.0);
    EXPECT_LE(sampled_max(steps, 0.0, upper, false, upper), 1.0 + 1e-12) << "degree " << degree;
    // Lottes' weights optimize his V-cycle bound, not the sqrt(t) measure
    // the plain fourth kind is optimal for: the table is not that kind again.
    const solver::ChebyshevSteps plain = solver::chebyshev_steps(ChebyshevKind::fourth, degree, lambda);
    EXPECT_GT(sampled_max(steps, 0.0, upper, true, upper), sampled_max(plain, 0.0, upper, true, upper));
  }
  // Degree 1 is damped Jacobi with weight 1.125 * 4 / 3 / upper.
  EXPECT_NEAR(
      solver::chebyshev_residual_factor(solver::chebyshev_steps(ChebyshevKind::optimized_fourth, 1, lambda), upper),
      1.0 - 1.5, 1e-15);
  EXPECT_THROW(solver::chebyshev_steps(ChebyshevKind::optimized_fourth, 5, lambda), Error);
  EXPECT_THROW(solver::chebyshev_steps(ChebyshevKind::first, 0, lambda), Error);
}

TEST(LatticeHierarchy, BoxCoarsensByTwoAndProlongsAffineFieldsExactly) {
  const Mesh mesh = make_box_lattice(8, 8, 8, kH);
  const solver::LatticeHierarchy h = solver::build_lattice_hierarchy(mesh, all_free(mesh), 1, 10);
  ASSERT_EQ(h.levels.size(), 4u);  // 8^3, 4^3, 2^3, 1 cell
  EXPECT_EQ(h.levels[1].cells.size(), 64u);
  EXPECT_EQ(h.levels[1].vertex_count, 125u);
  EXPECT_EQ(h.levels[3].cells.size(), 1u);
  EXPECT_EQ(h.levels[3].vertex_count, 8u);
  expect_affine_prolongation(h);
  // The restriction lists are the prolongation's transpose.
  const solver::LatticeLevel& f = h.levels[0];
  double forward = 0.0, backward = 0.0;
  for (size_t v = 0; v < f.vertex_count; ++v)
    for (int k = 0; k < 8; ++k)
      forward += f.prolongation_weights[8 * v + k] * (1 + v % 7) * (1 + f.prolongation_vertices[8 * v + k] % 5);
  for (size_t c = 0; c < h.levels[1].vertex_count; ++c)
    for (int k = f.restriction_offsets[c]; k < f.restriction_offsets[c + 1]; ++k)
      backward += f.restriction_weights[k] * (1 + f.restriction_vertices[k] % 7) * (1 + c % 5);
  EXPECT_NEAR(forward, backward, 1e-9 * forward);
}

TEST(LatticeHierarchy, PartlyFilledAndNonBoxLatticesKeepTheirCells) {
  // 5 x 3 x 7 cells: odd sizes leave coarse cells partly filled.
  const Mesh odd = make_box_lattice(5, 3, 7, kH);
  const solver::LatticeHierarchy a = solver::build_lattice_hierarchy(odd, all_free(odd), 1, 10);
  EXPECT_EQ(a.levels[1].cells.size(), 3u * 2u * 4u);
  expect_affine_prolongation(a);
  // An L shape with a hole.
  const Mesh l_shape =
      lattice_subset(8, 8, 4, [](int i, int j, int k) { return (i < 3 || j < 3) && !(i == 1 && j == 1 && k == 2); });
  const solver::LatticeHierarchy b = solver::build_lattice_hierarchy(l_shape, all_free(l_shape), 1, 10);
  ASSERT_GE(b.levels.size(), 3u);
  expect_affine_prolongation(b);
  // Every fine cell has its parent; every coarse cell at least one child.
  for (size_t l = 1; l < b.levels.size(); ++l) {
    std::vector<int> seen(b.levels[l - 1].cells.size(), 0);
    for (size_t c = 0; c < b.levels[l].cells.size(); ++c) {
      int children = 0;
      for (int o = 0; o < 8; ++o)
        if (int child = b.levels[l].children[8 * c + o]; child >= 0) ++seen[child], ++children;
      EXPECT_GT(children, 0);
    }
    for (int s : seen) EXPECT_EQ(s, 1);
  }
}

// Two 4x2x4 slabs stacked in y; for x >= 2 the vertices between them are
// duplicated (a slit, as the voxelizer leaves across a thin gap). duplicate:
// per original vertex its copy, or -1.
Mesh slit_lattice(std::vector<int>* duplicate_out = nullptr) {
  Mesh mesh = make_box_lattice(4, 2, 4, kH);
  std::vector<int> duplicate(mesh.vertex_count(), -1);
  for (size_t e = 0; e < mesh.element_count(); ++e) {
    const auto x0 = mesh.vertex(mesh.elements[8 * e]);
    if (std::lround(x0[1] / kH) != 1) continue;  // upper slab's cells
    for (int a = 0; a < 8; ++a) {
      const int v = mesh.elements[8 * e + a];
      const auto x = mesh.vertex(v);
      if (std::lround(x[1] / kH) != 1 || x[0] < 2 * kH - 1e-9) continue;  // on the slit plane, x >= 2h
      if (duplicate[v] < 0) {
        duplicate[v] = static_cast<int>(mesh.vertex_count());
        mesh.positions.push_back(x);
      }
      mesh.elements[8 * e + a] = duplicate[v];
    }
  }
  if (duplicate_out) *duplicate_out = duplicate;
  return mesh;
}

TEST(LatticeHierarchy, SlitIsNotGluedOnCoarseLevels) {
  std::vector<int> duplicate;
  const Mesh mesh = slit_lattice(&duplicate);
  const solver::LatticeHierarchy h = solver::build_lattice_hierarchy(mesh, all_free(mesh), 1, 2);
  ASSERT_EQ(h.levels.size(), 2u);
  // The parents at x = 1 (fine x 2..3) hold two unconnected groups each.
  EXPECT_EQ(h.levels[1].cells.size(), 2u * 1u * 2u + 2u);
  // A vertex below the slit and its copy above prolong from different
  // coarse vertices at the same point.
  for (size_t v = 0; v < duplicate.size(); ++v) {
    if (duplicate[v] < 0) continue;
    const auto x = mesh.vertex(v);
    if (std::abs(x[0] - 4 * kH) > 1e-9 || std::lround(x[2] / kH) % 2 != 0) continue;  // a coarse lattice point
    const auto& p = h.levels[0].prolongation_vertices;
    const auto& w = h.levels[0].prolongation_weights;
    for (int k = 0; k < 8; ++k) {
      EXPECT_EQ(w[8 * v + k], w[8 * duplicate[v] + k]);
      if (w[8 * v + k] > 0.0) {
        EXPECT_NE(p[8 * v + k], p[8 * duplicate[v] + k]);
      }
    }
  }
  expect_affine_prolongation(h);
}

TEST(LatticeHierarchy, CoarseMasksKeepDofsThatReachFreeOnes) {
  const Mesh mesh = make_box_lattice(4, 4, 4, kH);
  std::vector<char> mask(3 * mesh.vertex_count(), 1);
  for (size_t v = 0; v < mesh.vertex_count(); ++v) mask[3 * v] = 0;  // every x component fixed
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    if (mesh.positions(v, 2) < 1e-9) mask[3 * v + 1] = mask[3 * v + 2] = 0;  // bottom face fixed
  const solver::LatticeHierarchy h = solver::build_lattice_hierarchy(mesh, mask, 1, 10);
  for (size_t l = 1; l < h.levels.size(); ++l)
    for (size_t v = 0; v < h.levels[l].vertex_count; ++v) {
      EXPECT_EQ(h.levels[l].mask[3 * v], 0) << "x DOFs reach no free DOF";
      EXPECT_EQ(h.levels[l].mask[3 * v + 1], 1) << "y DOFs reach free DOFs above the bottom";
    }
}

TEST(LatticeHierarchy, RefusesMeshesThatAreNotLattices) {
  const Mesh tets = make_tet_box(2, 2, 2, kH);
  EXPECT_THROW(solver::build_lattice_hierarchy(tets, all_free(tets), 1, 10), Error);
  Mesh jittered = make_box_lattice(2, 2, 2, kH);
  jittered.positions(13, 0) += 0.05 * kH;
  EXPECT_FALSE(solver::is_hex8_lattice(jittered));
  try {
    solver::build_lattice_hierarchy(jittered, all_free(jittered), 1, 10);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not a hex8 lattice"), std::string::npos) << e.what();
  }
}

// --- on the device ------------------------------------------------------------

// A deformed, partly constrained L-shaped lattice at nu = 0.45.
struct DeviceCase {
  Mesh mesh = lattice_subset(6, 5, 4, [](int i, int j, int) { return i < 3 || j < 2; });
  fem::RestState rest = fem::compute_rest_state(mesh);
  Material material = Material::from_youngs_modulus(MaterialModel::stable_neo_hookean, 1.0, 0.45);
  std::vector<double> x;
  std::vector<char> mask;
  DeviceCase() {
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> u(-0.15 * kH, 0.15 * kH);
    x = mesh.positions.xyz();
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
      const double px = mesh.positions(v, 0), pz = mesh.positions(v, 2);
      x[3 * v] = px + 0.3 * pz * px + u(rng);  // a bend plus noise
      x[3 * v + 1] += u(rng);
      x[3 * v + 2] = pz * 1.1 + u(rng);
    }
    mask.assign(3 * mesh.vertex_count(), 1);
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
      if (mesh.positions(v, 2) < 1e-9) mask[3 * v] = mask[3 * v + 1] = mask[3 * v + 2] = 0;
      if (mesh.positions(v, 0) < 1e-9) mask[3 * v] = 0;  // a sliding face
    }
  }
};

// DeviceCase's built-fine-level multigrid options (coarsest level at 50 DOFs),
// the V-cycle in double unless float_cycle.
MultigridOptions built_fine_level(bool fine_level_float, bool float_cycle = false) {
  MultigridOptions options;
  options.coarsest_dofs = 50;
  options.fine_level = MultigridFineLevel::built;
  options.fine_level_float = fine_level_float;
  options.float_cycle = float_cycle;
  return options;
}

// DeviceCase's model (cached product) with its constraint mask set.
std::unique_ptr<solver::ElasticModel<double>> masked_model(const DeviceCase& c) {
  auto model = std::make_unique<solver::ElasticModel<double>>(
      device_for(Precision::double_), c.mesh, c.rest, uniform_material(c.mesh, c.material), ProductVariant::cached);
  model->set_mask(std::vector<double>(c.mask.begin(), c.mask.end()));
  return model;
}

// The device's coarse cell matrices, assembled, against P^T D A D P with A
// the fine operator column by column through the (unmasked) matrix-free
// product, two levels deep.
void expect_galerkin_coarse_operators(solver::ElasticModel<double>& model,
                                      const solver::MultigridPreconditioner<double>& mg, const Mesh& mesh) {
  const size_t n = 3 * mesh.vertex_count();
  Eigen::MatrixXd k(n, n);
  viennacl::vector<double> y(n);
  for (size_t j = 0; j < n; ++j) {
    std::vector<double> e(n, 0.0);
    e[j] = 1.0;
    model.product(upload<double>(e), y);
    const std::vector<double> column = download(y);
    for (size_t i = 0; i < n; ++i) k(i, j) = column[i];
  }
  Eigen::MatrixXd a = k;
  const solver::LatticeHierarchy& h = mg.hierarchy();
  for (int l = 1; l < 3; ++l) {
    const solver::LatticeLevel& fine = h.levels[l - 1];
    const size_t nf = 3 * fine.vertex_count, nc = 3 * h.levels[l].vertex_count;
    Eigen::MatrixXd p = Eigen::MatrixXd::Zero(nf, nc);
    for (size_t v = 0; v < fine.vertex_count; ++v)
      for (int s = 0; s < 8; ++s)
        for (int d = 0; d < 3; ++d)
          p(3 * v + d, 3 * fine.prolongation_vertices[8 * v + s] + d) += fine.prolongation_weights[8 * v + s];
    Eigen::VectorXd dmask(nf);
    for (size_t i = 0; i < nf; ++i) dmask[i] = fine.mask[i];
    const Eigen::MatrixXd dp = dmask.asDiagonal() * p;
    const Eigen::MatrixXd expected = dp.transpose() * a * dp;
    // The device's cell matrices, assembled.
    const std::vector<double> cells = mg.level_matrices(l);
    const solver::LatticeLevel& coarse = h.levels[l];
    Eigen::MatrixXd assembled = Eigen::MatrixXd::Zero(nc, nc);
    for (size_t cell = 0; cell < coarse.cells.size(); ++cell)
      for (int col = 0; col < 24; ++col)
        for (int row = 0; row < 24; ++row)
          assembled(3 * coarse.elements[8 * cell + row / 3] + row % 3,
                    3 * coarse.elements[8 * cell + col / 3] + col % 3) += cells[576 * cell + 24 * col + row];
    const double error = (assembled - expected).norm() / expected.norm();
    EXPECT_LT(error, 1e-12) << "level " << l;
    // Each cell matrix exactly symmetric (its lower triangle mirrored): the
    // two triangles' sums round differently.
    size_t asymmetric = 0;
    for (size_t cell = 0; cell < coarse.cells.size(); ++cell)
      for (int col = 0; col < 24; ++col)
        for (int row = col + 1; row < 24; ++row)
          asymmetric += cells[576 * cell + 24 * col + row] != cells[576 * cell + 24 * row + col];
    EXPECT_EQ(asymmetric, 0u) << "level " << l << ": entries unequal to their mirror";
    std::printf("level %d: %zu DOFs, |A_device - P^T D A D P| / |P^T D A D P| = %.2e\n", l, nc, error);
    a = expected;
  }
}

// From the linearization cache (cached variant) and from the fine element
// matrices (element-matrices variant), exactly symmetric, projected and true Hessian, with
// each layout of the per-point data (value-major, the CPUs' default;
// point-major; tiled, the GPUs' default).
class CoarseOperator : public ::testing::TestWithParam<std::tuple<ProductVariant, bool, solver::PointDataLayout>> {};

TEST_P(CoarseOperator, IsTheAssembledGalerkinProduct) {
  const auto [variant, projected, layout] = GetParam();
  DeviceCase c;
  device::OpenClContext& cl = device_for(Precision::double_);
  solver::ModelTerms terms;
  terms.hex8_point_data = layout;
  solver::ElasticModel<double> model(cl, c.mesh, c.rest, uniform_material(c.mesh, c.material), variant,
                                     device::MaterialKernel::specialized, terms);
  MultigridOptions options;
  options.coarsest_dofs = 1;
  options.fine_level_float = false;  // the exact Galerkin product (float: FloatFineLevel... below)
  solver::MultigridPreconditioner<double> mg(model, c.mesh, c.mask, options);
  ASSERT_GE(mg.levels(), 3);
  const viennacl::vector<double> x = upload<double>(c.x);
  model.linearize(x, projected);
  model.setup_preconditioner();
  mg.setup();
  expect_galerkin_coarse_operators(model, mg, c.mesh);
}

INSTANTIATE_TEST_SUITE_P(Multigrid, CoarseOperator,
                         ::testing::Combine(::testing::Values(ProductVariant::cached, ProductVariant::element_matrices),
                                            ::testing::Bool(),
                                            ::testing::Values(solver::PointDataLayout::value_major,
                                                              solver::PointDataLayout::point_major,
                                                              solver::PointDataLayout::tiled)));

// With implicit Euler's inertia (and its elastic scale) and a rough obstacle
// pressing into the top, the first coarse level carries their per-vertex
// blocks (inertia, contact, friction) too: still exactly P^T D A D P of the
// operator CG solves with.
TEST(Multigrid, CoarseOperatorsCarryInertiaAndContact) {
  DeviceCase c;
  double top = 0.0;
  for (size_t v = 0; v < c.mesh.vertex_count(); ++v) top = std::max(top, c.x[3 * v + 2]);
  Obstacle lid;
  lid.type = ObstacleType::plane;
  lid.point = {0.0, 0.0, top - 0.5 * kH};
  lid.direction = {0.0, 0.0, -1.0};
  lid.friction = 0.5;
  solver::ModelTerms terms;
  terms.inertia = true;
  terms.obstacles = 1;
  terms.friction = true;
  for (ProductVariant variant : {ProductVariant::cached, ProductVariant::element_matrices}) {
    solver::ElasticModel<double> model(device_for(Precision::double_), c.mesh, c.rest,
                                       uniform_material(c.mesh, c.material), variant,
                                       device::MaterialKernel::specialized, terms);
    std::vector<double> coefficient(c.mesh.vertex_count());
    for (size_t v = 0; v < coefficient.size(); ++v) coefficient[v] = 2.0 + 0.1 * static_cast<double>(v % 7);
    model.set_inertia(coefficient, c.x, 0.3);
    const std::vector<double> records = solver::obstacle_records({lid}, 0.0);
    model.contact().set_obstacles(records, 10.0, 0.1 * kH);
    // The step started at the rest positions with its anchors there: the
    // pressed vertices have slid since, so their friction blocks are not zero.
    model.contact().set_friction(c.mesh.positions.xyz(), c.mesh.positions.xyz(), records,
                                 solver::friction_records({lid}, ContactOptions{}, 0.0, 0.0), 0.01 * kH);
    MultigridOptions options;
    options.coarsest_dofs = 1;
    options.fine_level = MultigridFineLevel::built;  // carries no per-vertex blocks: refused by name
    try {
      solver::MultigridPreconditioner<double> refused(model, c.mesh, c.mask, options);
      ADD_FAILURE() << "a built fine level with inertia and contact was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("fine_level"), std::string::npos) << e.what();
    }
    options.fine_level.reset();
    solver::MultigridPreconditioner<double> mg(model, c.mesh, c.mask, options);
    EXPECT_FALSE(mg.fine_level_built());  // unset: the model's operator, which has them
    ASSERT_GE(mg.levels(), 3);
    const viennacl::vector<double> x = upload<double>(c.x);
    ASSERT_GT(model.contact().contact_state(x).contacts, 4);
    model.linearize(x, true);
    model.setup_preconditioner();
    mg.setup();
    expect_galerkin_coarse_operators(model, mg, c.mesh);
  }
}

// With obstacles a hierarchy is not reused across a change of the set of
// vertices in contact (whose contact blocks it lacks: a squash then crawled,
// docs/performance.md), nor, with friction, into a new step (its normal forces
// are re-lagged); with the set unchanged it is.
TEST(Multigrid, ContactSetChangeRebuildsTheHierarchy) {
  DeviceCase c;
  double top = 0.0;
  for (size_t v = 0; v < c.mesh.vertex_count(); ++v) top = std::max(top, c.x[3 * v + 2]);
  const double thickness = 0.1 * kH;
  auto lid_at = [&](double z) {
    Obstacle lid;
    lid.type = ObstacleType::plane;
    lid.point = {0.0, 0.0, z};
    lid.direction = {0.0, 0.0, -1.0};
    lid.friction = 0.5;
    return lid;
  };
  for (bool friction : {false, true}) {
    SCOPED_TRACE(friction ? "friction" : "frictionless");
    solver::ModelTerms terms;
    terms.obstacles = 1;
    terms.friction = friction;
    solver::ElasticModel<double> model(device_for(Precision::double_), c.mesh, c.rest,
                                       uniform_material(c.mesh, c.material), ProductVariant::cached,
                                       device::MaterialKernel::specialized, terms);
    model.set_mask(std::vector<double>(c.mask.begin(), c.mask.end()));
    auto place = [&](double z) {
      const std::vector<double> records = solver::obstacle_records({lid_at(z)}, 0.0);
      model.contact().set_obstacles(records, 10.0, thickness);
      if (friction)
        model.contact().set_friction(c.x, c.x, records,
                                     solver::friction_records({lid_at(z)}, ContactOptions{}, 0.0, 0.0), 0.01 * kH);
    };
    MultigridOptions options;
    options.coarsest_dofs = 1;
    options.rebuild_every = 8;
    options.rebuild_each_load_step = false;
    solver::DeviceProblem<double> problem(
        model, Preconditioner::multigrid,
        std::make_unique<solver::MultigridPreconditioner<double>>(model, c.mesh, c.mask, options));
    const viennacl::vector<double> x = upload<double>(c.x);
    place(top + 2.0 * thickness);  // clear of the body
    ASSERT_EQ(model.contact().contact_state(x).contacts, 0);
    problem.linearize(x, true);
    problem.linearize(x, true);
    EXPECT_EQ(problem.preconditioner_builds(), 1);  // reused: nothing changed
    place(top - 0.5 * kH);                          // the top layer in contact
    ASSERT_GT(model.contact().contact_state(x).contacts, 4);
    problem.linearize(x, true);
    EXPECT_EQ(problem.preconditioner_builds(), 2);  // the set changed
    problem.linearize(x, true);
    EXPECT_EQ(problem.preconditioner_builds(), 2);  // the same set
    problem.refresh(x, true);                       // a new step
    problem.linearize(x, true);
    EXPECT_EQ(problem.preconditioner_builds(), friction ? 3 : 2);
  }
}

TEST(Multigrid, VCycleIsSymmetricPositiveAndKeepsConstrainedDofsZero) {
  DeviceCase c;
  const std::unique_ptr<solver::ElasticModel<double>> owned = masked_model(c);
  solver::ElasticModel<double>& model = *owned;
  const std::vector<double> mask(c.mask.begin(), c.mask.end());
  struct Smoothing {
    int degree;
    ChebyshevKind kind;
    MultigridFineLevel fine;
  };
  for (const Smoothing& smoothing : {Smoothing{1, ChebyshevKind::first, MultigridFineLevel::built},
                                     Smoothing{3, ChebyshevKind::first, MultigridFineLevel::built},
                                     Smoothing{2, ChebyshevKind::fourth, MultigridFineLevel::built},
                                     Smoothing{3, ChebyshevKind::optimized_fourth, MultigridFineLevel::built},
                                     Smoothing{2, ChebyshevKind::optimized_fourth, MultigridFineLevel::current}})
    for (bool float_cycle : {false, true})
      for (bool device_coarse : {false, true}) {
        const int degree = smoothing.degree;
        SCOPED_TRACE(std::string(to_string(smoothing.kind)) + " " + to_string(smoothing.fine) +
                     (float_cycle ? " float cycle" : "") + (device_coarse ? " coarsest solve on the device" : ""));
        MultigridOptions options;
        options.coarsest_dofs = 50;
        options.smoother_degree = degree;
        options.chebyshev_kind = smoothing.kind;
        options.fine_level = smoothing.fine;
        options.float_cycle = float_cycle;
        options.coarse_solve_on_device = device_coarse;
        solver::MultigridPreconditioner<double> mg(model, c.mesh, c.mask, options);
        // A float cycle needs a built fine level; a current one keeps double.
        ASSERT_EQ(mg.float_cycle(), float_cycle && smoothing.fine == MultigridFineLevel::built);
        model.linearize(upload<double>(c.x), true);
        model.setup_preconditioner();
        mg.setup();
        const auto [a, b] = masked_random_pair(mask, 7);
        viennacl::vector<double> ma = upload<double>(a), mb = upload<double>(b);
        mg.apply(ma);
        mg.apply(mb);
        SCOPED_TRACE("degree " + std::to_string(degree));
        // Double: exactly symmetric to the sums' rounding. A float cycle: to
        // float's rounding of its vectors and stencils (measured 3e-8).
        expect_symmetric_positive(mask, a, b, download(ma), download(mb), mg.float_cycle() ? 1e-6 : 1e-12);
      }
}

// MultigridOptions::fine_level: right after a build, the V-cycle over the
// build's element matrices (built) is the V-cycle over the model's product
// (current) up to rounding. After a new projected linearization without a
// build (projected or not) the built one is bitwise the V-cycle of the
// build, still symmetric, while the current one follows the new operator.
TEST(Multigrid, BuiltFineLevelIsTheBuildsOperatorUntilTheNextBuild) {
  DeviceCase c;
  const std::unique_ptr<solver::ElasticModel<double>> owned = masked_model(c);
  solver::ElasticModel<double>& model = *owned;
  const std::vector<double> mask(c.mask.begin(), c.mask.end());
  MultigridOptions options = built_fine_level(false);  // the same matrices as the model's, to rounding
  solver::MultigridPreconditioner<double> built(model, c.mesh, c.mask, options);
  options.fine_level = MultigridFineLevel::current;
  solver::MultigridPreconditioner<double> current(model, c.mesh, c.mask, options);
  ASSERT_TRUE(built.fine_level_built());
  ASSERT_FALSE(current.fine_level_built());
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> a(mask.size()), b(mask.size());
  for (size_t i = 0; i < mask.size(); ++i) {
    a[i] = mask[i] * u(rng);
    b[i] = mask[i] * u(rng);
  }
  auto apply = [&](const solver::MultigridPreconditioner<double>& mg, const std::vector<double>& v) {
    viennacl::vector<double> z = upload<double>(v);
    mg.apply(z);
    return download(z);
  };
  model.linearize(upload<double>(c.x), true);
  model.setup_preconditioner();
  built.setup();
  current.setup();
  const std::vector<double> built_a = apply(built, a), current_a = apply(current, a);
  EXPECT_LT(relative_difference(built_a, current_a), 1e-10);

  // A different deformation, linearized without a build (a reused hierarchy).
  std::vector<double> moved = c.x;
  for (size_t v = 0; v < c.mesh.vertex_count(); ++v) moved[3 * v + 2] += 0.2 * c.mesh.positions(v, 2);
  model.linearize(upload<double>(moved), true);
  built.update_fine_bound();
  current.update_fine_bound();
  EXPECT_EQ(apply(built, a), built_a);
  EXPECT_GT(relative_difference(apply(current, a), current_a), 1e-3);
  expect_symmetric_positive(mask, a, b, apply(built, a), apply(built, b), 1e-12);

  // A true-Hessian linearization (adaptive mode) keeps it too.
  model.linearize(upload<double>(moved), false);
  built.update_fine_bound();
  EXPECT_EQ(apply(built, a), built_a);
}

// Every smoothed level applies its operator from blocks assembled per vertex
// (snh_stencil_assemble): the product must be D (sum of the level's cell
// matrices) p, also across a slit, where a vertex has two neighbours at one
// lattice offset (more than 27 blocks a vertex), and exactly symmetric blocks
// in float.
TEST(Multigrid, AssembledLevelOperatorsAreTheirCellMatrices) {
  std::vector<int> duplicate;
  const Mesh slit = slit_lattice(&duplicate);
  ASSERT_GT(fem::vertex_neighbours(slit.elements, slit.vertex_count(), 8).width, 27);
  DeviceCase c;
  for (const Mesh* mesh : {static_cast<const Mesh*>(&c.mesh), &slit}) {
    const fem::RestState rest = fem::compute_rest_state(*mesh);
    std::vector<char> mask(3 * mesh->vertex_count(), 1);
    for (size_t v = 0; v < mesh->vertex_count(); ++v)
      if (mesh->positions(v, 2) < 1e-9) mask[3 * v] = mask[3 * v + 1] = mask[3 * v + 2] = 0;
    std::vector<double> x = mesh->positions.xyz();
    for (size_t v = 0; v < mesh->vertex_count(); ++v) x[3 * v] += 0.2 * mesh->positions(v, 2) * x[3 * v + 1];
    solver::ElasticModel<double> model(device_for(Precision::double_), *mesh, rest, uniform_material(*mesh, c.material),
                                       ProductVariant::cached);
    model.set_mask(std::vector<double>(mask.begin(), mask.end()));
    for (const auto& [narrow, float_cycle] : {std::pair{false, false}, {true, false}, {true, true}}) {
      MultigridOptions options = built_fine_level(narrow, float_cycle);
      options.coarsest_dofs = 1;
      solver::MultigridPreconditioner<double> mg(model, *mesh, mask, options);
      ASSERT_GE(mg.levels(), 3);
      model.linearize(upload<double>(x), true);
      mg.setup();
      std::mt19937_64 rng(3);
      std::uniform_real_distribution<double> u(-1.0, 1.0);
      for (int l = 0; l + 1 < mg.levels(); ++l) {
        const solver::LatticeLevel& level = mg.hierarchy().levels[l];
        const size_t n = 3 * level.vertex_count;
        const std::vector<double> cells = mg.level_matrices(l);
        std::vector<double> p(n), expected(n, 0.0);
        for (double& value : p) value = u(rng);
        for (size_t cell = 0; cell < level.cells.size(); ++cell)
          for (int col = 0; col < 24; ++col)
            for (int row = 0; row < 24; ++row)
              expected[3 * level.elements[8 * cell + row / 3] + row % 3] +=
                  cells[576 * cell + 24 * col + row] * p[3 * level.elements[8 * cell + col / 3] + col % 3];
        for (size_t i = 0; i < n; ++i) expected[i] *= level.mask[i];
        viennacl::vector<double> y(n);
        mg.level_product(l, upload<double>(p), y);
        // Double: rounding only. Float fine level: the float rounding of the
        // assembled blocks (the cells' are float already). Float cycle: every
        // level's blocks and products in float.
        const double bound = (l == 0 && narrow) || float_cycle ? 1e-6 : 1e-14;
        EXPECT_LT(relative_difference(download(y), expected), bound)
            << "level " << l << " float " << narrow << " cycle " << float_cycle;
        if (l > 0 || !narrow) continue;
        // Exact symmetry: a.(A b) and b.(A a) on the free DOFs agree to the
        // products' rounding in double (a float cycle: in float).
        std::vector<double> a(n), b(n);
        for (size_t i = 0; i < n; ++i) {
          a[i] = level.mask[i] * u(rng);
          b[i] = level.mask[i] * u(rng);
        }
        viennacl::vector<double> ya(n), yb(n);
        mg.level_product(0, upload<double>(a), ya);
        mg.level_product(0, upload<double>(b), yb);
        const std::vector<double> aa = download(ya), bb = download(yb);
        double ab = 0.0, ba = 0.0, scale = 0.0;
        for (size_t i = 0; i < n; ++i) {
          ab += a[i] * bb[i];
          ba += b[i] * aa[i];
          scale += std::abs(a[i] * bb[i]);
        }
        EXPECT_LT(std::abs(ab - ba), (float_cycle ? 1e-6 : 1e-14) * scale);
      }
    }
  }
}

// Two preconditioners applied to one vector, random on the free DOFs.
std::pair<std::vector<double>, std::vector<double>> apply_both(const solver::MultigridPreconditioner<double>& first,
                                                               const solver::MultigridPreconditioner<double>& second,
                                                               const std::vector<double>& mask, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> a(mask.size());
  for (size_t i = 0; i < mask.size(); ++i) a[i] = mask[i] * u(rng);
  viennacl::vector<double> z1 = upload<double>(a), z2 = upload<double>(a);
  first.apply(z1);
  second.apply(z2);
  return {download(z1), download(z2)};
}

// MultigridOptions::fine_level_float (the default in double): the built fine
// level's matrices in float are half the bytes, exactly symmetric (so the
// V-cycle stays symmetric: VCycleIsSymmetricPositiveAndKeepsConstrainedDofsZero
// runs with it), and change the V-cycle and the first coarse operator only
// at float's rounding of the matrices: within 1e-5 of the double fine
// level's (1e-6 for the coarse cells, relative to their norm).
TEST(Multigrid, FloatFineLevelHalvesItsMatricesAndStaysClose) {
  DeviceCase c;
  const std::unique_ptr<solver::ElasticModel<double>> owned = masked_model(c);
  solver::ElasticModel<double>& model = *owned;
  const std::vector<double> mask(c.mask.begin(), c.mask.end());
  solver::MultigridPreconditioner<double> single(model, c.mesh, c.mask, built_fine_level(true));
  solver::MultigridPreconditioner<double> full(model, c.mesh, c.mask, built_fine_level(false));
  // Half of the cell matrices' and of the assembled blocks' bytes (the
  // upper layout's where blocks are per vertex, CPUs).
  const size_t count = c.mesh.vertex_count(), tile = model.data().cache_tile;
  const size_t entries = solver::stencil_entries(
      solver::device_stencil_tables(c.mesh.elements, count, 8, fem::vertex_slots(c.mesh.elements, count), tile), count,
      tile);
  EXPECT_EQ(full.memory_bytes() - single.memory_bytes(), (c.mesh.element_count() * 576 + entries) * sizeof(float));
  model.linearize(upload<double>(c.x), true);
  model.setup_preconditioner();
  single.setup();
  full.setup();
  const double coarse = relative_difference(single.level_matrices(1), full.level_matrices(1));
  EXPECT_LT(coarse, 1e-6);
  EXPECT_GT(coarse, 0.0) << "the float matrices reached the coarse level";
  const auto [in_single, in_full] = apply_both(single, full, mask, 5);
  const double vcycle = relative_difference(in_single, in_full);
  EXPECT_LT(vcycle, 1e-5);
  std::printf("float fine level: coarse cells %.2e, V-cycle %.2e relative to double\n", coarse, vcycle);
}

// MultigridOptions::float_cycle (the default in double with a built fine
// level): the V-cycle's vectors, stencils, inverse blocks and transfer
// weights in float, its builds in double. It must give the double cycle's
// result to float's rounding (within 1e-5 relative, the bound of the float
// fine level above), keep constrained DOFs exactly zero, take less device
// memory, and leave the coarse cell matrices (double builds) bitwise those
// of the double cycle. Symmetry: VCycleIsSymmetricPositive... above.
TEST(Multigrid, FloatCycleIsTheDoubleCycleToFloatRounding) {
  DeviceCase c;
  const std::unique_ptr<solver::ElasticModel<double>> owned = masked_model(c);
  solver::ElasticModel<double>& model = *owned;
  const std::vector<double> mask(c.mask.begin(), c.mask.end());
  MultigridOptions options = built_fine_level(true, true);
  options.fine_level.reset();
  solver::MultigridPreconditioner<double> single(model, c.mesh, c.mask, options);
  options.float_cycle = false;
  solver::MultigridPreconditioner<double> full(model, c.mesh, c.mask, options);
  ASSERT_TRUE(single.float_cycle());
  ASSERT_FALSE(full.float_cycle());
  EXPECT_LT(single.memory_bytes(), full.memory_bytes());
  model.linearize(upload<double>(c.x), true);
  model.setup_preconditioner();
  single.setup();
  full.setup();
  for (int l = 1; l < single.levels(); ++l) EXPECT_EQ(single.level_matrices(l), full.level_matrices(l)) << l;
  const auto [in_float, in_double] = apply_both(single, full, mask, 9);
  for (size_t i = 0; i < mask.size(); ++i) {
    if (mask[i] == 0.0) {
      EXPECT_EQ(in_float[i], 0.0) << "constrained DOF " << i;
    }
  }
  const double vcycle = relative_difference(in_float, in_double);
  EXPECT_LT(vcycle, 1e-5);
  EXPECT_GT(vcycle, 0.0) << "the cycle ran in float";
  std::printf("float cycle: V-cycle %.2e relative to double\n", vcycle);
}

// Boundary vertices follow x = A X + b; the equilibrium of any homogeneous
// material is then that affine map everywhere.
TEST(Multigrid, PatchTestSolvesToTheAffineField) {
  const Mesh mesh = lattice_subset(7, 5, 6, [](int i, int j, int k) { return !(i >= 4 && j >= 3 && k >= 3); });
  Eigen::Matrix3d f;
  f << 1.08, 0.05, -0.02, 0.03, 0.95, 0.04, -0.01, 0.02, 1.03;
  const Eigen::Vector3d t(0.01, -0.02, 0.03);
  std::vector<int32_t> boundary;
  std::vector<int> uses(mesh.vertex_count(), 0);
  for (int32_t v : mesh.elements) ++uses[v];
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    if (uses[v] < 8) boundary.push_back(static_cast<int32_t>(v));  // interior lattice vertices have 8 cells
  ConstraintSet set{"boundary", boundary, {}, {}};
  set.targets = [&](double, Points& xyz) {
    for (size_t i = 0; i < boundary.size(); ++i) {
      const Eigen::Vector3d rest(mesh.positions(boundary[i], 0), mesh.positions(boundary[i], 1),
                                 mesh.positions(boundary[i], 2));
      const Eigen::Vector3d x = f * rest + t;
      for (int d = 0; d < 3; ++d) xyz(i, d) = x[d];
    }
  };
  SolveOptions options;
  options.preconditioner = Preconditioner::multigrid;
  options.multigrid.coarsest_dofs = 30;
  QuasistaticSolver solver(mesh, Material::from_youngs_modulus(MaterialModel::stable_neo_hookean, 1.0, 0.49), {set},
                           options);
  const SolveResult r = solver.solve();
  ASSERT_TRUE(r.converged);
  EXPECT_EQ(r.preconditioner, Preconditioner::multigrid);
  double worst = 0.0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Eigen::Vector3d rest(mesh.positions(v, 0), mesh.positions(v, 1), mesh.positions(v, 2));
    const Eigen::Vector3d x = f * rest + t;
    for (int d = 0; d < 3; ++d) worst = std::max(worst, std::abs(r.positions(v, d) - x[d]));
  }
  EXPECT_LT(worst, 1e-6 * kH);
  std::printf("patch test: max deviation from the affine field %.2e (h = %g), %d Newton, %d CG\n", worst, kH,
              r.steps[0].newton_iterations, r.steps[0].cg_iterations);
}

// A solver on `mesh` (bottom face pinned, E = 1, nu = 0.3) with `options`
// must be refused with an error that names `word`.
void expect_refused(const Mesh& mesh, const SolveOptions& options, const std::string& word) {
  std::vector<int32_t> bottom;
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    if (mesh.positions(v, 2) < 1e-9) bottom.push_back(static_cast<int32_t>(v));
  try {
    QuasistaticSolver solver(mesh, Material::from_youngs_modulus(MaterialModel::stable_neo_hookean, 1.0, 0.3),
                             {{"bottom", bottom, {}, {}}}, options);
    FAIL() << "no error naming '" << word << "'";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
  }
}

SolveResult twist(Preconditioner preconditioner, int res, double nu, std::optional<int> rebuild_every = std::nullopt,
                  int steps = 1, std::optional<MultigridFineLevel> fine_level = std::nullopt,
                  bool fine_level_float = true, std::optional<Precision> product_precision = std::nullopt,
                  std::optional<ProductVariant> product = std::nullopt) {
  const Mesh mesh = make_box_lattice(res, res, res, 1.0 / res);
  std::vector<int32_t> bottom, top;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    if (mesh.positions(v, 2) < 1e-9) bottom.push_back(static_cast<int32_t>(v));
    if (mesh.positions(v, 2) > 1.0 - 1e-9) top.push_back(static_cast<int32_t>(v));
  }
  ConstraintSet fixed{"bottom", bottom, {}, {}};
  ConstraintSet turned{"top",
                       top,
                       [](double t) {
                         return RigidTransform::rotation_about({0, 0, 1}, 0.6 * t, {0.5, 0.5, 1});
                       },
                       {}};
  SolveOptions options;
  options.preconditioner = preconditioner;
  options.multigrid.coarsest_dofs = 100;
  options.multigrid.rebuild_every = rebuild_every;
  options.multigrid.fine_level = fine_level;
  options.multigrid.fine_level_float = fine_level_float;
  options.product_precision = product_precision;
  options.product = product;
  options.load_steps = steps;
  QuasistaticSolver solver(mesh, Material::from_youngs_modulus(MaterialModel::stable_neo_hookean, 1.0, nu),
                           {fixed, turned}, options);
  return solver.solve();
}

TEST(Multigrid, SameAnswerAsBlockJacobiInFewerCgIterationsAndRepeatable) {
  const SolveResult jacobi = twist(Preconditioner::block_jacobi, 6, 0.49);
  const SolveResult mg = twist(Preconditioner::multigrid, 6, 0.49);
  const SolveResult again = twist(Preconditioner::multigrid, 6, 0.49);
  ASSERT_TRUE(jacobi.converged);
  ASSERT_TRUE(mg.converged);
  double worst = 0.0;
  for (size_t i = 0; i < mg.positions.xyz().size(); ++i)
    worst = std::max(worst, std::abs(mg.positions.xyz()[i] - jacobi.positions.xyz()[i]));
  EXPECT_LT(worst, 1e-6);
  EXPECT_LT(mg.steps[0].cg_iterations, jacobi.steps[0].cg_iterations);
  EXPECT_EQ(mg.positions, again.positions) << "not bitwise repeatable";
  std::printf("twist 6^3: block-Jacobi %d Newton / %d CG, multigrid %d / %d; max position difference %.2e\n",
              jacobi.steps[0].newton_iterations, jacobi.steps[0].cg_iterations, mg.steps[0].newton_iterations,
              mg.steps[0].cg_iterations, worst);
}

// Mixed precision (SolveOptions::product_precision float): CG's products in
// float, everything Newton measures in double, so the solve converges to
// double's tolerance and the same answer as double products, with multigrid
// and block-Jacobi (the cached variant: others keep double), at nu = 0.49
// and at the stiffer 0.499; the result reports the products' precision.
// Float is the default.
TEST(Multigrid, FloatProductsGiveTheDoubleAnswer) {
  for (double nu : {0.49, 0.499})
    for (Preconditioner preconditioner : {Preconditioner::multigrid, Preconditioner::block_jacobi}) {
      SCOPED_TRACE(std::string(to_string(preconditioner)) + " nu " + std::to_string(nu));
      const SolveResult exact =
          twist(preconditioner, 6, nu, std::nullopt, 2, std::nullopt, true, Precision::double_, ProductVariant::cached);
      // Unset: float (the default).
      const SolveResult mixed =
          twist(preconditioner, 6, nu, std::nullopt, 2, std::nullopt, true, std::nullopt, ProductVariant::cached);
      ASSERT_TRUE(exact.converged);
      ASSERT_TRUE(mixed.converged);
      EXPECT_EQ(exact.product_precision, Precision::double_);
      EXPECT_EQ(mixed.product_precision, Precision::single);
      EXPECT_LE(mixed.final_residual_norm, mixed.tolerance);
      double worst = 0.0;
      for (size_t i = 0; i < exact.positions.xyz().size(); ++i)
        worst = std::max(worst, std::abs(exact.positions.xyz()[i] - mixed.positions.xyz()[i]));
      EXPECT_LT(worst, 1e-6);
      EXPECT_NE(exact.positions, mixed.positions) << "the float products did not run";
      int newton[2] = {0, 0}, cg[2] = {0, 0};
      for (int k = 0; k < 2; ++k)
        for (const StepResult& st : (k ? mixed : exact).steps) {
          newton[k] += st.newton_iterations;
          cg[k] += st.cg_iterations;
        }
      std::printf(
          "twist 6^3 nu %.3f %s: double products %d Newton / %d CG, float products %d / %d; max position "
          "difference %.2e\n",
          nu, to_string(preconditioner), newton[0], cg[0], newton[1], cg[1], worst);
    }
}

// The hierarchy reused between linearizations (MultigridOptions::
// rebuild_every) preconditions the same Newton iterations: the same answer
// within the Newton tolerance, built fewer times than there were
// linearizations, and at least once per load step.
TEST(Multigrid, ReusedHierarchyGivesTheSameAnswerWithFewerBuilds) {
  const SolveResult every = twist(Preconditioner::multigrid, 6, 0.49, 1, 2);
  const SolveResult reused = twist(Preconditioner::multigrid, 6, 0.49, 8, 2);
  ASSERT_TRUE(every.converged);
  ASSERT_TRUE(reused.converged);
  double worst = 0.0;
  for (size_t i = 0; i < every.positions.xyz().size(); ++i)
    worst = std::max(worst, std::abs(every.positions.xyz()[i] - reused.positions.xyz()[i]));
  EXPECT_LT(worst, 1e-6);
  int every_builds = 0, reused_builds = 0, reused_newton = 0;
  for (const StepResult& s : every.steps) {
    EXPECT_GE(s.preconditioner_builds,
              s.newton_iterations);  // one per linearization (two where CG met negative curvature)
    every_builds += s.preconditioner_builds;
  }
  for (const StepResult& s : reused.steps) {
    EXPECT_GE(s.preconditioner_builds, 1) << "step " << s.step;
    reused_builds += s.preconditioner_builds;
    reused_newton += s.newton_iterations;
  }
  EXPECT_LT(reused_builds, reused_newton);
  std::printf(
      "twist 6^3, 2 steps: rebuilt every linearization %d builds / %d CG; reused %d builds for %d Newton / "
      "%d CG; max position difference %.2e\n",
      every_builds, every.steps[0].cg_iterations + every.steps[1].cg_iterations, reused_builds, reused_newton,
      reused.steps[0].cg_iterations + reused.steps[1].cg_iterations, worst);
  SolveOptions bad;
  bad.preconditioner = Preconditioner::multigrid;
  bad.multigrid.rebuild_every = 0;  // set: at least 1
  expect_refused(make_box_lattice(2, 2, 2, 0.5), bad, "rebuild_every");
}

// The fine level frozen with the build or following each linearization: the
// same Newton solve either way, to the Newton tolerance.
TEST(Multigrid, BuiltAndCurrentFineLevelsGiveTheSameAnswer) {
  const SolveResult built = twist(Preconditioner::multigrid, 6, 0.49, 4, 2, MultigridFineLevel::built);
  const SolveResult current = twist(Preconditioner::multigrid, 6, 0.49, 4, 2, MultigridFineLevel::current);
  const SolveResult built_double =
      twist(Preconditioner::multigrid, 6, 0.49, 4, 2, MultigridFineLevel::built, /*fine_level_float=*/false);
  ASSERT_TRUE(built.converged);
  ASSERT_TRUE(current.converged);
  ASSERT_TRUE(built_double.converged);
  double worst = 0.0, worst_double = 0.0;
  for (size_t i = 0; i < built.positions.xyz().size(); ++i) {
    worst = std::max(worst, std::abs(built.positions.xyz()[i] - current.positions.xyz()[i]));
    worst_double = std::max(worst_double, std::abs(built.positions.xyz()[i] - built_double.positions.xyz()[i]));
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_LT(worst_double, 1e-6) << "float against double fine-level matrices";
  auto totals = [](const SolveResult& r) {
    int newton = 0, cg = 0;
    for (const StepResult& s : r.steps) {
      newton += s.newton_iterations;
      cg += s.cg_iterations;
    }
    return std::pair<int, int>(newton, cg);
  };
  std::printf("twist 6^3, 2 steps: fine level built %d Newton / %d CG, current %d / %d; max difference %.2e\n",
              totals(built).first, totals(built).second, totals(current).first, totals(current).second, worst);
}

// rebuild_every unset (the default): 2 linearizations per build when each
// load step rebuilds (quasistatic), 4 when the hierarchy is carried (dynamics).
TEST(MultigridRebuild, DefaultCountFollowsThePerStepRebuild) {
  MultigridOptions o;
  EXPECT_FALSE(o.rebuild_every.has_value());
  EXPECT_EQ(solver::resolved_rebuild_every(o), 2);
  o.rebuild_each_load_step = false;
  EXPECT_EQ(solver::resolved_rebuild_every(o), 4);
  o.rebuild_every = 3;
  EXPECT_EQ(solver::resolved_rebuild_every(o), 3);
  MultigridOptions quasistatic;
  solver::MultigridRebuild r(quasistatic);
  r.built(true);
  r.reused();  // the second linearization on this build
  EXPECT_TRUE(r.due(true));
}

TEST(MultigridRebuild, BuildsAtStepsAfterEveryAndWhenCgSlowsDown) {
  MultigridOptions o;
  o.rebuild_every = 3;
  o.rebuild_growth = 2.0;
  solver::MultigridRebuild r(o);
  EXPECT_TRUE(r.due(true));  // nothing built yet
  r.built(true);
  r.solved(1, 0.05, true);  // one iteration: not compared, no baseline
  EXPECT_FALSE(r.due(true));
  r.reused();
  r.solved(4, 1e-4, true);  // baseline: 1 decade per iteration
  EXPECT_FALSE(r.due(true));
  r.reused();
  EXPECT_TRUE(r.due(true));  // three linearizations served
  r.built(true);
  r.solved(4, 1e-4, true);
  r.solved(6, 1e-3, true);  // 0.5 decades per iteration: half the rate, not less
  EXPECT_FALSE(r.due(true));
  r.solved(8, 1e-3, true);  // 0.375: slower than half
  EXPECT_TRUE(r.due(true));
  r.built(true);
  r.solved(3, 0.5, false);  // did not reach its tolerance
  EXPECT_TRUE(r.due(true));
  r.built(true);
  r.new_step();
  EXPECT_TRUE(r.due(true));
  // A true Hessian reuses a projected build, even when one is due, but is
  // not kept once a projected linearization comes.
  r.built(true);
  EXPECT_FALSE(r.due(false));
  r.new_step();
  EXPECT_FALSE(r.due(false));
  EXPECT_TRUE(r.due(true));
  solver::MultigridRebuild first(o);
  EXPECT_TRUE(first.due(false));
  first.built(false);
  EXPECT_FALSE(first.due(false));
  EXPECT_TRUE(first.due(true));
  EXPECT_EQ(first.builds(), 1);
  EXPECT_EQ(r.builds(), 5);
  // Carried across steps (dynamics' default): a new step alone does not
  // rebuild; the count still does.
  o.rebuild_each_load_step = false;
  solver::MultigridRebuild carried(o);
  carried.built(true);
  carried.new_step();
  EXPECT_FALSE(carried.due(true));
  carried.reused();
  carried.new_step();
  carried.reused();
  EXPECT_TRUE(carried.due(true));
}

// Unset, the per-step rebuild follows the solve: on for quasistatic load
// steps, off under dynamics; set, it is kept.
TEST(Multigrid, PerStepRebuildFollowsDynamicsUnlessSet) {
  const Mesh mesh = make_box_lattice(4, 4, 4, 0.25);
  SolveOptions options;
  options.preconditioner = Preconditioner::multigrid;
  options.multigrid.coarsest_dofs = 50;
  options.load_steps = 4;
  DynamicsOptions dynamics;
  dynamics.time_step = 0.1;
  dynamics.density = 1.0;
  options.body_force = {0.0, 0.0, -1.0};
  const Material material = StableNeoHookean::from_youngs_modulus(10.0, 0.4);
  auto builds = [&](std::optional<DynamicsOptions> d, std::optional<bool> each) {
    SolveOptions o = options;
    o.dynamics = d;
    o.multigrid.rebuild_each_load_step = each;
    ConstraintSet bottom{"bottom", {}, {}, {}};
    for (size_t v = 0; v < mesh.vertex_count(); ++v)
      if (mesh.positions(v, 2) == 0.0) bottom.vertices.push_back(static_cast<int32_t>(v));
    const SolveResult r = Simulation(mesh, material, {bottom}, o).solve();
    EXPECT_TRUE(r.converged);
    std::vector<int> per_step;
    for (const StepResult& s : r.steps) per_step.push_back(s.preconditioner_builds);
    return per_step;
  };
  for (int b : builds(std::nullopt, std::nullopt)) EXPECT_GE(b, 1);  // quasistatic: every load step
  const std::vector<int> carried = builds(dynamics, std::nullopt);
  EXPECT_EQ(carried.front(), 1);
  EXPECT_GE(std::count(carried.begin(), carried.end(), 0), 1);  // some time steps reuse the last build
  for (int b : builds(dynamics, true)) EXPECT_GE(b, 1);         // asked for: every time step
}

TEST(Multigrid, RefusesTetMeshesByName) {
  SolveOptions options;
  options.preconditioner = Preconditioner::multigrid;
  expect_refused(make_tet_box(2, 2, 2, kH), options, "multigrid");
}

TEST(Multigrid, PreconditionerNamesParse) {
  for (Preconditioner p : {Preconditioner::none, Preconditioner::block_jacobi, Preconditioner::multigrid})
    EXPECT_EQ(parse_preconditioner(to_string(p)), p);
  EXPECT_THROW(parse_preconditioner("jacobi"), Error);
  EXPECT_THROW(parse_preconditioner("automatic"), Error);  // unset is no value
  EXPECT_EQ(parse_optional("automatic", parse_preconditioner), std::nullopt);
  EXPECT_EQ(parse_optional("none", parse_preconditioner), Preconditioner::none);
}

// MultigridOptions' unset smoothing (resolved_smoothing): degree 1 of the
// optimized fourth kind below 600,000 DOFs and nu 0.495, else degree 2 of the
// first kind; one of the two set leaves the other at its fixed default.
TEST(Multigrid, AutomaticSmoothingFollowsSizeAndPoissonRatio) {
  auto resolved = [](MultigridOptions o, size_t dofs, double nu) {
    const MultigridOptions r = resolved_smoothing(o, dofs, nu);
    return std::make_pair(r.smoother_degree.value(), r.chebyshev_kind.value());
  };
  const MultigridOptions automatic;
  EXPECT_FALSE(automatic.smoother_degree.has_value());
  EXPECT_FALSE(automatic.chebyshev_kind.has_value());
  const auto light = std::make_pair(1, ChebyshevKind::optimized_fourth);
  const auto heavy = std::make_pair(2, ChebyshevKind::first);
  EXPECT_EQ(resolved(automatic, 107811, 0.49), light);
  EXPECT_EQ(resolved(automatic, 599999, 0.3), light);
  EXPECT_EQ(resolved(automatic, 600000, 0.49), heavy);
  EXPECT_EQ(resolved(automatic, 969111, 0.49), heavy);
  EXPECT_EQ(resolved(automatic, 107811, 0.495), heavy);
  EXPECT_EQ(resolved(automatic, 107811, 0.499), heavy);
  MultigridOptions degree = automatic;
  degree.smoother_degree = 3;
  EXPECT_EQ(resolved(degree, 1000, 0.3), std::make_pair(3, ChebyshevKind::first));
  MultigridOptions kind = automatic;
  kind.chebyshev_kind = ChebyshevKind::fourth;
  EXPECT_EQ(resolved(kind, 1000, 0.3), std::make_pair(2, ChebyshevKind::fourth));
  for (ChebyshevKind k : {ChebyshevKind::first, ChebyshevKind::fourth, ChebyshevKind::optimized_fourth})
    EXPECT_EQ(parse_chebyshev_kind(to_string(k)), k);

  // The largest nu over the materials the elements use; the model and the
  // solve report what was resolved.
  const Mesh mesh = make_box_lattice(4, 4, 4, kH);
  MaterialMap map = uniform_material(mesh, StableNeoHookean::from_youngs_modulus(1.0, 0.3));
  EXPECT_NEAR(max_poisson_ratio(map), 0.3, 1e-12);
  map.materials.push_back(StableNeoHookean::from_youngs_modulus(1.0, 0.499));
  EXPECT_NEAR(max_poisson_ratio(map), 0.3, 1e-12) << "a material no element uses";
  map.element_material[5] = 1;
  EXPECT_NEAR(max_poisson_ratio(map), 0.499, 1e-12);
  for (double nu : {0.45, 0.499}) {
    const SolveResult r = twist(Preconditioner::multigrid, 4, nu);
    ASSERT_EQ(r.preconditioner, Preconditioner::multigrid);
    EXPECT_EQ(std::make_pair(r.multigrid_smoother_degree.value(), r.multigrid_chebyshev.value()),
              nu < 0.495 ? light : heavy);
  }
}

}  // namespace
}  // namespace snh::test

namespace snh::test {
namespace {

// Block-Jacobi's blocks come from the element matrices when the variant keeps
// them (projected linearization) and from the cache otherwise: the same
// blocks up to rounding.
TEST(Multigrid, BlockJacobiBlocksFromElementMatricesMatchTheCache) {
  DeviceCase c;
  device::OpenClContext& cl = device_for(Precision::double_);
  std::vector<std::vector<double>> blocks;
  for (ProductVariant v : {ProductVariant::cached, ProductVariant::element_matrices}) {
    solver::ElasticModel<double> model(cl, c.mesh, c.rest, uniform_material(c.mesh, c.material), v);
    model.set_mask(std::vector<double>(c.mask.begin(), c.mask.end()));
    model.linearize(upload<double>(c.x), true);
    model.setup_preconditioner();
    blocks.push_back(model.preconditioner_blocks());
  }
  double worst = 0.0, scale = 0.0;
  for (size_t i = 0; i < blocks[0].size(); ++i) {
    worst = std::max(worst, std::abs(blocks[0][i] - blocks[1][i]));
    scale = std::max(scale, std::abs(blocks[0][i]));
  }
  EXPECT_LT(worst, 1e-12 * scale);
}

}  // namespace
}  // namespace snh::test

namespace snh::test {
namespace {

TEST(Multigrid, AutomaticChoosesMultigridOnLargeLattices) {
  EXPECT_EQ(default_preconditioner(make_box_lattice(15, 15, 15, 0.1)), Preconditioner::multigrid);     // 12,288 DOFs
  EXPECT_EQ(default_preconditioner(make_box_lattice(11, 11, 11, 0.1)), Preconditioner::multigrid);     // 5,184
  EXPECT_EQ(default_preconditioner(make_box_lattice(10, 10, 10, 0.1)), Preconditioner::block_jacobi);  // 3,993
  EXPECT_EQ(default_preconditioner(make_tet_box(15, 15, 15, 0.1)), Preconditioner::block_jacobi);
  Mesh jittered = make_box_lattice(15, 15, 15, 0.1);
  jittered.positions(100, 0) += 0.01;
  EXPECT_EQ(default_preconditioner(jittered), Preconditioner::block_jacobi);
  // The same with dynamics (one time step of a free fall), but block-Jacobi
  // with self-contact, which the coarse levels do not carry.
  SolveOptions options;
  DynamicsOptions dynamics;
  dynamics.time_step = 0.01;
  dynamics.density = 1.0;
  options.dynamics = dynamics;
  options.body_force = {0.0, 0.0, -1.0};
  options.load_steps = 1;
  const Mesh lattice = make_box_lattice(15, 15, 15, 0.1);
  const Material material = StableNeoHookean::from_youngs_modulus(10.0, 0.3);
  EXPECT_EQ(Simulation(lattice, material, {}, options).solve().preconditioner, Preconditioner::multigrid);
  options.contact.self = true;
  options.contact.stiffness = 1.0;
  options.contact.thickness = 0.01;
  EXPECT_EQ(Simulation(lattice, material, {}, options).solve().preconditioner, Preconditioner::block_jacobi);
}

// A block dropped onto a plane under implicit Euler, on a lattice large
// enough for two levels: multigrid (inertia and contact on its coarse level)
// and block-Jacobi land it in the same place, multigrid in far fewer CG
// iterations.
TEST(Multigrid, DynamicsWithContactMatchesBlockJacobi) {
  const Mesh mesh = make_box_lattice(8, 8, 8, 0.0125);
  SolveOptions options;
  DynamicsOptions dynamics;
  dynamics.time_step = 1.0 / 60.0;
  dynamics.density = 1000.0;
  options.dynamics = dynamics;
  options.body_force = {0.0, 0.0, -9810.0};
  Obstacle floor;
  floor.type = ObstacleType::plane;
  floor.point = {0.0, 0.0, -0.01};
  floor.direction = {0.0, 0.0, 1.0};
  options.obstacles = {floor};
  options.contact.stiffness = 1e4;
  options.contact.thickness = 0.005;
  options.load_steps = 12;
  options.absolute_tolerance = 1e-10;
  std::vector<SolveResult> runs;
  for (Preconditioner p : {Preconditioner::block_jacobi, Preconditioner::multigrid}) {
    options.preconditioner = p;
    Simulation sim(mesh, StableNeoHookean::from_youngs_modulus(1e5, 0.45), {}, options);
    runs.push_back(sim.solve());
    ASSERT_TRUE(runs.back().converged) << to_string(p);
    EXPECT_GT(runs.back().steps.back().contacts, 0) << to_string(p);
  }
  double difference = 0.0;
  for (size_t i = 0; i < runs[0].positions.xyz().size(); ++i)
    difference = std::max(difference, std::abs(runs[0].positions.xyz()[i] - runs[1].positions.xyz()[i]));
  int cg[2] = {0, 0};
  for (int k = 0; k < 2; ++k)
    for (const StepResult& s : runs[k].steps) cg[k] += s.cg_iterations;
  std::printf("drop: block-Jacobi %d CG, multigrid %d CG, positions differ by %.2e\n", cg[0], cg[1], difference);
  EXPECT_LT(difference, 1e-11);  // both stop at an absolute residual of 1e-10
  EXPECT_LT(3 * cg[1], cg[0]);
}

}  // namespace
}  // namespace snh::test
