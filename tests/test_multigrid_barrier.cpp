// Multigrid with barrier self-contact (solver/multigrid/multigrid.h): the first coarse
// level is P^T D (K + the barrier's diagonal blocks) D P exactly, the V-cycle
// with the barrier active is symmetric positive, the fine level follows the
// model's product (built is refused by name, as is the penalty), and a
// squash that folds onto itself solves with multigrid to block-Jacobi's
// answer, every step converged and free of intersections.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "device/opencl_context.h"
#include "device/viennacl_binding.h"
#include "fem/rest_state.h"
#include "snh/error.h"
#include "snh/simulation.h"
#include "snh/surface_intersections.h"
#include "solver/contact/barrier_contact.h"
#include "solver/model/elastic_model.h"
#include "solver/multigrid/lattice_hierarchy.h"
#include "solver/multigrid/multigrid.h"
#include "stability.h"
#include "support/device_test_support.h"
#include "viennacl/vector.hpp"

namespace snh::test {
namespace {

// An 8x8x2 lattice (h = 0.25) squashed to a tenth of its height, so that its
// top face comes within dhat = 0.3 h of its bottom face (0.2 h apart, 2 h at
// rest: no pair is left out at rest), the bottom face pinned. kappa = 0.03
// makes the barrier about half of the first coarse level's trace, so that
// both parts of the coarse operator are checked.
struct SquashedSlab {
  static constexpr double kH = 0.25, kDhat = 0.3 * kH, kSquash = 0.1, kKappa = 0.03;
  Mesh mesh = make_box_lattice(8, 8, 2, kH);
  fem::RestState rest = fem::compute_rest_state(mesh);
  Material material = Material::from_youngs_modulus(MaterialModel::stable_neo_hookean, 1.0, 0.4);
  std::vector<double> x;
  std::vector<char> mask;
  SquashedSlab() {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-0.02 * kH, 0.02 * kH);
    x = mesh.positions.xyz();
    mask.assign(3 * mesh.vertex_count(), 1);
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
      x[3 * v] += u(rng);
      x[3 * v + 1] += u(rng);
      x[3 * v + 2] *= kSquash;
      if (mesh.positions(v, 2) < 1e-9) {
        mask[3 * v] = mask[3 * v + 1] = mask[3 * v + 2] = 0;
        x[3 * v] = mesh.positions(v, 0);
        x[3 * v + 1] = mesh.positions(v, 1);
      }
    }
  }
  solver::ModelTerms terms() const {
    solver::ModelTerms t;
    t.self_barrier = true;
    return t;
  }
  std::unique_ptr<solver::ElasticModel<double>> model(bool barrier) const {
    auto m = std::make_unique<solver::ElasticModel<double>>(
        device_for(Precision::double_), mesh, rest, uniform_material(mesh, material), ProductVariant::cached,
        device::MaterialKernel::specialized, barrier ? terms() : solver::ModelTerms{});
    m->set_mask(std::vector<double>(mask.begin(), mask.end()));
    if (barrier) m->contact().set_self_barrier(kDhat, kKappa);
    return m;
  }
};

MultigridOptions three_levels() {
  MultigridOptions options;
  options.coarsest_dofs = 1;
  options.max_levels = 3;
  return options;
}

