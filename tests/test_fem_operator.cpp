// The device's matrix-free finite-element operators (solver::ElasticModel:
// energy, residual, PSD-projected product in both variants, block-Jacobi
// blocks, constraint mask, external force) against the explicitly assembled
// host reference (reference/fem_reference.h), on tiny hex8 lattices (uniform
// and jittered rest shapes) and a tet4 box, with and without the barrier,
// in both precisions.
//
// Errors are relative to the reference quantity's norm. Double: the same
// element math, rounding alike, so 1e-12 outright. Float: the device runs in
// float against the double reference evaluated at the same float-rounded
// inputs; the rounding of F (a sum of x_a dN_a/dX with |x| |dN/dX| a few
// times |F|), of J - alpha and of the SVD is amplified by lambda / mu, so the
// bound is kFloatUlps * FLT_EPSILON * (1 + lambda / mu); each test prints its
// measured worst case in these units.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "device/opencl_context.h"
#include "device/viennacl_binding.h"
#include "fem/rest_state.h"
#include "material/element_reference.h"
#include "reference/fem_reference.h"
#include "snh/material.h"
#include "snh/mesh.h"
#include "snh/regions.h"
#include "snh/simulation.h"
#include "solver/model/elastic_model.h"
#include "solver/newton/matrix_free.h"
#include "support/device_test_support.h"
#include "support/random_vectors.h"
#include "vector_compare.h"
#include "viennacl/ocl/backend.hpp"
#include "viennacl/vector.hpp"

namespace snh::test {
namespace {

constexpr double kDoubleBound = 1e-12;
constexpr double kFloatUlps = 16.0;
constexpr double kH = 0.5;  // lattice spacing

template <typename Real>
constexpr Precision precision_of = std::is_same_v<Real, double> ? Precision::double_ : Precision::single;

struct Scene {
  std::string name;
  Mesh mesh;
  fem::RestState rest;
  StableNeoHookean material;
  reference::SnhParameters params() const { return {material.mu, material.lambda, material.barrier}; }
};

// A 3x2x2 lattice with every vertex moved by up to 0.1 h: no two elements
// share a rest shape.
Mesh jittered_lattice() { return jittered(make_box_lattice(3, 2, 2, kH), kH); }

const std::vector<Scene>& scenes() {
  static const std::vector<Scene> all = [] {
    const std::vector<std::pair<std::string, Mesh>> meshes = {
        {"hex8_uniform", make_box_lattice(3, 2, 2, kH)},
        {"hex8_jittered", jittered_lattice()},
        {"tet4", make_tet_box(2, 2, 2, kH)},
    };
    const std::vector<std::pair<std::string, StableNeoHookean>> materials = {
        {"nu0.3_barrier", StableNeoHookean::from_youngs_modulus(1.0, 0.3, Barrier::on)},
        {"nu0.45_no_barrier", StableNeoHookean::from_youngs_modulus(1.0, 0.45, Barrier::off)},
    };
    std::vector<Scene> out;
    for (const auto& [mesh_name, mesh] : meshes)
      for (const auto& [material_name, material] : materials) {
        validate_mesh(mesh);
        out.push_back({mesh_name + "/" + material_name, mesh, fem::compute_rest_state(mesh), material});
      }
    return out;
  }();
  return all;
}

// Node 0 of element 0 pushed through its element: to 1.7 times the way to
// the element's centroid.
std::vector<double> with_inverted_element(const Mesh& mesh) {
  std::vector<double> x = perturbed(mesh, 0.05 * kH, 99);
  const int n = nodes_per_element(mesh.type);
  const int32_t v = mesh.elements[0];
  for (int i = 0; i < 3; ++i) {
    double centroid = 0.0;
    for (int a = 0; a < n; ++a) centroid += x[3 * mesh.elements[a] + i] / n;
    x[3 * v + i] += 1.7 * (centroid - x[3 * v + i]);
  }
  return x;
}

struct Case {
  const Scene* scene;
  std::string name;
  std::vector<double> x;
};

// Whether the device tests in precision p (double models with float
// products count as double) run scene s. Each kernel program is an element
// type, a barrier setting and a precision; the tests cover that grid
// pairwise, each element type and each barrier setting in both precisions
// and each element type with and without the barrier, in half the
// programs: double runs hex8 without the barrier (as the single-scene tests
// below do) and tet4 with it, float the other two.
bool in_grid(const Scene& s, Precision p) {
  const bool tet = s.mesh.type == ElementType::tet4;
  return (tet == s.material.barrier) == (p == Precision::double_);
}

// Random positions (0.2 h) and one with an inverted element, per scene (of
// the grid of precision p, when given).
std::vector<Case> cases(std::optional<Precision> p = std::nullopt) {
  std::vector<Case> out;
  for (const Scene& s : scenes()) {
    if (p && !in_grid(s, *p)) continue;
    out.push_back({&s, s.name + "/random", perturbed(s.mesh, 0.2 * kH, 12345)});
    out.push_back({&s, s.name + "/inverted", with_inverted_element(s.mesh)});
  }
  return out;
}

// The smallest eigenvalue of the unprojected 9x9 Hessian over all points.
double min_hessian_eigenvalue(const Scene& s, const std::vector<double>& x) {
  double lowest = INFINITY;
  for (size_t e = 0; e < s.mesh.element_count(); ++e)
    for (int q = 0; q < s.rest.quadrature; ++q) {
      reference::Mat3<double> f;
      fem::deformation_gradient(s.mesh, s.rest, x.data(), e, q, f.data());
      for (double v : reference::snh_hessian_eigensystem<double>(f, s.params()).values) lowest = std::min(lowest, v);
    }
  return lowest;
}

std::vector<double> multiply(const Eigen::SparseMatrix<double>& k, const std::vector<double>& p) {
  const Eigen::VectorXd y = k * Eigen::Map<const Eigen::VectorXd>(p.data(), static_cast<Eigen::Index>(p.size()));
  return {y.data(), y.data() + y.size()};
}

std::vector<double> masked(const std::vector<double>& mask, std::vector<double> v) {
  for (size_t i = 0; i < v.size(); ++i) v[i] *= mask[i];
  return v;
}

double norm(const std::vector<double>& v) {
  double s = 0.0;
  for (double c : v) s += c * c;
  return std::sqrt(s);
}

// Constrains vertices 0, n/2 and n-1 fully and vertex 1 in z only.
std::vector<double> constraint_mask(const Mesh& mesh) {
  const size_t n = mesh.vertex_count();
  std::vector<double> mask(3 * n, 1.0);
  for (size_t v : {size_t{0}, n / 2, n - 1})
    for (int i = 0; i < 3; ++i) mask[3 * v + i] = 0.0;
  mask[3 * 1 + 2] = 0.0;
  return mask;
}

// The worst error over a test's cases, in units of the precision's bound
// scale (eps (1 + lambda / mu) in float, plain relative error in double).
template <typename Real>
struct Tolerance {
  double worst = 0.0;
  std::string where;

