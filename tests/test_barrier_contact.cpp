// Barrier self-contact (solver/contact/barrier_contact.h, barrier_terms.h): the host
// detection (no pair at rest, pairs sharing a vertex excluded, gradient
// against differences, assembled Hessian symmetric and PSD, bitwise
// repeatable), the CCD step bound on a lattice, the device terms (the mesh's
// boundary and an embedded surface, double and float) against the host
// reference, builds without it unchanged, and the squash to 5% that
// folds through itself without it and holds with it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "fem/rest_state.h"
#include "snh/error.h"
#include "snh/scene.h"
#include "snh/scenes.h"
#include "snh/simulation.h"
#include "snh/surface.h"
#include "snh/surface_intersections.h"
#include "solver/contact/barrier_contact.h"
#include "solver/model/elastic_model.h"
#include "solver/newton/newton_driver.h"
#include "stability.h"
#include "support/device_test_support.h"

namespace snh::test {
namespace {

namespace fs = std::filesystem;

using V3 = std::array<double, 3>;
V3 at(const std::vector<double>& x, int v) { return {x[3 * v], x[3 * v + 1], x[3 * v + 2]}; }
double orient(const V3& a, const V3& b, const V3& c, const V3& d) {
  const V3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]},
      w{d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}
// Segment pq properly crosses triangle abc (strict signs: touching is not
// counted).
bool segment_crosses(const V3& p, const V3& q, const V3& a, const V3& b, const V3& c) {
  const double op = orient(a, b, c, p), oq = orient(a, b, c, q);
  if (!(op * oq < 0.0)) return false;
  const double s0 = orient(p, q, a, b), s1 = orient(p, q, b, c), s2 = orient(p, q, c, a);
  return (s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0);
}
// Pairs of surface triangles sharing no vertex where an edge of one crosses
// the other.
int intersecting_triangle_pairs(const solver::BarrierContact& surface, const std::vector<double>& x) {
  const std::vector<int>& t = surface.triangles();
  const size_t n = t.size() / 3;
  int count = 0;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) {
      bool shared = false;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) shared = shared || t[3 * i + a] == t[3 * j + b];
      if (shared) continue;
      bool hit = false;
      for (int pass = 0; pass < 2 && !hit; ++pass) {
        const size_t e = pass ? j : i, f = pass ? i : j;
        const V3 a = at(x, t[3 * f]), b = at(x, t[3 * f + 1]), c = at(x, t[3 * f + 2]);
        for (int k = 0; k < 3 && !hit; ++k)
          hit = segment_crosses(at(x, t[3 * e + k]), at(x, t[3 * e + (k + 1) % 3]), a, b, c);
      }
      count += hit;
    }
  return count;
}

// Two 2 x 2 x 1 lattices of unit cells, one mesh: B above A, shifted by
// (0.3, 0.2) and 0.07 clear of A's top face (z = 1): point-triangle and
// edge-edge pairs (crossing and parallel edges) within dhat = 0.2, and a
// step of B down through A.
struct Fixture {
  Mesh mesh = make_box_lattice(2, 2, 1, 1.0);
  int first_b = 0;
  std::vector<double> x;
  Fixture() {
    const Mesh b = make_box_lattice(2, 2, 1, 1.0, {0.3, 0.2, 1.07});
    first_b = static_cast<int>(mesh.vertex_count());
    for (size_t v = 0; v < b.vertex_count(); ++v) mesh.positions.push_back(b.vertex(v));
    for (int32_t v : b.elements) mesh.elements.push_back(v + first_b);
    x = mesh.positions.xyz();
  }
  // B's vertices moved by dz.
  std::vector<double> b_down(double dz) const {
    std::vector<double> p(x.size(), 0.0);
    for (size_t v = first_b; v < mesh.vertex_count(); ++v) p[3 * v + 2] = dz;
    return p;
  }
};

