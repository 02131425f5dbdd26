// Self-collision (solver/contact/self_contact.h): detection of a sample pushed into a
// non-adjacent element (hex8 and tet4), its rest-space closest point, the
// exclusion of adjacent elements, the frozen-weight penalty's gradient and
// Hessian against finite differences and PSD, the device terms against the
// host reference, and bitwise determinism of a solve.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <random>

#include "device/opencl_context.h"
#include "device/viennacl_binding.h"
#include "fem/rest_state.h"
#include "snh/error.h"
#include "snh/scenes.h"
#include "snh/simulation.h"
#include "solver/contact/self_contact.h"
#include "solver/model/elastic_model.h"
#include "support/device_test_support.h"

namespace snh::test {
namespace {

int vertex_at(const Mesh& mesh, double x, double y, double z) {
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    if (std::abs(mesh.positions(v, 0) - x) < 1e-9 && std::abs(mesh.positions(v, 1) - y) < 1e-9 &&
        std::abs(mesh.positions(v, 2) - z) < 1e-9)
      return static_cast<int>(v);
  return -1;
}

// A 6 x 2 x 2 lattice of unit cells; its corner vertex (0, 0, 2) pushed to
// (4.5, 0.3, 1.5), inside cell (4, 0, 1), which shares no vertex with the
// corner's cell. At rest that point's nearest surface is the face y = 0,
// 0.3 away (the top z = 2 is 0.5 away), so the closest point is (4.5, 0, 1.5).
void check_pushed_sample(const Mesh& mesh, int cell_first, int cell_count) {
  const bool hex = mesh.type == ElementType::hex8;
  const solver::SelfContactDetector detector(mesh);
  EXPECT_TRUE(detector.detect(mesh.positions.xyz()).empty()) << "contacts at rest";
  const int s = vertex_at(mesh, 0, 0, 2);
  ASSERT_GE(s, 0);
  std::vector<double> x = mesh.positions.xyz();
  x[3 * s] = 4.5;
  x[3 * s + 1] = 0.3;
  x[3 * s + 2] = 1.5;
  const std::vector<solver::SelfContactPair> pairs = detector.detect(x);
  ASSERT_EQ(pairs.size(), 1u);
  const solver::SelfContactPair& c = pairs[0];
  EXPECT_EQ(c.sample, s);
  EXPECT_GE(c.element, cell_first);
  EXPECT_LT(c.element, cell_first + cell_count);
  double y[3] = {0, 0, 0}, wsum = 0.0;
  for (int j = 0; j < 3; ++j) {
    EXPECT_GE(c.weight[j], 0.0);
    wsum += c.weight[j];
    EXPECT_NEAR(mesh.positions(c.vertex[j], 1), 0.0, 1e-12) << "triangle off the face y = 0";
    for (int d = 0; d < 3; ++d) y[d] += c.weight[j] * mesh.positions(c.vertex[j], d);
  }
  EXPECT_NEAR(wsum, 1.0, 1e-12);
  EXPECT_NEAR(y[0], 4.5, 1e-12);
  EXPECT_NEAR(y[1], 0.0, 1e-12);
  EXPECT_NEAR(y[2], 1.5, 1e-12);
  // The spring: from the sample to Y's deformed position (undeformed there).
  EXPECT_NEAR(solver::self_contact_length(c, x), 0.3, 1e-12);

  // Pushed into its own element, or (hex) into a neighbour of its elements:
  // not reported (the one-ring exclusion; a tet's one-ring is smaller than
  // its hex's, so x = 3.5 is only checked on hexes).
  const int t = vertex_at(mesh, 2, 0, 2);
  ASSERT_GE(t, 0);
  for (double to : hex ? std::vector<double>{2.5, 3.5} : std::vector<double>{2.5}) {
    std::vector<double> z = mesh.positions.xyz();
    z[3 * t] = to;
    z[3 * t + 1] = 0.5;
    z[3 * t + 2] = 1.5;
    EXPECT_TRUE(detector.detect(z).empty()) << "sample moved to x = " << to;
  }
  // Two cells away it is a contact again.
  std::vector<double> z = mesh.positions.xyz();
  z[3 * t] = 4.5;
  z[3 * t + 1] = 0.3;
  z[3 * t + 2] = 1.5;
  EXPECT_EQ(detector.detect(z).size(), 1u);
}

TEST(SelfContact, DetectsASamplePushedIntoANonAdjacentHex) {
  const Mesh mesh = make_box_lattice(6, 2, 2, 1.0);
  const solver::SelfContactDetector detector(mesh);
  // 2 (6 2 + 6 2 + 2 2) faces, two triangles each; every vertex but the
  // 5 x 1 x 1 interior ones is a sample.
  EXPECT_EQ(detector.triangle_count(), 2u * 2 * (12 + 12 + 4));
  EXPECT_EQ(detector.samples().size(), mesh.vertex_count() - 5);
  const int cell = 4 + 6 * (0 + 2 * 1);
  check_pushed_sample(mesh, cell, 1);
}

TEST(SelfContact, DetectsASamplePushedIntoANonAdjacentTet) {
  const Mesh mesh = make_tet_box(6, 2, 2, 1.0);
  const int cell = 4 + 6 * (0 + 2 * 1);
  check_pushed_sample(mesh, 6 * cell, 6);
}

// E = k/2 sum |x_s - sum w x_j|^2 with frozen weights: gradient and Hessian
// against central differences, and the Hessian k (a a^T) (x) I is PSD with
// the one non-zero eigenvalue k |a|^2 per direction.
TEST(SelfContact, FrozenPenaltyGradientHessianAndPsd) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0), w01(0.05, 1.0);
  const int vertices = 7;
  std::vector<double> x(3 * vertices);
  for (double& e : x) e = u(rng);
  std::vector<solver::SelfContactPair> contacts(3);
  const int pick[3][4] = {{0, 1, 2, 3}, {4, 1, 5, 6}, {2, 0, 6, 5}};
  for (int c = 0; c < 3; ++c) {
    contacts[c].sample = pick[c][0];
    double a = w01(rng), b = w01(rng), d = w01(rng), sum = a + b + d;
    contacts[c].weight = {a / sum, b / sum, d / sum};
    contacts[c].vertex = {pick[c][1], pick[c][2], pick[c][3]};
  }
  const double k = 13.0;
  std::vector<double> g(x.size(), 0.0);
  solver::self_contact_gradient(contacts, k, x, g);
  for (size_t i = 0; i < x.size(); ++i) {
    double best = 1e300;
    for (double h = 1e-3; h >= 1e-8; h /= 10) {
      std::vector<double> a = x, b = x;
      a[i] += h;
      b[i] -= h;
      const double fd =
          (solver::self_contact_energy(contacts, k, a) - solver::self_contact_energy(contacts, k, b)) / (2 * h);
      best = std::min(best, std::abs(fd - g[i]));
    }
    EXPECT_LT(best, 1e-8 * (1 + std::abs(g[i]))) << i;
  }
  // Hessian by differences of the gradient (exact: the energy is quadratic).
  const int n = static_cast<int>(x.size());
  Eigen::MatrixXd fd(n, n), exact = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    std::vector<double> a = x, b = x, ga(n, 0.0), gb(n, 0.0);
    a[i] += 1e-4;
    b[i] -= 1e-4;
    solver::self_contact_gradient(contacts, k, a, ga);
    solver::self_contact_gradient(contacts, k, b, gb);
    for (int r = 0; r < n; ++r) fd(r, i) = (ga[r] - gb[r]) / 2e-4;
  }
  for (const auto& c : contacts) {
    const int idx[4] = {c.sample, c.vertex[0], c.vertex[1], c.vertex[2]};
    const double coef[4] = {1.0, -c.weight[0], -c.weight[1], -c.weight[2]};
    for (int p = 0; p < 4; ++p)
      for (int q = 0; q < 4; ++q)
        for (int d = 0; d < 3; ++d) exact(3 * idx[p] + d, 3 * idx[q] + d) += k * coef[p] * coef[q];
  }
  EXPECT_LT((fd - exact).norm(), 1e-7 * exact.norm());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(exact);
  EXPECT_GE(eigen.eigenvalues().minCoeff(), -1e-12 * k);
  for (const auto& c : contacts) {  // one spring alone: eigenvalue k |a|^2, three times
    const double a2 = 1 + c.weight[0] * c.weight[0] + c.weight[1] * c.weight[1] + c.weight[2] * c.weight[2];
    Eigen::MatrixXd one = Eigen::MatrixXd::Zero(n, n);
    const int idx[4] = {c.sample, c.vertex[0], c.vertex[1], c.vertex[2]};
    const double coef[4] = {1.0, -c.weight[0], -c.weight[1], -c.weight[2]};
    for (int p = 0; p < 4; ++p)
      for (int q = 0; q < 4; ++q)
        for (int d = 0; d < 3; ++d) one(3 * idx[p] + d, 3 * idx[q] + d) += k * coef[p] * coef[q];
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> e(one);
    EXPECT_NEAR(e.eigenvalues().maxCoeff(), k * a2, 1e-10 * k);
    EXPECT_GE(e.eigenvalues().minCoeff(), -1e-12 * k);
  }
}

