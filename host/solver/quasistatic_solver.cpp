// QuasistaticSolver: load stepping over Newton solves on the device.
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>

#include "device/opencl_context.h"
#include "device/viennacl_binding.h"
#include "fem/rest_state.h"
#include "snh/error.h"
#include "snh/simulation.h"
#include "solver/elastic_model.h"
#include "solver/newton.h"

namespace snh {

RigidTransform RigidTransform::rotation_about(const std::array<double, 3>& axis, double angle,
                                              const std::array<double, 3>& center) {
  const double len = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  if (!(len > 0.0)) throw Error("RigidTransform: rotation axis must be non-zero");
  const double x = axis[0] / len, y = axis[1] / len, z = axis[2] / len;
  const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  RigidTransform r;
  // Rodrigues, column-major.
  r.rotation = {t * x * x + c,     t * x * y + s * z, t * x * z - s * y, t * x * y - s * z, t * y * y + c,
                t * y * z + s * x, t * x * z + s * y, t * y * z - s * x, t * z * z + c};
  r.center = center;
  return r;
}

RigidTransform RigidTransform::translation_by(const std::array<double, 3>& offset) {
  RigidTransform r;
  r.translation = offset;
  return r;
}

std::array<double, 3> RigidTransform::apply(const std::array<double, 3>& p) const {
  const double d[3] = {p[0] - center[0], p[1] - center[1], p[2] - center[2]};
  std::array<double, 3> out;
  for (int i = 0; i < 3; ++i)
    out[i] = rotation[i] * d[0] + rotation[3 + i] * d[1] + rotation[6 + i] * d[2] + center[i] + translation[i];
  return out;
}

DeformationStatistics deformation_statistics(const Mesh& mesh, const std::vector<double>& x) {
  const fem::RestState rest = fem::compute_rest_state(mesh);
  DeformationStatistics s;
  s.min_j = std::numeric_limits<double>::infinity();
  s.max_j = -std::numeric_limits<double>::infinity();
  double volume = 0.0;
  for (size_t e = 0; e < mesh.element_count(); ++e) {
    bool inverted = false;
    for (int q = 0; q < rest.quadrature; ++q) {
      double f[9];
      fem::deformation_gradient(mesh, rest, x.data(), e, q, f);
      const double j = fem::determinant(f);
      s.min_j = std::min(s.min_j, j);
      s.max_j = std::max(s.max_j, j);
      inverted = inverted || !(j > 0.0);
      volume += j * rest.weight(e, q);
    }
    s.inverted_elements += inverted ? 1 : 0;
  }
  s.volume_ratio = volume / rest.rest_volume;
  return s;
}

void validate_solve_inputs(const Mesh& mesh, const std::vector<ConstraintSet>& constraints,
                           const SolveOptions& options) {
  const size_t n = mesh.vertex_count();
  for (const ConstraintSet& c : constraints) {
    if (c.vertices.empty()) throw Error("constraint set '" + c.name + "' selects no vertex");
    for (int32_t v : c.vertices)
      if (v < 0 || static_cast<size_t>(v) >= n)
        throw Error("constraint set '" + c.name + "' refers to vertex " + std::to_string(v) + ", but the mesh has " +
                    std::to_string(n) + " vertices");
  }
  if (!options.initial_positions.empty() && options.initial_positions.size() != 3 * n)
    throw Error("solve options: initial_positions has " + std::to_string(options.initial_positions.size()) +
                " entries, expected " + std::to_string(3 * n));
  for (double v : options.initial_positions)
    if (!std::isfinite(v)) throw Error("solve options: initial_positions has a non-finite entry");
  if (options.load_steps < 1) throw Error("solve options: load_steps must be >= 1");
  if (options.max_newton_iterations < 0 || options.max_cg_iterations < 1)
    throw Error("solve options: iteration limits must be positive");
  if (!(options.absolute_tolerance >= 0.0) || !(options.relative_tolerance >= 0.0))
    throw Error("solve options: tolerances must be >= 0");
}

void apply_constraints(const Mesh& mesh, const std::vector<ConstraintSet>& constraints, double t,
                       std::vector<double>& x) {
  for (const ConstraintSet& c : constraints) {
    if (c.targets) {
      std::vector<double> xyz(3 * c.vertices.size());
      c.targets(t, xyz);
      if (xyz.size() != 3 * c.vertices.size())
        throw Error("constraint set '" + c.name + "': targets callback returned the wrong size");
      for (size_t k = 0; k < c.vertices.size(); ++k)
        for (int d = 0; d < 3; ++d) x[3 * c.vertices[k] + d] = xyz[3 * k + d];
      continue;
    }
    const RigidTransform motion = c.motion ? c.motion(t) : RigidTransform::identity();
    for (int32_t v : c.vertices) {
      const auto p = motion.apply(mesh.vertex(v));
      for (int d = 0; d < 3; ++d) x[3 * v + d] = p[d];
    }
  }
  for (double v : x)
    if (!std::isfinite(v)) throw Error("constraints produced a non-finite target position");
}

struct QuasistaticSolver::Impl {
  Mesh mesh;
  MaterialMap materials;
  std::vector<ConstraintSet> constraints;
  SolveOptions options;
  MeshWarnings mesh_warnings;
  fem::RestState rest;
  device::OpenClContext cl;
  long viennacl_context_id;