// kappa times the barrier energy at x: its gradient against central
// differences (step 1e-7, within 1e-6 of its largest entry), and its Hessian,
// each vertex's blocks in ascending columns, assembled dense: symmetric, PSD
// and not zero. `hessian` gets the Hessian.
void expect_gradient_and_psd_hessian(const solver::BarrierContact& contact, const std::vector<double>& x, double kappa,
                                     solver::BarrierHessian& hessian) {
  auto energy = [&](const std::vector<double>& y) { return kappa * contact.energy(y, contact.near_pairs(y), nullptr); };
  std::vector<double> g(x.size(), 0.0);
  contact.add_gradient(x, contact.near_pairs(x), kappa, g);
  double scale = 0.0;
  for (double e : g) scale = std::max(scale, std::abs(e));
  ASSERT_GT(scale, 0.0);
  for (size_t i = 0; i < x.size(); ++i) {
    std::vector<double> plus = x, minus = x;
    plus[i] += 1e-7;
    minus[i] -= 1e-7;
    EXPECT_NEAR((energy(plus) - energy(minus)) / 2e-7, g[i], 1e-6 * scale) << i;
  }
  hessian = contact.hessian(x, contact.near_pairs(x), kappa);
  const solver::BarrierHessian& h = hessian;
  const size_t n = x.size();
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  for (size_t v = 0; v + 1 < h.offsets.size(); ++v)
    for (int k = h.offsets[v]; k < h.offsets[v + 1]; ++k) {
      if (k > h.offsets[v]) {
        EXPECT_LT(h.columns[k - 1], h.columns[k]);
      }
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) dense(3 * v + i, 3 * h.columns[k] + j) = h.blocks[9 * k + 3 * i + j];
    }
  EXPECT_LT((dense - dense.transpose()).norm(), 1e-12 * dense.norm());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(0.5 * (dense + dense.transpose()));
  EXPECT_GE(eigen.eigenvalues().minCoeff(), -1e-10 * dense.norm());
  EXPECT_GT(eigen.eigenvalues().maxCoeff(), 0.0);
}

TEST(BarrierContact, NoPairAtRestAndNearPairsExcludeNeighbours) {
  const Mesh lattice = make_box_lattice(3, 2, 2, 1.0);
  solver::BarrierContact rest(lattice);
  EXPECT_EQ(rest.triangle_count(), 2u * (2 * 3 * 2 + 2 * 3 * 2 + 2 * 2 * 2));
  rest.set_distance(solver::kDefaultSelfDistance * rest.length_scale());
  EXPECT_TRUE(rest.near_pairs(lattice.positions.xyz()).empty());
  // Even at 0.55 h nothing of the rest surface is in range: the closest
  // non-adjacent rest features, the quad diagonals of two faces meeting at
  // an edge, are h / sqrt(3) apart.
  rest.set_distance(0.55);
  EXPECT_TRUE(rest.near_pairs(lattice.positions.xyz()).empty());
  EXPECT_NEAR(rest.min_distance(lattice.positions.xyz(), 2.0), std::sqrt(1.0 / 3.0), 1e-12);

  const Fixture f;
  solver::BarrierContact contact(f.mesh);
  contact.set_distance(0.2);
  const std::vector<solver::BarrierPair> pairs = contact.near_pairs(f.x);
  ASSERT_FALSE(pairs.empty());
  int kinds[2] = {0, 0};
  for (const solver::BarrierPair& p : pairs) {
    ++kinds[p.kind];
    // Across the gap only: one side in A, the other in B.
    const bool a0 = p.vertex[0] < f.first_b;
    const int split = p.kind == 0 ? 1 : 2;
    for (int k = 0; k < 4; ++k) EXPECT_EQ(p.vertex[k] < f.first_b, k < split ? a0 : !a0) << "a pair within one body";
  }
  EXPECT_GT(kinds[0], 0);
  EXPECT_GT(kinds[1], 0);
  double smallest = 0.0;
  contact.energy(f.x, pairs, &smallest);
  EXPECT_NEAR(smallest, 0.07, 1e-12);
  EXPECT_NEAR(contact.min_distance(f.x, 0.2), 0.07, 1e-12);
  EXPECT_EQ(pairs, contact.near_pairs(f.x));  // the same order every time
}

TEST(BarrierContact, GradientMatchesDifferencesAndHessianIsSymmetricPsdAndRepeatable) {
  const Fixture f;
  solver::BarrierContact contact(f.mesh);
  contact.set_distance(0.2);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  std::vector<double> x = f.x;
  for (double& e : x) e += jitter(rng);
  const double kappa = 3.0;
  solver::BarrierHessian h;
  ASSERT_NO_FATAL_FAILURE(expect_gradient_and_psd_hessian(contact, x, kappa, h));
  const solver::BarrierHessian again = contact.hessian(x, contact.near_pairs(x), kappa);
  EXPECT_EQ(again.blocks, h.blocks);  // bitwise
  EXPECT_EQ(again.columns, h.columns);
}

// The fixture's boundary as an embedded surface whose vertices sit inside
// their cells (0.9 of the way from the cell's farthest corner to their own
// corner): its positions are W x, not mesh vertices.
struct EmbeddedFixture : Fixture {
  TriangleSurface surface;
  Embedding embedding;
  EmbeddedFixture() {
    const MeshBoundary boundary = boundary_surface(mesh);
    surface = boundary.surface;
    const size_t n = surface.vertex_count();
    embedding.element.assign(n, -1);
    embedding.weights.assign(8 * n, 0.0);
    for (size_t s = 0; s < n; ++s) {
      const int32_t m = boundary.vertices[s];
      for (size_t e = 0; e < mesh.element_count() && embedding.element[s] < 0; ++e)
        for (int k = 0; k < 8; ++k)
          if (mesh.elements[8 * e + k] == m) {
            embedding.element[s] = static_cast<int32_t>(e);
            int far = k;
            double farthest = 0.0;
            for (int l = 0; l < 8; ++l) {
              double d2 = 0.0;
              for (int d = 0; d < 3; ++d) {
                const double a = mesh.positions(mesh.elements[8 * e + l], d) - mesh.positions(m, d);
                d2 += a * a;
              }
              if (d2 > farthest) farthest = d2, far = l;
            }
            embedding.weights[8 * s + k] = 0.9;
            embedding.weights[8 * s + far] = 0.1;
          }
    }
    surface.positions = embedded_positions(embedding, mesh, mesh.positions);
  }
};

