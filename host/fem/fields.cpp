// Element fields, elastic forces and reactions on the host, in double: the
// kinematics of fem/rest_state.h and the kernels' own material math (the
// double instantiation of material/element_reference.h), so what ParaView
// shows is what the device solved.
#include "snh/fields.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "fem/matrix_order.h"
#include "fem/rest_state.h"
#include "material/element_reference.h"
#include "snh/error.h"
#include "snh/simulation.h"

namespace snh {
namespace {

using reference::Mat3;
using reference::MaterialSpec;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Checks shared by the fields and the forces; returns each material's spec.
std::vector<MaterialSpec> checked_specs(const char* who, const Mesh& mesh, const MaterialMap& materials,
                                        const std::vector<double>& x) {
  validate_mesh(mesh);
  const size_t vertices = mesh.vertex_count(), elements = mesh.element_count();
  if (x.size() != 3 * vertices) {
    std::ostringstream s;
    s << who << ": the positions have " << x.size() << " values, but the mesh has " << vertices << " vertices ("
      << 3 * vertices << " values expected)";
    throw Error(s.str());
  }
  for (size_t i = 0; i < x.size(); ++i)
    if (!std::isfinite(x[i])) {
      std::ostringstream s;
      s << who << ": the positions are not finite at vertex " << i / 3 << " (" << x[i] << ")";
      throw Error(s.str());
    }
  if (materials.materials.empty()) throw Error(std::string(who) + ": the material map has no material");
  if (materials.element_material.size() != elements) {
    std::ostringstream s;
    s << who << ": the material map has " << materials.element_material.size() << " element entries, but the mesh has "
      << elements << " elements";
    throw Error(s.str());
  }
  for (size_t e = 0; e < elements; ++e) {
    const int32_t m = materials.element_material[e];
    if (m < 0 || static_cast<size_t>(m) >= materials.materials.size()) {
      std::ostringstream s;
      s << who << ": the material map gives element " << e << " material " << m << ", but it has "
        << materials.materials.size() << " materials";
      throw Error(s.str());
    }
  }
  std::vector<MaterialSpec> specs;
  for (const Material& m : materials.materials) specs.push_back(reference::spec_of(m));
  return specs;
}

// Material models such as log Neo-Hookean without inversion handling have no
// energy at J <= 0: name the element instead of returning NaN.
void require_defined(const char* who, const Material& material, size_t e, int q, double j) {
  if (j > 0.0 || material.defined_for_inversion()) return;
  std::ostringstream s;
  s << who << ": material " << material.description()
    << " is undefined for J <= 0 (neohookean without inversion handling), and element " << e << " has J = " << j
    << " at quadrature point " << q;
  throw Error(s.str());
}

void require_finite(const char* who, const char* what, const double* values, int count, size_t e, int q) {
  for (int i = 0; i < count; ++i)
    if (!std::isfinite(values[i])) {
      std::ostringstream s;
      s << who << ": the " << what << " of element " << e << " at quadrature point " << q << " is not finite ("
        << values[i] << ")";
      throw Error(s.str());
    }
}

Mat3<double> deformation_gradient(const Mesh& mesh, const fem::RestState& rest, const std::vector<double>& x, size_t e,
                                  int q) {
  Mat3<double> f;
  fem::deformation_gradient(mesh, rest, x.data(), e, q, f.data());
  return f;
}

// sqrt(3/2 s:s) with s = sigma - tr(sigma)/3 I (sigma column-major).
double von_mises(const double* sigma) {
  const double mean = (sigma[0] + sigma[4] + sigma[8]) / 3.0;
  double ss = 0.0;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) {
      const double s = sigma[3 * c + r] - (r == c ? mean : 0.0);
      ss += s * s;
    }
  return std::sqrt(1.5 * ss);
}

void check_field_size(const char* name, size_t size, size_t expected) {
  if (size == expected) return;
  std::ostringstream s;
  s << "element_fields_for_vtu: field " << name << " has " << size << " values, " << expected << " expected";
  throw Error(s.str());
}

void check_vector(const std::string& set, const char* what, const std::vector<double>& v, size_t expected) {
  if (v.size() == expected) return;
  std::ostringstream s;
  s << "reaction of constraint set '" << set << "': " << what << " has " << v.size() << " values, " << expected
    << " expected (xyz per vertex)";
  throw Error(s.str());
}

}  // namespace