// The SNH_SELF_CONTACT kernels against the host reference: energy, residual,
// Hessian product (cached and assembled variants) and the block-Jacobi
// diagonal gain exactly the frozen springs' terms.
TEST(SelfContact, DeviceTermsMatchTheHostReference) {
  const Mesh mesh = make_box_lattice(6, 2, 2, 1.0);
  const fem::RestState rest = fem::compute_rest_state(mesh);
  const MaterialMap map = uniform_material(mesh, StableNeoHookean::from_youngs_modulus(10.0, 0.3));
  solver::ModelTerms terms;
  terms.self_contact = true;
  solver::ElasticModel<double> with(device_for(Precision::double_), mesh, rest, map, ProductVariant::cached,
                                    device::MaterialKernel::specialized, terms);
  solver::ElasticModel<double> without(device_for(Precision::double_), mesh, rest, map, ProductVariant::cached);
  EXPECT_NE(with.data().config.defines().find("-DSNH_SELF_CONTACT=1"), std::string::npos)
      << with.data().config.defines();
  EXPECT_EQ(without.data().config.defines().find("SNH_SELF_CONTACT"), std::string::npos);
  const double k = 7.0;
  with.contact().set_self_contact_stiffness(k);
  // Two corners pushed into far cells (two springs), the rest jittered.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  std::vector<double> x = mesh.positions.xyz(), p(x.size());
  for (double& e : x) e += jitter(rng);
  for (double& e : p) e = jitter(rng);
  const int s0 = vertex_at(mesh, 0, 0, 2), s1 = vertex_at(mesh, 6, 2, 0);
  x[3 * s0] = 4.5, x[3 * s0 + 1] = 0.3, x[3 * s0 + 2] = 1.5;
  x[3 * s1] = 1.4, x[3 * s1 + 1] = 1.6, x[3 * s1 + 2] = 0.35;
  viennacl::vector<double> xd(x.size()), pd(x.size());
  viennacl::copy(x.begin(), x.end(), xd.begin());
  viennacl::copy(p.begin(), p.end(), pd.begin());
  EXPECT_TRUE(with.contact().refresh_self_contact(xd));
  EXPECT_FALSE(with.contact().refresh_self_contact(xd));  // the same set
  const std::vector<solver::SelfContactPair> contacts = with.contact().self_contacts();
  ASSERT_EQ(contacts.size(), 2u);
  const double energy = solver::self_contact_energy(contacts, k, x);
  EXPECT_GT(energy, 0.0);
  std::vector<double> gradient(x.size(), 0.0), product(x.size(), 0.0);
  solver::self_contact_gradient(contacts, k, x, gradient);
  solver::self_contact_gradient(contacts, k, p, product);  // linear: H p = grad E(p)
  for (double& g : gradient) g = -g;                       // the force
  expect_vertex_term_matches(with, without, xd, pd, energy, gradient, product);
  // Block-Jacobi: the inverted diagonal blocks of (elastic + k a_i^2 I).
  with.products().set_variant(ProductVariant::cached);
  without.products().set_variant(ProductVariant::cached);
  with.linearize(xd, true);
  without.linearize(xd, true);
  with.setup_preconditioner();
  without.setup_preconditioner();
  const std::vector<double> bw = with.preconditioner_blocks(), bo = without.preconditioner_blocks();
  std::vector<double> diagonal(mesh.vertex_count(), 0.0);
  for (const auto& c : contacts) {
    diagonal[c.sample] += k;
    for (int j = 0; j < 3; ++j) diagonal[c.vertex[j]] += k * c.weight[j] * c.weight[j];
  }
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Eigen::Matrix3d inv_with = Eigen::Map<const Eigen::Matrix3d>(&bw[9 * v]);
    const Eigen::Matrix3d inv_without = Eigen::Map<const Eigen::Matrix3d>(&bo[9 * v]);
    const Eigen::Matrix3d expected = inv_without.inverse() + diagonal[v] * Eigen::Matrix3d::Identity();
    EXPECT_LT((inv_with.inverse() - expected).norm(), 1e-9 * expected.norm()) << v;
  }
  const solver::ContactState state = with.contact().contact_state(xd);
  EXPECT_EQ(state.self_contacts, 2);
  EXPECT_NEAR(state.max_self_penetration,
              std::max(solver::self_contact_length(contacts[0], x), solver::self_contact_length(contacts[1], x)),
              1e-15);
}