TEST(BarrierContact, EmbeddedSurfaceGradientHessianAndStepBoundAreCarriedByTheCells) {
  const EmbeddedFixture f;
  solver::BarrierContact contact(f.mesh, f.surface, f.embedding);
  contact.set_distance(0.3);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  std::vector<double> x = f.x;
  for (double& e : x) e += jitter(rng);
  ASSERT_FALSE(contact.near_pairs(x).empty());
  const double kappa = 2.0;
  // W^T H W: symmetric and PSD over the lattice's DOFs, and its product with
  // a direction equals the gradient's directional difference within the
  // projection (here the pair Hessians' clamped parts are checked by sign).
  solver::BarrierHessian h;
  ASSERT_NO_FATAL_FAILURE(expect_gradient_and_psd_hessian(contact, x, kappa, h));
  ASSERT_EQ(h.offsets.size(), f.mesh.vertex_count() + 1);
  // B's cells down through A's: the bound stops the embedded surfaces apart.
  contact.set_distance(0.02);
  const std::vector<double> p = f.b_down(-0.6);
  const double alpha = contact.step_bound(f.x, p);
  EXPECT_GT(alpha, 0.0);
  EXPECT_LT(alpha, 1.0);
  std::vector<double> y = f.x, full = f.x;
  for (size_t i = 0; i < y.size(); ++i) y[i] += alpha * p[i], full[i] += p[i];
  EXPECT_EQ(count_self_intersections(embedded_positions(f.embedding, f.mesh, Points::from_xyz(y)), f.surface.triangles)
                .intersecting_pairs,
            0u);
  EXPECT_GT(
      count_self_intersections(embedded_positions(f.embedding, f.mesh, Points::from_xyz(full)), f.surface.triangles)
          .intersecting_pairs,
      0u);
}

// Pairs closer than dhat at rest (B starts 0.07 above A, dhat 0.2) are
// left out: none is near at rest, and a step down is no longer bounded by
// them; a larger gap keeps every pair.
TEST(BarrierContact, PairsCloserThanDhatAtRestAreLeftOut) {
  const Fixture f;
  solver::BarrierContact contact(f.mesh);
  contact.set_distance(0.2);
  const size_t near = contact.near_pairs(f.x).size();
  ASSERT_GT(near, 0u);
  EXPECT_EQ(contact.exclude_pairs_near(f.x), near);
  EXPECT_TRUE(contact.near_pairs(f.x).empty());
  EXPECT_EQ(contact.step_bound(f.x, f.b_down(-0.05)), 1.0);
  contact.set_distance(0.05);
  EXPECT_EQ(contact.exclude_pairs_near(f.x), 0u);
  EXPECT_LT(contact.step_bound(f.x, f.b_down(-0.6)), 1.0);
}