  static double scale(const Scene& s) {
    return std::is_same_v<Real, double> ? 1.0 : FLT_EPSILON * (1.0 + s.material.lambda / s.material.mu);
  }
  static double bound(const Scene& s) { return std::is_same_v<Real, double> ? kDoubleBound : kFloatUlps * scale(s); }
  void check(double error, const Scene& s, const std::string& what) {
    EXPECT_LE(error, bound(s)) << what;
    if (error / scale(s) > worst) {
      worst = error / scale(s);
      where = what;
    }
  }
  ~Tolerance() {
    if (std::is_same_v<Real, double>)
      std::printf("[ measured ] double: worst relative error %.3g at %s\n", worst, where.c_str());
    else
      std::printf("[ measured ] float: worst error %.3g FLT_EPSILON (1 + lambda/mu) at %s\n", worst, where.c_str());
  }
};

// --- the reference itself -------------------------------------------------

TEST(FemOperator, ReferenceIsConsistent) {
  EXPECT_TRUE(scenes()[0].rest.uniform);
  EXPECT_FALSE(scenes()[2].rest.uniform);
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const Scene& s = *c.scene;
    if (c.name.find("inverted") != std::string::npos) {
      EXPECT_GT(deformation_statistics(s.mesh, Points::from_xyz(c.x)).inverted_elements, 0);
    }
    // Projection is active: some point's Hessian is indefinite.
    EXPECT_LT(min_hessian_eigenvalue(s, c.x), 0.0);
    // Forces are -dE/dx (central differences of the energy).
    const std::vector<double> f = reference::assembled_forces(s.mesh, s.rest, s.material, c.x);
    const std::vector<double> p = random_vector(c.x.size(), 1.0, 5);
    double best = INFINITY;
    double fp = 0.0;
    for (size_t i = 0; i < p.size(); ++i) fp += f[i] * p[i];
    for (double t : {1e-3, 1e-4, 1e-5, 1e-6}) {
      std::vector<double> xp = c.x, xm = c.x;
      for (size_t i = 0; i < p.size(); ++i) {
        xp[i] += t * p[i];
        xm[i] -= t * p[i];
      }
      const double fd = -(reference::assembled_energy(s.mesh, s.rest, s.material, xp) -
                          reference::assembled_energy(s.mesh, s.rest, s.material, xm)) /
                        (2 * t);
      best = std::min(best, std::abs(fd - fp) / (norm(f) * norm(p)));
    }
    EXPECT_LT(best, 1e-7);
    // K is symmetric positive semidefinite.
    const Eigen::MatrixXd k =
        Eigen::MatrixXd(reference::assembled_projected_stiffness(s.mesh, s.rest, s.material, c.x));
    EXPECT_LT((k - k.transpose()).norm(), 1e-13 * k.norm());
    const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(k).eigenvalues();
    EXPECT_GT(lambda.minCoeff(), -1e-12 * lambda.maxCoeff());
  }
}

// --- energy, residual, product ------------------------------------------

template <typename Real>
void check_energy() {
  Tolerance<Real> tolerance;
  for (const Case& c : cases(precision_of<Real>)) {
    const Scene& s = *c.scene;
    solver::ElasticModel<Real> model(device_for(precision_of<Real>), s.mesh, s.rest,
                                     uniform_material(s.mesh, s.material), ProductVariant::cached);
    const std::vector<double> x = rounded<Real>(c.x);
    const double reference = reference::assembled_energy(s.mesh, s.rest, s.material, x);
    const double device = model.energy(upload<Real>(x));
    tolerance.check(std::abs(device - reference) / std::abs(reference), s, c.name);
  }
}

TEST(FemOperator, EnergyMatchesAssembledDouble) { check_energy<double>(); }
TEST(FemOperator, EnergyMatchesAssembledFloat) { check_energy<float>(); }

template <typename Real>
void check_residual() {
  Tolerance<Real> tolerance;
  for (const Case& c : cases(precision_of<Real>)) {
    const Scene& s = *c.scene;
    solver::ElasticModel<Real> model(device_for(precision_of<Real>), s.mesh, s.rest,
                                     uniform_material(s.mesh, s.material), ProductVariant::cached);
    const std::vector<double> x = rounded<Real>(c.x);
    viennacl::vector<Real> r(model.dofs());
    model.residual(upload<Real>(x), r);
    tolerance.check(relative_difference(download(r), reference::assembled_forces(s.mesh, s.rest, s.material, x)), s,
                    c.name);
  }
}

TEST(FemOperator, ResidualMatchesAssembledForcesDouble) { check_residual<double>(); }
TEST(FemOperator, ResidualMatchesAssembledForcesFloat) { check_residual<float>(); }

template <typename Real>
void check_product() {
  Tolerance<Real> tolerance;
  for (const Case& c : cases(precision_of<Real>)) {
    const Scene& s = *c.scene;
    solver::ElasticModel<Real> model(device_for(precision_of<Real>), s.mesh, s.rest,
                                     uniform_material(s.mesh, s.material), ProductVariant::cached);
    const std::vector<double> x = rounded<Real>(c.x), p = rounded<Real>(random_vector(c.x.size(), 1.0, 777));
    const std::vector<double> expected =
        multiply(reference::assembled_projected_stiffness(s.mesh, s.rest, s.material, x), p);
    model.linearize(upload<Real>(x));
    const viennacl::vector<Real> pd = upload<Real>(p);
    for (ProductVariant variant : {ProductVariant::cached, ProductVariant::recompute, ProductVariant::element_matrices,
                                   ProductVariant::assembled}) {
      model.products().set_variant(variant);
      model.linearize(upload<Real>(x));
      viennacl::vector<Real> y(model.dofs());
      model.product(pd, y);
      tolerance.check(relative_difference(download(y), expected), s, c.name + "/" + to_string(variant));
      if (variant == ProductVariant::element_matrices) {
        // Its two kernels, a work-item per element (CPUs) or per row (GPUs),
        // sum each row in one order: the same values.
        const bool rows = model.products().matrix_product_rows();
        EXPECT_EQ(rows, device_for(precision_of<Real>).info().is_gpu);
        model.products().set_matrix_product_rows(!rows);
        viennacl::vector<Real> other(model.dofs());
        model.product(pd, other);
        model.products().set_matrix_product_rows(rows);
        EXPECT_EQ(download(other), download(y)) << c.name << ": the element-matrices product per row and per element";
      }
    }
  }
}

TEST(FemOperator, ProductMatchesAssembledStiffnessDouble) { check_product<double>(); }
TEST(FemOperator, ProductMatchesAssembledStiffnessFloat) { check_product<float>(); }

// Mixed precision (ProductVariants::set_float_products): a double model whose
// products run in float on float copies of the double linearization (the
// cached variant's cache, the assembled one's blocks), p and the result in
// double. For both variants, against the reference at the unrounded inputs
// the product must meet the float bound, and it must differ from the double
// product by more than the double bound (the float kernel ran). The float
// copy that linearize() writes must equal the one set_float_products()
// narrows from what exists, value for value; the product is deterministic;
// and a model switched back off must give the double product again, bit for
// bit. `more` runs the variant's own checks while the products are float.
using FloatProductChecks = std::function<void(solver::ElasticModel<double>&, const viennacl::vector<double>& xd,
                                              const viennacl::vector<double>& pd, const std::vector<double>& narrowed)>;

void check_float_products(ProductVariant variant, uint64_t seed, const FloatProductChecks& more) {
  Tolerance<float> tolerance;
  for (const Case& c : cases(Precision::double_)) {
    SCOPED_TRACE(c.name);
    const Scene& s = *c.scene;
    solver::ElasticModel<double> model(device_for(Precision::double_), s.mesh, s.rest,
                                       uniform_material(s.mesh, s.material), variant);
    const std::vector<double> p = random_vector(c.x.size(), 1.0, seed);
    const std::vector<double> expected =
        multiply(reference::assembled_projected_stiffness(s.mesh, s.rest, s.material, c.x), p);
    const viennacl::vector<double> xd = upload<double>(c.x), pd = upload<double>(p);
    viennacl::vector<double> y(model.dofs());
    model.linearize(xd);
    model.product(pd, y);
    const std::vector<double> in_double = download_raw(y);
    EXPECT_FALSE(model.products().float_products());
    model.products().set_float_products(true);  // narrows what the linearization above made
    ASSERT_TRUE(model.products().float_products());
    model.product(pd, y);
    const std::vector<double> narrowed = download_raw(y);
    tolerance.check(relative_difference(narrowed, expected), s, c.name);
    EXPECT_GT(relative_difference(narrowed, in_double), kDoubleBound);
    model.linearize(xd);  // writes the float copy itself
    model.product(pd, y);
    EXPECT_EQ(download_raw(y), narrowed);
    model.product(pd, y);
    EXPECT_EQ(download_raw(y), narrowed) << "not deterministic";
    more(model, xd, pd, narrowed);
    model.products().set_float_products(false);
    model.linearize(xd);
    model.product(pd, y);
    EXPECT_EQ(download_raw(y), in_double);
  }
}

// The cached variant's lanes and scalar kernels agree value for value (the
// same float operations in the same order, fem_lanes.cl), and other
// variants keep double.
TEST(FemOperator, FloatProductsMeetTheFloatBoundInDoubleModels) {
  check_float_products(ProductVariant::cached, 777,
                       [](solver::ElasticModel<double>& model, const viennacl::vector<double>& xd,
                          const viennacl::vector<double>& pd, const std::vector<double>& narrowed) {
                         viennacl::vector<double> y(model.dofs());
                         if (model.lanes().point_lanes_available()) {
                           model.lanes().set_point_lanes(!model.lanes().point_lanes());
                           model.linearize(xd);
                           model.product(pd, y);
                           EXPECT_EQ(download_raw(y), narrowed) << "lanes and scalar kernels differ";
                         }
                         model.products().set_variant(ProductVariant::recompute);
                         EXPECT_FALSE(model.products().float_products());
                         model.products().set_variant(ProductVariant::cached);
                       });
}

// The assembled variant: the blocks narrowed to float and multiplied with
// double p and y.
TEST(FemOperator, AssembledFloatProductsMeetTheFloatBoundInDoubleModels) {
  check_float_products(ProductVariant::assembled, 778,
                       [](solver::ElasticModel<double>&, const viennacl::vector<double>&,
                          const viennacl::vector<double>&, const std::vector<double>&) {});
}

// The multigrid's float fine-level matrices (element_matrices_into with
// single_precision): with float products on, computed in float from the
// cache's float copy. They stay exactly symmetric, within the float bound
// of the ones computed in double and stored in float (relative to the
// largest entry), not equal to them (the float path ran), deterministic,
// and their diagonal blocks (written in double) agree with their entries.
TEST(FemOperator, FloatMatricesFromTheFloatCopiesMeetTheFloatBound) {
  Tolerance<float> tolerance;
  for (const Case& c : cases(Precision::double_)) {
    SCOPED_TRACE(c.name);
    const Scene& s = *c.scene;
    device::OpenClContext& cl = device_for(Precision::double_);
    solver::ElasticModel<double> model(cl, s.mesh, s.rest, uniform_material(s.mesh, s.material),
                                       ProductVariant::cached);
    const size_t n = 3 * static_cast<size_t>(s.rest.nodes), ne = s.mesh.element_count();
    device::Buffer kd = cl.buffer(CL_MEM_READ_WRITE, ne * n * n * sizeof(float));
    device::Buffer bd = cl.buffer(CL_MEM_READ_WRITE, ne * 3 * n * sizeof(double));
    auto matrices = [&](std::vector<double>* blocks) {
      model.products().element_matrices_into(kd.get(), bd.get(), true);
      std::vector<float> k(ne * n * n);
      cl.read(kd.get(), k.size() * sizeof(float), k.data());
      if (blocks) {
        blocks->resize(ne * 3 * n);
        cl.read(bd.get(), blocks->size() * sizeof(double), blocks->data());
      }
      return k;
    };
    model.linearize(upload<double>(c.x));
    const std::vector<float> from_double = matrices(nullptr);
    model.products().set_float_products(true);
    model.linearize(upload<double>(c.x));
    std::vector<double> blocks;
    const std::vector<float> from_copies = matrices(&blocks);
    EXPECT_EQ(matrices(nullptr), from_copies) << "not deterministic";
    double largest = 0.0, worst = 0.0;
    for (size_t i = 0; i < from_copies.size(); ++i) {
      largest = std::max(largest, std::abs(static_cast<double>(from_double[i])));
      worst = std::max(worst, std::abs(static_cast<double>(from_copies[i]) - from_double[i]));
    }
    EXPECT_GT(worst, 0.0) << "the float path did not run";
    tolerance.check(worst / largest, s, c.name);
    for (size_t e = 0; e < ne; ++e)
      for (size_t col = 0; col < n; ++col)
        for (size_t row = 0; row < n; ++row) {
          const float kc = from_copies[e * n * n + col * n + row];
          ASSERT_EQ(kc, from_copies[e * n * n + row * n + col]) << "element " << e;
          if (row / 3 == col / 3) {  // the node's diagonal block, column-major [e][9 a + 3 d + i]
            ASSERT_EQ(blocks[e * 3 * n + 9 * (col / 3) + 3 * (col % 3) + row % 3], static_cast<double>(kc));
          }
        }
  }
}

// The float copies exist only while the products run in float: element
// matrices and recompute hold none; the assembled variant holds its blocks'
// copy (9 floats per stored block), the cached one its cache's.
TEST(FemOperator, FloatProductsHoldFloatCopiesOnlyWithTheirVariants) {
  const Scene& s = scenes()[1];
  solver::ElasticModel<double> model(device_for(Precision::double_), s.mesh, s.rest,
                                     uniform_material(s.mesh, s.material), ProductVariant::element_matrices);
  const viennacl::vector<double> xd = upload<double>(s.mesh.positions.xyz());
  model.linearize(xd);
  const size_t matrices = model.memory_bytes();
  model.products().set_float_products(true);
  EXPECT_FALSE(model.products().float_products());
  EXPECT_EQ(model.memory_bytes(), matrices);
  model.products().set_float_products(false);
  model.products().set_variant(ProductVariant::assembled);
  model.linearize(xd);
  const size_t assembled = model.memory_bytes();
  model.products().set_float_products(true);
  EXPECT_TRUE(model.products().float_products());
  EXPECT_EQ(model.memory_bytes(), assembled + model.products().assembled_blocks() * 9 * sizeof(float));
  model.products().set_float_products(false);
  EXPECT_EQ(model.memory_bytes(), assembled);
  model.products().set_variant(ProductVariant::cached);
  const size_t cached = model.memory_bytes();
  model.products().set_float_products(true);
  EXPECT_TRUE(model.products().float_products());
  EXPECT_GE(model.memory_bytes(), cached + model.data().cache_values() * sizeof(float));
}

// Assembled with float products, a double model writes and keeps only the
// blocks' float copy (the products read nothing else); switched back to
// double products without a new linearization, it assembles the double
// blocks from the same element matrices: the double product bit for bit.
TEST(FemOperator, AssembledFloatProductsKeepOnlyTheFloatBlocks) {
  const Scene& s = scenes()[1];
  solver::ElasticModel<double> model(device_for(Precision::double_), s.mesh, s.rest,
                                     uniform_material(s.mesh, s.material), ProductVariant::assembled);
  const std::vector<double> x = perturbed(s.mesh, 0.2 * kH, 31);
  const viennacl::vector<double> xd = upload<double>(x), pd = upload<double>(random_vector(x.size(), 1.0, 32));
  viennacl::vector<double> y(model.dofs());
  model.linearize(xd);
  model.product(pd, y);
  const std::vector<double> in_double = download_raw(y);
  const size_t with_double = model.memory_bytes();
  const size_t blocks = model.products().assembled_blocks() * 9;
  model.products().set_float_products(true);
  model.linearize(xd);
  EXPECT_EQ(model.memory_bytes(), with_double - blocks * sizeof(double) + blocks * sizeof(float));
  model.product(pd, y);
  const std::vector<double> in_float = download_raw(y);
  EXPECT_NE(in_float, in_double);
  model.products().set_float_products(false);
  EXPECT_EQ(model.memory_bytes(), with_double);
  model.product(pd, y);
  EXPECT_EQ(download_raw(y), in_double);
}

// A float model ignores the switch.
TEST(FemOperator, FloatProductsAreTheWorkingPrecisionInFloatModels) {
  const Scene& s = scenes()[0];
  solver::ElasticModel<float> model(device_for(Precision::single), s.mesh, s.rest, uniform_material(s.mesh, s.material),
                                    ProductVariant::cached);
  model.products().set_float_products(true);
  EXPECT_FALSE(model.products().float_products());
}

// --- constraints and external force ---------------------------------------

// The residual is masked; for p in the free subspace the product is the
// stiffness with constrained rows and columns removed. For a p with
// constrained entries the documented contract is y = mask * K p (only the
// rows are masked): CG only ever feeds it free-subspace vectors.
template <typename Real>
void check_mask() {
  Tolerance<Real> tolerance;
  for (const Case& c : cases(precision_of<Real>)) {
    const Scene& s = *c.scene;
    solver::ElasticModel<Real> model(device_for(precision_of<Real>), s.mesh, s.rest,
                                     uniform_material(s.mesh, s.material), ProductVariant::cached);
    const std::vector<double> mask = constraint_mask(s.mesh);
    model.set_mask(std::vector<Real>(mask.begin(), mask.end()));
    const std::vector<double> x = rounded<Real>(c.x), p = rounded<Real>(random_vector(c.x.size(), 1.0, 31));
    const viennacl::vector<Real> xd = upload<Real>(x);
    viennacl::vector<Real> r(model.dofs());
    model.residual(xd, r);
    const std::vector<double> rh = download(r);
    tolerance.check(relative_difference(rh, masked(mask, reference::assembled_forces(s.mesh, s.rest, s.material, x))),
                    s, c.name + "/residual");
    for (size_t i = 0; i < mask.size(); ++i)
      if (mask[i] == 0.0) {
        EXPECT_EQ(rh[i], 0.0) << c.name << " residual DOF " << i;
      }

    const Eigen::SparseMatrix<double> k = reference::assembled_projected_stiffness(s.mesh, s.rest, s.material, x);
    model.linearize(xd);
    for (ProductVariant variant : {ProductVariant::cached, ProductVariant::recompute, ProductVariant::element_matrices,
                                   ProductVariant::assembled}) {
      model.products().set_variant(variant);
      model.linearize(xd);
      const std::string name = c.name + "/" + to_string(variant);
      viennacl::vector<Real> y(model.dofs());
      const std::vector<double> free_p = masked(mask, p);
      model.product(upload<Real>(free_p), y);
      const std::vector<double> yh = download(y);
      tolerance.check(relative_difference(yh, masked(mask, multiply(k, free_p))), s, name + "/free_p");
      for (size_t i = 0; i < mask.size(); ++i)
        if (mask[i] == 0.0) {
          EXPECT_EQ(yh[i], 0.0) << name << " product DOF " << i;
        }
      model.product(upload<Real>(p), y);
      tolerance.check(relative_difference(download(y), masked(mask, multiply(k, p))), s, name + "/any_p");
    }
  }
}

TEST(FemOperator, MaskRemovesConstrainedRowsAndColumnsDouble) { check_mask<double>(); }
TEST(FemOperator, MaskRemovesConstrainedRowsAndColumnsFloat) { check_mask<float>(); }

template <typename Real>
void check_external_force() {
  Tolerance<Real> tolerance;
  for (const Case& c : cases(precision_of<Real>)) {
    const Scene& s = *c.scene;
    solver::ElasticModel<Real> model(device_for(precision_of<Real>), s.mesh, s.rest,
                                     uniform_material(s.mesh, s.material), ProductVariant::cached);
    const std::vector<double> mask = constraint_mask(s.mesh);
    model.set_mask(std::vector<Real>(mask.begin(), mask.end()));
    const std::vector<double> x = rounded<Real>(c.x);
    const std::vector<double> forces = reference::assembled_forces(s.mesh, s.rest, s.material, x);
    // Of the size of the elastic forces, so neither dominates.
    const std::vector<double> f =
        rounded<Real>(random_vector(x.size(), norm(forces) / std::sqrt(double(x.size())), 2024));
    model.set_external_force(f);
    const viennacl::vector<Real> xd = upload<Real>(x);
    viennacl::vector<Real> r(model.dofs());
    model.residual(xd, r);
    std::vector<double> expected(x.size());
    for (size_t i = 0; i < x.size(); ++i) expected[i] = mask[i] * (forces[i] + f[i]);
    tolerance.check(relative_difference(download(r), expected), s, c.name + "/residual");

    const double elastic = reference::assembled_energy(s.mesh, s.rest, s.material, x);
    double work = 0.0;
    for (size_t i = 0; i < x.size(); ++i) work += f[i] * x[i];
    tolerance.check(std::abs(model.energy(xd) - (elastic - work)) / (std::abs(elastic) + std::abs(work)), s,
                    c.name + "/energy");
  }
}

TEST(FemOperator, ExternalForceEntersResidualAndEnergyDouble) { check_external_force<double>(); }
TEST(FemOperator, ExternalForceEntersResidualAndEnergyFloat) { check_external_force<float>(); }

// --- preconditioner -------------------------------------------------------

// Each vertex's inverse block times its assembled diagonal block (restricted
// to the vertex's free DOFs) is the identity there; constrained DOFs give
// zero rows and columns. The error is relative to the block's condition
// number.
template <typename Real>
void check_preconditioner() {
  Tolerance<Real> tolerance;
  for (const Case& c : cases(precision_of<Real>)) {
    const Scene& s = *c.scene;
    solver::ElasticModel<Real> model(device_for(precision_of<Real>), s.mesh, s.rest,
                                     uniform_material(s.mesh, s.material), ProductVariant::cached);
    const std::vector<double> mask = constraint_mask(s.mesh);
    model.set_mask(std::vector<Real>(mask.begin(), mask.end()));
    const std::vector<double> x = rounded<Real>(c.x);
    model.linearize(upload<Real>(x));
    model.setup_preconditioner();
    const std::vector<Real> blocks = model.preconditioner_blocks();
    const Eigen::MatrixXd k = Eigen::MatrixXd(reference::assembled_projected_stiffness(s.mesh, s.rest, s.material, x));
    double worst = 0.0;
    for (size_t v = 0; v < s.mesh.vertex_count(); ++v) {
      std::vector<int> free;
      for (int i = 0; i < 3; ++i) {
        if (mask[3 * v + i] != 0.0) free.push_back(i);
        for (int j = 0; j < 3; ++j) {
          if (mask[3 * v + i] == 0.0 || mask[3 * v + j] == 0.0) {
            EXPECT_EQ(blocks[9 * v + 3 * j + i], Real(0)) << c.name << " vertex " << v << " entry " << i << j;
          }
        }
      }
      const int m = static_cast<int>(free.size());
      if (m == 0) continue;
      Eigen::MatrixXd inverse(m, m), diagonal(m, m);
      for (int a = 0; a < m; ++a)
        for (int b = 0; b < m; ++b) {
          inverse(a, b) = blocks[9 * v + 3 * free[b] + free[a]];
          diagonal(a, b) = k(3 * v + free[a], 3 * v + free[b]);
        }
      const Eigen::VectorXd sv = Eigen::JacobiSVD<Eigen::MatrixXd>(diagonal).singularValues();
      const double condition = sv(0) / sv(m - 1);
      const double error = (inverse * diagonal - Eigen::MatrixXd::Identity(m, m)).norm() / condition;
      worst = std::max(worst, error);
    }
    tolerance.check(worst, s, c.name);
  }
}

TEST(FemOperator, PreconditionerInvertsFreeDiagonalBlocksDouble) { check_preconditioner<double>(); }
TEST(FemOperator, PreconditionerInvertsFreeDiagonalBlocksFloat) { check_preconditioner<float>(); }

// --- finite differences -----------------------------------------------------

// Near rest the product is the exact Hessian: K p = -(r(x + t p) - r(x - t p))
// / 2t. At rest itself the twist (rotation) eigenvalues are zero, so a small
// random perturbation alone makes some of them slightly negative and the
// projection would clamp them; a uniform 3% stretch makes them clearly
// positive (about 3 lambda s), which the test asserts before relying on it.
TEST(FemOperator, ProductMatchesFiniteDifferencesNearRest) {
  double worst = 0.0;
  for (const Scene& s : scenes()) {
    if (!in_grid(s, Precision::double_)) continue;
    SCOPED_TRACE(s.name);
    std::vector<double> x = perturbed(s.mesh, 0.01 * kH, 555);
    for (double& c : x) c *= 1.03;
    ASSERT_GT(min_hessian_eigenvalue(s, x), 0.0) << "the projection would change the Hessian here";
    solver::ElasticModel<double> model(device_for(Precision::double_), s.mesh, s.rest,
                                       uniform_material(s.mesh, s.material), ProductVariant::cached);
    const std::vector<double> p = random_vector(x.size(), 1.0, 8);
    model.linearize(upload<double>(x));
    viennacl::vector<double> y(model.dofs()), rp(model.dofs()), rm(model.dofs());
    model.product(upload<double>(p), y);
    const std::vector<double> yh = download(y);
    double best = INFINITY;
    for (double t : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7}) {
      std::vector<double> xp = x, xm = x;
      for (size_t i = 0; i < x.size(); ++i) {
        xp[i] += t * p[i];
        xm[i] -= t * p[i];
      }
      model.residual(upload<double>(xp), rp);
      model.residual(upload<double>(xm), rm);
      const std::vector<double> a = download(rp), b = download(rm);
      std::vector<double> fd(x.size());
      for (size_t i = 0; i < x.size(); ++i) fd[i] = -(a[i] - b[i]) / (2 * t);
      best = std::min(best, relative_difference(fd, yh));
    }
    EXPECT_LT(best, 1e-6);
    worst = std::max(worst, best);
  }
  std::printf("[ measured ] finite differences: worst best-over-t relative error %.3g\n", worst);
}

