// Regions with their own materials (snh::MaterialMap): the map's checks, the
// kernel switches a map builds, the device's per-element material tables
// against the host reference over the map (energy, forces, the projected
// product in all four variants) for same-model and mixed-model maps on hex8
// and tet4 meshes, the uniform map's kernels unchanged, a bar of two
// materials in series against 1D elasticity, and scene files with regions.
//
// Device vs host bounds as in test_fem_operator.cpp: double 1e-12 relative;
// float kFloatUlps FLT_EPSILON (1 + lambda / mu) with the largest
// lambda / mu of the map's materials (each element's error scales with its
// own material's; the map's worst bounds them all).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <Eigen/Sparse>
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "device/material_args.h"
#include "device/opencl_context.h"
#include "device/viennacl_binding.h"
#include "fem/rest_state.h"
#include "reference/fem_reference.h"
#include "snh/error.h"
#include "snh/material.h"
#include "snh/mesh.h"
#include "snh/regions.h"
#include "snh/scene.h"
#include "snh/simulation.h"
#include "solver/model/elastic_model.h"
#include "support/device_test_support.h"
#include "support/random_vectors.h"
#include "vector_compare.h"
#include "viennacl/vector.hpp"

namespace snh::test {
namespace {

constexpr double kDoubleBound = 1e-12;
constexpr double kFloatUlps = 16.0;
constexpr double kH = 0.5;
const std::string kScenes = std::string(SNH_DATA_DIR) + "/scenes/";

constexpr ProductVariant kVariants[] = {ProductVariant::cached, ProductVariant::recompute,
                                        ProductVariant::element_matrices, ProductVariant::assembled};

template <typename Real>
constexpr Precision precision_of = std::is_same_v<Real, double> ? Precision::double_ : Precision::single;

Material snh(double e, double nu) { return Material::from_youngs_modulus(MaterialModel::stable_neo_hookean, e, nu); }

Material model(MaterialModel m, double e, double nu, MaterialOptions o = {}) {
  return Material::from_youngs_modulus(m, e, nu, o);
}

std::array<double, 3> centroid(const Mesh& mesh, size_t e) {
  const int n = nodes_per_element(mesh.type);
  std::array<double, 3> c{0, 0, 0};
  for (int a = 0; a < n; ++a)
    for (int d = 0; d < 3; ++d) c[d] += mesh.positions(mesh.elements[n * e + a], d) / n;
  return c;
}

double extent_x(const Mesh& mesh) {
  double hi = 0.0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) hi = std::max(hi, mesh.positions(v, 0));
  return hi;
}

// Two materials: the base below the middle of x, the region above it.
// Three: the region "left" is the lowest third in x (a block), "odd" every
// other remaining element (interleaved, so neighbouring work-items read
// different table entries).
MaterialMap split(const Mesh& mesh, const std::vector<Material>& materials) {
  const double length = extent_x(mesh);
  std::vector<MaterialRegion> regions;
  if (materials.size() == 2) {
    MaterialRegion right{"right", {}, materials[1]};
    for (size_t e = 0; e < mesh.element_count(); ++e)
      if (centroid(mesh, e)[0] > 0.5 * length) right.elements.push_back(static_cast<int32_t>(e));
    regions.push_back(right);
  } else {
    MaterialRegion left{"left", {}, materials[1]}, odd{"odd", {}, materials[2]};
    for (size_t e = 0; e < mesh.element_count(); ++e) {
      if (centroid(mesh, e)[0] < length / 3)
        left.elements.push_back(static_cast<int32_t>(e));
      else if (e % 2 == 1)
        odd.elements.push_back(static_cast<int32_t>(e));
    }
    regions = {left, odd};
  }
  return make_material_map(mesh, materials[0], regions);
}

Mesh jittered_lattice() { return jittered(make_box_lattice(4, 2, 2, kH), kH); }

struct MapCase {
  std::string name;
  Mesh mesh;
  fem::RestState rest;
  MaterialMap map;
  bool mixed;  // materials of different models: the run-time-model kernels
};

// Same-model maps (one specialized kernel, parameters per element) and
// mixed-model maps (run-time model), two and three materials, on hex8
// lattices (uniform and jittered rest shapes) and a tet4 box. The mixed
// ones cover every field of the table: Fung's and Arruda-Boyce's c0, c1,
// the nonlinearity alphas, a lambda part of another model with its J0, the
// barrier flag.
const std::vector<MapCase>& map_cases() {
  static const std::vector<MapCase> all = [] {
    MaterialOptions adjusted;
    adjusted.alpha = 1.5;
    MaterialOptions mixed_parts;
    mixed_parts.alpha = 1.5;
    mixed_parts.lambda_model = MaterialModel::neohookean;
    mixed_parts.alpha_lambda = 0.75;
    const Mesh hex_uniform = make_box_lattice(4, 2, 2, kH), hex_jittered = jittered_lattice(),
               tet = make_tet_box(3, 2, 2, kH);
    const std::vector<std::tuple<std::string, Mesh, std::vector<Material>, bool>> cases = {
        {"hex8_jittered/snh_soft_stiff", hex_jittered, {snh(1.0, 0.3), snh(10.0, 0.3)}, false},
        {"hex8_uniform/snh_three", hex_uniform, {snh(1.0, 0.45), snh(4.0, 0.45), snh(16.0, 0.47)}, false},
        {"hex8_uniform/corotational_alpha_two",
         hex_uniform,
         {model(MaterialModel::corotational, 1.0, 0.4, adjusted),
          model(MaterialModel::corotational, 5.0, 0.3, adjusted)},
         false},
        {"hex8_jittered/mixed_three",
         hex_jittered,
         {snh(1.0, 0.3), model(MaterialModel::corotational, 3.0, 0.35, mixed_parts),
          model(MaterialModel::neohookean, 2.0, 0.4)},
         true},
        {"tet4/snh_three", tet, {snh(2.0, 0.45), snh(1.0, 0.45), snh(8.0, 0.45)}, false},
        {"tet4/mixed_two",
         tet,
         {model(MaterialModel::fung, 1.0, 0.3), model(MaterialModel::arruda_boyce, 6.0, 0.4)},
         true},
        {"tet4/mixed_three",
         tet,
         {snh(1.0, 0.45), model(MaterialModel::stvk_kikuuwe, 4.0, 0.3),
          model(MaterialModel::fixed_corotational, 2.0, 0.2)},
         true},
    };
    std::vector<MapCase> out;
    for (const auto& [name, mesh, materials, mixed] : cases) {
      validate_mesh(mesh);
      out.push_back({name, mesh, fem::compute_rest_state(mesh), split(mesh, materials), mixed});
    }
    return out;
  }();
  return all;
}

std::vector<double> multiply(const Eigen::SparseMatrix<double>& k, const std::vector<double>& p) {
  const Eigen::VectorXd y = k * Eigen::Map<const Eigen::VectorXd>(p.data(), static_cast<Eigen::Index>(p.size()));
  return {y.data(), y.data() + y.size()};
}

template <typename Real>
struct Tolerance {
  double worst = 0.0;
  std::string where;