// A rigged embedded scene turns barrier self-contact on by default, on its
// embedded surface, and its frames report the barrier's pairs, distance and
// time; "self": false turns it off.
TEST(BarrierContact, RiggedScenesHaveSelfContactByDefaultAndFramesReportIt) {
  const std::string path = std::string(SNH_DATA_DIR) + "/scenes/arm.json";
  const SceneFile f = load_scene(path);
  ASSERT_TRUE(f.rig);
  EXPECT_TRUE(f.scene.options.contact.self);
  EXPECT_EQ(f.scene.options.contact.self_method, SelfContactMethod::barrier);
  EXPECT_EQ(f.scene.options.contact.self_surface.triangles, f.embedded->surface.triangles);
  SceneRunOptions first;
  first.max_frames = 3;
  const SceneRun run = run_scene(f, f.scene.options, first);
  ASSERT_EQ(run.frames.size(), 3u);
  EXPECT_TRUE(run.converged);
  double seconds = 0.0;
  for (const FrameRecord& r : run.frames) {
    EXPECT_GT(r.min_self_distance, 0.0);
    seconds += r.self_contact_seconds;
  }
  EXPECT_GT(seconds, 0.0);

  const fs::path dir = fs::temp_directory_path() / ("snh_rig_self_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  nlohmann::json doc;
  std::ifstream(path) >> doc;
  doc["contact"] = {{"self", false}};
  doc["embed"]["surface"] = std::string(SNH_DATA_DIR) + "/arm/arm.obj";
  doc["rig"]["animation"] = std::string(SNH_DATA_DIR) + "/arm/arm_flexion.json";
  doc.erase("output");
  std::ofstream(dir / "arm.json") << doc.dump();
  EXPECT_FALSE(load_scene((dir / "arm.json").string()).scene.options.contact.self);
  fs::remove_all(dir);
}

// The shipped embedded contact scenes with barrier self-contact: every step
// converges and the embedded (output) surface never intersects itself.
TEST(BarrierContact, EmbeddedScenesHoldWithoutIntersection) {
  for (const char* name : {"hand_head", "limbs_pressed"}) {
    SCOPED_TRACE(name);
    SceneFile f = load_scene(std::string(SNH_DATA_DIR) + "/scenes/" + name + ".json");
    ASSERT_TRUE(f.embedded);
    ASSERT_TRUE(f.check_intersections);
    ASSERT_TRUE(f.scene.options.contact.self);
    ASSERT_EQ(f.scene.options.contact.self_method, SelfContactMethod::barrier);
    ASSERT_FALSE(f.scene.options.contact.self_surface.triangles.empty());
    const SceneRun run = run_scene(f, f.scene.options);
    EXPECT_TRUE(run.converged);
    ASSERT_FALSE(run.surface_intersections.empty());
    for (const SelfIntersections& step : run.surface_intersections) EXPECT_EQ(step.intersecting_pairs, 0u);
  }
}

TEST(BarrierContact, StepBoundStopsAStepThroughTheSurface) {
  const Fixture f;
  solver::BarrierContact contact(f.mesh);
  contact.set_distance(0.02);
  // B down by 0.57: its bottom meets A's top at alpha = 0.07 / 0.57.
  const std::vector<double> p = f.b_down(-0.57);
  const double bound = contact.step_bound(f.x, p);
  EXPECT_GT(bound, 0.0);
  EXPECT_LT(bound, 0.07 / 0.57);
  std::vector<double> y = f.x;
  for (size_t i = 0; i < y.size(); ++i) y[i] += bound * p[i];
  EXPECT_GT(contact.min_distance(y, 0.2), 0.0);
  EXPECT_EQ(intersecting_triangle_pairs(contact, y), 0);
  // Without the bound, the full step crosses.
  std::vector<double> full = f.x;
  for (size_t i = 0; i < full.size(); ++i) full[i] += p[i];
  EXPECT_GT(intersecting_triangle_pairs(contact, full), 0);
  // A step sideways stays whole.
  std::vector<double> along(f.x.size(), 0.0);
  for (size_t v = f.first_b; v < f.mesh.vertex_count(); ++v) along[3 * v] = 0.3;
  EXPECT_EQ(contact.step_bound(f.x, along), 1.0);
}

// The SNH_SELF_BARRIER model `with` (dhat and kappa set, the surface of
// `host`) against the host reference at jittered positions of f: energy,
// residual, products (cached and assembled) and block-Jacobi's diagonal
// gain exactly kappa sum b, its force and its projected Hessian, within
// 1e-12; the pair count matches; evaluating again gives the same bits; the
// step bound is the host's.
void expect_barrier_matches(const Fixture& f, solver::ElasticModel<double>& with, solver::ElasticModel<double>& without,
                            const solver::BarrierContact& host, double kappa) {
  // B 0.04 closer than at rest, jittered: pairs within a dhat below the
  // rest gap (pairs closer at rest are left out).
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.005, 0.005);
  std::vector<double> x = f.x, p(x.size());
  const std::vector<double> closer = f.b_down(-0.04);
  for (size_t i = 0; i < x.size(); ++i) x[i] += closer[i] + jitter(rng);
  for (double& e : p) e = jitter(rng);
  viennacl::vector<double> xd(x.size()), pd(x.size());
  viennacl::copy(x.begin(), x.end(), xd.begin());
  viennacl::copy(p.begin(), p.end(), pd.begin());
  const std::vector<solver::BarrierPair> pairs = host.near_pairs(x);
  ASSERT_FALSE(pairs.empty());
  const double energy = kappa * host.energy(x, pairs, nullptr);
  EXPECT_GT(energy, 0.0);
  std::vector<double> force(x.size(), 0.0);
  host.add_gradient(x, pairs, kappa, force);
  for (double& e : force) e = -e;
  const solver::BarrierHessian h = host.hessian(x, pairs, kappa);
  std::vector<double> product(x.size(), 0.0);
  for (size_t v = 0; v + 1 < h.offsets.size(); ++v)
    for (int k = h.offsets[v]; k < h.offsets[v + 1]; ++k)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) product[3 * v + i] += h.blocks[9 * k + 3 * i + j] * p[3 * h.columns[k] + j];
  expect_vertex_term_matches(with, without, xd, pd, energy, force, product);
  with.energy(xd);
  EXPECT_EQ(with.contact().self_barrier()->state().pairs, static_cast<int>(pairs.size()));
  double smallest = 0.0;
  host.energy(x, pairs, &smallest);
  EXPECT_NEAR(with.contact().self_barrier()->state().min_distance, smallest, 1e-15);
  // Repeatable: the same x and p give the same bits (no atomics).
  auto twice = [&](auto run) {
    viennacl::vector<double> a(x.size()), b(x.size());
    a.clear();
    b.clear();
    run(a);
    run(b);
    EXPECT_EQ(download_raw(a), download_raw(b));
  };
  twice([&](viennacl::vector<double>& out) { with.residual(xd, out); });
  twice([&](viennacl::vector<double>& out) {
    with.linearize(xd, true);
    out.clear();
    with.product(pd, out);
  });
  // Block-Jacobi: the inverted diagonal blocks of (elastic + barrier).
  with.products().set_variant(ProductVariant::cached);
  without.products().set_variant(ProductVariant::cached);
  with.linearize(xd, true);
  without.linearize(xd, true);
  with.setup_preconditioner();
  without.setup_preconditioner();
  const std::vector<double> bw = with.preconditioner_blocks(), bo = without.preconditioner_blocks();
  int touched = 0;
  for (size_t v = 0; v < f.mesh.vertex_count(); ++v) {
    Eigen::Matrix3d block = Eigen::Matrix3d::Zero();
    for (int k = h.offsets[v]; k < h.offsets[v + 1]; ++k)
      if (h.columns[k] == static_cast<int>(v))
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) block(i, j) = h.blocks[9 * k + 3 * i + j];
    touched += block.norm() > 0.0;
    const Eigen::Matrix3d inv_with = Eigen::Map<const Eigen::Matrix3d>(&bw[9 * v]);
    const Eigen::Matrix3d inv_without = Eigen::Map<const Eigen::Matrix3d>(&bo[9 * v]);
    const Eigen::Matrix3d expected = inv_without.inverse() + block;
    EXPECT_LT((inv_with.inverse() - expected).norm(), 1e-9 * expected.norm()) << v;
  }
  EXPECT_GT(touched, 0);
  // The step bound through the device model: as the host's (the minimum of
  // per-pair times of impact, each over [0, 1]).
  for (double dz : {-0.57, -0.3, -0.05}) {
    const std::vector<double> down = f.b_down(dz);
    const double reference = host.step_bound(x, down);
    EXPECT_NEAR(with.contact().step_bound(xd, upload<double>(down)), reference, 1e-15) << dz;
    if (dz == -0.57) {
      EXPECT_LT(reference, 1.0);
    }
  }
}