TEST(SelfContact, OptionsAreValidated) {
  const Mesh mesh = make_box_lattice(2, 1, 1, 1.0);
  const ConstraintSet fixed{"fixed", {0, 3, 6, 9}, {}, {}, {true, true, true}};
  SolveOptions options;
  options.contact.self = true;
  options.contact.self_method = SelfContactMethod::penalty;
  EXPECT_THROW(Simulation(mesh, StableNeoHookean::from_youngs_modulus(10.0, 0.3), {fixed}, options), Error);
  options.contact.self_stiffness = -1.0;
  options.contact.stiffness = 1.0;
  EXPECT_THROW(Simulation(mesh, StableNeoHookean::from_youngs_modulus(10.0, 0.3), {fixed}, options), Error);
  options.contact.self_stiffness.reset();
  options.preconditioner = Preconditioner::multigrid;
  EXPECT_THROW(Simulation(mesh, StableNeoHookean::from_youngs_modulus(10.0, 0.3), {fixed}, options), Error);
}

// Self-contact combined with dynamics and an obstacle: the kernels carry all
// three terms and a block falling onto a plane behaves as without
// self-contact while no sample is in contact (bitwise the same positions).
TEST(SelfContact, CombinesWithDynamicsAndObstacles) {
  const Mesh mesh = make_box_lattice(2, 2, 2, 0.05);
  SolveOptions options;
  DynamicsOptions d;
  d.time_step = 0.01;
  d.density = 1000.0;
  options.dynamics = d;
  options.body_force = {0.0, 0.0, -9810.0};
  options.obstacles = {Obstacle::plane({0, 0, -0.002}, {0, 0, 1})};
  options.contact.stiffness = 1e4;
  options.contact.thickness = 0.005;
  options.load_steps = 5;
  const StableNeoHookean material = StableNeoHookean::from_youngs_modulus(1e5, 0.4);
  const SolveResult plain = QuasistaticSolver(mesh, material, {}, options).solve();
  options.contact.self = true;
  options.contact.self_method = SelfContactMethod::penalty;
  const SolveResult with = QuasistaticSolver(mesh, material, {}, options).solve();
  ASSERT_TRUE(with.converged);
  for (const char* term : {"-DSNH_INERTIA=1", "-DSNH_OBSTACLES=1", "-DSNH_SELF_CONTACT=1"})
    EXPECT_NE(with.kernel_specialization.find(term), std::string::npos) << term;
  EXPECT_GT(with.steps.back().contacts, 0);  // resting on the plane
  for (const StepResult& s : with.steps) EXPECT_EQ(s.self_contacts, 0);
  ASSERT_EQ(plain.positions.xyz().size(), with.positions.xyz().size());
  for (size_t i = 0; i < plain.positions.xyz().size(); ++i)
    EXPECT_EQ(plain.positions.xyz()[i], with.positions.xyz()[i]) << i;
}