  static double scale(const MaterialMap& map) {
    if (std::is_same_v<Real, double>) return 1.0;
    double ratio = 0.0;
    for (const Material& m : map.materials) ratio = std::max(ratio, m.lambda / m.mu);
    return FLT_EPSILON * (1.0 + ratio);
  }
  static double bound(const MaterialMap& map) {
    return std::is_same_v<Real, double> ? kDoubleBound : kFloatUlps * scale(map);
  }
  void check(double error, const MaterialMap& map, const std::string& what) {
    EXPECT_LE(error, bound(map)) << what;
    if (error / scale(map) > worst) {
      worst = error / scale(map);
      where = what;
    }
  }
  ~Tolerance() {
    if (std::is_same_v<Real, double>)
      std::printf("[ measured ] double: worst relative error %.3g at %s\n", worst, where.c_str());
    else
      std::printf("[ measured ] float: worst error %.3g FLT_EPSILON (1 + max lambda/mu) at %s\n", worst, where.c_str());
  }
};

// --- the map and its kernel switches ----------------------------------------

TEST(Regions, MakeMaterialMapNamesTheProblem) {
  const Mesh mesh = make_box_lattice(2, 2, 1, 1.0);  // 4 elements
  auto error_of = [&](const std::vector<MaterialRegion>& regions) -> std::string {
    try {
      make_material_map(mesh, snh(1.0, 0.3), regions);
    } catch (const Error& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(error_of({{"fat", {}, snh(1.0, 0.4)}}).find("material region 'fat' selects no element"), std::string::npos);
  const std::string range = error_of({{"fat", {1, 4}, snh(1.0, 0.4)}});
  EXPECT_NE(range.find("'fat' refers to element 4, but the mesh has 4 elements"), std::string::npos) << range;
  EXPECT_NE(error_of({{"fat", {-1}, snh(1.0, 0.4)}}).find("element -1"), std::string::npos);
  const std::string twice = error_of({{"fat", {0, 1}, snh(1.0, 0.4)}, {"skin", {2, 1}, snh(5.0, 0.4)}});
  EXPECT_NE(twice.find("element 1 is in material regions 'fat' and 'skin'"), std::string::npos) << twice;

  const MaterialMap map = make_material_map(mesh, snh(1.0, 0.3), {{"fat", {3, 1, 3}, snh(2.0, 0.4)}});
  EXPECT_EQ(map.element_material, (std::vector<int32_t>{0, 1, 0, 1}));
  EXPECT_EQ(map.names, (std::vector<std::string>{"base", "fat"}));
  EXPECT_EQ(map.of_element(3).mu, snh(2.0, 0.4).mu);
  EXPECT_NO_THROW(validate_material_map(mesh, map));

  auto invalid = [&](MaterialMap m) -> std::string {
    try {
      validate_material_map(mesh, m);
    } catch (const Error& e) {
      return e.what();
    }
    return "no error";
  };
  MaterialMap short_map = map;
  short_map.element_material.pop_back();
  EXPECT_NE(invalid(short_map).find("element_material has 3 entries, but the mesh has 4 elements"), std::string::npos);
  MaterialMap bad_index = map;
  bad_index.element_material[2] = 2;
  EXPECT_NE(invalid(bad_index).find("element 2 has material 2, but the map has 2 materials"), std::string::npos);
  MaterialMap negative = map;
  negative.element_material[0] = -1;
  EXPECT_NE(invalid(negative).find("element 0 has material -1"), std::string::npos);
  MaterialMap empty = map;
  empty.materials.clear();
  EXPECT_NE(invalid(empty).find("no material"), std::string::npos);
  // The solver checks the map on construction, the device model too.
  EXPECT_THROW(QuasistaticSolver(mesh, bad_index, {}), Error);
  EXPECT_THROW(solver::ElasticModel<double>(device_for(Precision::double_), mesh, fem::compute_rest_state(mesh),
                                            short_map, ProductVariant::cached),
               Error);
}

TEST(Regions, KernelSwitchesAreOnlyWhatTheMapNeeds) {
  const Mesh mesh = make_box_lattice(2, 1, 1, 1.0);
  const Material soft = snh(1.0, 0.3), stiff = snh(10.0, 0.3);
  // Uniform: the material's switches and nothing more.
  const MaterialMap uniform = uniform_material(mesh, soft);
  EXPECT_EQ(device::material_defines(uniform), device::material_defines(soft));
  EXPECT_EQ(device::material_defines(uniform), "-DSNH_MODEL=0 -DSNH_BARRIER=1 -DSNH_NONLINEAR=0");
  EXPECT_EQ(device::material_defines(uniform, device::MaterialKernel::runtime), "-DSNH_GENERAL_KERNEL=1");
  // Same model, barrier, path and lambda model: specialized, parameters per element.
  const MaterialMap same = make_material_map(mesh, soft, {{"stiff", {1}, stiff}});
  EXPECT_EQ(device::material_defines(same), "-DSNH_MODEL=0 -DSNH_BARRIER=1 -DSNH_NONLINEAR=0 -DSNH_REGIONS=1");
  EXPECT_EQ(device::material_defines(same, device::MaterialKernel::runtime), "-DSNH_GENERAL_KERNEL=1 -DSNH_REGIONS=1");
  EXPECT_EQ(device::material_defines(same, device::MaterialKernel::all_terms),
            "-DSNH_MODEL=0 -DSNH_BARRIER=1 -DSNH_NONLINEAR=1 -DSNH_REGIONS=1");
  // Anything of the four differing: the run-time model.
  MaterialOptions alpha;
  alpha.alpha = 1.5;
  MaterialOptions lambda_part;
  lambda_part.lambda_model = MaterialModel::neohookean;
  const std::vector<Material> others = {
      snh(1.0, 0.45),  // no barrier (automatic for nu >= 0.4)
      model(MaterialModel::stable_neo_hookean, 1.0, 0.3, alpha),
      model(MaterialModel::stable_neo_hookean, 1.0, 0.3, lambda_part),
      model(MaterialModel::corotational, 1.0, 0.3),
  };
  for (const Material& other : others) {
    SCOPED_TRACE(other.description());
    EXPECT_EQ(device::material_defines(make_material_map(mesh, soft, {{"other", {0}, other}})),
              "-DSNH_GENERAL_KERNEL=1 -DSNH_REGIONS=1");
  }
  // Same alpha/mixing path and lambda model: still specialized.
  const MaterialOptions o = lambda_part;
  EXPECT_EQ(
      device::material_defines(make_material_map(mesh, model(MaterialModel::corotational, 1.0, 0.3, o),
                                                 {{"stiff", {0}, model(MaterialModel::corotational, 7.0, 0.2, o)}})),
      "-DSNH_MODEL=3 -DSNH_BARRIER=0 -DSNH_NONLINEAR=1 -DSNH_LAMBDA_MODEL=6 -DSNH_REGIONS=1");

  // The engine's specialization string: the uniform map's is the string of
  // before regions existed; a map's names the regions switch.
  auto& cl = device_for(Precision::double_);
  const fem::RestState rest = fem::compute_rest_state(mesh);
  EXPECT_EQ(solver::ElasticModel<double>(cl, mesh, rest, uniform, ProductVariant::cached).data().config.defines(),
            "-DSNH_HEX8=1 " + device::material_defines(soft) + " -DSNH_UNIFORM_REST=1");
  EXPECT_EQ(solver::ElasticModel<double>(cl, mesh, rest, same, ProductVariant::cached).data().config.defines(),
            "-DSNH_HEX8=1 -DSNH_MODEL=0 -DSNH_BARRIER=1 -DSNH_NONLINEAR=0 -DSNH_REGIONS=1 -DSNH_UNIFORM_REST=1");
}

TEST(Regions, MaterialTableFollowsTheRecordLayout) {
  const Mesh mesh = make_box_lattice(2, 1, 1, 1.0);
  MaterialOptions o;
  o.alpha = 1.5;
  o.lambda_model = MaterialModel::neohookean;
  o.alpha_lambda = 0.75;
  o.neohookean_j0 = 0.2;
  const Material a = snh(1.0, 0.3), b = model(MaterialModel::corotational, 3.0, 0.35, o);
  const std::vector<double> t = device::material_table<double>(make_material_map(mesh, a, {{"b", {1}, b}}));
  ASSERT_EQ(t.size(), 20u);
  EXPECT_EQ(std::vector<double>(t.begin(), t.begin() + 10),
            (std::vector<double>{a.mu, a.lambda, a.c0, a.c1, a.lambda_c0, 1.0, 1.0, 0.0, 1.0, -1.0}));
  EXPECT_EQ(std::vector<double>(t.begin() + 10, t.end()),
            (std::vector<double>{b.mu, b.lambda, b.c0, b.c1, b.lambda_c0, 0.75, 1.5, 3.0, 0.0, 6.0}));
  EXPECT_EQ(b.lambda_c0, 0.2);
}

// --- device against the host reference over the map ---------------------------

template <typename Real>
void check_device_against_reference() {
  Tolerance<Real> tolerance;
  for (const MapCase& c : map_cases()) {
    SCOPED_TRACE(c.name);
    solver::ElasticModel<Real> model(device_for(precision_of<Real>), c.mesh, c.rest, c.map, ProductVariant::cached);
    const std::string spec = model.data().config.defines();
    EXPECT_NE(spec.find("-DSNH_REGIONS=1"), std::string::npos) << spec;
    EXPECT_EQ(spec.find("-DSNH_GENERAL_KERNEL=1") != std::string::npos, c.mixed) << spec;
    const std::vector<double> x = rounded<Real>(perturbed(c.mesh, 0.2 * kH, 12345)),
                              p = rounded<Real>(random_vector(x.size(), 1.0, 777));
    const viennacl::vector<Real> xd = upload<Real>(x), pd = upload<Real>(p);

    const double energy = reference::assembled_energy(c.mesh, c.rest, c.map, x);
    tolerance.check(std::abs(model.energy(xd) - energy) / std::abs(energy), c.map, c.name + "/energy");

    viennacl::vector<Real> y(model.dofs());
    model.residual(xd, y);
    tolerance.check(relative_difference(download(y), reference::assembled_forces(c.mesh, c.rest, c.map, x)), c.map,
                    c.name + "/forces");

    const std::vector<double> expected =
        multiply(reference::assembled_projected_stiffness(c.mesh, c.rest, c.map, x), p);
    for (ProductVariant variant : kVariants) {
      model.products().set_variant(variant);
      model.linearize(xd);
      model.product(pd, y);
      tolerance.check(relative_difference(download(y), expected), c.map, c.name + "/" + to_string(variant));
    }
  }
}

TEST(Regions, DeviceMatchesReferenceOverTheMapDouble) { check_device_against_reference<double>(); }
TEST(Regions, DeviceMatchesReferenceOverTheMapFloat) { check_device_against_reference<float>(); }

// The host reference reads the map: its forces differ from those of the
// base material alone exactly at the vertices of region elements (and are
// bitwise the same elsewhere).
TEST(Regions, RegionsChangeTheOperatorWhereTheyAre) {
  const MapCase& c = map_cases()[0];
  const std::vector<double> x = perturbed(c.mesh, 0.2 * kH, 5);
  const std::vector<double> with = reference::assembled_forces(c.mesh, c.rest, c.map, x),
                            without = reference::assembled_forces(c.mesh, c.rest,
                                                                  uniform_material(c.mesh, c.map.materials[0]), x);
  const int n = nodes_per_element(c.mesh.type);
  std::vector<bool> touched(c.mesh.vertex_count(), false);
  for (size_t e = 0; e < c.mesh.element_count(); ++e)
    if (c.map.element_material[e] != 0)
      for (int a = 0; a < n; ++a) touched[c.mesh.elements[n * e + a]] = true;
  for (size_t v = 0; v < c.mesh.vertex_count(); ++v)
    for (int d = 0; d < 3; ++d) {
      if (touched[v])
        EXPECT_NE(with[3 * v + d], without[3 * v + d]) << "vertex " << v;
      else
        EXPECT_EQ(with[3 * v + d], without[3 * v + d]) << "vertex " << v;
    }
}

// --- the uniform map's kernels are those of before ----------------------------

// A uniform map builds the switches of its material alone (checked above);
// the regions build of a map whose materials are all that material reads
// the same numbers from its table, so every operator is bitwise equal; and
// the run-time-model regions build of a same-model map evaluates the same
// expressions as the specialized one (no contraction): bitwise equal too.
template <typename Real>
void check_bitwise() {
  for (const MapCase& c : map_cases()) {
    if (c.mixed) continue;
    SCOPED_TRACE(c.name);
    const Material& base = c.map.materials[0];
    MaterialMap same_everywhere = c.map;
    for (Material& m : same_everywhere.materials) m = base;
    auto& cl = device_for(precision_of<Real>);
    solver::ElasticModel<Real> uniform(cl, c.mesh, c.rest, uniform_material(c.mesh, base), ProductVariant::cached);
    solver::ElasticModel<Real> table(cl, c.mesh, c.rest, same_everywhere, ProductVariant::cached);
    solver::ElasticModel<Real> specialized(cl, c.mesh, c.rest, c.map, ProductVariant::cached);
    solver::ElasticModel<Real> runtime(cl, c.mesh, c.rest, c.map, ProductVariant::cached,
                                       device::MaterialKernel::runtime);
    EXPECT_EQ(uniform.data().config.defines().find("SNH_REGIONS"), std::string::npos);
    EXPECT_NE(table.data().config.defines().find("-DSNH_REGIONS=1"), std::string::npos);
    EXPECT_NE(runtime.data().config.defines().find("-DSNH_GENERAL_KERNEL=1 -DSNH_REGIONS=1"), std::string::npos);
    const viennacl::vector<Real> xd = upload<Real>(perturbed(c.mesh, 0.2 * kH, 42)),
                                 pd = upload<Real>(random_vector(3 * c.mesh.vertex_count(), 1.0, 43));
    auto outputs = [&](solver::ElasticModel<Real>& m) {
      std::vector<Real> out = {static_cast<Real>(m.energy(xd))};
      viennacl::vector<Real> y(m.dofs());
      m.residual(xd, y);
      const std::vector<Real> r = download_raw(y);
      out.insert(out.end(), r.begin(), r.end());
      for (ProductVariant variant : kVariants) {
        m.products().set_variant(variant);
        m.linearize(xd);
        m.product(pd, y);
        const std::vector<Real> k = download_raw(y);
        out.insert(out.end(), k.begin(), k.end());
      }
      return out;
    };
    EXPECT_EQ(outputs(uniform), outputs(table));
    const std::vector<Real> a = outputs(specialized), b = outputs(runtime);
    EXPECT_EQ(a, b);
    EXPECT_NE(a, outputs(uniform));  // the regions do change the results
  }
}

TEST(Regions, UniformMaterialsInATableAreBitwiseTheUniformKernelsDouble) { check_bitwise<double>(); }
TEST(Regions, UniformMaterialsInATableAreBitwiseTheUniformKernelsFloat) { check_bitwise<float>(); }

// --- the solver -------------------------------------------------------------

// Two halves of Young's moduli E1 (x < L/2) and E2 in series, the ends
// clamped, stretched by a mean strain eps = 1e-3. With nu = 0 the linear
// elastic solution is exact uniaxial strain in each half, eps_i = sigma /
// E_i (no lateral contraction, so the clamps and the interface add
// nothing), and the elements reproduce piecewise-linear displacements
// exactly: the discrete solution has eps1 / eps2 = E2 / E1 up to the
// energy's nonlinearity. With sigma(eps) = E (eps + c eps^2) in both halves,
// eps1 / eps2 = E2 / E1 (1 - c (eps1 - eps2) + ...), |eps1 - eps2| < 2 eps:
// the bound 2e-3 = 2 eps allows |c| up to 1 (measured: 1.5e-4, c ~ 0.1).
// One material would give a ratio of 1.
double series_strain_ratio(const Mesh& mesh, double e1, double e2, std::string* specialization) {
  const double length = extent_x(mesh), strain = 1e-3;
  MaterialRegion right{"E2", {}, snh(e2, 0.0)};
  for (size_t e = 0; e < mesh.element_count(); ++e)
    if (centroid(mesh, e)[0] > 0.5 * length) right.elements.push_back(static_cast<int32_t>(e));
  ConstraintSet left_end{"left", {}, {}, {}}, right_end{"right", {}, {}, {}};
  std::vector<int32_t> middle;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const double x = mesh.positions(v, 0);
    if (std::abs(x) < 1e-9) left_end.vertices.push_back(static_cast<int32_t>(v));
    if (std::abs(x - length) < 1e-9) right_end.vertices.push_back(static_cast<int32_t>(v));
    if (std::abs(x - 0.5 * length) < 1e-9) middle.push_back(static_cast<int32_t>(v));
  }
  right_end.motion = [=](double t) { return RigidTransform::translation_by({t * strain * length, 0.0, 0.0}); };
  SolveOptions options;
  options.absolute_tolerance = 1e-13;
  QuasistaticSolver solver(mesh, make_material_map(mesh, snh(e1, 0.0), {right}), {left_end, right_end}, options);
  const SolveResult r = solver.solve();
  EXPECT_TRUE(r.converged);
  *specialization = r.kernel_specialization;
  double u = 0.0;
  for (int32_t v : middle) u += (r.positions(v, 0) - mesh.positions(v, 0)) / static_cast<double>(middle.size());
  const double eps1 = u / (0.5 * length), eps2 = (strain * length - u) / (0.5 * length);
  return eps1 / eps2;
}

TEST(Regions, BarOfTwoMaterialsInSeriesStrainsInverselyToStiffness) {
  const Mesh hexes = make_box_lattice(8, 2, 2, 0.25);
  for (const Mesh& mesh : {hexes, split_hexes_into_tets(hexes)}) {
    SCOPED_TRACE(to_string(mesh.type));
    for (const auto& [e1, e2] : {std::pair{1.0, 4.0}, std::pair{3.0, 1.0}}) {
      std::string specialization;
      const double ratio = series_strain_ratio(mesh, e1, e2, &specialization);
      EXPECT_NE(specialization.find("-DSNH_REGIONS=1"), std::string::npos) << specialization;
      EXPECT_NEAR(ratio / (e2 / e1), 1.0, 2e-3) << "E1 " << e1 << ", E2 " << e2;
      std::printf("[ measured ] %s E1 = %g, E2 = %g: eps1 / eps2 = %.6f (E2 / E1 = %.6f, relative deviation %.2e)\n",
                  to_string(mesh.type), e1, e2, ratio, e2 / e1, ratio / (e2 / e1) - 1.0);
    }
  }
}

// A region whose material is undefined for J <= 0 (log Neo-Hookean, J0 = 0)
// starting inverted: the error names the region and its material.
TEST(Regions, UndefinedMaterialNamesItsRegion) {
  const Mesh mesh = make_box_lattice(2, 1, 1, 1.0);
  MaterialOptions no_inversion;
  no_inversion.neohookean_j0 = 0.0;
  const Material log_nh = model(MaterialModel::neohookean, 1.0, 0.3, no_inversion);
  SolveOptions options;
  options.initial_positions = mesh.positions;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) options.initial_positions(v, 0) *= -1.0;  // J = -1 everywhere
  QuasistaticSolver solver(mesh, make_material_map(mesh, snh(1.0, 0.3), {{"gel", {1}, log_nh}}), {}, options);
  try {
    solver.solve();
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("material " + log_nh.description() + " of region 'gel'"), std::string::npos) << what;
    EXPECT_NE(what.find("element 1 "), std::string::npos) << what;
  }
}