// The SNH_SELF_BARRIER model against the host reference: energy, residual,
// products (cached and assembled) and block-Jacobi's diagonal gain exactly
// kappa sum b, its force and its projected Hessian.
TEST(BarrierContact, DeviceTermsMatchTheHostReference) {
  const Fixture f;
  const fem::RestState rest = fem::compute_rest_state(f.mesh);
  const MaterialMap map = uniform_material(f.mesh, StableNeoHookean::from_youngs_modulus(10.0, 0.3));
  solver::ModelTerms terms;
  terms.self_barrier = true;
  solver::ElasticModel<double> with(device_for(Precision::double_), f.mesh, rest, map, ProductVariant::cached,
                                    device::MaterialKernel::specialized, terms);
  solver::ElasticModel<double> without(device_for(Precision::double_), f.mesh, rest, map, ProductVariant::cached);
  EXPECT_NE(with.data().config.defines().find("-DSNH_SELF_BARRIER=1"), std::string::npos)
      << with.data().config.defines();
  EXPECT_EQ(without.data().config.defines().find("SNH_SELF_BARRIER"), std::string::npos);
  EXPECT_EQ(with.data().elastic_config.defines(), without.data().config.defines());
  EXPECT_THROW(without.contact().set_self_barrier(0.2, 1.0), Error);
  EXPECT_THROW(with.contact().set_self_barrier(0.0, 1.0), Error);
  // dhat below the rest gap of 0.07 (pairs closer at rest are left out),
  // B moved 0.04 closer.
  const double dhat = 0.05, kappa = 2.0;
  with.contact().set_self_barrier(dhat, kappa);
  solver::BarrierContact host(f.mesh);
  host.set_distance(dhat);
  expect_barrier_matches(f, with, without, host, kappa);
  EXPECT_EQ(without.contact().step_bound(upload<double>(f.x), upload<double>(f.b_down(-0.57))),
            std::numeric_limits<double>::infinity());
}

