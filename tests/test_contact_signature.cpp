// The obstacle contact set's signature (ModelContact::contact_set_signature,
// solver/model/vertex_terms.h), which decides whether multigrid rebuilds: reduced
// on the device to the host's value in one read of two integers, 0 without
// contact, and changed exactly when the set of vertices in a contact layer
// changes, whatever their depths.
#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <random>
#include <set>
#include <type_traits>
#include <vector>

#include "fem/rest_state.h"
#include "snh/simulation.h"
#include "solver/contact/obstacles.h"
#include "solver/model/elastic_model.h"
#include "solver/model/vertex_terms.h"
#include "support/device_test_support.h"

namespace snh::test {
namespace {

constexpr double kStiffness = 7.0, kThickness = 0.05;

// A 3 x 3 x 2 lattice of 0.1 cells over the plane z = 0; each vertex in
// `in` is put inside the layer (depth 0.01 to 0.05), the others above it, at
// heights drawn from `rng`.
template <typename Real>
class PlaneContact {
 public:
  PlaneContact()
      : mesh_(make_box_lattice(3, 3, 2, 0.1)),
        rest_(fem::compute_rest_state(mesh_)),
        model_(device_for(std::is_same_v<Real, double> ? Precision::double_ : Precision::single), mesh_, rest_,
               uniform_material(mesh_, StableNeoHookean::from_youngs_modulus(10.0, 0.3)), ProductVariant::cached,
               device::MaterialKernel::specialized, terms()) {
    model_.contact().set_obstacles(solver::obstacle_records({Obstacle::plane({0, 0, 0}, {0, 0, 1})}, 0.0), kStiffness,
                                   kThickness);
  }
  size_t vertices() const { return mesh_.vertex_count(); }

  // The vertices `in` put in the layer, the others above it; checks the
  // count of contacts. Returns the depths' signs (1 in the layer, else 0).
  std::vector<Real> place(const std::set<size_t>& in, std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<double> x = mesh_.positions.xyz();
    std::vector<Real> depth(vertices(), Real(0));
    for (size_t v = 0; v < vertices(); ++v) {
      x[3 * v + 2] = in.count(v) ? 0.04 * unit(rng) : 0.06 + 0.1 * unit(rng);
      depth[v] = in.count(v) ? Real(1) : Real(0);
    }
    const viennacl::vector<Real> xd = upload<Real>(x);
    EXPECT_EQ(model_.contact().contact_state(xd).contacts, static_cast<int>(in.size()));
    return depth;
  }

  // The signature with the vertices `in` in the layer; checks it against the
  // host's hash of the same set.
  uint64_t signature(const std::set<size_t>& in, std::mt19937& rng) {
    const std::vector<Real> depth = place(in, rng);
    const uint64_t s = model_.contact().contact_set_signature();
    EXPECT_EQ(s, solver::contact_set_signature(depth));
    return s;
  }
  solver::ElasticModel<Real>& model() { return model_; }

 private:
  static solver::ModelTerms terms() {
    solver::ModelTerms t;
    t.obstacles = 1;
    return t;
  }
  Mesh mesh_;
  fem::RestState rest_;
  solver::ElasticModel<Real> model_;
};

template <typename Real>
void expect_signature_follows_the_set() {
  PlaneContact<Real> contact;
  std::mt19937 rng(7);
  const size_t n = contact.vertices();
  EXPECT_EQ(contact.signature({}, rng), 0u);
  std::set<size_t> bottom;
  for (size_t v = 0; v < 16; ++v) bottom.insert(v);  // z = 0: the first 4 x 4 vertices
  const uint64_t rest = contact.signature(bottom, rng);
  EXPECT_NE(rest, 0u);
  // Other depths, the same set: the same signature.
  EXPECT_EQ(contact.signature(bottom, rng), rest);
  // One vertex more, one less, one swapped for another: each another value;
  // back to the set, back to its value.
  std::set<size_t> more = bottom, less = bottom, swapped = bottom;
  more.insert(20);
  less.erase(5);
  swapped.erase(5);
  swapped.insert(20);
  const uint64_t a = contact.signature(more, rng), b = contact.signature(less, rng),
                 c = contact.signature(swapped, rng);
  EXPECT_NE(a, rest);
  EXPECT_NE(b, rest);
  EXPECT_NE(c, rest);
  EXPECT_NE(a, b);
  EXPECT_NE(a, c);
  EXPECT_NE(b, c);
  EXPECT_EQ(contact.signature(bottom, rng), rest);
  // Random sets: equal signatures exactly for equal sets.
  std::bernoulli_distribution pick(0.3);
  std::map<uint64_t, std::set<size_t>> seen;
  for (int trial = 0; trial < 60; ++trial) {
    std::set<size_t> in;
    for (size_t v = 0; v < n; ++v)
      if (pick(rng)) in.insert(v);
    const uint64_t s = contact.signature(in, rng);
    EXPECT_EQ(s == 0, in.empty());
    const auto [at, fresh] = seen.emplace(s, in);
    if (!fresh) {
      EXPECT_EQ(at->second, in) << "two sets with one signature";
    }
  }
  EXPECT_GT(seen.size(), 50u);
}

TEST(ContactSignature, ChangesExactlyWhenTheContactSetChangesDouble) { expect_signature_follows_the_set<double>(); }

TEST(ContactSignature, ChangesExactlyWhenTheContactSetChangesFloat) { expect_signature_follows_the_set<float>(); }

// On a device with fp64 (pocl, GPUs) the signature is one read of two
// integers, whatever the lattice's size.
TEST(ContactSignature, IsOneReadOfTwoIntegers) {
  device::OpenClContext& cl = device_for(Precision::double_);
  if (!cl.info().has_fp64) GTEST_SKIP() << "the device has no fp64: the depths are read and hashed on the host";
  PlaneContact<double> contact;
  std::mt19937 rng(3);
  contact.place({1, 2, 3}, rng);
  const device::TransferCounts before = cl.counts();
  EXPECT_NE(contact.model().contact().contact_set_signature(), 0u);
  const device::TransferCounts after = cl.counts();
  EXPECT_EQ(after.blocking_readbacks - before.blocking_readbacks, 1);
  EXPECT_EQ(after.bytes_to_host - before.bytes_to_host, static_cast<int64_t>(2 * sizeof(uint64_t)));
  EXPECT_EQ(after.kernel_launches - before.kernel_launches, 2);  // the partials and their total
}

TEST(ContactSignature, HostHashIsTheSumOfTheMixesAndZeroForNone) {
  EXPECT_EQ(solver::contact_set_signature(std::vector<double>{0.0, -1.0, 0.0}), 0u);
  EXPECT_EQ(solver::contact_set_signature(std::vector<double>{}), 0u);
  const uint64_t one = solver::contact_set_signature(std::vector<double>{0.0, 0.5, 0.0});
  const uint64_t two = solver::contact_set_signature(std::vector<double>{0.0, 0.0, 2.0});
  const uint64_t both = solver::contact_set_signature(std::vector<double>{0.0, 0.1, 1e-30});
  EXPECT_NE(one, 0u);
  EXPECT_NE(one, two);
  EXPECT_EQ(both, one + two);  // modulo 2^64
  EXPECT_EQ(solver::contact_set_signature(std::vector<float>{0.0f, 3.0f, 0.0f}), one);
}

}  // namespace
}  // namespace snh::test