// --- scene files ------------------------------------------------------------

std::string scene_error(const std::string& text) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "snh_regions_bad_scene.json";
  std::ofstream(path) << text;
  try {
    load_scene(path.string());
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(RegionsSceneFile, SelectsByBoxAndIdsWithTheirOwnMaterials) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "snh_regions_scene.json";
  std::ofstream(path) << R"({"mesh": {"generator": "box", "cells": [4, 1, 1], "size": 1.0},
    "material": {"E": 2.0, "nu": 0.3},
    "regions": [
      {"name": "muscle", "select": {"box": {"min": [2, -1, -1], "max": [4, 2, 2]}}, "material": {"E": 9.0, "nu": 0.3}},
      {"name": "skin", "select": {"ids": [0]},
       "material": {"model": "corotational", "E": 5.0, "nu": 0.2, "alpha": 1.5}}]})";
  const SceneFile f = load_scene(path.string());
  EXPECT_EQ(f.materials.names, (std::vector<std::string>{"base", "muscle", "skin"}));
  EXPECT_EQ(f.materials.element_material, (std::vector<int32_t>{2, 0, 1, 1}));  // centroids x = 0.5 .. 3.5
  EXPECT_EQ(f.materials.materials[0].mu, f.material.mu);
  EXPECT_EQ(f.materials.materials[1].lame().mu, snh(9.0, 0.3).lame().mu);
  EXPECT_EQ(f.materials.materials[2].model, MaterialModel::corotational);
  EXPECT_EQ(f.materials.materials[2].alpha_mu, 1.5);
  EXPECT_EQ(device::material_defines(f.materials), "-DSNH_GENERAL_KERNEL=1 -DSNH_REGIONS=1");
}

