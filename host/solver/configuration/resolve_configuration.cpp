// resolve_configuration (snh/configuration.h): every automatic choice of the
// solver made in one place, each recorded with its reason. The rules are
// the measured ones of docs/performance.md; Simulation and the engines it
// builds read the result only.
#include <sstream>

#include "snh/configuration.h"
#include "snh/error.h"
#include "solver/configuration/measured_thresholds.h"
#include "solver/contact/barrier_contact.h"
#include "solver/multigrid/lattice_hierarchy.h"
#include "solver/multigrid/multigrid.h"
#include "solver/newton/stopping_test.h"

namespace snh {

namespace {

std::string number(double value) {
  std::ostringstream s;
  s.precision(6);
  s << value;
  return s.str();
}

std::string count(size_t value) {
  std::string digits = std::to_string(value), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

const char* on_off(bool on) { return on ? "on" : "off"; }

const char* broad_phase_name(SelfBroadPhase b) { return b == SelfBroadPhase::device ? "device" : "host"; }

// The resolution under way: the options being filled in and the settings
// recorded so far.
struct Resolution {
  const SolveOptions& given;
  const Mesh& mesh;
  const MaterialMap& materials;
  const DeviceInfo& device;
  // The model's terms these options give (penalty or barrier self-contact,
  // friction, per-vertex terms), as the engines build them.
  solver::ModelTerms terms;
  ResolvedConfiguration out;

  void add(const std::string& name, const std::string& value, const std::string& reason) {
    out.settings.push_back({name, value, reason});
  }
  // A setting that is never automatic: given or the default.
  template <typename T>
  void add_plain(const std::string& name, const T& value, const T& fallback, const std::string& text) {
    add(name, text, value == fallback ? "default" : "given");
  }
  size_t dofs() const { return 3 * mesh.vertex_count(); }
};

void resolve_preconditioner(Resolution& r) {
  SolveOptions& o = r.out.options;
  using solver::kMultigridFromDofs;
  if (r.given.preconditioner) {
    r.add("preconditioner", to_string(*o.preconditioner), "given");
  } else if (r.given.contact.self) {
    // With self-contact multigrid takes fewer CG iterations but measured slower
    // (docs/performance.md, "Default preconditioner with self-contact").
    o.preconditioner = Preconditioner::block_jacobi;
    r.add("preconditioner", to_string(*o.preconditioner), "self-contact is on: block-Jacobi measured faster");
  } else {
    o.preconditioner = default_preconditioner(r.mesh);
    const bool lattice = solver::is_hex8_lattice(r.mesh);
    std::string why =
        !lattice ? "the mesh is not a hex8 lattice"
        : r.dofs() >= kMultigridFromDofs
            ? "a hex8 lattice of " + count(r.dofs()) + " DOFs (multigrid from " + count(kMultigridFromDofs) + ")"
            : count(r.dofs()) + " DOFs, below multigrid's " + count(kMultigridFromDofs);
    r.add("preconditioner", to_string(*o.preconditioner), why);
  }
  if (o.preconditioner == Preconditioner::multigrid) {
    if (r.terms.self_contact)
      throw Error(
          "preconditioner multigrid: its coarse levels do not carry the self-contact penalty's springs "
          "(contact.self_method penalty); use the barrier, or block-jacobi or automatic with it");
    solver::require_hex8_lattice(r.mesh);
  }
}

void resolve_products(Resolution& r) {
  SolveOptions& o = r.out.options;
  if (r.given.product) {
    r.add("product", to_string(*o.product), "given");
  } else {
    o.product = default_product_variant(r.mesh.type, o.precision, r.device.is_gpu, *o.preconditioner);
    const bool cpu_multigrid = !r.device.is_gpu && o.preconditioner == Preconditioner::multigrid;
    r.add("product", to_string(*o.product),
          cpu_multigrid ? "multigrid on a CPU device reuses its hierarchy: the cached linearization"
                        : std::string("measured fastest on ") + (r.device.is_gpu ? "GPUs" : "CPU devices"));
  }
  const bool narrow_kind = o.product == ProductVariant::cached || o.product == ProductVariant::assembled;
  const Precision asked = r.given.product_precision.value_or(Precision::single);
  if (o.precision == Precision::single) {
    o.product_precision = Precision::single;
    r.add("product_precision", "float", "a float solve");
  } else if (!narrow_kind) {
    o.product_precision = Precision::double_;
    r.add("product_precision", "double", std::string("the ") + to_string(*o.product) + " products run in double");
  } else {
    o.product_precision = asked;
    r.add("product_precision", to_string(asked),
          r.given.product_precision ? "given" : "default: float products in double solves, Newton still double");
  }
}

void resolve_multigrid(Resolution& r) {
  SolveOptions& o = r.out.options;
  MultigridOptions& m = o.multigrid;
  const MultigridOptions& asked = r.given.multigrid;
  const double nu = max_poisson_ratio(r.materials);
  m = resolved_smoothing(m, r.dofs(), nu);
  const bool smoothing_given = asked.smoother_degree || asked.chebyshev_kind;
  r.add("multigrid.smoother_degree", std::to_string(*m.smoother_degree),
        asked.smoother_degree ? "given"
        : smoothing_given     ? "the fixed default beside a given polynomial"
        : *m.smoother_degree == 1
            ? count(r.dofs()) + " DOFs below " + count(solver::kDegreeOneBelowDofs) + " and Poisson's ratio " +
                  number(nu) + " below " + number(solver::kDegreeOneBelowPoisson)
            : count(r.dofs()) + " DOFs or Poisson's ratio " + number(nu) + ": at least " +
                  count(solver::kDegreeOneBelowDofs) + " or " + number(solver::kDegreeOneBelowPoisson));
  r.add("multigrid.chebyshev", to_string(*m.chebyshev_kind),
        asked.chebyshev_kind ? "given"
        : smoothing_given    ? "the fixed default beside a given degree"
                             : "with the degree above");
  const bool vertex_terms = solver::has_vertex_terms(r.terms);
  if (asked.fine_level == MultigridFineLevel::built && vertex_terms)
    throw Error(
        "multigrid: fine_level built does not carry the inertia, obstacle contact or self-contact barrier blocks "
        "(use automatic or current)");
  if (!asked.fine_level) m.fine_level = vertex_terms ? MultigridFineLevel::current : MultigridFineLevel::built;
  r.add("multigrid.fine_level", to_string(*m.fine_level),
        asked.fine_level ? "given"
        : vertex_terms   ? "inertia, obstacles or the barrier add per-vertex terms a built level does not carry"
                         : "no per-vertex terms: the build's element matrices are reused");
  if (!m.rebuild_each_load_step) m.rebuild_each_load_step = !r.given.dynamics.has_value();
  r.add("multigrid.rebuild_each_load_step", on_off(*m.rebuild_each_load_step),
        asked.rebuild_each_load_step ? "given"
        : r.given.dynamics           ? "dynamics: the hierarchy is carried across time steps"
                                     : "quasistatic load steps");
  m.rebuild_every = solver::resolved_rebuild_every(m);  // < 1: the multigrid refuses it
  r.add("multigrid.rebuild_every", std::to_string(*m.rebuild_every),
        asked.rebuild_every ? "given" : "measured for the rebuilds above");
  const bool built = m.fine_level == MultigridFineLevel::built, wide = o.precision == Precision::double_;
  m.float_cycle = m.float_cycle && built && wide;
  r.add("multigrid.float_cycle", on_off(m.float_cycle),
        !asked.float_cycle ? "given"
        : !wide            ? "a float solve"
        : !built           ? "needs a built fine level"
                           : "default in double with a built fine level");
  m.fine_level_float = m.fine_level_float && built && wide;
  r.add("multigrid.fine_level_float", on_off(m.fine_level_float),
        !asked.fine_level_float ? "given"
        : !wide                 ? "a float solve"
        : !built                ? "needs a built fine level"
                                : "default in double with a built fine level");
  r.add("multigrid.coarse_solve", m.coarse_solve_on_device ? "device" : "host",
        m.coarse_solve_on_device ? "given: Chebyshev on the device"
                                 : "default: the exact LDL^T factor on the host (equally fast on pocl)");
  r.add_plain("multigrid.coarsest_dofs", m.coarsest_dofs, MultigridOptions{}.coarsest_dofs, count(m.coarsest_dofs));
  r.add_plain("multigrid.max_levels", m.max_levels, MultigridOptions{}.max_levels, std::to_string(m.max_levels));
}

void resolve_contact(Resolution& r) {
  SolveOptions& o = r.out.options;
  ContactOptions& c = o.contact;
  if (r.terms.self_barrier) {
    if (!c.self_broad_phase) {
      c.self_broad_phase = r.device.is_gpu ? SelfBroadPhase::device : SelfBroadPhase::host;
      r.add("contact.self_broad_phase", broad_phase_name(*c.self_broad_phase),
            r.device.is_gpu ? "a GPU: no read of x" : "a CPU device: the host's grid beats the device's sorts");
    } else {
      r.add("contact.self_broad_phase", broad_phase_name(*c.self_broad_phase), "given");
    }
    // The length the default reach is a fraction of: the surface's own.
    const solver::BarrierContact surface = c.self_surface.triangles.empty()
                                               ? solver::BarrierContact(r.mesh)
                                               : solver::BarrierContact(r.mesh, c.self_surface, c.self_embedding);
    const double length = surface.length_scale();
    if (!c.self_distance) c.self_distance = solver::kDefaultSelfDistance * length;
    r.add("contact.self_distance", number(*c.self_distance),
          r.given.contact.self_distance
              ? "given"
              : number(solver::kDefaultSelfDistance) + " of the mean rest surface edge (" + number(length) + ")");
    r.out.barrier_stiffness = solver::default_barrier_stiffness(r.materials, length, *c.self_distance);
    r.add("contact.barrier_stiffness", number(r.out.barrier_stiffness), "E h^2 / dhat^3, E the stiffest material");
  }
  if (r.terms.self_contact) {
    if (!c.self_stiffness) c.self_stiffness = c.stiffness;
    r.add("contact.self_stiffness", number(*c.self_stiffness),
          r.given.contact.self_stiffness ? "given" : "the obstacles' contact stiffness");
  }
  if (r.terms.friction) {
    if (!c.friction_slip) c.friction_slip = 1e-2 * vertex_spacing(r.mesh);
    r.add("contact.friction_slip", number(*c.friction_slip),
          r.given.contact.friction_slip ? "given" : "1% of the vertex spacing");
  }
}

void resolve_stopping(Resolution& r) {
  SolveOptions& o = r.out.options;
  const solver::StoppingTest stop = solver::stopping_test(r.mesh, r.materials, r.given);
  r.out.absolute_tolerance = stop.absolute;
  r.out.relative_tolerance = stop.relative;
  // The strain criterion as the absolute value it gives, so that the
  // options resolve to the same test again.
  o.strain_tolerance = 0.0;
  o.absolute_tolerance = stop.absolute;
  const double strain = stop.strain;
  std::string why =
      r.given.absolute_tolerance > 0.0 && r.given.absolute_tolerance >= stop.absolute ? "given"
      : strain > 0.0
          ? "strain " + number(strain) + " x E h^2 sqrt(n)" +
                (r.given.strain_tolerance ? "" : " (the default strain in " + std::string(to_string(o.precision)) + ")")
          : "off";
  r.add("absolute_tolerance", number(stop.absolute), why);
  r.add("relative_tolerance", number(stop.relative), stop.relative > 0.0 ? "given" : "off");
}

void resolve_limits(Resolution& r) {
  SolveOptions& o = r.out.options;
  const SolverTuning tuning;
  r.add_plain("max_newton_iterations", o.max_newton_iterations, defaults::max_newton_iterations,
              std::to_string(o.max_newton_iterations));
  r.add_plain("max_cg_iterations", o.max_cg_iterations, defaults::max_cg_iterations,
              std::to_string(o.max_cg_iterations));
  if (o.cg_check_every > 0 && !r.device.has_fp64) {
    o.cg_check_every = 0;
    r.add("cg", "viennacl", "the device has no fp64 for the device CG's inner products");
  } else {
    r.add("cg", o.cg_check_every > 0 ? "device" : "viennacl",
          o.cg_check_every == tuning.cg_check_every ? "default"
          : o.cg_check_every > 0                    ? "given"
                                                    : "given: cg_check_every 0");
  }
  if (o.cg_check_every > 0)
    r.add_plain("cg_check_every", o.cg_check_every, tuning.cg_check_every, std::to_string(o.cg_check_every));
  r.add_plain("hessian", o.hessian, tuning.hessian, to_string(o.hessian));
  r.add_plain("line_search_halvings", o.line_search_halvings, tuning.line_search_halvings,
              std::to_string(o.line_search_halvings));
  r.add_plain("forcing_max", o.forcing_max, tuning.forcing_max, number(o.forcing_max));
}

}  // namespace

const ResolvedSetting& ResolvedConfiguration::setting(const std::string& name) const {
  for (const ResolvedSetting& s : settings)
    if (s.name == name) return s;
  throw Error("resolved configuration: no setting named '" + name + "'");
}

ResolvedConfiguration resolve_configuration(const SolveOptions& options, const Mesh& mesh, const MaterialMap& materials,
                                            const DeviceInfo& device) {
  Resolution r{options, mesh, materials, device, solver::model_terms(options), {}};
  r.out.options = options;
  r.add("device", device.platform + " / " + device.name,
        options.device.match.empty() ? "SNH_DEVICE if set, else the first GPU, else the first device"
                                     : "matches '" + options.device.match + "'");
  r.add_plain("precision", options.precision, Precision::double_, to_string(options.precision));
  resolve_preconditioner(r);
  resolve_products(r);
  if (r.out.options.preconditioner == Preconditioner::multigrid) resolve_multigrid(r);
  resolve_contact(r);
  resolve_stopping(r);
  resolve_limits(r);
  return std::move(r.out);
}

}  // namespace snh