// --- determinism ------------------------------------------------------------

template <typename Real>
void check_determinism() {
  for (const Case& c : cases(precision_of<Real>)) {
    SCOPED_TRACE(c.name);
    const Scene& s = *c.scene;
    solver::ElasticModel<Real> model(device_for(precision_of<Real>), s.mesh, s.rest,
                                     uniform_material(s.mesh, s.material), ProductVariant::cached);
    const viennacl::vector<Real> xd = upload<Real>(c.x), pd = upload<Real>(random_vector(c.x.size(), 1.0, 3));
    viennacl::vector<Real> a(model.dofs()), b(model.dofs());
    model.residual(xd, a);
    model.residual(xd, b);
    EXPECT_EQ(download_raw(a), download_raw(b));
    EXPECT_EQ(model.energy(xd), model.energy(xd));
    model.linearize(xd);
    for (ProductVariant variant : {ProductVariant::cached, ProductVariant::recompute, ProductVariant::element_matrices,
                                   ProductVariant::assembled}) {
      model.products().set_variant(variant);
      model.linearize(xd);
      model.product(pd, a);
      model.product(pd, b);
      EXPECT_EQ(download_raw(a), download_raw(b));
    }
  }
}

TEST(FemOperator, DeterministicResidualAndProductDouble) { check_determinism<double>(); }
TEST(FemOperator, DeterministicResidualAndProductFloat) { check_determinism<float>(); }