ElementFields compute_element_fields(const Mesh& mesh, const MaterialMap& materials, const Points& points) {
  const char* who = "compute_element_fields";
  const std::vector<double>& x = points.xyz();
  const std::vector<MaterialSpec> specs = checked_specs(who, mesh, materials, x);
  const fem::RestState rest = fem::compute_rest_state(mesh);
  const size_t elements = mesh.element_count();
  ElementFields out;
  out.deformation_gradient.resize(9 * elements);
  out.j.resize(elements);
  out.pk1.resize(9 * elements);
  out.cauchy.resize(9 * elements);
  out.von_mises.resize(elements);
  out.energy_density.resize(elements);
  out.min_j.resize(elements);
  for (size_t e = 0; e < elements; ++e) {
    const Material& material = materials.of_element(e);
    const MaterialSpec& spec = specs[materials.element_material[e]];
    double volume = 0.0, deformed_volume = 0.0, energy = 0.0, min_j = std::numeric_limits<double>::infinity();
    double f_sum[9] = {}, p_sum[9] = {}, pft_sum[9] = {};
    for (int q = 0; q < rest.quadrature; ++q) {
      const double w = rest.weight(e, q);
      const Mat3<double> f = deformation_gradient(mesh, rest, x, e, q);
      const double j = fem::determinant(f.data());
      require_defined(who, material, e, q, j);
      const double psi = reference::material_energy<double>(f, spec);
      const Mat3<double> p = reference::material_pk1<double>(f, spec);
      require_finite(who, "energy density", &psi, 1, e, q);
      require_finite(who, "first Piola-Kirchhoff stress", p.data(), 9, e, q);
      volume += w;
      deformed_volume += w * j;
      energy += w * psi;
      min_j = std::min(min_j, j);
      for (int i = 0; i < 9; ++i) {
        f_sum[i] += w * f[i];
        p_sum[i] += w * p[i];
      }
      // (P F^T)_rc = sum_k P_rk F_ck.
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
          for (int k = 0; k < 3; ++k) pft_sum[3 * c + r] += w * p[3 * k + r] * f[3 * k + c];
    }
    // The sums are column-major (the element math's vec); the fields row-major.
    double mean[9];
    for (int i = 0; i < 9; ++i) mean[i] = f_sum[i] / volume;
    fem::transpose3(mean, out.deformation_gradient.data() + 9 * e);
    for (int i = 0; i < 9; ++i) mean[i] = p_sum[i] / volume;
    fem::transpose3(mean, out.pk1.data() + 9 * e);
    out.j[e] = deformed_volume / volume;
    out.energy_density[e] = energy / volume;
    out.min_j[e] = min_j;
    double* cauchy = out.cauchy.data() + 9 * e;
    if (min_j > 0.0) {
      double sigma[9];
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
          sigma[3 * c + r] = 0.5 * (pft_sum[3 * c + r] + pft_sum[3 * r + c]) / deformed_volume;
      out.von_mises[e] = von_mises(sigma);
      fem::transpose3(sigma, cauchy);
    } else {
      std::fill(cauchy, cauchy + 9, kNaN);
      out.von_mises[e] = kNaN;
    }
  }
  return out;
}

std::vector<VtuCellField> element_fields_for_vtu(const ElementFields& fields, const MaterialMap& materials) {
  const size_t elements = fields.j.size();
  check_field_size("F", fields.deformation_gradient.size(), 9 * elements);
  check_field_size("P", fields.pk1.size(), 9 * elements);
  check_field_size("cauchy", fields.cauchy.size(), 9 * elements);
  check_field_size("von_mises", fields.von_mises.size(), elements);
  check_field_size("energy_density", fields.energy_density.size(), elements);
  check_field_size("min_J", fields.min_j.size(), elements);
  std::vector<VtuCellField> out;
  // The fields are row-major, VTK's tensor component order.
  out.push_back({"F", fields.deformation_gradient, 9});
  out.push_back({"J", fields.j, 1});
  out.push_back({"min_J", fields.min_j, 1});
  out.push_back({"P", fields.pk1, 9});
  // VTK's ASCII reader stops at a "nan" and drops the array: undefined
  // stresses (J <= 0) go out as 0, their elements marked by min_J <= 0.
  std::vector<double> cauchy = fields.cauchy, von_mises = fields.von_mises;
  for (size_t e = 0; e < elements; ++e)
    if (std::isnan(von_mises[e])) {
      von_mises[e] = 0.0;
      std::fill(cauchy.begin() + 9 * e, cauchy.begin() + 9 * (e + 1), 0.0);
    }
  out.push_back({"cauchy", cauchy, 9});
  out.push_back({"von_mises", von_mises, 1});
  out.push_back({"energy_density", fields.energy_density, 1});
  if (!materials.uniform()) {
    check_field_size("region (the material map's element entries)", materials.element_material.size(), elements);
    out.push_back(
        {"region", std::vector<double>(materials.element_material.begin(), materials.element_material.end()), 1});
  }
  return out;
}

