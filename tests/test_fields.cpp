// Element fields, elastic forces and reactions: exact kinematics under affine
// motions, the material's own stress, forces against the assembled reference
// and the energy's finite differences, and reactions that balance the load
// of a solved body.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>

#include "fem/matrix_order.h"
#include "fem/rest_state.h"
#include "material/element_reference.h"
#include "reference/fem_reference.h"
#include "snh/error.h"
#include "snh/fields.h"
#include "snh/io.h"
#include "snh/simulation.h"
#include "support/errors.h"
#include "support/lattices.h"
#include "vtu_test_support.h"

namespace snh::test {
namespace {

namespace fs = std::filesystem;
using Mat = std::array<double, 9>;  // column-major 3x3, the element math's vec (ElementFields are row-major)
using Vec = std::array<double, 3>;

double max_abs(const double* a, size_t n) {
  double m = 0.0;
  for (size_t i = 0; i < n; ++i) m = std::max(m, std::abs(a[i]));
  return m;
}

double max_diff(const double* a, const double* b, size_t n) {
  double m = 0.0;
  for (size_t i = 0; i < n; ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Vec& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }
Vec sum(const Vec& a, const Vec& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec difference(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

Mesh jittered_lattice(int n) { return jittered_unit_cube(n, 11); }

struct NamedMesh {
  std::string name;
  Mesh mesh;
};

std::vector<NamedMesh> test_meshes() {
  return {{"hex lattice", make_box_lattice(2, 2, 2, 0.5)},
          {"jittered hex", jittered_lattice(3)},
          {"tet box", make_tet_box(2, 2, 2, 0.5)},
          {"jittered tet", split_hexes_into_tets(jittered_lattice(2))}};
}

// A large affine motion with shear and rotation; det A = 1.1135.
const Mat kA{1.3, 0.2, -0.1, 0.15, 0.8, 0.25, -0.2, 0.1, 1.1};
const Vec kB{0.1, -0.2, 0.3};

Points affine(const Mesh& mesh, const Mat& a, const Vec& b) {
  Points x(mesh.vertex_count());
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const auto p = mesh.vertex(v);
    for (int i = 0; i < 3; ++i) x(v, i) = a[i] * p[0] + a[3 + i] * p[1] + a[6 + i] * p[2] + b[i];
  }
  return x;
}

// A smooth non-affine deformation (stretch, bend and twist), J > 0.
Points bent(const Mesh& mesh) {
  Points x(mesh.vertex_count());
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const auto p = mesh.vertex(v);
    x(v, 0) = 1.1 * p[0] + 0.08 * std::sin(2.0 * p[1]) + 0.05 * p[2] * p[2];
    x(v, 1) = p[1] + 0.1 * p[0] * p[2] - 0.04 * std::cos(1.5 * p[0]);
    x(v, 2) = 0.93 * p[2] + 0.06 * std::sin(1.7 * p[0] + p[1]);
  }
  return x;
}

// Half of the elements (the even ones) in a Fung region: per-element
// materials must reach the right elements.
MaterialMap two_materials(const Mesh& mesh) {
  std::vector<int32_t> even;
  for (size_t e = 0; e < mesh.element_count(); e += 2) even.push_back(static_cast<int32_t>(e));
  return make_material_map(mesh, StableNeoHookean::from_youngs_modulus(1.0, 0.45, Barrier::on),
                           {{"fung", even, Material::from_youngs_modulus(MaterialModel::fung, 2.0, 0.4)}});
}

// Element e's row-major tensor of an ElementFields field, column-major.
Mat element_matrix(const std::vector<double>& field, size_t e) {
  Mat m;
  for (int i = 0; i < 9; ++i) m[i] = field[9 * e + fem::transposed_index(i)];
  return m;
}

TEST(Fields, AffineMotionGivesTheMotionsGradientAndTheMaterialsStress) {
  const double det_a = fem::determinant(kA.data());
  for (const NamedMesh& m : test_meshes()) {
    SCOPED_TRACE(m.name);
    const MaterialMap materials = two_materials(m.mesh);
    const ElementFields f = compute_element_fields(m.mesh, materials, affine(m.mesh, kA, kB));
    ASSERT_EQ(f.j.size(), m.mesh.element_count());
    for (size_t e = 0; e < m.mesh.element_count(); ++e) {
      SCOPED_TRACE("element " + std::to_string(e));
      const reference::MaterialSpec spec = reference::spec_of(materials.of_element(e));
      const Mat fe = element_matrix(f.deformation_gradient, e), pe = element_matrix(f.pk1, e);
      // F = sum_a x_a (dN_a/dX)^T reproduces A exactly in exact arithmetic
      // (isoparametric elements reproduce linear fields); up to 8 products of
      // |x| <= 2 and |dN/dX| <= ~6 round at ~1e-15, so 1e-13 is rounding.
      EXPECT_LT(max_diff(fe.data(), kA.data(), 9), 1e-13);
      EXPECT_NEAR(f.j[e], det_a, 1e-13);
      EXPECT_NEAR(f.min_j[e], det_a, 1e-13);
      // The material at F vs at A: |dP/dF| = O(lambda + mu) = O(10) times
      // the 1e-13 difference in F.
      const Mat p_ref = reference::material_pk1<double>(kA, spec);
      EXPECT_LT(max_diff(pe.data(), p_ref.data(), 9), 1e-11 * std::max(1.0, max_abs(p_ref.data(), 9)));
      const double psi = reference::material_energy<double>(kA, spec);
      EXPECT_NEAR(f.energy_density[e], psi, 1e-12 * std::max(1.0, std::abs(psi)));
      // sigma = P F^T / J from the element's own P, F, J, unsymmetrized: it
      // must already be symmetric (isotropic energy) and equal the output.
      Mat sigma{};
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
          for (int k = 0; k < 3; ++k) sigma[3 * c + r] += pe[3 * k + r] * fe[3 * k + c] / f.j[e];
      const double scale = max_abs(sigma.data(), 9);
      EXPECT_GT(scale, 1e-3);  // a real stress, not a trivially passing zero
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < c; ++r) EXPECT_NEAR(sigma[3 * c + r], sigma[3 * r + c], 1e-12 * scale);
      EXPECT_LT(max_diff(sigma.data(), element_matrix(f.cauchy, e).data(), 9), 1e-12 * scale);
    }
  }
}

// The public tensors are row-major, m[3 row + col]: under the simple shear
// x' = x + s y, F(0, 1) = s is entry 1 of the element's nine values, and P
// is the row-major transpose of the element math's column-major vec(P).
TEST(Fields, TensorsAreRowMajor) {
  const double s = 0.5;
  const Mesh mesh = make_box_lattice(1, 1, 1, 1.0);
  const StableNeoHookean snh = StableNeoHookean::from_youngs_modulus(1.0, 0.3);
  const Mat shear{1, 0, 0, s, 1, 0, 0, 0, 1};  // column-major: F(0, 1) = s
  const ElementFields f = compute_element_fields(mesh, uniform_material(mesh, snh), affine(mesh, shear, {0, 0, 0}));
  const std::array<double, 9> expected{1, s, 0, 0, 1, 0, 0, 0, 1};
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(f.deformation_gradient[i], expected[i], 1e-14) << i;
  const Mat p = reference::material_pk1<double>(shear, reference::spec_of(snh));
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(f.pk1[3 * r + c], p[3 * c + r], 1e-13) << r << c;
}

// SNH's P = mu_t F + lambda (J - alpha) cof F with mu_t = mu (1 - 1/(I_C + 1))
// (barrier) or mu (none), so sigma = (mu_t F F^T + lambda (J - alpha) J I) / J:
// the lambda part is a pressure and the deviator is mu_t dev(F F^T) / J.
double snh_von_mises(const StableNeoHookean& m, const Mat& f) {
  double b[9] = {}, ic = 0.0;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k) b[3 * c + r] += f[3 * k + r] * f[3 * k + c];
  for (double v : f) ic += v * v;
  const double mu_t = m.barrier ? m.mu * (1.0 - 1.0 / (ic + 1.0)) : m.mu;
  const double j = fem::determinant(f.data()), tr = b[0] + b[4] + b[8];
  double bb = 0.0;
  for (double v : b) bb += v * v;
  return mu_t / j * std::sqrt(1.5 * (bb - tr * tr / 3.0));
}

TEST(Fields, VonMisesIsZeroUnderDilationAndAnalyticUnderStretchAndShear) {
  for (const NamedMesh& m :
       {NamedMesh{"hex", make_box_lattice(1, 1, 1, 1.0)}, NamedMesh{"tet", make_tet_box(1, 1, 1, 1.0)}})
    for (Barrier barrier : {Barrier::on, Barrier::off}) {
      SCOPED_TRACE(m.name + (barrier == Barrier::on ? " barrier" : " no barrier"));
      const StableNeoHookean snh = StableNeoHookean::from_youngs_modulus(1.0, 0.45, barrier);
      const MaterialMap materials = uniform_material(m.mesh, snh);
      // F = 1.2 I: a pure pressure, no deviator (1e-12 of the pressure:
      // rounding in P's SVD path).
      ElementFields f =
          compute_element_fields(m.mesh, materials, affine(m.mesh, {1.2, 0, 0, 0, 1.2, 0, 0, 0, 1.2}, kB));
      for (size_t e = 0; e < m.mesh.element_count(); ++e) {
        EXPECT_GT(std::abs(f.cauchy[9 * e]), 0.1);
        EXPECT_LT(f.von_mises[e], 1e-12 * std::abs(f.cauchy[9 * e]));
      }
      // Uniaxial stretch with lateral contraction, and simple shear.
      for (const Mat& a : {Mat{1.4, 0, 0, 0, 0.9, 0, 0, 0, 0.9}, Mat{1, 0, 0, 0.6, 1, 0, 0, 0, 1}}) {
        f = compute_element_fields(m.mesh, materials, affine(m.mesh, a, kB));
        const double expected = snh_von_mises(snh, a);
        EXPECT_GT(expected, 0.05);
        for (size_t e = 0; e < m.mesh.element_count(); ++e) EXPECT_NEAR(f.von_mises[e], expected, 1e-12 * expected);
      }
    }
}

TEST(Fields, ElasticForcesMatchTheAssembledReference) {
  const StableNeoHookean snh = StableNeoHookean::from_youngs_modulus(1.0, 0.45);
  for (const NamedMesh& m : test_meshes()) {
    SCOPED_TRACE(m.name);
    const Points x = bent(m.mesh);
    const Points forces = elastic_forces(m.mesh, uniform_material(m.mesh, snh), x);
    const std::vector<double> expected =
        reference::assembled_forces(m.mesh, fem::compute_rest_state(m.mesh), snh, x.xyz());
    ASSERT_EQ(forces.xyz().size(), expected.size());
    // The same terms summed in another order (per element first): rounding
    // of a sum of at most 64 terms, each at most the largest net force here.
    const double scale = max_abs(expected.data(), expected.size());
    EXPECT_GT(scale, 1e-3);
    EXPECT_LT(max_diff(forces.data(), expected.data(), forces.xyz().size()), 1e-13 * scale);
    // Deterministic: the same bits every time.
    EXPECT_EQ(elastic_forces(m.mesh, uniform_material(m.mesh, snh), x), forces);
  }
}

TEST(Fields, ElasticForcesAreMinusTheEnergyGradient) {
  for (const NamedMesh& m : test_meshes()) {
    SCOPED_TRACE(m.name);
    const MaterialMap materials = two_materials(m.mesh);
    const fem::RestState rest = fem::compute_rest_state(m.mesh);
    // E = sum_e energy_density_e * rest volume_e: the energy the fields report.
    auto energy = [&](const Points& x) {
      const ElementFields f = compute_element_fields(m.mesh, materials, x);
      double total = 0.0;
      for (size_t e = 0; e < m.mesh.element_count(); ++e) {
        double volume = 0.0;
        for (int q = 0; q < rest.quadrature; ++q) volume += rest.weight(e, q);
        total += f.energy_density[e] * volume;
      }
      return total;
    };
    Points x = bent(m.mesh);
    const Points forces = elastic_forces(m.mesh, materials, x);
    const double scale = max_abs(forces.data(), forces.xyz().size());
    ASSERT_GT(scale, 1e-3);
    for (size_t dof = 0; dof < x.xyz().size(); dof += 5) {
      // Central differences, best over steps 1e-3 .. 1e-8 (truncation h^2
      // against rounding eps E / h); relative to the largest force.
      double best = 1e300;
      for (double h = 1e-3; h >= 1e-8; h /= 10) {
        const double x0 = x.data()[dof];
        x.data()[dof] = x0 + h;
        const double plus = energy(x);
        x.data()[dof] = x0 - h;
        const double minus = energy(x);
        x.data()[dof] = x0;
        best = std::min(best, std::abs((plus - minus) / (2 * h) + forces.data()[dof]) / scale);
      }
      EXPECT_LT(best, 1e-7) << "dof " << dof;
    }
  }
}

TEST(Fields, InvertedElementsHaveFiniteEnergyAndStressButNoCauchy) {
  const Mesh mesh = make_tet_box(1, 1, 1, 1.0);
  // A reflection through z = 0: every element has J = -1.
  const Points x = affine(mesh, {1, 0, 0, 0, 1, 0, 0, 0, -1}, {0, 0, 0});
  const MaterialMap materials = uniform_material(mesh, StableNeoHookean::from_youngs_modulus(1.0, 0.3, Barrier::on));
  const ElementFields f = compute_element_fields(mesh, materials, x);
  for (size_t e = 0; e < mesh.element_count(); ++e) {
    EXPECT_NEAR(f.j[e], -1.0, 1e-14);
    EXPECT_NEAR(f.min_j[e], -1.0, 1e-14);
    EXPECT_TRUE(std::isfinite(f.energy_density[e]));
    EXPECT_GT(f.energy_density[e], 0.0);  // SNH is defined through inversion, and costly there
    for (int i = 0; i < 9; ++i) {
      EXPECT_TRUE(std::isfinite(f.pk1[9 * e + i]));
      EXPECT_TRUE(std::isnan(f.cauchy[9 * e + i]));
    }
    EXPECT_TRUE(std::isnan(f.von_mises[e]));
  }
  const Points inverted_forces = elastic_forces(mesh, materials, x);
  for (double v : inverted_forces.xyz()) EXPECT_TRUE(std::isfinite(v));
  // In the .vtu the undefined stresses are 0 (VTK's ASCII reader cannot
  // read "nan"), marked by min_J.
  for (const VtuCellField& field : element_fields_for_vtu(f, materials))
    for (double v : field.values) EXPECT_TRUE(std::isfinite(v)) << field.name;

  // A material undefined for J <= 0 names the element instead of a NaN.
  const Material log_nh = Material::from_youngs_modulus(MaterialModel::neohookean, 1.0, 0.3, [] {
    MaterialOptions o;
    o.neohookean_j0 = 0.0;
    return o;
  }());
  for (const std::string& message : {error_of([&] { compute_element_fields(mesh, uniform_material(mesh, log_nh), x); }),
                                     error_of([&] { elastic_forces(mesh, uniform_material(mesh, log_nh), x); })}) {
    EXPECT_TRUE(contains(message, "element 0 ")) << message;
    EXPECT_TRUE(contains(message, "J <= 0")) << message;
  }
}

TEST(Fields, BadInputsNameTheInput) {
  const Mesh mesh = make_box_lattice(2, 1, 1, 0.5);
  const MaterialMap materials = uniform_material(mesh, StableNeoHookean::from_youngs_modulus(1.0, 0.3));
  const Points x = mesh.positions;
  std::string message = error_of([&] { compute_element_fields(mesh, materials, Points(2)); });
  EXPECT_TRUE(contains(message, "positions have 6 values")) << message;
  message = error_of([&] { elastic_forces(mesh, materials, Points(x.size() + 1)); });
  EXPECT_TRUE(contains(message, "elastic_forces")) << message;
  EXPECT_TRUE(contains(message, "positions")) << message;
  Points nan_x = x;
  nan_x(2, 1) = std::nan("");
  message = error_of([&] { compute_element_fields(mesh, materials, nan_x); });
  EXPECT_TRUE(contains(message, "not finite at vertex 2")) << message;

  MaterialMap short_map = materials;
  short_map.element_material.pop_back();
  message = error_of([&] { compute_element_fields(mesh, short_map, x); });
  EXPECT_TRUE(contains(message, "material map has 1 element entries")) << message;
  MaterialMap bad_index = materials;
  bad_index.element_material[1] = 3;
  message = error_of([&] { elastic_forces(mesh, bad_index, x); });
  EXPECT_TRUE(contains(message, "element 1 material 3")) << message;

  ElementFields fields = compute_element_fields(mesh, materials, x);
  fields.pk1.pop_back();
  message = error_of([&] { element_fields_for_vtu(fields, materials); });
  EXPECT_TRUE(contains(message, "field P")) << message;

  const Points forces = elastic_forces(mesh, materials, x);
  message = error_of([&] { reaction("wall", {0, 1}, {true, true, true}, x, Points(1), {}, {0, 0, 0}); });
  EXPECT_TRUE(contains(message, "'wall'")) << message;
  EXPECT_TRUE(contains(message, "elastic_force has 3 values")) << message;
  message = error_of([&] { reaction("wall", {0}, {true, true, true}, x, forces, Points(2), {0, 0, 0}); });
  EXPECT_TRUE(contains(message, "external_force has 6 values")) << message;
  message = error_of([&] { reaction("wall", {0, 99}, {true, true, true}, x, forces, {}, {0, 0, 0}); });
  EXPECT_TRUE(contains(message, "vertex 99")) << message;
  message = error_of([&] { constraint_reactions(mesh, materials, {{"hand", {}, {}, {}}}, x, {}); });
  EXPECT_TRUE(contains(message, "'hand'")) << message;
}

TEST(Fields, ReactionCountsPrescribedComponentsAndEachVertexOnce) {
  // Hand-made forces: reaction = -(elastic + external) on the prescribed
  // components only; torque = sum (x - about) x reaction.
  const Points x = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}};
  const Points elastic = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}};
  const Points external = {{0, 0, -1}, {0, 0, -1}, {0, 0, -1}};
  const Reaction r = reaction("s", {1, 2, 1}, {true, false, true}, x, elastic, external, {0, 0, 0});
  EXPECT_EQ(r.name, "s");
  EXPECT_EQ(r.force, (Vec{-11, 0, -13}));
  // (1,0,0) x (-4,0,-5) + (0,2,0) x (-7,0,-8) = (0,5,0) + (-16,0,14)
  EXPECT_EQ(r.torque, (Vec{-16, 5, 14}));
  EXPECT_EQ(centroid({1, 2, 2}, x), (Vec{0.5, 1, 0}));
}

