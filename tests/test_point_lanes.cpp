// Per-point lanes (kernels/fem_lanes.cl, PointLanes::set_point_lanes): the
// linearization, the cached and recompute products, the element matrices and
// the block-Jacobi blocks over 8-wide vectors, a lane per quadrature point of a hex8 element or per
// tet4 element, against fem.cl's scalar kernels on the same device (the
// cached product runs over lanes in float only: PointLanes::set_point_lanes).
// Every lane runs the scalar kernel's operations on the same values (no
// contraction, correctly rounded division and square root), so the
// linearization cache and the products must be equal value for value, not
// merely close, except where a material calls exp (Fung): OpenCL's exp is
// not correctly rounded, and pocl's vector and scalar versions round
// differently at some arguments; the point's SVD frame, eigensystem and
// product carry that to its other entries (largest difference seen: 5.6e-17
// with entries of order 1), so there the bound is 1e-14 of the largest
// entry. For every model, the alpha/mixing path, materials per region and
// the run-time material kernel, at projected and true-Hessian
// linearizations, on lattices of an odd element count with jittered rest
// shapes (no shared rest data) and a uniform one and on tet4 boxes whose
// element count is not a multiple of 8, with large rotations and stretches,
// an inverted element and a collapsed one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "fem/rest_state.h"
#include "snh/error.h"
#include "snh/material.h"
#include "snh/mesh.h"
#include "snh/regions.h"
#include "solver/model/elastic_model.h"
#include "support/device_test_support.h"
#include "support/random_vectors.h"

namespace snh::test {
namespace {

template <typename Real>
constexpr Precision precision_of = std::is_same_v<Real, double> ? Precision::double_ : Precision::single;

constexpr double kH = 0.5;

// Positions that reach every branch of the per-point math: a rotation by
// 2.5 rad about a skew axis with a stretch of 1.8 / 0.6, random noise of
// 0.2 h, element 0 inverted (a node pushed through its centroid) and the
// last element flattened (a node moved onto another: J near 0).
std::vector<double> hard_positions(const Mesh& mesh) {
  std::vector<double> x(3 * mesh.vertex_count());
  const double c = std::cos(2.5), s = std::sin(2.5);
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-0.2 * kH, 0.2 * kH);
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const double px = 1.8 * mesh.positions(v, 0), py = 0.6 * mesh.positions(v, 1), pz = mesh.positions(v, 2);
    x[3 * v] = c * px - s * pz + u(rng);
    x[3 * v + 1] = py + u(rng);
    x[3 * v + 2] = s * px + c * pz + u(rng);
  }
  const int n = nodes_per_element(mesh.type);
  const int32_t* e0 = &mesh.elements[0];
  for (int i = 0; i < 3; ++i) {
    double centroid = 0.0;
    for (int a = 0; a < n; ++a) centroid += x[3 * e0[a] + i] / n;
    x[3 * e0[0] + i] += 1.7 * (centroid - x[3 * e0[0] + i]);
  }
  // The last element flattened: its last node moved onto its first.
  const int32_t* last = &mesh.elements[n * (mesh.element_count() - 1)];
  for (int i = 0; i < 3; ++i) x[3 * last[n - 1] + i] = x[3 * last[0] + i] + 1e-7 * (i + 1);
  return x;
}

// The direction the products are taken along: entries uniform in [-1, 1].
std::vector<double> random_direction(size_t size, unsigned seed) { return random_vector(size, 1.0, seed); }

template <typename Real>
struct Outputs {
  std::vector<Real> cache[2];      // projected, true Hessian
  std::vector<Real> product[2];    // recompute product at each
  std::vector<Real> cached[2];     // cached product at each
  std::vector<Real> jacobi[2];     // block-Jacobi's inverted blocks at each
  std::vector<Real> matrices[2];   // element matrices at each
  std::vector<Real> blocks[2];     // and their diagonal blocks
  std::vector<Real> assembled[2];  // the assembled product (block stencil) at each, when asked for
};