Points elastic_forces(const Mesh& mesh, const MaterialMap& materials, const Points& points) {
  const char* who = "elastic_forces";
  const std::vector<double>& x = points.xyz();
  const std::vector<MaterialSpec> specs = checked_specs(who, mesh, materials, x);
  const fem::RestState rest = fem::compute_rest_state(mesh);
  const int n = rest.nodes;
  Points forces(points.size());
  std::vector<double> element_force(3 * static_cast<size_t>(n));
  // Each element's forces are summed over its points first, then added to
  // its vertices in element order: one fixed order, whatever the mesh.
  for (size_t e = 0; e < mesh.element_count(); ++e) {
    const MaterialSpec& spec = specs[materials.element_material[e]];
    std::fill(element_force.begin(), element_force.end(), 0.0);
    for (int q = 0; q < rest.quadrature; ++q) {
      const Mat3<double> f = deformation_gradient(mesh, rest, x, e, q);
      require_defined(who, materials.of_element(e), e, q, fem::determinant(f.data()));
      const Mat3<double> p = reference::material_pk1<double>(f, spec);
      require_finite(who, "first Piola-Kirchhoff stress", p.data(), 9, e, q);
      const double w = rest.weight(e, q);
      // f_a = -w P dN_a/dX.
      for (int a = 0; a < n; ++a) {
        const double* g = rest.gradient(e, q, a);
        for (int i = 0; i < 3; ++i) element_force[3 * a + i] -= w * (p[i] * g[0] + p[3 + i] * g[1] + p[6 + i] * g[2]);
      }
    }
    const int32_t* nodes = mesh.elements.data() + static_cast<size_t>(n) * e;
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < 3; ++i) forces(static_cast<size_t>(nodes[a]), i) += element_force[3 * a + i];
  }
  return forces;
}

Reaction reaction(const std::string& name, const std::vector<int32_t>& vertices, const std::array<bool, 3>& components,
                  const Points& x, const Points& elastic_force, const Points& external_force,
                  const std::array<double, 3>& about) {
  if (x.xyz().size() % 3 != 0)
    throw Error("reaction of constraint set '" + name + "': x has " + std::to_string(x.xyz().size()) +
                " values, not xyz per vertex");
  const size_t count = x.size();
  check_vector(name, "elastic_force", elastic_force.xyz(), x.xyz().size());
  if (!external_force.empty()) check_vector(name, "external_force", external_force.xyz(), x.xyz().size());
  Reaction r;
  r.name = name;
  r.about = about;
  std::vector<bool> seen(count, false);
  for (int32_t v : vertices) {
    if (v < 0 || static_cast<size_t>(v) >= count) {
      std::ostringstream s;
      s << "reaction of constraint set '" << name << "': vertex " << v << " is out of range (" << count << " vertices)";
      throw Error(s.str());
    }
    if (seen[v]) continue;
    seen[v] = true;
    double rv[3], arm[3];
    const size_t p = static_cast<size_t>(v);
    for (int i = 0; i < 3; ++i) {
      rv[i] = components[i] ? -(elastic_force(p, i) + (external_force.empty() ? 0.0 : external_force(p, i))) : 0.0;
      arm[i] = x(p, i) - about[i];
      r.force[i] += rv[i];
    }
    r.torque[0] += arm[1] * rv[2] - arm[2] * rv[1];
    r.torque[1] += arm[2] * rv[0] - arm[0] * rv[2];
    r.torque[2] += arm[0] * rv[1] - arm[1] * rv[0];
  }
  return r;
}

std::array<double, 3> centroid(const std::vector<int32_t>& vertices, const Points& x) {
  const size_t count = x.size();
  std::vector<bool> seen(count, false);
  std::array<double, 3> sum{0, 0, 0};
  size_t distinct = 0;
  for (int32_t v : vertices) {
    if (v < 0 || static_cast<size_t>(v) >= count)
      throw Error("centroid: vertex " + std::to_string(v) + " is out of range (" + std::to_string(count) +
                  " vertices)");
    if (seen[v]) continue;
    seen[v] = true;
    ++distinct;
    for (int i = 0; i < 3; ++i) sum[i] += x(static_cast<size_t>(v), i);
  }
  if (distinct == 0) throw Error("centroid: no vertex given");
  for (double& s : sum) s /= static_cast<double>(distinct);
  return sum;
}

std::vector<Reaction> constraint_reactions(const Mesh& mesh, const MaterialMap& materials,
                                           const std::vector<ConstraintSet>& constraints, const Points& x,
                                           const Points& external_force) {
  const Points forces = elastic_forces(mesh, materials, x);
  std::vector<Reaction> out;
  for (const ConstraintSet& c : constraints) {
    if (c.vertices.empty()) throw Error("reaction of constraint set '" + c.name + "': it selects no vertex");
    for (int32_t v : c.vertices)
      if (v < 0 || static_cast<size_t>(v) >= mesh.vertex_count())
        throw Error("reaction of constraint set '" + c.name + "': vertex " + std::to_string(v) + " is out of range (" +
                    std::to_string(mesh.vertex_count()) + " vertices)");
    out.push_back(reaction(c.name, c.vertices, c.components, x, forces, external_force, centroid(c.vertices, x)));
  }
  return out;
}

}  // namespace snh