TEST(RegionsSceneFile, BadRegionsNameTheKey) {
  const std::string mesh = R"("mesh": {"generator": "box", "cells": [2, 2, 2], "size": 0.5})";
  auto expect = [&](const std::string& regions, const std::string& message) {
    const std::string what = scene_error("{" + mesh + R"(, "regions": )" + regions + "}");
    EXPECT_NE(what.find(message), std::string::npos) << what;
  };
  expect(R"({})", "regions: expected an array");
  expect(R"([{"select": {"ids": [0]}, "material": {}, "colour": 1}])", "regions[0].colour: unknown key");
  expect(R"([{"material": {}}])", "regions[0].select: missing");
  expect(R"([{"select": {"ids": [0]}}])", "regions[0].material: missing");
  expect(R"([{"select": {"box": {"min": [5, 5, 5], "max": [6, 6, 6]}}, "material": {}}])",
         "regions[0].select: selects no element");
  expect(R"([{"select": {"ids": [0]}, "material": {}}, {"select": {"ids": [99]}, "material": {}}])",
         "regions[1].select.ids: element 99 is out of range (the mesh has 8 elements)");
  expect(R"([{"select": {"cells": [0]}, "material": {}}])", "regions[0].select.cells: unknown key");
  expect(R"([{"select": {"ids": [0]}, "material": {"nu": "half"}}])", "regions[0].material.nu: expected a number");
  expect(R"([{"select": {"ids": [0]}, "material": {"nu": 0.5}}])", "regions[0].material: ");
  expect(R"([{"select": {"ids": [0]}, "material": {"model": "jelly"}}])", "regions[0].material: ");
  expect(R"([{"name": "a", "select": {"ids": [0, 1]}, "material": {}},
             {"name": "b", "select": {"ids": [1]}, "material": {}}])",
         "regions: element 1 is in material regions 'a' and 'b'");
}

