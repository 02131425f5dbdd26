// Barrier self-contact's broad phase on the device (solver/
// barrier_broad_phase.h) against the host reference (BarrierContact): the
// candidate pairs at x and along a step, and the pairs within dhat, are the
// host's list, in its order (sorted by kind, then primitive indices), with
// the same mollifier thresholds, on a mesh's boundary, on an embedded
// surface and with pairs left out at rest; and two runs give the same bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "snh/simulation.h"
#include "snh/surface.h"
#include "solver/contact/barrier_contact.h"
#include "solver/contact/barrier_terms.h"
#include "stability.h"
#include "support/device_test_support.h"

namespace snh::test {
namespace {

// Two n x n x 1 lattices of cells h, B above A with a gap of 0.14 h and
// shifted by (0.26 h, 0.42 h); by default n = 4, h = 0.5 (a gap of 0.07).
struct Stack {
  Mesh mesh;
  int first_b = 0;
  explicit Stack(int n = 4, double h = 0.5) : mesh(make_box_lattice(n, n, 1, h)) {
    const Mesh b = make_box_lattice(n, n, 1, h, {0.26 * h, 0.42 * h, 1.14 * h});
    first_b = static_cast<int>(mesh.vertex_count());
    for (size_t v = 0; v < b.vertex_count(); ++v) mesh.positions.push_back(b.vertex(v));
    for (int32_t v : b.elements) mesh.elements.push_back(v + first_b);
  }
  // The rest positions with B moved down by dz (and along x by dx) and every
  // coordinate jittered.
  std::vector<double> pressed(double dz, double jitter, unsigned seed, double dx = 0.0) const {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> shake(-jitter, jitter);
    std::vector<double> x = mesh.positions.xyz();
    for (size_t v = first_b; v < mesh.vertex_count(); ++v) {
      x[3 * v] += dx;
      x[3 * v + 2] += dz;
    }
    for (double& c : x) c += shake(rng);
    return x;
  }
};

// An embedded surface: the boundary of the lattice, each vertex carried by a
// cell holding it with weight 0.9 on its own corner and 0.1 on corner 7 - k.
struct Embedded {
  TriangleSurface surface;
  Embedding embedding;
  explicit Embedded(const Mesh& mesh) {
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
            embedding.weights[8 * s + k] = 0.9;
            embedding.weights[8 * s + (7 - k)] = 0.1;  // another corner of the cell
          }
    }
    surface.positions = embedded_positions(embedding, mesh, mesh.positions);
  }
};

void expect_same_list(const std::vector<solver::BarrierPair>& device, const std::vector<solver::BarrierPair>& host,
                      const char* what) {
  ASSERT_EQ(device.size(), host.size()) << what;
  for (size_t i = 0; i < host.size(); ++i) {
    EXPECT_EQ(device[i].kind, host[i].kind) << what << " pair " << i;
    EXPECT_EQ(device[i].vertex, host[i].vertex) << what << " pair " << i;
    EXPECT_EQ(device[i].ex, host[i].ex) << what << " pair " << i;
  }
}

int kinds(const std::vector<solver::BarrierPair>& pairs, int kind) {
  int n = 0;
  for (const solver::BarrierPair& p : pairs) n += p.kind == kind;
  return n;
}

// The device's lists at x and along x + t p against the host's, for the
// terms' own surface and dhat (the host reference with the same pairs left
// out at rest).
void expect_lists_match(solver::BarrierTerms<double>& terms, const solver::BarrierContact& host,
                        const std::vector<double>& x, const std::vector<double>& p, size_t min_near) {
  const viennacl::vector<double> xd = upload<double>(x), pd = upload<double>(p);
  const std::vector<solver::BarrierPair> candidates = host.candidate_pairs(x, nullptr);
  const std::vector<solver::BarrierPair> swept = host.candidate_pairs(x, &p);
  const std::vector<solver::BarrierPair> near = host.near_pairs(x);
  ASSERT_GE(near.size(), min_near);
  EXPECT_GT(kinds(candidates, 0), 0);
  EXPECT_GT(kinds(candidates, 1), 0);
  EXPECT_GT(swept.size(), candidates.size());
  expect_same_list(terms.candidate_pairs(solver::mem(xd), nullptr), candidates, "candidates");
  expect_same_list(terms.candidate_pairs(solver::mem(xd), solver::mem(pd)), swept, "swept candidates");
  expect_same_list(terms.near_pairs(solver::mem(xd)), near, "near pairs");
  // Again: the same list (and the same energy bits) on a second run.
  EXPECT_EQ(terms.near_pairs(solver::mem(xd)), near);
  const double energy = terms.energy(solver::mem(xd));
  EXPECT_GT(energy, 0.0);
  EXPECT_EQ(terms.energy(solver::mem(xd)), energy);
  EXPECT_EQ(terms.state().pairs, static_cast<int>(near.size()));
}

TEST(BarrierBroadPhase, DeviceListsAreTheHostsOnAMeshBoundary) {
  const Stack s;
  solver::BarrierTerms<double> terms(device_for(Precision::double_), s.mesh, nullptr);
  terms.set_candidates_on_host(false);  // the device's grid, whatever the device
  const double dhat = 0.05;
  terms.set_parameters(dhat, 2.0);
  EXPECT_EQ(terms.excluded_at_rest(), 0u);
  solver::BarrierContact host(s.mesh);
  host.set_distance(dhat);
  EXPECT_EQ(host.exclude_pairs_near(s.mesh.positions.xyz()), 0u);
  // B 0.04 closer, jittered by up to 0.004: pairs within dhat of every kind;
  // a step of up to 0.3 sweeps boxes over several cells.
  const std::vector<double> x = s.pressed(-0.04, 0.004, 3);
  std::vector<double> p(x.size());
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> step(-0.3, 0.3);
  for (double& e : p) e = step(rng);
  expect_lists_match(terms, host, x, p, 20);
  // Nothing within dhat at rest.
  const viennacl::vector<double> rest = upload<double>(s.mesh.positions.xyz());
  EXPECT_TRUE(terms.near_pairs(solver::mem(rest)).empty());
}