// Vertices of `mesh` with coordinate `axis` at `value`.
std::vector<int32_t> plane(const Mesh& mesh, int axis, double value) {
  std::vector<int32_t> out;
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    if (std::abs(mesh.positions(v, axis) - value) < 1e-9) out.push_back(static_cast<int32_t>(v));
  return out;
}

// How far the free DOFs' forces may leave the reactions unbalanced: their
// sum is at most sqrt(free DOFs) times the residual norm (Cauchy-Schwarz),
// plus the host-vs-device rounding of the forces (1e-12 of the load).
double balance_bound(const Mesh& mesh, size_t constrained_vertices, double residual, double load) {
  return std::sqrt(3.0 * double(mesh.vertex_count() - constrained_vertices)) * residual + 1e-12 * load;
}

TEST(Fields, ReactionsOfAPulledAndTwistedBarBalance) {
  for (const NamedMesh& m :
       {NamedMesh{"hex", make_box_lattice(4, 2, 2, 0.25)}, NamedMesh{"tet", make_tet_box(4, 2, 2, 0.25)}}) {
    SCOPED_TRACE(m.name);
    const Mesh& mesh = m.mesh;  // 1 x 0.5 x 0.5
    const ConstraintSet fixed{"fixed", plane(mesh, 0, 0.0), {}, {}};
    ConstraintSet end{"end", plane(mesh, 0, 1.0), {}, {}};
    end.motion = [](double t) {
      RigidTransform motion = RigidTransform::rotation_about({1, 0, 0}, 0.5 * t, {1.0, 0.25, 0.25});
      motion.translation = {0.15 * t, 0, 0};
      return motion;
    };
    SolveOptions options;
    options.load_steps = 2;
    options.absolute_tolerance = 1e-10;
    const StableNeoHookean material = StableNeoHookean::from_youngs_modulus(1.0, 0.45);
    QuasistaticSolver solver(mesh, material, {fixed, end}, options);
    const SolveResult r = solver.solve();
    ASSERT_TRUE(r.converged);
    const std::vector<Reaction> reactions =
        constraint_reactions(mesh, uniform_material(mesh, material), {fixed, end}, r.positions, {});
    ASSERT_EQ(reactions.size(), 2u);
    EXPECT_EQ(reactions[0].name, "fixed");
    const Reaction &a = reactions[0], &b = reactions[1];
    // The torque is about each set's current centroid; the end's is its rest
    // centroid carried by the motion.
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(b.about[i], (Vec{1.15, 0.25, 0.25})[i], 1e-12);
    EXPECT_NEAR(a.about[0], 0.0, 1e-12);

    const double load = norm(b.force);
    const double bound = balance_bound(mesh, fixed.vertices.size() + end.vertices.size(), r.final_residual_norm, load);
    // A real pull and twist: the end is held out (+x) and turned (+x torque).
    EXPECT_GT(b.force[0], 1e4 * bound);
    EXPECT_GT(b.torque[0], 1e3 * bound);
    EXPECT_LT(norm(sum(a.force, b.force)), bound);
    // Torques about one common point p: T_p = T_about + (about - p) x F.
    const Vec p{0.5, 0.25, 0.25};
    const Vec ta = sum(a.torque, cross(difference(a.about, p), a.force));
    const Vec tb = sum(b.torque, cross(difference(b.about, p), b.force));
    double arm = 0.0;  // the largest |x - p|
    for (size_t v = 0; v < mesh.vertex_count(); ++v)
      arm = std::max(arm, norm(difference({r.positions(v, 0), r.positions(v, 1), r.positions(v, 2)}, p)));
    EXPECT_LT(norm(sum(ta, tb)), arm * bound);
    // The same with the torque taken about p directly.
    const Points forces = elastic_forces(mesh, uniform_material(mesh, material), r.positions);
    const Reaction ap = reaction("fixed", fixed.vertices, {true, true, true}, r.positions, forces, {}, p);
    const Reaction bp = reaction("end", end.vertices, {true, true, true}, r.positions, forces, {}, p);
    EXPECT_LT(norm(sum(ap.torque, bp.torque)), arm * bound);
    EXPECT_LT(norm(difference(ap.torque, ta)), 1e-12 * arm * load);
  }
}