// The elbow at a small size (18 x 3 x 3 hexes, flexed 140 degrees in its 28
// steps; 7 without self-contact, where the elastic solve needs no more):
// without self-contact the inner side passes through itself (the detector
// finds samples deep inside non-adjacent elements); with it every
// step converges and no sample is deeper than the contact thickness, and a
// rerun gives bitwise the same positions.
TEST(SelfContact, ElbowFoldsWithoutPassingThrough) {
  SceneParameters parameters;
  parameters.resolution = 3;
  Scene scene = make_scene("elbow", parameters);
  ASSERT_TRUE(scene.options.contact.self);
  const double thickness = scene.options.contact.thickness;
  const solver::SelfContactDetector detector(scene.mesh);

  Scene free = scene;
  free.options.contact.self = false;
  free.options.load_steps = 7;
  const SolveResult passed = QuasistaticSolver(free.mesh, free.material, free.constraints, free.options).solve();
  ASSERT_TRUE(passed.converged);
  const auto crossing = detector.detect(passed.positions.xyz());
  double deepest = 0.0;
  for (const auto& c : crossing) deepest = std::max(deepest, solver::self_contact_length(c, passed.positions.xyz()));
  EXPECT_GE(crossing.size(), 4u);
  EXPECT_GT(deepest, 3.0 * thickness) << "the inner side should pass through itself without self-contact";

  QuasistaticSolver solver(scene.mesh, scene.material, scene.constraints, scene.options);
  const SolveResult held = solver.solve();
  ASSERT_TRUE(held.converged);
  EXPECT_NE(held.kernel_specialization.find("-DSNH_SELF_CONTACT=1"), std::string::npos);
  for (const StepResult& s : held.steps) {
    EXPECT_TRUE(s.converged) << s.step;
    EXPECT_LE(s.max_self_penetration, thickness) << s.step;
    EXPECT_EQ(s.contacts, s.self_contacts);  // no obstacles
  }
  EXPECT_GT(held.steps.back().self_contacts, 0);
  double held_deepest = 0.0;
  for (const auto& c : detector.detect(held.positions.xyz()))
    held_deepest = std::max(held_deepest, solver::self_contact_length(c, held.positions.xyz()));
  EXPECT_LE(held_deepest, thickness);
  EXPECT_GT(held.min_j, 0.0);

  const SolveResult again = solver.solve();
  ASSERT_EQ(again.positions.xyz().size(), held.positions.xyz().size());
  for (size_t i = 0; i < held.positions.xyz().size(); ++i)
    ASSERT_EQ(again.positions.xyz()[i], held.positions.xyz()[i]) << i;
}

// The elbow's tet4 version at its full size (2,304 tets). Its inner side
// touches from step 21 on, where new samples enter the active set between
// Newton iterations; every step must still converge (steps 21 and 28
// stagnated when progress was compared across active sets) and hold the
// samples within the contact thickness.
TEST(SelfContact, TetElbowConvergesEveryStepWithinTheThickness) {
  SceneParameters parameters;
  parameters.element_type = ElementType::tet4;
  Scene scene = make_scene("elbow", parameters);
  ASSERT_EQ(scene.mesh.element_count(), 2304u);
  const double thickness = scene.options.contact.thickness;
  const SolveResult held = QuasistaticSolver(scene.mesh, scene.material, scene.constraints, scene.options).solve();
  EXPECT_TRUE(held.converged);
  for (const StepResult& s : held.steps) {
    EXPECT_TRUE(s.converged) << s.step << ": " << s.status;
    EXPECT_LE(s.max_self_penetration, thickness) << s.step;
  }
  EXPECT_GT(held.steps.back().self_contacts, 0);
  EXPECT_EQ(held.inverted_elements, 0);
}

}  // namespace
}  // namespace snh::test