// The first coarse level's cell matrices, assembled, against P^T D (K + B) D P
// with K the elastic operator (a model without the barrier, column by column
// through its product) and B the barrier's diagonal blocks per vertex; the
// barrier's blocks must be there (10-90% of the coarse trace).
TEST(MultigridBarrier, FirstCoarseLevelCarriesTheBarriersDiagonalBlocks) {
  SquashedSlab s;
  auto barrier_model = s.model(true);
  auto elastic_model = s.model(false);
  solver::MultigridPreconditioner<double> mg(*barrier_model, s.mesh, s.mask, three_levels());
  EXPECT_FALSE(mg.fine_level_built());  // automatic: the model's product, which has the barrier
  ASSERT_GE(mg.levels(), 2);
  const viennacl::vector<double> x = upload<double>(s.x);
  barrier_model->energy(x);
  ASSERT_GT(barrier_model->contact().self_barrier()->state().pairs, 8) << "the squash brings no pair within dhat";
  barrier_model->linearize(x, true);
  elastic_model->linearize(x, true);
  barrier_model->setup_preconditioner();
  mg.setup();

  const size_t n = 3 * s.mesh.vertex_count();
  Eigen::MatrixXd k(n, n);
  viennacl::vector<double> y(n);
  for (size_t j = 0; j < n; ++j) {
    std::vector<double> e(n, 0.0);
    e[j] = 1.0;
    elastic_model->product(upload<double>(e), y);
    const std::vector<double> column = download(y);
    for (size_t i = 0; i < n; ++i) k(i, j) = column[i];
  }
  std::vector<double> diagonal(9 * s.mesh.vertex_count());
  barrier_model->context().read(barrier_model->contact().self_barrier()->diagonal(), diagonal.size() * sizeof(double),
                                diagonal.data());
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(n, n);
  for (size_t v = 0; v < s.mesh.vertex_count(); ++v)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) b(3 * v + i, 3 * v + j) = diagonal[9 * v + 3 * i + j];
  const solver::LatticeHierarchy& h = mg.hierarchy();
  const solver::LatticeLevel& fine = h.levels[0];
  const size_t nc = 3 * h.levels[1].vertex_count;
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(n, nc);
  for (size_t v = 0; v < fine.vertex_count; ++v)
    for (int c = 0; c < 8; ++c)
      for (int d = 0; d < 3; ++d)
        p(3 * v + d, 3 * fine.prolongation_vertices[8 * v + c] + d) += fine.prolongation_weights[8 * v + c];
  Eigen::VectorXd dmask(n);
  for (size_t i = 0; i < n; ++i) dmask[i] = fine.mask[i];
  const Eigen::MatrixXd dp = dmask.asDiagonal() * p;
  const Eigen::MatrixXd elastic = dp.transpose() * k * dp, expected = dp.transpose() * (k + b) * dp;
  const std::vector<double> cells = mg.level_matrices(1);
  const solver::LatticeLevel& coarse = h.levels[1];
  Eigen::MatrixXd assembled = Eigen::MatrixXd::Zero(nc, nc);
  for (size_t cell = 0; cell < coarse.cells.size(); ++cell)
    for (int col = 0; col < 24; ++col)
      for (int row = 0; row < 24; ++row)
        assembled(3 * coarse.elements[8 * cell + row / 3] + row % 3,
                  3 * coarse.elements[8 * cell + col / 3] + col % 3) += cells[576 * cell + 24 * col + row];
  const double error = (assembled - expected).norm() / expected.norm();
  const double barrier_share = (expected.trace() - elastic.trace()) / expected.trace();
  std::printf("level 1: %zu DOFs, barrier %.1f%% of the trace, |A_device - P^T D (K + B) D P| / |.| = %.2e\n", nc,
              100.0 * barrier_share, error);
  EXPECT_LT(error, 1e-12);
  EXPECT_GT(barrier_share, 0.1);
  EXPECT_LT(barrier_share, 0.9);
}

// za = M a, zb = M b: a.(M b) = b.(M a) to the sums' rounding, a.(M a) > 0,
// and zero on the constrained DOFs; with the fine level current and the
// coarsest level solved on the host or on the device.
TEST(MultigridBarrier, VCycleIsSymmetricPositive) {
  SquashedSlab s;
  auto model = s.model(true);
  const std::vector<double> mask(s.mask.begin(), s.mask.end());
  for (bool device_coarse : {false, true}) {
    SCOPED_TRACE(device_coarse ? "coarsest solve on the device" : "coarsest solve on the host");
    MultigridOptions options = three_levels();
    options.coarse_solve_on_device = device_coarse;
    solver::MultigridPreconditioner<double> mg(*model, s.mesh, s.mask, options);
    model->energy(upload<double>(s.x));
    ASSERT_GT(model->contact().self_barrier()->state().pairs, 8);
    model->linearize(upload<double>(s.x), true);
    model->setup_preconditioner();
    mg.setup();
    const auto [a, b] = masked_random_pair(mask, 3);
    viennacl::vector<double> ma = upload<double>(a), mb = upload<double>(b);
    mg.apply(ma);
    mg.apply(mb);
    expect_symmetric_positive(mask, a, b, download(ma), download(mb), 1e-12);
  }
}