  Impl(Mesh m, MaterialMap mat, std::vector<ConstraintSet> c, SolveOptions o)
      : mesh(std::move(m)),
        materials(std::move(mat)),
        constraints(std::move(c)),
        options(std::move(o)),
        mesh_warnings(validate_mesh(mesh)),
        rest(fem::compute_rest_state(mesh)),
        cl(options.device, options.precision),
        viennacl_context_id(device::bind_viennacl(cl)) {
    validate_solve_inputs(mesh, constraints, options);
    validate_material_map(mesh, materials);
  }

  // Double precision state for SolveOptions::fallback_to_double, made on
  // the first float step that fails: a context of its own on the same device
  // (kernels are built per context precision) with its ViennaCL binding.
  struct DoubleFallback {
    std::unique_ptr<device::OpenClContext> cl;
    long viennacl_context_id = 0;
    std::unique_ptr<solver::ElasticModel<double>> model;
    std::unique_ptr<solver::NewtonSolver<double>> newton;
  };

  template <typename Real>
  std::unique_ptr<solver::ElasticModel<Real>> make_model(device::OpenClContext& context, ProductVariant product) {
    auto model = std::make_unique<solver::ElasticModel<Real>>(context, mesh, rest, materials, product);
    std::vector<Real> mask(3 * mesh.vertex_count(), Real(1));
    for (const ConstraintSet& c : constraints)
      for (int32_t v : c.vertices) mask[3 * v] = mask[3 * v + 1] = mask[3 * v + 2] = Real(0);
    model->set_mask(mask);
    model->set_external_force(options.external_force);
    return model;
  }

  // A material undefined for J <= 0 (log Neo-Hookean without inversion
  // handling, as the model or as the lambda part) cannot start a step from
  // an inverted or flat element: name it instead of returning NaN. (Inside a
  // step the line search never accepts a non-finite energy.)
  void require_defined(const std::vector<double>& x, int step) const {
    for (size_t e = 0; e < mesh.element_count(); ++e) {
      const Material& material = materials.of_element(e);
      if (material.defined_for_inversion()) continue;
      const std::string region =
          materials.uniform() ? "" : " of region '" + materials.names[materials.element_material[e]] + "'";
      for (int q = 0; q < rest.quadrature; ++q) {
        double f[9];
        fem::deformation_gradient(mesh, rest, x.data(), e, q, f);
        const double j = fem::determinant(f);
        if (!(j > 0.0))
          throw Error("material " + material.description() + region +
                      " without inversion handling (neohookean J0 = 0) is undefined for J <= 0, and element " +
                      std::to_string(e) + " has J = " + std::to_string(j) + " at quadrature point " +
                      std::to_string(q) + " at the start of load step " + std::to_string(step) +
                      " (use J0 > 0 or another model)");
      }
    }
  }

  // Solves load step s from x in precision Real on the current ViennaCL context.
  template <typename Real>
  static StepResult solve_in(solver::NewtonSolver<Real>& newton, int s, std::vector<double>& x,
                             std::vector<NewtonIteration>& history, std::chrono::steady_clock::time_point start) {
    std::vector<Real> xr(x.begin(), x.end());
    viennacl::vector<Real> xd(x.size());
    viennacl::copy(xr.begin(), xr.end(), xd.begin());
    StepResult step = newton.solve_step(s, xd, history, start);
    viennacl::copy(xd.begin(), xd.end(), xr.begin());
    std::copy(xr.begin(), xr.end(), x.begin());
    return step;
  }