TEST(Fields, BaseReactionOfABlockUnderGravityIsMinusItsWeight) {
  const double h = 0.5;
  const Mesh mesh = make_box_lattice(2, 2, 2, h);
  const ConstraintSet base{"base", plane(mesh, 2, 0.0), {}, {}};
  // Lumped body force (density * g, with a sideways part so that the base
  // must also carry a moment): an eighth of each hex's weight per node.
  const Vec g{0.02, 0.0, -0.05};
  SolveOptions options;
  options.external_force = Points(mesh.vertex_count());
  for (size_t e = 0; e < mesh.element_count(); ++e)
    for (int a = 0; a < 8; ++a)
      for (int d = 0; d < 3; ++d) options.external_force(mesh.elements[8 * e + a], d) += g[d] * h * h * h / 8;
  options.absolute_tolerance = 1e-12;
  const StableNeoHookean material = StableNeoHookean::from_youngs_modulus(1.0, 0.3);
  QuasistaticSolver solver(mesh, material, {base}, options);
  const SolveResult r = solver.solve();
  ASSERT_TRUE(r.converged);
  double sag = 0.0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) sag = std::min(sag, r.positions(v, 2) - mesh.positions(v, 2));
  EXPECT_LT(sag, -1e-3);

  const std::vector<Reaction> reactions =
      constraint_reactions(mesh, uniform_material(mesh, material), {base}, r.positions, options.external_force);
  ASSERT_EQ(reactions.size(), 1u);
  const Reaction& rb = reactions[0];
  const Vec weight = g;  // unit cube: weight = g * volume
  const double bound = balance_bound(mesh, base.vertices.size(), r.final_residual_norm, norm(weight));
  EXPECT_LT(norm(sum(rb.force, weight)), bound) << rb.force[0] << " " << rb.force[1] << " " << rb.force[2];
  // The moment of the load about the base's centroid is what the base holds.
  Vec moment{0, 0, 0};
  double arm = 0.0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec lever = difference({r.positions(v, 0), r.positions(v, 1), r.positions(v, 2)}, rb.about);
    moment =
        sum(moment,
            cross(lever, {options.external_force(v, 0), options.external_force(v, 1), options.external_force(v, 2)}));
    arm = std::max(arm, norm(lever));
  }
  EXPECT_GT(norm(moment), 1e3 * arm * bound);
  EXPECT_LT(norm(sum(rb.torque, moment)), arm * bound);
}