// What CG multiplies by (solver/newton/matrix_free.h's HessianOperator) at a true-
// Hessian linearization with negative curvature: K p as it is along a
// direction of positive curvature, the infinitely stiff response p / eps^2
// with the flag set along the most negative eigenvector, and nothing flagged
// for a zero p.
TEST(FemOperator, HessianOperatorFlagsNegativeCurvatureOnly) {
  const Mesh mesh = make_box_lattice(1, 1, 1, 1.0);
  const fem::RestState rest = fem::compute_rest_state(mesh);
  device::OpenClContext& cl = device_for(Precision::double_);
  solver::ElasticModel<double> model(
      cl, mesh, rest, uniform_material(mesh, StableNeoHookean::from_youngs_modulus(1.0, 0.45, Barrier::off)),
      ProductVariant::cached);
  // Squashed to a fifth along z and sheared: the true Hessian is indefinite.
  std::vector<double> x = mesh.positions.xyz();
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    x[3 * v] += 0.6 * mesh.positions(v, 2);
    x[3 * v + 2] *= 0.2;
  }
  const viennacl::vector<double> xd = upload<double>(x);
  model.linearize(xd, false);
  const size_t n = model.dofs();
  Eigen::MatrixXd k(n, n);
  viennacl::vector<double> e(n), y(n);
  for (size_t j = 0; j < n; ++j) {
    std::vector<double> unit(n, 0.0);
    unit[j] = 1.0;
    e = upload<double>(unit);
    model.product(e, y);
    const std::vector<double> column = download(y);
    for (size_t i = 0; i < n; ++i) k(i, j) = column[i];
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(0.5 * (k + k.transpose()));
  ASSERT_LT(eigen.eigenvalues()(0), -1e-3 * eigen.eigenvalues()(n - 1)) << "the state should be indefinite";
  solver::HessianOperator<double> op(model);
  const auto as_vector = [](const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); };
  // The most positive direction: K p, no flag.
  const viennacl::vector<double> positive = upload<double>(as_vector(eigen.eigenvectors().col(n - 1)));
  op.apply(positive, y);
  EXPECT_FALSE(op.negative_curvature());
  EXPECT_FALSE(op.breakdown());
  viennacl::vector<double> ky(n);
  model.product(positive, ky);
  EXPECT_EQ(download(y), download(ky));
  // A zero direction: nothing to flag.
  const viennacl::vector<double> zero = upload<double>(std::vector<double>(n, 0.0));
  op.apply(zero, y);
  EXPECT_FALSE(op.negative_curvature());
  EXPECT_FALSE(op.breakdown());
  // The most negative direction: flagged, answered stiffly.
  const std::vector<double> hp = as_vector(eigen.eigenvectors().col(0));
  op.apply(upload<double>(hp), y);
  EXPECT_TRUE(op.negative_curvature());
  EXPECT_FALSE(op.breakdown());
  const std::vector<double> stiff = download(y);
  const double scale = 1.0 / (DBL_EPSILON * DBL_EPSILON);
  for (size_t i = 0; i < n; ++i) EXPECT_DOUBLE_EQ(stiff[i], hp[i] * scale) << i;
  op.reset();
  EXPECT_FALSE(op.negative_curvature());
}

}  // namespace
}  // namespace snh::test