// A built fine level (the build's element matrices) would smooth without the
// barrier: refused by name. The penalty's springs stay refused too.
TEST(MultigridBarrier, BuiltFineLevelAndThePenaltyAreRefusedByName) {
  SquashedSlab s;
  auto model = s.model(true);
  MultigridOptions options = three_levels();
  options.fine_level = MultigridFineLevel::built;
  try {
    solver::MultigridPreconditioner<double> refused(*model, s.mesh, s.mask, options);
    ADD_FAILURE() << "a built fine level with the barrier was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("fine_level built"), std::string::npos) << e.what();
  }
  SolveOptions penalty;
  penalty.preconditioner = Preconditioner::multigrid;
  penalty.contact.self = true;
  penalty.contact.self_method = SelfContactMethod::penalty;
  penalty.contact.stiffness = 1.0;
  penalty.contact.thickness = 0.01;
  try {
    Simulation(s.mesh, s.material, {}, penalty);
    ADD_FAILURE() << "multigrid with the self-contact penalty was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("penalty"), std::string::npos) << e.what();
  }
}

// The stability suite's frictionless squash with barrier self-contact (4^3
// hexes, the lid closing to 5% of the height and opening again in 16 time
// steps; inertia, obstacle contact and the barrier on the coarse levels):
// with multigrid (three levels) every step converges with no intersecting
// surface triangles, the positions are block-Jacobi's within the Newton
// tolerance, and CG does not crawl.
TEST(MultigridBarrier, SquashSolvesToTheBlockJacobiAnswerWithoutIntersection) {
  Scene scene = bench::make_stability_case("squash_h0.05_nu0.46", Precision::double_, 4, 0.0);
  ASSERT_TRUE(scene.options.contact.self);
  ASSERT_EQ(scene.options.contact.self_method, SelfContactMethod::barrier);
  scene.options.load_steps = 16;
  scene.options.multigrid.coarsest_dofs = 50;
  const solver::BarrierContact surface(scene.mesh);
  const std::vector<int32_t> triangles(surface.triangles().begin(), surface.triangles().end());
  struct Run {
    std::vector<double> positions;
    size_t most_pairs = 0;
    int steps = 0, converged = 0, newton = 0, cg = 0, most_self_pairs = 0;
  };
  auto run = [&](Preconditioner preconditioner) {
    SolveOptions options = scene.options;
    options.preconditioner = preconditioner;
    Simulation sim(scene.mesh, uniform_material(scene.mesh, scene.material), scene.constraints, options);
    Run r;
    sim.solve(0, {}, [&](int, const Points& x) {
      const StepResult& step = sim.last_step();
      r.most_pairs = std::max(r.most_pairs, count_self_intersections(x, triangles).intersecting_pairs);
      r.converged += step.converged ? 1 : 0;
      r.newton += step.newton_iterations;
      r.cg += step.cg_iterations;
      r.most_self_pairs = std::max(r.most_self_pairs, step.self_contact_pairs);
      r.positions = x.xyz();
      ++r.steps;
    });
    return r;
  };
  const Run jacobi = run(Preconditioner::block_jacobi);
  const Run mg = run(Preconditioner::multigrid);
  for (const Run* r : {&jacobi, &mg}) {
    EXPECT_EQ(r->steps, 16);
    EXPECT_EQ(r->converged, r->steps);
    EXPECT_EQ(r->most_pairs, 0u);
  }
  EXPECT_GT(mg.most_self_pairs, 0) << "the squash no longer brings the surface within dhat of itself";
  double worst = 0.0;
  for (size_t i = 0; i < mg.positions.size(); ++i)
    worst = std::max(worst, std::abs(mg.positions[i] - jacobi.positions[i]));
  std::printf("squash 4^3: block-Jacobi %d Newton / %d CG, multigrid %d / %d; max position difference %.2e\n",
              jacobi.newton, jacobi.cg, mg.newton, mg.cg, worst);
  EXPECT_LT(worst, 1e-6);
  // A fine smoother with the build's barrier blocks, reused over 4
  // linearizations, took 7,277 CG against block-Jacobi's 1,422; with each
  // linearization's blocks 1,251.
  EXPECT_LT(mg.cg, 2 * jacobi.cg);
}

}  // namespace
}  // namespace snh::test