// The same on an embedded surface (positions W x, 8 weights per vertex
// lifted on the device): energy, force W^T g, products W^T H W p,
// block-Jacobi's diagonal blocks and the step bound as the host's.
TEST(BarrierContact, DeviceTermsOnAnEmbeddedSurfaceMatchTheHostReference) {
  const EmbeddedFixture f;
  const fem::RestState rest = fem::compute_rest_state(f.mesh);
  const MaterialMap map = uniform_material(f.mesh, StableNeoHookean::from_youngs_modulus(10.0, 0.3));
  solver::ModelTerms terms;
  terms.self_barrier = true;
  solver::ElasticModel<double> with(device_for(Precision::double_), f.mesh, rest, map, ProductVariant::cached,
                                    device::MaterialKernel::specialized, terms);
  solver::ElasticModel<double> without(device_for(Precision::double_), f.mesh, rest, map, ProductVariant::cached);
  // The embedded surfaces are 0.27 apart at rest.
  const double dhat = 0.25, kappa = 2.0;
  with.contact().set_self_barrier(dhat, kappa);
  with.contact().set_self_barrier_surface(f.mesh, f.surface, f.embedding);
  solver::BarrierContact host(f.mesh, f.surface, f.embedding);
  host.set_distance(dhat);
  expect_barrier_matches(f, with, without, host, kappa);
}

// A float solve on a device with fp64: the pair math still in double from
// the float positions, so the energy matches the host reference at those
// positions to 1e-12; the force, blocks and products are rounded to float
// once per entry and summed in float, so they match within a few float
// roundings of the largest term they are summed with.
TEST(BarrierContact, FloatDeviceTermsMatchTheHostReferenceWithinFloatRounding) {
  if (!device_for(Precision::single).info().has_fp64) GTEST_SKIP() << "the device has no fp64";
  const Fixture f;
  const fem::RestState rest = fem::compute_rest_state(f.mesh);
  const MaterialMap map = uniform_material(f.mesh, StableNeoHookean::from_youngs_modulus(10.0, 0.3));
  solver::ModelTerms terms;
  terms.self_barrier = true;
  auto& cl = device_for(Precision::single);
  solver::ElasticModel<float> with(cl, f.mesh, rest, map, ProductVariant::cached, device::MaterialKernel::specialized,
                                   terms);
  solver::ElasticModel<float> without(cl, f.mesh, rest, map, ProductVariant::cached);
  const double dhat = 0.05, kappa = 2.0;  // below the rest gap of 0.07
  with.contact().set_self_barrier(dhat, kappa);
  EXPECT_TRUE(with.contact().self_barrier()->pairs_in_double());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.005, 0.005);
  std::vector<double> x = f.x, p(x.size());
  const std::vector<double> closer = f.b_down(-0.04);
  for (size_t i = 0; i < x.size(); ++i) x[i] += closer[i] + jitter(rng);
  for (double& e : p) e = jitter(rng);
  x = rounded<float>(x);
  p = rounded<float>(p);
  solver::BarrierContact host(f.mesh);
  host.set_distance(dhat);
  const std::vector<solver::BarrierPair> pairs = host.near_pairs(x);
  ASSERT_FALSE(pairs.empty());
  const double energy = kappa * host.energy(x, pairs, nullptr);
  std::vector<double> gradient(x.size(), 0.0);
  host.add_gradient(x, pairs, kappa, gradient);
  const solver::BarrierHessian h = host.hessian(x, pairs, kappa);
  std::vector<double> product(x.size(), 0.0), magnitude(x.size(), 0.0);
  for (size_t v = 0; v + 1 < h.offsets.size(); ++v)
    for (int k = h.offsets[v]; k < h.offsets[v + 1]; ++k)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          product[3 * v + i] += h.blocks[9 * k + 3 * i + j] * p[3 * h.columns[k] + j];
          magnitude[3 * v + i] += std::abs(h.blocks[9 * k + 3 * i + j] * p[3 * h.columns[k] + j]);
        }
  const viennacl::vector<float> xd = upload<float>(x), pd = upload<float>(p);
  EXPECT_NEAR(with.energy(xd) - without.energy(xd), energy, 1e-12 * energy + 1e-6 * std::abs(without.energy(xd)));
  viennacl::vector<float> rw(x.size()), ro(x.size()), yw(x.size()), yo(x.size());
  with.residual(xd, rw);
  without.residual(xd, ro);
  const std::vector<double> a = download(rw), b = download(ro);
  double scale = 0.0;
  for (size_t i = 0; i < a.size(); ++i) scale = std::max({scale, std::abs(a[i]), std::abs(b[i])});
  int moved = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a[i] - b[i], -gradient[i], 4 * FLT_EPSILON * (scale + std::abs(gradient[i]))) << i;
    moved += gradient[i] != 0.0;
  }
  EXPECT_GT(moved, 0);
  with.linearize(xd, true);
  without.linearize(xd, true);
  with.product(pd, yw);
  without.product(pd, yo);
  const std::vector<double> c = download(yw), d = download(yo);
  for (size_t i = 0; i < c.size(); ++i)
    EXPECT_NEAR(c[i] - d[i], product[i], 8 * FLT_EPSILON * (std::abs(c[i]) + std::abs(d[i]) + magnitude[i])) << i;
}