// Lists of thousands of entries: the sorts run their stages across blocks
// of 256 entries as well as within them.
TEST(BarrierBroadPhase, DeviceListsAreTheHostsOnALargerSurface) {
  const double h = 1.0 / 16;
  const Stack s(16, h);
  solver::BarrierTerms<double> terms(device_for(Precision::double_), s.mesh, nullptr);
  terms.set_candidates_on_host(false);  // the device's grid, whatever the device
  const double dhat = 0.1 * h;
  terms.set_parameters(dhat, 2.0);
  solver::BarrierContact host(s.mesh);
  host.set_distance(dhat);
  EXPECT_EQ(host.exclude_pairs_near(s.mesh.positions.xyz()), 0u);
  const std::vector<double> x = s.pressed(-0.08 * h, 0.008 * h, 9);
  std::vector<double> p(x.size());
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> step(-0.5 * h, 0.5 * h);
  for (double& e : p) e = step(rng);
  expect_lists_match(terms, host, x, p, 300);
}

TEST(BarrierBroadPhase, DeviceListsAreTheHostsOnAnEmbeddedSurface) {
  const Stack s;
  const Embedded e(s.mesh);
  solver::BarrierTerms<double> terms(device_for(Precision::double_), s.mesh, nullptr);
  terms.set_candidates_on_host(false);  // the device's grid, whatever the device
  const double dhat = 0.05;
  terms.set_parameters(dhat, 2.0);
  terms.set_surface(solver::BarrierContact(s.mesh, e.surface, e.embedding));
  solver::BarrierContact host(s.mesh, e.surface, e.embedding);
  host.set_distance(dhat);
  // The embedded surfaces are 0.07 + 2 * 0.1 * 0.5 (the far corner's pull)
  // apart at rest: B 0.14 closer.
  const std::vector<double> x = s.pressed(-0.14, 0.004, 5);
  std::vector<double> p(x.size());
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> step(-0.2, 0.2);
  for (double& c : p) c = step(rng);
  expect_lists_match(terms, host, x, p, 20);
}

TEST(BarrierBroadPhase, PairsLeftOutAtRestAreLeftOutOnTheDevice) {
  const Stack s;
  solver::BarrierTerms<double> terms(device_for(Precision::double_), s.mesh, nullptr);
  terms.set_candidates_on_host(false);  // the device's grid, whatever the device
  // dhat above the rest gap: the pairs across it are left out.
  const double dhat = 0.1;
  terms.set_parameters(dhat, 2.0);
  solver::BarrierContact host(s.mesh);
  host.set_distance(dhat);
  const size_t left_out = host.exclude_pairs_near(s.mesh.positions.xyz());
  ASSERT_GT(left_out, 10u);
  EXPECT_EQ(terms.excluded_at_rest(), left_out);
  const viennacl::vector<double> rest = upload<double>(s.mesh.positions.xyz());
  EXPECT_TRUE(terms.near_pairs(solver::mem(rest)).empty());
  EXPECT_EQ(terms.energy(solver::mem(rest)), 0.0);
  // Closer and moved along by a cell: some of the pairs in range are
  // left out, others are not.
  const std::vector<double> x = s.pressed(-0.03, 0.005, 7, 0.5);
  const std::vector<solver::BarrierPair> near = host.near_pairs(x);
  solver::BarrierContact all(s.mesh);
  all.set_distance(dhat);
  EXPECT_GT(all.near_pairs(x).size(), near.size());
  std::vector<double> p(x.size());
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> step(-0.1, 0.1);
  for (double& c : p) c = step(rng);
  expect_lists_match(terms, host, x, p, 5);
}

// A squash with barrier self-contact solved with the host's candidate pairs
// and with the device's: the same pairs in the same order, so the same
// iterations and positions bit for bit (SelfBroadPhase).
TEST(BarrierBroadPhase, HostAndDeviceCandidatesSolveAlikeBitForBit) {
  Scene scene = bench::make_stability_case("squash_h0.05_nu0.46", Precision::double_, 4, 0.0);
  scene.options.load_steps = 8;
  auto run = [&](SelfBroadPhase where) {
    SolveOptions options = scene.options;
    options.contact.self_broad_phase = where;
    Simulation sim(scene.mesh, uniform_material(scene.mesh, scene.material), scene.constraints, options);
    const SolveResult r = sim.solve();
    return std::make_pair(r, sim.positions());
  };
  const auto [host, x_host] = run(SelfBroadPhase::host);
  const auto [device, x_device] = run(SelfBroadPhase::device);
  ASSERT_EQ(host.steps.size(), device.steps.size());
  int pairs = 0;
  for (size_t s = 0; s < host.steps.size(); ++s) {
    EXPECT_EQ(host.steps[s].newton_iterations, device.steps[s].newton_iterations) << s;
    EXPECT_EQ(host.steps[s].cg_iterations, device.steps[s].cg_iterations) << s;
    EXPECT_EQ(host.steps[s].self_contact_pairs, device.steps[s].self_contact_pairs) << s;
    pairs = std::max(pairs, host.steps[s].self_contact_pairs);
  }
  EXPECT_GT(pairs, 0) << "no pair came within dhat: the comparison shows nothing";
  EXPECT_EQ(x_host, x_device);  // bitwise
}

}  // namespace
}  // namespace snh::test