  template <typename Real>
  SolveResult run(const StepCallback& on_step) {
    device::use_viennacl(viennacl_context_id);
    const auto start = std::chrono::steady_clock::now();
    const ProductVariant product = options.product == ProductVariant::automatic
                                       ? default_product_variant(mesh.type, options.precision, cl.info().is_gpu)
                                       : options.product;
    std::unique_ptr<solver::ElasticModel<Real>> model = make_model<Real>(cl, product);
    solver::NewtonSolver<Real> newton(*model, options);
    const bool may_fall_back = options.fallback_to_double && options.precision == Precision::single;
    DoubleFallback fallback;
    bool in_double = false;

    SolveResult result;
    result.device = cl.info();
    result.product = product;
    result.kernel_specialization =
        model->specialization() + " -DSNH_DOUBLE=" + (options.precision == Precision::double_ ? "1" : "0");
    std::vector<double> x = options.initial_positions.empty() ? mesh.positions : options.initial_positions;
    result.converged = true;
    for (int s = 1; s <= options.load_steps; ++s) {
      apply_constraints(mesh, constraints, static_cast<double>(s) / options.load_steps, x);
      require_defined(x, s);
      const std::vector<double> step_start = may_fall_back ? x : std::vector<double>();
      StepResult step;
      if (!in_double) {
        step = solve_in<Real>(newton, s, x, result.history, start);
        step.precision_used = to_string(options.precision);
      }
      if (may_fall_back && (in_double || !step.converged)) {
        if (!in_double && !cl.info().has_fp64) {
          result.warnings.push_back("step " + std::to_string(s) + ": float did not converge (" + step.status +
                                    ") and fallback_to_double was asked, but the device has no fp64");
        } else {
          if (!fallback.cl) {
            fallback.cl = std::make_unique<device::OpenClContext>(options.device, Precision::double_);
            fallback.viennacl_context_id = device::bind_viennacl(*fallback.cl);
            const ProductVariant double_product =
                options.product == ProductVariant::automatic
                    ? default_product_variant(mesh.type, Precision::double_, fallback.cl->info().is_gpu)
                    : options.product;
            fallback.model = make_model<double>(*fallback.cl, double_product);
            fallback.newton = std::make_unique<solver::NewtonSolver<double>>(*fallback.model, options);
          }
          device::use_viennacl(fallback.viennacl_context_id);
          std::string note;
          if (!in_double) {
            std::ostringstream why;
            why << "float " << step.status << " after " << step.newton_iterations << " Newton / " << step.cg_iterations
                << " CG iterations (residual " << step.residual_norm << "); re-solved in double";
            note = why.str();
            x = step_start;
          }
          const size_t first_record = result.history.size();
          StepResult redo = solve_in<double>(*fallback.newton, s, x, result.history, start);
          device::use_viennacl(viennacl_context_id);
          redo.precision_used = "double";
          if (!in_double) {
            if (first_record < result.history.size()) {
              std::string& r = result.history[first_record].recovery;
              r = "float " + step.status + " -> double" + (r.empty() ? "" : "; " + r);
            }
            redo.newton_iterations += step.newton_iterations;
            redo.cg_iterations += step.cg_iterations;
            redo.fallback = note;
            result.warnings.push_back("step " + std::to_string(s) + ": " + note +
                                      (redo.converged ? " (converged)" : " (did not converge: " + redo.status + ")") +
                                      (s < options.load_steps ? "; the remaining steps run in double" : ""));
          } else {
            redo.fallback = "double (after a float failure in an earlier step)";
          }
          in_double = true;
          step = redo;
        }
      }
      result.converged = result.converged && step.converged;
      result.final_residual_norm = step.residual_norm;
      result.steps.push_back(step);
      if (on_step) on_step(s, x);
    }
    result.positions = x;
    if (!mesh_warnings.unused_vertices.empty())
      result.warnings.push_back("mesh: " + std::to_string(mesh_warnings.unused_vertices.size()) +
                                " vertices belong to no element (first: " +
                                std::to_string(mesh_warnings.unused_vertices.front()) + "); they do not move");
    const DeformationStatistics stats = deformation_statistics(mesh, x);
    result.volume_ratio = stats.volume_ratio;
    result.min_j = stats.min_j;
    result.max_j = stats.max_j;
    result.inverted_elements = stats.inverted_elements;
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  }
};

QuasistaticSolver::QuasistaticSolver(Mesh mesh, const Material& material, std::vector<ConstraintSet> constraints,
                                     SolveOptions options)
    // The map is made before Impl's constructor moves the mesh.
    : impl_(std::make_unique<Impl>(std::move(mesh), uniform_material(mesh, material), std::move(constraints),
                                   std::move(options))) {}
QuasistaticSolver::QuasistaticSolver(Mesh mesh, MaterialMap materials, std::vector<ConstraintSet> constraints,
                                     SolveOptions options)
    : impl_(std::make_unique<Impl>(std::move(mesh), std::move(materials), std::move(constraints), std::move(options))) {
}
QuasistaticSolver::~QuasistaticSolver() = default;
QuasistaticSolver::QuasistaticSolver(QuasistaticSolver&&) noexcept = default;
QuasistaticSolver& QuasistaticSolver::operator=(QuasistaticSolver&&) noexcept = default;

SolveResult QuasistaticSolver::solve(const StepCallback& on_step) {
  return impl_->options.precision == Precision::double_ ? impl_->run<double>(on_step) : impl_->run<float>(on_step);
}

const Mesh& QuasistaticSolver::mesh() const { return impl_->mesh; }
const DeviceInfo& QuasistaticSolver::device() const { return impl_->cl.info(); }

}  // namespace snh