// A problem without the hook and the same problem with an unbounded one:
// the driver runs them bit for bit alike (problems without barrier
// self-contact are untouched).
struct Quartic {
  using Vector = std::vector<double>;
  size_t dofs() const { return 2; }
  double epsilon() const { return 1e-16; }
  Vector vector() const { return Vector(2, 0.0); }
  double energy(const Vector& x) { return std::pow(x[0] - 1, 4) + 0.5 * x[1] * x[1] + x[0] * x[1] * 0.1; }
  double last_min_j() const { return 1.0; }
  void residual(const Vector& x, Vector& r) {
    r[0] = -(4 * std::pow(x[0] - 1, 3) + 0.1 * x[1]);
    r[1] = -(x[1] + 0.1 * x[0]);
  }
  double norm(const Vector& v) const { return std::sqrt(dot(v, v)); }
  double dot(const Vector& a, const Vector& b) const { return a[0] * b[0] + a[1] * b[1]; }
  Vector x_lin;
  void linearize(const Vector& x, bool) { x_lin = x; }
  solver::LinearSolve solve(const Vector& r, Vector& p, double, int) {
    const double a = std::max(12 * std::pow(x_lin[0] - 1, 2), 1e-3), b = 0.1, c = 1.0, det = a * c - b * b;
    p[0] = (c * r[0] - b * r[1]) / det;
    p[1] = (a * r[1] - b * r[0]) / det;
    return {1, 0.0, false, false};
  }
  void precondition(const Vector& r, Vector& p) { p = r; }
  void step(const Vector& x, double alpha, const Vector& p, Vector& out) {
    for (int i = 0; i < 2; ++i) out[i] = x[i] + alpha * p[i];
  }
  void swap(Vector& a, Vector& b) { a.swap(b); }
  bool has_true_hessian() const { return false; }
};
struct UnboundedQuartic : Quartic {
  double step_bound(const Vector&, const Vector&) { return std::numeric_limits<double>::infinity(); }
};
struct BoundedQuartic : Quartic {
  double step_bound(const Vector&, const Vector&) { return 0.25; }
};

TEST(BarrierContact, DriverWithoutABoundIsUnchangedAndABoundCapsEveryStep) {
  static_assert(!solver::HasStepBound<Quartic>::value && solver::HasStepBound<UnboundedQuartic>::value);
  SolveOptions options;
  auto run = [&](auto& problem) {
    solver::NewtonDriver<std::decay_t<decltype(problem)>> driver(problem, options);
    std::vector<double> x{-2.0, 3.0};
    std::vector<NewtonIteration> history;
    const StepResult r =
        driver.solve_step(0, x, solver::StoppingTest{1e-10, 0.0}, history, std::chrono::steady_clock::now());
    return std::make_pair(history, x);
  };
  Quartic plain;
  UnboundedQuartic unbounded;
  BoundedQuartic bounded;
  const auto [h0, x0] = run(plain);
  const auto [h1, x1] = run(unbounded);
  const auto [h2, x2] = run(bounded);
  EXPECT_EQ(x0, x1);  // bitwise
  ASSERT_EQ(h0.size(), h1.size());
  for (size_t i = 0; i < h0.size(); ++i) {
    EXPECT_EQ(h0[i].residual_norm, h1[i].residual_norm);
    EXPECT_EQ(h0[i].step_length, h1[i].step_length);
  }
  for (const NewtonIteration& it : h2) EXPECT_LE(it.step_length, 0.25);
}

// A slide off a saddle, E = -x^2 / 2 + x^4 / 4 from x = 0.01, with the
// projected Hessian's curvature (at least 1) far above the true one: Newton
// extrapolates past alpha = 1 (doubling while the descent holds). A
// barrier's bound stops at alpha = 1 (continuous collision detection clears
// at most the step asked for), so each extension is cleared on its own: a
// far wall lets Newton reach the minimum at x = 1 as fast as without a
// bound, a near one is never passed.
struct Slide {
  using Vector = std::vector<double>;
  double wall = std::numeric_limits<double>::infinity();
  size_t dofs() const { return 1; }
  double epsilon() const { return 1e-16; }
  Vector vector() const { return Vector(1, 0.0); }
  double energy(const Vector& x) { return -0.5 * x[0] * x[0] + 0.25 * std::pow(x[0], 4); }
  double last_min_j() const { return 1.0; }
  void residual(const Vector& x, Vector& r) { r[0] = x[0] - std::pow(x[0], 3); }
  double norm(const Vector& v) const { return std::abs(v[0]); }
  double dot(const Vector& a, const Vector& b) const { return a[0] * b[0]; }
  Vector x_lin;
  void linearize(const Vector& x, bool) { x_lin = x; }
  solver::LinearSolve solve(const Vector& r, Vector& p, double, int) {
    p[0] = r[0] / std::max(3 * x_lin[0] * x_lin[0] - 1, 1.0);
    return {1, 0.0, false, false};
  }
  void precondition(const Vector& r, Vector& p) { p = r; }
  void step(const Vector& x, double alpha, const Vector& p, Vector& out) { out[0] = x[0] + alpha * p[0]; }
  void swap(Vector& a, Vector& b) { a.swap(b); }
  bool has_true_hessian() const { return false; }
  // The largest alpha <= 1 that keeps x + alpha p at or before the wall.
  double step_bound(const Vector& x, const Vector& p) { return p[0] > 0.0 ? std::min(1.0, (wall - x[0]) / p[0]) : 1.0; }
};