// assembled: the assembled variant's product too.
template <typename Real>
Outputs<Real> run(solver::ElasticModel<Real>& model, int nodes, const std::vector<double>& x,
                  const std::vector<double>& p, bool assembled = false) {
  Outputs<Real> out;
  device::OpenClContext& cl = device_for(precision_of<Real>);
  const viennacl::vector<Real> xd = upload<Real>(x), pd = upload<Real>(p);
  model.products().set_variant(ProductVariant::recompute);
  for (int projected = 0; projected < 2; ++projected) {
    model.linearize(xd, projected == 0);
    std::vector<Real>& cache = out.cache[projected];
    cache.resize(model.data().cache_values());
    cl.read(model.data().cache.get(), cache.size() * sizeof(Real), cache.data());
    viennacl::vector<Real> y(model.dofs());
    model.product(pd, y);
    out.product[projected] = download_raw(y);
    model.products().set_variant(ProductVariant::cached);
    model.product(pd, y);
    out.cached[projected] = download_raw(y);
    model.products().set_variant(ProductVariant::recompute);
    model.setup_preconditioner();
    out.jacobi[projected] = model.preconditioner_blocks();
    const size_t n = 3 * static_cast<size_t>(nodes);
    std::vector<Real>& k = out.matrices[projected];
    std::vector<Real>& b = out.blocks[projected];
    k.resize(model.data().element_count * n * n);
    b.resize(model.data().element_count * 3 * n);
    device::Buffer kd = cl.buffer(CL_MEM_READ_WRITE, k.size() * sizeof(Real));
    device::Buffer bd = cl.buffer(CL_MEM_READ_WRITE, b.size() * sizeof(Real));
    model.products().element_matrices_into(kd.get(), bd.get());
    cl.read(kd.get(), k.size() * sizeof(Real), k.data());
    cl.read(bd.get(), b.size() * sizeof(Real), b.data());
    if (assembled) {
      model.products().set_variant(ProductVariant::assembled);
      model.linearize(xd, projected == 0);
      model.product(pd, y);
      out.assembled[projected] = download_raw(y);
      model.products().set_variant(ProductVariant::recompute);
    }
  }
  return out;
}

// relative: 0 (equal values) or the bound on the largest difference
// relative to the largest entry.
template <typename Real>
void expect_equal_values(const std::vector<Real>& lanes, const std::vector<Real>& scalar, double relative,
                         const std::string& what) {
  ASSERT_EQ(lanes.size(), scalar.size()) << what;
  size_t differ = 0, first = lanes.size();
  double largest = 0.0, worst = 0.0;
  for (size_t i = 0; i < lanes.size(); ++i) {
    ASSERT_TRUE(std::isfinite(scalar[i])) << what << " entry " << i;
    largest = std::max(largest, std::abs(static_cast<double>(scalar[i])));
    worst = std::max(worst, std::abs(static_cast<double>(lanes[i]) - static_cast<double>(scalar[i])));
    if (lanes[i] != scalar[i]) {
      ++differ;
      first = std::min(first, i);
    }
  }
  if (relative == 0.0) {
    EXPECT_EQ(differ, 0u) << what << ": first at " << first << ", lanes " << lanes[first] << " scalar "
                          << scalar[first];
  } else {
    EXPECT_LE(worst, relative * largest) << what << " (" << differ << " entries differ)";
  }
}

bool calls_exp(const MaterialMap& map) {
  for (const Material& m : map.materials)
    if (m.model == MaterialModel::fung || m.lambda_model == MaterialModel::fung) return true;
  return false;
}

Material with(MaterialModel model, double alpha = 1.0, std::optional<MaterialModel> lambda_model = std::nullopt,
              double alpha_lambda = 1.0) {
  MaterialOptions o;
  o.alpha = alpha;
  o.lambda_model = lambda_model;
  o.alpha_lambda = alpha_lambda;
  return Material::from_youngs_modulus(model, 1.0, 0.45, o);
}

using Maps = std::vector<std::pair<std::string, MaterialMap>>;