// The .vtu's cell tensors: NumberOfComponents 9, row-major, read back bit
// for bit from the XML and by meshio as ParaView-style (cells, 9) arrays.
std::string run_command(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return "";
  std::string text;
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) text.append(buffer, n);
  pclose(pipe);
  return text;
}

TEST(FieldsVtu, TensorCellDataReadsBackInVtkOrder) {
  const fs::path dir = fs::temp_directory_path() / "snh_fields_vtu";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const Mesh mesh = jittered_lattice(2);
  const MaterialMap materials = two_materials(mesh);
  const ElementFields f = compute_element_fields(mesh, materials, bent(mesh));
  const std::string path = (dir / "fields.vtu").string();
  write_vtu(path, mesh, bent(mesh), {}, element_fields_for_vtu(f, materials));
  const std::string vtu = read_text(path);
  for (const char* tensor : {"F", "P", "cauchy"})
    EXPECT_TRUE(contains(vtu, "Name=\"" + std::string(tensor) + "\" NumberOfComponents=\"9\"")) << tensor;
  for (const char* scalar : {"J", "min_J", "von_mises", "energy_density", "region"})
    EXPECT_TRUE(contains(vtu, "Name=\"" + std::string(scalar) + "\" format=\"ascii\"")) << scalar;
  // Row-major like ElementFields: component 3 r + c of element e is F_rc.
  const std::vector<double> fv = read_array(vtu, "F");
  ASSERT_EQ(fv.size(), 9 * mesh.element_count());
  EXPECT_EQ(fv, f.deformation_gradient);
  EXPECT_EQ(read_array(vtu, "J"), f.j);
  EXPECT_EQ(read_array(vtu, "region"), (std::vector<double>{1, 0, 1, 0, 1, 0, 1, 0}));

  // meshio (scripts/setup.sh installs python3-meshio) as a second reader.
  const std::string script =
      "import meshio, sys\n"
      "m = meshio.read(sys.argv[1])\n"
      "for k in sorted(m.cell_data): print(k, *m.cell_data[k][0].shape)\n"
      "print('F0', *[repr(float(v)) for v in m.cell_data['F'][0][0]])\n";
  std::ofstream(dir / "read.py") << script;
  const std::string out = run_command("/usr/bin/python3 " + (dir / "read.py").string() + " " + path + " 2>&1");
  EXPECT_TRUE(contains(out, "F 8 9\n")) << out;
  EXPECT_TRUE(contains(out, "cauchy 8 9\n")) << out;
  EXPECT_TRUE(contains(out, "von_mises 8\n")) << out;
  ASSERT_NE(out.find("F0"), std::string::npos) << out;
  std::istringstream lines(out.substr(out.find("F0")));
  std::string tag;
  lines >> tag;
  for (int i = 0; i < 9; ++i) {
    double v = 0.0;
    lines >> v;
    EXPECT_EQ(v, fv[i]) << out;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace snh::test