// The shipped example: a bar of a stiff and a soft half stretched 20%.
// Linear 1D theory gives strain ratio E_stiff / E_soft = 4; the clamped ends
// (nu = 0.45: the clamps hold the lateral contraction, more of the soft
// half's) and the large strain move it, so the check is a band around 4
// that excludes 1 (one material) by far.
TEST(RegionsSceneFile, ShippedSoftStiffBarStretchesTheSoftHalfMore) {
  const SceneFile f = load_scene(kScenes + "soft_stiff_bar.json");
  ASSERT_EQ(f.materials.materials.size(), 2u);
  EXPECT_EQ(std::count(f.materials.element_material.begin(), f.materials.element_material.end(), 1),
            static_cast<long>(f.scene.mesh.element_count() / 2));
  QuasistaticSolver solver(f.scene.mesh, f.materials, f.scene.constraints, f.scene.options);
  const SolveResult r = solver.solve();
  EXPECT_TRUE(r.converged);
  EXPECT_NE(r.kernel_specialization.find("-DSNH_MODEL=0"), std::string::npos) << r.kernel_specialization;
  EXPECT_NE(r.kernel_specialization.find("-DSNH_REGIONS=1"), std::string::npos) << r.kernel_specialization;
  EXPECT_EQ(r.kernel_specialization.find("GENERAL"), std::string::npos) << r.kernel_specialization;
  const Mesh& mesh = f.scene.mesh;
  const double length = extent_x(mesh);
  double u_middle = 0.0, u_end = 0.0;
  int middle = 0, end = 0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const double x = mesh.positions(v, 0), u = r.positions(v, 0) - x;
    if (std::abs(x - 0.5 * length) < 1e-9) {
      u_middle += u;
      ++middle;
    }
    if (std::abs(x - length) < 1e-9) {
      u_end += u;
      ++end;
    }
  }
  u_middle /= middle;
  u_end /= end;
  const double stiff = u_middle, soft = u_end - u_middle;  // the stiff half is x < L/2
  std::printf("[ measured ] soft_stiff_bar: soft / stiff half elongation %.4f (1D linear: 4)\n", soft / stiff);
  EXPECT_GT(soft / stiff, 3.0);
  EXPECT_LT(soft / stiff, 5.0);
}

// `snh-gpu-bench scene --file` with regions: the summary names the regions
// and the kernel switches.
TEST(RegionsSceneFile, SceneCommandReportsRegionsAndSwitches) {
  const std::filesystem::path json_path = std::filesystem::temp_directory_path() / "snh_regions_scene_summary.json";
  std::filesystem::remove(json_path);
  const std::string command = std::string(SNH_BENCH_BINARY) + " scene --file " + kScenes +
                              "soft_stiff_bar.json --json " + json_path.string() + " > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  std::ifstream in(json_path);
  ASSERT_TRUE(in.good());
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_NE(j["kernel_specialization"].get<std::string>().find("-DSNH_REGIONS=1"), std::string::npos);
  ASSERT_EQ(j["regions"].size(), 1u);
  EXPECT_EQ(j["regions"][0]["name"], "stiff_half");
  EXPECT_NEAR(j["regions"][0]["youngs_modulus"].get<double>(), 4.0, 1e-12);
  EXPECT_EQ(j["regions"][0]["elements"].get<int>() * 2, j["elements"].get<int>());
}

}  // namespace
}  // namespace snh::test