// maps: materials over `meshes[0]`'s elements (the meshes have one element count).
template <typename Real>
void check_cases(const std::vector<Mesh>& meshes, const Maps& maps, device::MaterialKernel build) {
  for (const Mesh& mesh : meshes) {
    const fem::RestState rest = fem::compute_rest_state(mesh);
    const std::vector<double> x = hard_positions(mesh);
    const std::vector<double> p = random_direction(x.size(), 7);
    for (const auto& [name, map] : maps) {
      SCOPED_TRACE(name + " / " + to_string(mesh.type) + (rest.uniform ? " uniform rest" : " own rest shapes"));
      device::OpenClContext& cl = device_for(precision_of<Real>);
      // The lanes program reads the value-major or point-major cache: on a
      // GPU, whose default is the tiled one, the point-major.
      solver::ModelTerms terms;
      if (cl.info().is_gpu) terms.hex8_point_data = solver::PointDataLayout::point_major;
      solver::ElasticModel<Real> model(cl, mesh, rest, map, ProductVariant::recompute, build, terms);
      // The lanes program is the default on CPU devices (pocl), the scalar
      // kernels (a work-item per element) on GPUs.
      EXPECT_EQ(model.lanes().point_lanes(), !cl.info().is_gpu) << cl.info().name;
      model.lanes().set_point_lanes(true);
      const bool regions = !map.uniform();
      const int nodes = nodes_per_element(mesh.type);
      // The material kernels' width: two of the device's native vectors
      // where it has 8-wide ones (16 lanes), but one element's material per
      // hex8 work-item with regions.
      const unsigned native =
          std::is_same_v<Real, double> ? cl.info().native_vector_width_double : cl.info().native_vector_width_float;
      EXPECT_EQ(model.lanes().material_lanes(), native >= 8 && !(nodes == 8 && regions) ? 16 : 8);
      const Outputs<Real> lanes = run(model, nodes, x, p);
      // The other width, where it exists: the linearization and the
      // recompute product (the kernels that read the cache keep 8 lanes).
      std::optional<Outputs<Real>> other;
      if (nodes == 8 && regions) {
        EXPECT_THROW(model.lanes().set_material_lanes(16), Error);
      } else {
        model.lanes().set_material_lanes(model.lanes().material_lanes() == 16 ? 8 : 16);
        other = run(model, nodes, x, p);
      }
      model.lanes().set_point_lanes(false);
      EXPECT_EQ(model.lanes().material_lanes(), 0);
      const Outputs<Real> scalar = run(model, nodes, x, p);
      const double relative = calls_exp(map) ? 1e-14 : 0.0;
      for (int k = 0; k < 2; ++k) {
        const std::string at = k == 0 ? "projected" : "true Hessian";
        if (other) {
          const std::string width = std::to_string(model.lanes().default_material_lanes() == 16 ? 8 : 16) + " lanes, ";
          expect_equal_values(other->cache[k], scalar.cache[k], relative, width + "linearization, " + at);
          expect_equal_values(other->product[k], scalar.product[k], relative, width + "recompute product, " + at);
        }
        expect_equal_values(lanes.cache[k], scalar.cache[k], relative, "linearization, " + at);
        expect_equal_values(lanes.product[k], scalar.product[k], relative, "recompute product, " + at);
        expect_equal_values(lanes.cached[k], scalar.cached[k], relative, "cached product, " + at);
        expect_equal_values(lanes.jacobi[k], scalar.jacobi[k], relative, "block-Jacobi blocks, " + at);
        expect_equal_values(lanes.matrices[k], scalar.matrices[k], relative, "element matrices, " + at);
        expect_equal_values(lanes.blocks[k], scalar.blocks[k], relative, "diagonal blocks, " + at);
      }
    }
  }
}

MaterialMap two_regions(const Mesh& mesh, const Material& base, const Material& other) {
  MaterialMap map = uniform_material(mesh, base);
  map.materials.push_back(other);
  map.names.push_back("other");
  for (size_t e = 0; e < mesh.element_count(); e += 2) map.element_material[e] = 1;
  return map;
}

// 3 x 3 x 1 cubes: 9 elements, the last work-item of 16 lanes (two
// elements) half full.
std::vector<Mesh> hex_meshes() { return {jittered(make_box_lattice(3, 3, 1, kH), kH), make_box_lattice(3, 3, 1, kH)}; }

// 3 x 2 x 1 cubes of 6 tetrahedra: 36 elements, the last work-item's lanes
// half full (8 lanes) or a quarter full (16).
std::vector<Mesh> tet_meshes() { return {jittered(make_tet_box(3, 2, 1, kH), kH), make_tet_box(3, 2, 1, kH)}; }