TEST(BarrierContact, DriverExtrapolatesPastABarriersUnitBoundWhereTheWayIsClear) {
  SolveOptions options;
  auto run = [&](Slide& problem) {
    solver::NewtonDriver<Slide> driver(problem, options);
    std::vector<double> x{0.01};
    std::vector<NewtonIteration> history;
    const StepResult r =
        driver.solve_step(0, x, solver::StoppingTest{1e-10, 0.0}, history, std::chrono::steady_clock::now());
    double longest = 0.0;
    for (const NewtonIteration& it : history) longest = std::max(longest, it.step_length);
    return std::make_tuple(r, x[0], longest);
  };
  Slide free_slide;  // no bound at all (infinity)
  free_slide.wall = std::numeric_limits<double>::infinity();
  Slide far;
  far.wall = 3.0;
  Slide near;
  near.wall = 0.3;
  const auto [r_free, x_free, longest_free] = run(free_slide);
  const auto [r_far, x_far, longest_far] = run(far);
  const auto [r_near, x_near, longest_near] = run(near);
  ASSERT_TRUE(r_free.converged);
  EXPECT_GT(longest_free, 1.0);
  EXPECT_TRUE(r_far.converged);
  EXPECT_NEAR(x_far, 1.0, 1e-9);
  EXPECT_GT(longest_far, 1.0) << "a barrier's unit bound kept Newton from extrapolating";
  EXPECT_EQ(r_far.newton_iterations, r_free.newton_iterations);
  EXPECT_LE(x_near, 0.3);
  EXPECT_GT(x_near, 0.01);
}

// The stability suite's frictionless squash at nu = 0.46, 4^3 hexes, the
// lid closing to 5% of the height and opening again, in 32 time steps:
// without self-contact the surface passes through itself; with barrier
// self-contact (the case's default) every step converges, the exact count of
// intersecting surface triangles (adjacent ones folded onto each other
// included) is 0 at the end of every step, the closest pair stays apart, and
// the body ends uninverted. (Elements may invert inside the body at the
// closed lid, with or without self-contact: the surface barrier does not
// act on the interior; the step reports them.)
TEST(BarrierContact, SquashToFivePercentHoldsWithoutIntersection) {
  Scene scene = bench::make_stability_case("squash_h0.05_nu0.46", Precision::double_, 4, 0.0);
  ASSERT_TRUE(scene.options.contact.self);
  ASSERT_EQ(scene.options.contact.self_method, SelfContactMethod::barrier);
  scene.options.load_steps = 32;
  const solver::BarrierContact surface(scene.mesh);
  const std::vector<int32_t> triangles(surface.triangles().begin(), surface.triangles().end());
  struct Run {
    size_t most_pairs = 0;
    double min_distance = std::numeric_limits<double>::infinity();
    bool converged = true;
    int steps = 0, inverted_at_end = -1;
  };
  auto run = [&](bool self) {
    SolveOptions options = scene.options;
    options.contact.self = self;
    Simulation sim(scene.mesh, uniform_material(scene.mesh, scene.material), scene.constraints, options);
    Run r;
    sim.solve(0, {}, [&](int, const Points& x) {
      const StepResult& step = sim.last_step();
      r.most_pairs = std::max(r.most_pairs, count_self_intersections(x, triangles).intersecting_pairs);
      r.converged = r.converged && step.converged;
      r.inverted_at_end = step.inverted_elements;
      ++r.steps;
      if (self) r.min_distance = std::min(r.min_distance, step.min_self_distance);
    });
    return r;
  };
  const Run without = run(false);
  EXPECT_GT(without.most_pairs, 0u) << "the squash without self-contact no longer folds through itself";
  const Run with = run(true);
  EXPECT_EQ(with.steps, 32);
  EXPECT_TRUE(with.converged);
  EXPECT_EQ(with.most_pairs, 0u);
  EXPECT_GT(with.min_distance, 0.0);
  EXPECT_EQ(with.inverted_at_end, 0);
}

}  // namespace
}  // namespace snh::test