Maps every_model(const Mesh& mesh) {
  Maps maps;
  for (MaterialModel m : {MaterialModel::stable_neo_hookean, MaterialModel::fung, MaterialModel::arruda_boyce,
                          MaterialModel::corotational, MaterialModel::fixed_corotational, MaterialModel::stvk_kikuuwe,
                          MaterialModel::neohookean})
    maps.push_back({to_string(m), uniform_material(mesh, with(m))});
  // Chen and Barbic 2024: alpha below and above 1, and mixed parts with two alphas.
  maps.push_back({"snh alpha 0.5", uniform_material(mesh, with(MaterialModel::stable_neo_hookean, 0.5))});
  maps.push_back({"fung alpha 2.5", uniform_material(mesh, with(MaterialModel::fung, 2.5))});
  maps.push_back({"neohookean 1.2 + fung lambda 3.0",
                  uniform_material(mesh, with(MaterialModel::neohookean, 1.2, MaterialModel::fung, 3.0))});
  return maps;
}

TEST(PointLanes, EveryModelMatchesTheScalarKernelsDouble) {
  // Every model on the uniform-rest lattice (the lattices' build) and the
  // jittered tet4 box; SNH and regions on every mesh (a kernel build per
  // mesh kind and material, so not every pair).
  const std::vector<Mesh> hexes = hex_meshes(), tets = tet_meshes();
  check_cases<double>({hexes[1]}, every_model(hexes[1]), device::MaterialKernel::specialized);
  check_cases<double>({tets[0]}, every_model(tets[0]), device::MaterialKernel::specialized);
  const Material snh = with(MaterialModel::stable_neo_hookean);
  // Materials per region (per-element parameters).
  check_cases<double>(
      hexes,
      {{"snh", uniform_material(hexes[0], snh)},
       {"regions",
        two_regions(hexes[0], snh, Material::from_youngs_modulus(MaterialModel::stable_neo_hookean, 3.0, 0.49))}},
      device::MaterialKernel::specialized);
  check_cases<double>({tets[1]}, {{"snh", uniform_material(tets[1], snh)}}, device::MaterialKernel::specialized);
}

TEST(PointLanes, RunTimeMaterialKernelMatchesDouble) {
  // One kernel for every material: model, barrier and path read per element
  // (hex8) or from the arguments (tet4).
  const std::vector<Mesh> hexes = hex_meshes();
  check_cases<double>(hexes,
                      {{"runtime regions of two models",
                        two_regions(hexes[0], with(MaterialModel::fung), with(MaterialModel::corotational, 0.7))}},
                      device::MaterialKernel::runtime);
  const std::vector<Mesh> tets = tet_meshes();
  check_cases<double>(tets, {{"runtime fung", uniform_material(tets[0], with(MaterialModel::fung, 0.7))}},
                      device::MaterialKernel::runtime);
}

TEST(PointLanes, FloatMatchesTheScalarKernels) {
  // The premise (correctly rounded float division and square root) holds on
  // pocl; on an NVIDIA H200 NVIDIA's OpenCL rounded the two programs'
  // float a few ulps apart, and GPUs run the scalar kernels by default.
  if (device_for(Precision::single).info().is_gpu)
    GTEST_SKIP() << "float lanes against the scalar kernels bit for bit: CPU (pocl) devices only";
  for (const std::vector<Mesh>& meshes : {hex_meshes(), tet_meshes()}) {
    check_cases<float>(
        meshes,
        {{"snh", uniform_material(meshes[0], with(MaterialModel::stable_neo_hookean))},
         {"stvk alpha 0.5 + snh lambda 1.5",
          uniform_material(meshes[0], with(MaterialModel::stvk_kikuuwe, 0.5, MaterialModel::stable_neo_hookean, 1.5))}},
        device::MaterialKernel::specialized);
  }
}

// The layouts of the per-point data (solver::PointDataLayout: the
// linearization cache, kernels/fem/element.h, and the rest gradients of a
// hex8 mesh with its own rest shapes, kernels/fem/element_data.h) on this
// test's device: the point-major one holds the value-major one's cache
// values point by point, the tiled one (the GPUs' default) the point-major
// one's tile by tile, and the products, block-Jacobi blocks and element
// matrices read from any of them are the same bit for bit, in the lanes
// program (value- and point-major) and in the scalar kernels (all three);
// so is the assembled product, whose block stencil the tiled layout stores
// in tiles of 32 vertices (kernels/fem/block_stencil.h). The meshes'
// elements and vertices fill one tile in part, or more than one.
template <typename Real>
void check_point_data_layouts() {
  std::vector<Mesh> meshes = hex_meshes();
  meshes.push_back(jittered(make_box_lattice(5, 4, 3, kH), kH));
  meshes.push_back(jittered(make_tet_box(3, 2, 1, kH), kH));
  for (const Mesh& mesh : meshes) {
    const fem::RestState rest = fem::compute_rest_state(mesh);
    const size_t n = static_cast<size_t>(rest.nodes), points = static_cast<size_t>(rest.quadrature);
    SCOPED_TRACE(std::string(to_string(mesh.type)) + " of " + std::to_string(mesh.element_count()) +
                 (rest.uniform ? ", uniform rest" : ", own rest shapes"));
    const std::vector<double> x = hard_positions(mesh);
    const std::vector<double> p = random_direction(x.size(), 11);
    const MaterialMap map = uniform_material(mesh, with(MaterialModel::stable_neo_hookean));
    device::OpenClContext& cl = device_for(precision_of<Real>);
    solver::ModelTerms value_major, point_major, tiled;
    value_major.hex8_point_data = solver::PointDataLayout::value_major;
    point_major.hex8_point_data = solver::PointDataLayout::point_major;
    tiled.hex8_point_data = solver::PointDataLayout::tiled;
    solver::ElasticModel<Real> a(cl, mesh, rest, map, ProductVariant::recompute, device::MaterialKernel::specialized,
                                 value_major);
    solver::ElasticModel<Real> b(cl, mesh, rest, map, ProductVariant::recompute, device::MaterialKernel::specialized,
                                 point_major);
    solver::ElasticModel<Real> c(cl, mesh, rest, map, ProductVariant::recompute, device::MaterialKernel::specialized,
                                 tiled);
    EXPECT_EQ(c.data().cache_tile, 32u);
    EXPECT_FALSE(c.lanes().point_lanes());
    EXPECT_FALSE(c.lanes().point_lanes_available());
    EXPECT_THROW(c.lanes().set_point_lanes(true), Error);
    const size_t tiles = (mesh.element_count() + 31) / 32;
    EXPECT_EQ(c.data().cache_values(), tiles * 32 * points * 30);
    for (bool lanes : {true, false}) {
      SCOPED_TRACE(lanes ? "lanes program" : "scalar kernels");
      a.lanes().set_point_lanes(lanes);
      b.lanes().set_point_lanes(lanes);
      const int nodes = static_cast<int>(n);
      const Outputs<Real> va = run(a, nodes, x, p, true), pm = run(b, nodes, x, p, true);
      std::optional<Outputs<Real>> tl;
      if (!lanes) tl = run(c, nodes, x, p, true);
      for (int k = 0; k < 2; ++k) {
        const std::string at = k == 0 ? "projected" : "true Hessian";
        ASSERT_EQ(va.cache[k].size(), pm.cache[k].size());
        size_t differ = 0, differ_tiled = 0;
        for (size_t e = 0; e < mesh.element_count(); ++e)
          for (size_t q = 0; q < points; ++q)
            for (size_t v = 0; v < 30; ++v) {
              const Real value = pm.cache[k][30 * (points * e + q) + v];
              differ += va.cache[k][30 * points * e + points * v + q] != value;
              if (tl) differ_tiled += tl->cache[k][30 * points * 32 * (e / 32) + 32 * (30 * q + v) + e % 32] != value;
            }
        EXPECT_EQ(differ, 0u) << "linearization, " + at;
        EXPECT_EQ(differ_tiled, 0u) << "tiled linearization, " + at;
        std::vector<std::pair<const Outputs<Real>*, std::string>> layouts = {{&va, ""}};
        if (tl) layouts.emplace_back(&*tl, "tiled ");
        for (const auto& [o, which] : layouts) {
          expect_equal_values(o->product[k], pm.product[k], 0.0, which + "recompute product, " + at);
          expect_equal_values(o->cached[k], pm.cached[k], 0.0, which + "cached product, " + at);
          expect_equal_values(o->jacobi[k], pm.jacobi[k], 0.0, which + "block-Jacobi blocks, " + at);
          expect_equal_values(o->matrices[k], pm.matrices[k], 0.0, which + "element matrices, " + at);
          expect_equal_values(o->blocks[k], pm.blocks[k], 0.0, which + "diagonal blocks, " + at);
          expect_equal_values(o->assembled[k], pm.assembled[k], 0.0, which + "assembled product, " + at);
        }
      }
    }
  }
}

// A double model's float products (ProductVariants::set_float_products) in
// the scalar kernels: the float copy each linearize() writes (strided in the
// tiled cache), the mixed cached product, and the float element matrices
// computed from the copies (fem.cl's SNH_MIXED build, the multigrid fine
// level's on GPUs), the same bit for bit from the point-major and tiled
// caches.
void check_float_copies_across_layouts() {
  std::vector<Mesh> meshes = {jittered(make_box_lattice(5, 4, 3, kH), kH), jittered(make_tet_box(3, 2, 1, kH), kH)};
  for (const Mesh& mesh : meshes) {
    const fem::RestState rest = fem::compute_rest_state(mesh);
    SCOPED_TRACE(to_string(mesh.type));
    const size_t n = 3 * static_cast<size_t>(rest.nodes), ne = mesh.element_count();
    device::OpenClContext& cl = device_for(Precision::double_);  // before the uploads: ViennaCL's context
    const std::vector<double> x = hard_positions(mesh);
    const viennacl::vector<double> xd = upload<double>(x), pd = upload<double>(random_direction(x.size(), 13));
    const MaterialMap map = uniform_material(mesh, with(MaterialModel::stable_neo_hookean));
    std::vector<double> products[2];
    std::vector<float> matrices[2];
    int i = 0;
    for (solver::PointDataLayout layout : {solver::PointDataLayout::point_major, solver::PointDataLayout::tiled}) {
      solver::ModelTerms terms;
      terms.hex8_point_data = layout;
      solver::ElasticModel<double> model(cl, mesh, rest, map, ProductVariant::cached,
                                         device::MaterialKernel::specialized, terms);
      model.lanes().set_point_lanes(false);
      model.products().set_float_products(true);
      model.linearize(xd);
      viennacl::vector<double> y(model.dofs());
      model.product(pd, y);
      products[i] = download_raw(y);
      device::Buffer kd = cl.buffer(CL_MEM_READ_WRITE, ne * n * n * sizeof(float));
      device::Buffer bd = cl.buffer(CL_MEM_READ_WRITE, ne * 3 * n * sizeof(double));
      model.products().element_matrices_into(kd.get(), bd.get(), true);
      matrices[i].resize(ne * n * n);
      cl.read(kd.get(), matrices[i].size() * sizeof(float), matrices[i].data());
      ++i;
    }
    EXPECT_EQ(products[1], products[0]) << "mixed cached product";
    EXPECT_EQ(matrices[1], matrices[0]) << "float element matrices from the float copies";
  }
}

TEST(PointLanes, FloatCopiesAreTheSameInEveryLayout) { check_float_copies_across_layouts(); }

TEST(PointLanes, PointDataLayoutsGiveTheSameValues) {
  check_point_data_layouts<double>();
  check_point_data_layouts<float>();
}

TEST(PointLanes, Tet4RegionsKeepTheScalarKernels) {
  // tet4 lanes are 8 elements: one material per work-item.
  const Mesh mesh = make_tet_box(2, 2, 2, kH);
  solver::ElasticModel<double> model(
      device_for(Precision::double_), mesh, fem::compute_rest_state(mesh),
      two_regions(mesh, with(MaterialModel::stable_neo_hookean), with(MaterialModel::stable_neo_hookean, 1.0)),
      ProductVariant::recompute);
  EXPECT_FALSE(model.lanes().point_lanes());
  EXPECT_THROW(model.lanes().set_point_lanes(true), Error);
  model.lanes().set_point_lanes(false);
}

}  // namespace
}  // namespace snh::test
