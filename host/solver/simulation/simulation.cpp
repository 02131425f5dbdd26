// Simulation: the per-frame driver. It holds the state (positions,
// velocities, targets, loads) and runs each load step (or implicit Euler
// time step) as one Newton solve (solver/newton/newton_driver.h) over the device
// problem. Its parts, one concern per file:
//   solver/simulation/load_stepping.h       constraint targets and force ramps per step
//   solver/newton/implicit_euler.h      the time steps under SolveOptions::dynamics
//   solver/simulation/precision_fallback.h  float steps re-solved in double
//   solver/simulation/simulation_engine.h   the model, problem and driver per precision
//   solver/simulation/solve_accounting.h    profiles, kernel times, result statistics
//   solver/simulation/simulation_state.h    checkpoint and restore
#include "snh/simulation.h"

#include <chrono>
#include <cmath>
#include <memory>

#include "device/opencl_context.h"
#include "device/phase_profile.h"
#include "device/readback.h"
#include "device/viennacl_binding.h"
#include "fem/rest_state.h"
#include "snh/configuration.h"
#include "snh/error.h"
#include "snh/loads.h"
#include "solver/contact/obstacles.h"
#include "solver/contact/prescribed_crossing.h"
#include "solver/model/elastic_model.h"
#include "solver/multigrid/lattice_hierarchy.h"
#include "solver/multigrid/multigrid.h"
#include "solver/newton/device_problem.h"
#include "solver/newton/implicit_euler.h"
#include "solver/newton/newton_driver.h"
#include "solver/simulation/constraint_checks.h"
#include "solver/simulation/load_stepping.h"
#include "solver/simulation/precision_fallback.h"
#include "solver/simulation/simulation_engine.h"
#include "solver/simulation/simulation_state.h"
#include "solver/simulation/solve_accounting.h"
#include "solver/simulation/solve_input_validation.h"
#include "solver/simulation/step_assessment.h"

namespace snh {

namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

struct Simulation::Impl {
  using Target = solver::SetTarget;

  template <typename Real>
  using Engine = solver::SimulationEngine<Real>;

  Mesh mesh;
  uint64_t fingerprint;  // mesh_fingerprint(mesh)
  MaterialMap materials;
  std::vector<ConstraintSet> constraints;
  MeshWarnings mesh_warnings;
  fem::RestState rest;
  device::OpenClContext cl;
  long viennacl_context_id;
  // Every automatic choice made (snh/configuration.h); `options` are its
  // resolved options, all the rest of the simulation reads.
  ResolvedConfiguration config;
  const SolveOptions& options;
  std::vector<char> prescribed;  // per DOF
  std::vector<std::string> warnings;
  Points x;
  // Dynamics: velocities, lumped mass per vertex, time.
  Points v;
  std::vector<double> mass;
  double time = 0.0;
  std::vector<double> obstacle_table;  // the obstacles placed for the coming Newton solve
  // Friction's lag (ContactOptions::friction): the step's start positions,
  // the obstacles placed at the step's start and their motion over the step;
  // the anchors (xyz per vertex and obstacle) kept across steps.
  bool friction = false;
  std::vector<double> friction_start, friction_start_table, friction_table, friction_anchor;
  // Anchors at x: no history of sticking.
  void reset_friction_anchors() {
    if (!friction) return;
    const size_t count = options.obstacles.size();
    friction_anchor.resize(count * x.xyz().size());
    for (size_t vertex = 0; vertex < x.size(); ++vertex)
      for (size_t o = 0; o < count; ++o)
        for (int d = 0; d < 3; ++d) friction_anchor[3 * (count * vertex + o) + d] = x(vertex, d);
  }
  // The embedded surface in contact with the obstacles (set_contact_surface).
  solver::ContactSurface contact_surface;
  std::vector<Target> targets;
  std::vector<double> force_from, force_to;  // lumped, xyz per vertex
  Points force_applied;                      // lumped
  std::vector<double> body_force_lumped;
  std::vector<double> user_force;
  std::array<double, 3> body_force{0, 0, 0};
  std::unique_ptr<Engine<float>> single;
  std::unique_ptr<Engine<double>> dual;  // double: the main engine or the float fallback
  StepResult last_step;                  // Simulation::last_step
  double callback_seconds = 0.0;         // in the caller's callbacks during the current solve
  solver::Counters solve_start;          // counters() when the current solve began

  // The running counters over the engines built so far: seconds per phase
  // and per kernel, preconditioner builds, and the callbacks' time.
  solver::Counters counters() const {
    solver::Counters c;
    if (single) c.phases = solver::sum(c.phases, single->model->profiler().seconds());
    if (dual) c.phases = solver::sum(c.phases, dual->model->profiler().seconds());
    c.kernels = cl.kernel_seconds();
    for (const device::OpenClContext* context :
         {single ? single->own_context.get() : nullptr, dual ? dual->own_context.get() : nullptr})
      if (context)
        for (const auto& [name, seconds] : context->kernel_seconds()) c.kernels[name] += seconds;
    // Traffic: the phases' by profiler, `other` the contexts' total less them.
    if (single) c.traffic = solver::sum(c.traffic, single->model->profiler().traffic());
    if (dual) c.traffic = solver::sum(c.traffic, dual->model->profiler().traffic());
    device::TransferCounts all = cl.counts();
    for (const device::OpenClContext* context :
         {single ? single->own_context.get() : nullptr, dual ? dual->own_context.get() : nullptr})
      if (context) all += context->counts();
    for (int k = 0; k < solver::kPhaseCount; ++k) all -= c.traffic[k];
    c.traffic[solver::kPhaseCount] = all;
    c.cg_iterations_past_convergence = (dual ? dual->problem->cg_iterations_past_convergence() : 0) +
                                       (single ? single->problem->cg_iterations_past_convergence() : 0);
    c.preconditioner_builds =
        (dual ? dual->problem->preconditioner_builds() : 0) + (single ? single->problem->preconditioner_builds() : 0);
    c.callback_seconds = callback_seconds;
    return c;
  }

  size_t device_memory_bytes() const {
    return (single ? single->problem->memory_bytes() : 0) + (dual ? dual->problem->memory_bytes() : 0);
  }

  // Runs a caller's callback, its time kept out of the profile.
  template <typename F>
  auto in_callback(F&& f) {
    const auto paused = Clock::now();
    struct Count {
      double& seconds;
      Clock::time_point since;
      ~Count() { seconds += std::chrono::duration<double>(Clock::now() - since).count(); }
    } count{callback_seconds, paused};
    return f();
  }

  Impl(Mesh m, const MaterialMap& map, std::vector<ConstraintSet> c, SolveOptions o)
      : mesh(std::move(m)),
        fingerprint(mesh_fingerprint(mesh)),
        materials(map),
        constraints(std::move(c)),
        mesh_warnings(validate_mesh(mesh)),
        rest(fem::compute_rest_state(mesh)),
        cl(o.device, o.precision),
        viennacl_context_id(device::bind_viennacl(cl)),
        options(config.options) {
    validate_solve_inputs(mesh, constraints, o);
    validate_material_map(mesh, materials);
    config = resolve_configuration(o, mesh, materials, cl.info());
    prescribed = solver::prescribed_dofs(mesh, constraints);
    user_force = options.external_force.xyz();
    body_force = options.body_force;
    update_body_force();
    total_force(force_to);
    force_from.assign(force_to.size(), 0.0);
    if (!options.ramp_loads || options.dynamics) force_from = force_to;
    // With dynamics inertia holds every rigid motion: no equilibrium needed.
    // Obstacles may hold what the constraints leave free: a warning at most.
    if (!options.dynamics) check_rigid_modes();
    if (options.dynamics) {
      mass = lumped_mass(mesh, options.dynamics->density);
      v = options.initial_velocities.empty() ? Points(mesh.vertex_count()) : options.initial_velocities;
    }
    if (!mesh_warnings.unused_vertices.empty())
      warnings.push_back("mesh: " + std::to_string(mesh_warnings.unused_vertices.size()) +
                         " vertices belong to no element (first: " +
                         std::to_string(mesh_warnings.unused_vertices.front()) + "); they do not move");
    x = options.initial_positions.empty() ? mesh.positions : options.initial_positions;
    targets.resize(constraints.size());
    friction = solver::has_friction(options.obstacles, options.contact);
    if (friction) reset_friction_anchors();
    if (options.precision == Precision::double_)
      dual = make_engine<double>(nullptr);
    else
      single = make_engine<float>(nullptr);
    const size_t left_out = dual ? excluded_at_rest(*dual) : excluded_at_rest(*single);
    if (left_out > 0)
      warnings.push_back("contact: " + std::to_string(left_out) +
                         " self-contact surface pairs are closer than its distance at rest (seams, or the surface "
                         "touching or crossing itself); they are left out of self-contact");
    const solver::BarrierTerms<double>* dual_barrier = dual ? dual->model->contact().self_barrier() : nullptr;
    const solver::BarrierTerms<float>* single_barrier = single ? single->model->contact().self_barrier() : nullptr;
    if (dual_barrier)
      crossing = std::make_unique<solver::PrescribedCrossingCheck>(dual_barrier->contact(), mesh.positions);
    if (single_barrier)
      crossing = std::make_unique<solver::PrescribedCrossingCheck>(single_barrier->contact(), mesh.positions);
  }

  // The surface pairs barrier self-contact leaves out at rest (closer than
  // its reach there).
  template <typename Real>
  static size_t excluded_at_rest(Engine<Real>& engine) {
    return engine.model->contact().self_barrier() ? engine.model->contact().self_barrier()->excluded_at_rest() : 0;
  }

  void check_rigid_modes() {
    if (options.dynamics) return;
    solver::check_rigid_modes(mesh, prescribed, options.obstacles.empty() ? force_to : std::vector<double>(), warnings);
  }

  void update_body_force() {
    const bool any = body_force[0] != 0.0 || body_force[1] != 0.0 || body_force[2] != 0.0;
    body_force_lumped = any ? lump_body_force(mesh, body_force).release() : std::vector<double>();
  }

  void total_force(std::vector<double>& f) const {
    f.assign(3 * mesh.vertex_count(), 0.0);
    for (size_t i = 0; i < user_force.size(); ++i) f[i] += user_force[i];
    for (size_t i = 0; i < body_force_lumped.size(); ++i) f[i] += body_force_lumped[i];
  }

  template <typename Real>
  std::unique_ptr<Engine<Real>> make_engine(std::unique_ptr<device::OpenClContext> context) {
    const solver::EngineSetup setup{mesh, rest, materials, config, prescribed};
    auto engine = solver::make_engine<Real>(setup, cl, viennacl_context_id, std::move(context));
    if (!contact_surface.empty()) engine->model->contact().set_contact_surface(contact_surface);
    return engine;
  }

  // Every engine's next linearization builds its preconditioner afresh
  // (Simulation::checkpoint and restore).
  void restart_preconditioners() {
    if (single) single->problem->restart_preconditioner();
    if (dual) dual->problem->restart_preconditioner();
  }

  Engine<double>& fallback_engine() {
    if (!dual) {
      auto context = std::make_unique<device::OpenClContext>(options.device, Precision::double_);
      dual = make_engine<double>(std::move(context));
    }
    return *dual;
  }

  int set_index(const std::string& name) const {
    for (size_t k = 0; k < constraints.size(); ++k)
      if (constraints[k].name == name) return static_cast<int>(k);
    std::string known;
    for (const ConstraintSet& c : constraints) known += (known.empty() ? "'" : ", '") + c.name + "'";
    throw Error("no constraint set named '" + name + "' (sets: " + (known.empty() ? "none" : known) + ")");
  }

  // A material undefined for J <= 0 (log Neo-Hookean without inversion
  // handling, as the model or as the lambda part) cannot start a step from
  // an inverted or flat element: name it instead of returning NaN. (Inside a
  // step the line search never accepts a non-finite energy.)
  void require_defined(const Points& positions, int step) const {
    for (size_t e = 0; e < mesh.element_count(); ++e) {
      const Material& material = materials.of_element(e);
      if (material.defined_for_inversion()) continue;
      for (int q = 0; q < rest.quadrature; ++q) {
        double f[9];
        fem::deformation_gradient(mesh, rest, positions.data(), e, q, f);
        const double j = fem::determinant(f);
        if (!(j > 0.0)) {
          const std::string region =
              materials.uniform() ? "" : " of region '" + materials.names[materials.element_material[e]] + "'";
          throw Error("material " + material.description() + region +
                      " without inversion handling (neohookean J0 = 0) is undefined for J <= 0, and element " +
                      std::to_string(e) + " has J = " + std::to_string(j) + " at quadrature point " +
                      std::to_string(q) + " at the start of load step " + std::to_string(step) +
                      " (use J0 > 0 or another model)");
        }
      }
    }
  }

  // Every set's targets at fraction s of this solve, into x; with barrier
  // self-contact the placement's CCD is noted (solver/contact/prescribed_crossing.h).
  void place_targets(double s) {
    const Points before = crossing ? x : Points();
    for (size_t k = 0; k < constraints.size(); ++k) solver::place_target(mesh, constraints[k], targets[k], s, x);
    if (crossing) crossing->placed(before, x);
  }
  std::unique_ptr<solver::PrescribedCrossingCheck> crossing;

  template <typename Real>
  StepResult solve_in(Engine<Real>& engine, int s, std::vector<NewtonIteration>& history, Clock::time_point start,
                      const ProgressCallback& progress, const solver::EulerStep* euler = nullptr) {
    device::use_viennacl(engine.viennacl_context_id);
    if (euler) {
      solver::set_incremental_potential(*engine.model, *euler, force_applied.xyz());
    } else {
      engine.model->set_external_force(force_applied.xyz());
    }
    if (!options.obstacles.empty())
      engine.model->contact().set_obstacles(obstacle_table, options.contact.stiffness, options.contact.thickness);
    if (friction)
      engine.model->contact().set_friction(friction_start, friction_anchor, friction_start_table, friction_table,
                                           *options.contact.friction_slip);
    const double barrier_seconds =
        engine.model->contact().self_barrier() ? engine.model->contact().self_barrier()->state().seconds : 0.0;
    const std::vector<Real> xr(x.xyz().begin(), x.xyz().end());
    // Wrapping a zero-filled buffer: ViennaCL's own sized vector would clear
    // it with a kernel behind the device counts.
    const device::Buffer x_buffer =
        engine.model->context().buffer(CL_MEM_READ_WRITE, xr.size() * sizeof(Real) + 128 * sizeof(Real));
    viennacl::vector<Real> xd(x_buffer.get(), xr.size());
    {
      solver::PhaseScope upload(&engine.model->profiler(), solver::Phase::transfers);
      device::write_to_device(engine.model->context(), xr, xd);
    }
    typename solver::NewtonDriver<solver::DeviceProblem<Real>>::Observer observe;
    if (options.on_iteration || progress)
      observe = [&](const NewtonIteration& rec, const viennacl::vector<Real>& xi) {
        return in_callback([&] {
          if (options.on_iteration) {
            std::vector<double> host;
            device::read_back(engine.model->context(), xi, host);
            options.on_iteration(rec, Points::from_xyz(std::move(host)));
          }
          return progress ? progress(rec) : true;
        });
      };
    const solver::StoppingTest stop{config.absolute_tolerance, config.relative_tolerance};
    StepResult step = engine.newton->solve_step(s, xd, stop, history, start, observe);
    if (friction) friction_anchor = engine.model->contact().next_friction_anchors(xd);
    const solver::ContactState contact = engine.model->contact().contact_state(xd);
    step.contacts = contact.contacts + contact.self_contacts;
    step.max_penetration = std::max(contact.max_penetration, contact.max_self_penetration);
    step.self_contacts = contact.self_contacts;
    step.max_self_penetration = contact.max_self_penetration;
    if (auto* barrier = engine.model->contact().self_barrier()) {
      engine.model->energy(xd);  // the barrier's pairs at the end x
      step.self_contact_pairs = barrier->state().pairs;
      step.min_self_distance = barrier->state().min_distance;
      step.self_contact_seconds = barrier->state().seconds - barrier_seconds;
    }
    std::vector<double> back;
    {
      solver::PhaseScope download(&engine.model->profiler(), solver::Phase::transfers);
      device::read_back(engine.model->context(), xd, back);
    }
    std::copy(back.begin(), back.end(), x.data());
    device::use_viennacl(viennacl_context_id);
    return step;
  }

  SolveResult solve(int load_steps, const ProgressCallback& progress, const StepCallback& on_step) {
    const int steps = load_steps > 0 ? load_steps : options.load_steps;
    if (steps < 1) throw Error("solve: load_steps must be >= 1");
    const auto start = Clock::now();
    callback_seconds = 0.0;
    solve_start = counters();
    SolveResult result;
    result.device = cl.info();
    result.product = *options.product;
    result.preconditioner = *options.preconditioner;
    result.product_precision =
        single || !dual->model->products().float_products() ? options.precision : Precision::single;
    if (const MultigridOptions* used =
            single ? single->problem->multigrid_options() : dual->problem->multigrid_options()) {
      result.multigrid_smoother_degree = used->smoother_degree;
      result.multigrid_chebyshev = used->chebyshev_kind;
      result.multigrid_float_cycle =
          single ? single->problem->multigrid_float_cycle() : dual->problem->multigrid_float_cycle();
    }
    result.tolerance = config.absolute_tolerance;
    result.kernel_specialization = single ? single->model->data().kernel_report() : dual->model->data().kernel_report();
    result.warnings = warnings;
    for (size_t k = 0; k < constraints.size(); ++k) solver::record_start(constraints[k], x.xyz(), targets[k]);
    precision_fallback.begin(options.precision);
    result.converged = true;
    for (int s = 1; s <= steps; ++s) {
      const auto step_clock = Clock::now();
      const solver::Counters step_start = counters();
      StepResult step;
      if (options.dynamics) {
        step = time_step(s, steps, result, start, progress);
      } else {
        const double fraction = solver::load_fraction(s, steps);
        if (friction) lag_friction(x.xyz(), solver::load_fraction(s - 1, steps), fraction);
        place_targets(fraction);
        if (!options.obstacles.empty()) obstacle_table = solver::obstacle_records(options.obstacles, fraction);
        std::vector<double> applied = force_applied.release();
        solver::ramp_force(force_from, force_to, fraction, applied);
        force_applied = Points::from_xyz(std::move(applied));
        step = solve_step(s, steps, result, start, progress);
      }
      const std::string label = (options.dynamics ? "time step " : "load step ") + std::to_string(s);
      solver::assess_step(mesh, rest, x.xyz(), options, label, step);
      if (crossing) crossing->assess(x, label, step);
      result.warnings.insert(result.warnings.end(), step.warnings.begin(), step.warnings.end());
      result.converged = result.converged && step.converged && step.status != StepStatus::inverted_elements;
      result.final_residual_norm = step.residual_norm;
      const solver::Counters step_end = counters();
      step.profile = solver::profile_between(step_start, step_end,
                                             std::chrono::duration<double>(Clock::now() - step_clock).count());
      step.preconditioner_builds = step_end.preconditioner_builds - step_start.preconditioner_builds;
      result.steps.push_back(step);
      last_step = step;
      if (on_step) in_callback([&] { on_step(s, x); });
      if (step.status == StepStatus::inverted_elements) break;  // SolveOptions::fail_on_inverted
      if (step.status == StepStatus::cancelled) {
        result.cancelled = true;
        break;
      }
    }
    return finish(result, start);
  }

  // Friction's lag for a step from load parameter t0 (positions `start`) to t1.
  void lag_friction(const std::vector<double>& start, double t0, double t1) {
    friction_start = start;
    friction_start_table = solver::obstacle_records(options.obstacles, t0);
    friction_table = solver::friction_records(options.obstacles, options.contact, t0, t1);
  }

  // Implicit Euler time step s of n (solver/newton/implicit_euler.h), loads in full.
  StepResult time_step(int s, int steps, SolveResult& result, Clock::time_point start,
                       const ProgressCallback& progress) {
    bool defined_for_inversion = true;
    for (const Material& m : materials.materials)
      defined_for_inversion = defined_for_inversion && m.defined_for_inversion();
    force_applied = Points::from_xyz(force_to);
    StepResult total = solver::implicit_euler_step(
        *options.dynamics, s, steps, defined_for_inversion, x, v, mass, time,
        [&](const std::vector<double>& from, const std::vector<double>& move) { return barrier_bound(from, move); },
        [&](const solver::EulerStep& euler, double t0, double t1) {
          if (friction) lag_friction(euler.start, t0, t1);
          place_targets(t1);
          if (!options.obstacles.empty()) obstacle_table = solver::obstacle_records(options.obstacles, t1);
        },
        [&](const solver::EulerStep& euler) { return solve_step(s, steps, result, start, progress, &euler); });
    total.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    total.time = time;
    return total;
  }

  solver::PrecisionFallback precision_fallback;

  // The largest fraction of `move` from `from` that barrier self-contact's
  // continuous collision detection clears (infinity without it): the
  // device's CCD, the one Newton's line search runs.
  double barrier_bound(const std::vector<double>& from, const std::vector<double>& move) {
    if (dual && dual->model->contact().self_barrier()) return device_barrier_bound(*dual, from, move);
    if (single && single->model->contact().self_barrier()) return device_barrier_bound(*single, from, move);
    return std::numeric_limits<double>::infinity();
  }
  template <typename Real>
  static double device_barrier_bound(Engine<Real>& engine, const std::vector<double>& from,
                                     const std::vector<double>& move) {
    device::OpenClContext& context = engine.model->context();
    const device::Buffer from_buffer = context.buffer(CL_MEM_READ_WRITE, from.size() * sizeof(Real));
    const device::Buffer move_buffer = context.buffer(CL_MEM_READ_WRITE, move.size() * sizeof(Real));
    viennacl::vector<Real> from_device(from_buffer.get(), from.size()), move_device(move_buffer.get(), move.size());
    {
      solver::PhaseScope upload(&engine.model->profiler(), solver::Phase::transfers);
      device::write_to_device(context, from, from_device);
      device::write_to_device(context, move, move_device);
    }
    return engine.model->contact().step_bound(from_device, move_device);
  }

  // One Newton solve from x at its step's targets and forces, with the
  // float-to-double fallback.
  StepResult solve_step(int s, int steps, SolveResult& result, Clock::time_point start,
                        const ProgressCallback& progress, const solver::EulerStep* euler = nullptr) {
    const bool may_fall_back = options.fallback_to_double && options.precision == Precision::single;
    require_defined(x, s);
    const Points step_start = may_fall_back ? x : Points();
    const std::vector<double> anchor_start = may_fall_back ? friction_anchor : std::vector<double>();
    return precision_fallback.step(
        s, steps, options.precision, may_fall_back, cl.info().has_fp64, result,
        [&] { return solve_in(*single, s, result.history, start, progress, euler); },
        [&] { return solve_in(fallback_engine(), s, result.history, start, progress, euler); },
        [&] {
          x = step_start;
          friction_anchor = anchor_start;
        });
  }

  SolveResult finish(SolveResult& result, Clock::time_point start) {
    // What this solve reached becomes where the next one starts from.
    for (size_t k = 0; k < constraints.size(); ++k) {
      Target& t = targets[k];
      if (t.kind == Target::Kind::transform && !result.cancelled) {
        t.from = t.to;
        t.from_known = true;
      }
    }
    if (!result.cancelled) force_from = force_to;
    result.positions = x;
    solver::record_deformation(mesh, x, result);
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    result.profile = solver::profile_between(solve_start, counters(), result.seconds);
    result.device_memory_bytes = device_memory_bytes();
    return std::move(result);
  }
};

Simulation::Simulation(Mesh mesh, const MaterialMap& materials, std::vector<ConstraintSet> constraints,
                       SolveOptions options)
    : impl_(std::make_unique<Impl>(std::move(mesh), materials, std::move(constraints), std::move(options))) {}

Simulation::Simulation(Mesh mesh, const Material& material, std::vector<ConstraintSet> constraints,
                       SolveOptions options)
    : Simulation(mesh, uniform_material(mesh, material), std::move(constraints), std::move(options)) {}

Simulation::~Simulation() = default;
Simulation::Simulation(Simulation&&) noexcept = default;
Simulation& Simulation::operator=(Simulation&&) noexcept = default;

void Simulation::set_transform(const std::string& set, const RigidTransform& transform) {
  for (double v : transform.rotation)
    if (!std::isfinite(v)) throw Error("set_transform('" + set + "'): non-finite matrix entry");
  for (int d = 0; d < 3; ++d)
    if (!std::isfinite(transform.translation[d]) || !std::isfinite(transform.center[d]))
      throw Error("set_transform('" + set + "'): non-finite translation or centre");
  Impl::Target& t = impl_->targets[impl_->set_index(set)];
  if (t.kind != Impl::Target::Kind::transform) {
    // A set that has not followed a transform yet starts from the identity
    // (its rest placement) if it is still there; else it moves linearly.
    t.from = RigidTransform::identity();
    const ConstraintSet& c = impl_->constraints[impl_->set_index(set)];
    bool at_rest = true;
    for (int32_t v : c.vertices)
      for (int d = 0; d < 3; ++d) at_rest = at_rest && impl_->x(v, d) == impl_->mesh.positions(v, d);
    t.from_known = at_rest;
  }
  t.kind = Impl::Target::Kind::transform;
  t.to = transform;
}

void Simulation::set_positions(const std::string& set, const Points& positions) {
  const int k = impl_->set_index(set);
  const ConstraintSet& c = impl_->constraints[k];
  const std::vector<double>& xyz = positions.xyz();
  if (xyz.size() != 3 * c.vertices.size())
    throw Error("set_positions('" + set + "'): " + std::to_string(xyz.size()) + " values, expected " +
                std::to_string(3 * c.vertices.size()) + " (xyz per vertex of the set)");
  for (double v : xyz)
    if (!std::isfinite(v)) throw Error("set_positions('" + set + "'): non-finite value");
  Impl::Target& t = impl_->targets[k];
  t.kind = Impl::Target::Kind::positions;
  t.xyz = xyz;
  t.from_known = false;
}

void Simulation::set_external_force(const Points& lumped) {
  SolveOptions check;
  check.external_force = lumped;
  validate_solve_inputs(impl_->mesh, {}, check);
  impl_->user_force = lumped.xyz();
  impl_->total_force(impl_->force_to);
  impl_->check_rigid_modes();
}

void Simulation::set_body_force(const std::array<double, 3>& per_rest_volume) {
  SolveOptions check;
  check.body_force = per_rest_volume;
  validate_solve_inputs(impl_->mesh, {}, check);
  impl_->body_force = per_rest_volume;
  impl_->update_body_force();
  impl_->total_force(impl_->force_to);
  impl_->check_rigid_modes();
}

void Simulation::set_state(const Points& positions) {
  SolveOptions check;
  check.initial_positions = positions;
  validate_solve_inputs(impl_->mesh, {}, check);
  impl_->x = positions;
  impl_->reset_friction_anchors();
}

void Simulation::set_velocities(const Points& velocities) {
  if (!impl_->options.dynamics) throw Error("set_velocities: the simulation has no dynamics (SolveOptions::dynamics)");
  SolveOptions check;
  check.dynamics = impl_->options.dynamics;
  check.initial_velocities = velocities;
  validate_solve_inputs(impl_->mesh, {}, check);
  impl_->v = velocities.empty() ? Points(impl_->mesh.vertex_count()) : velocities;
}

void Simulation::restart() {
  Impl& m = *impl_;
  m.x = m.options.initial_positions.empty() ? m.mesh.positions : m.options.initial_positions;
  m.reset_friction_anchors();
  if (m.options.dynamics) {
    m.v = m.options.initial_velocities.empty() ? Points(m.mesh.vertex_count()) : m.options.initial_velocities;
    m.time = 0.0;
  }
  m.targets.assign(m.constraints.size(), Impl::Target());
  m.user_force = m.options.external_force.xyz();
  m.body_force = m.options.body_force;
  m.update_body_force();
  m.total_force(m.force_to);
  m.force_from.assign(m.force_to.size(), 0.0);
  if (!m.options.ramp_loads || m.options.dynamics) m.force_from = m.force_to;
  m.force_applied.clear();
}

void Simulation::set_contact_surface(const Embedding& embedding) {
  Impl& m = *impl_;
  solver::ContactSurface surface = solver::contact_surface(m.mesh, embedding);
  if (m.options.obstacles.empty()) return;  // nothing to touch
  if (m.single) m.single->model->contact().set_contact_surface(surface);
  if (m.dual) m.dual->model->contact().set_contact_surface(surface);
  m.contact_surface = std::move(surface);
}

SimulationState Simulation::checkpoint() {
  Impl& m = *impl_;
  SimulationState s;
  s.vertex_count = m.mesh.vertex_count();
  s.mesh_fingerprint = m.fingerprint;
  s.positions = m.x;
  if (m.options.dynamics) s.velocities = m.v;
  s.time = m.time;
  if (m.friction) s.friction_anchors = Points::from_xyz(m.friction_anchor);
  for (size_t k = 0; k < m.constraints.size(); ++k)
    s.targets.push_back(solver::state_target(m.constraints[k], m.targets[k]));
  s.external_force = Points::from_xyz(m.user_force);
  s.body_force = m.body_force;
  s.force_from = Points::from_xyz(m.force_from);
  s.force_to = Points::from_xyz(m.force_to);
  s.force_applied = m.force_applied;
  m.restart_preconditioners();
  return s;
}

void Simulation::restore(const SimulationState& s) {
  Impl& m = *impl_;
  solver::check_restorable(s, m.mesh.vertex_count(), m.fingerprint, m.constraints, m.options.dynamics.has_value(),
                           m.friction ? m.options.obstacles.size() : 0);
  m.x = s.positions;
  if (m.options.dynamics) m.v = s.velocities;
  m.time = s.time;
  if (m.friction) m.friction_anchor = s.friction_anchors.xyz();
  for (size_t k = 0; k < s.targets.size(); ++k) m.targets[k] = solver::set_target(s.targets[k]);
  m.user_force = s.external_force.xyz();
  m.body_force = s.body_force;
  m.update_body_force();
  m.force_from = s.force_from.xyz();
  m.force_to = s.force_to.xyz();
  m.force_applied = s.force_applied;
  m.restart_preconditioners();
}

SolveResult Simulation::solve(int load_steps, const ProgressCallback& progress, const StepCallback& on_step) {
  return impl_->solve(load_steps, progress, on_step);
}

const Points& Simulation::positions() const { return impl_->x; }
const Points& Simulation::velocities() const { return impl_->v; }
double Simulation::time() const { return impl_->time; }
const Points& Simulation::applied_force() const { return impl_->force_applied; }
const StepResult& Simulation::last_step() const { return impl_->last_step; }
const Mesh& Simulation::mesh() const { return impl_->mesh; }
const MaterialMap& Simulation::materials() const { return impl_->materials; }
const std::vector<ConstraintSet>& Simulation::constraints() const { return impl_->constraints; }
const DeviceInfo& Simulation::device() const { return impl_->cl.info(); }
double Simulation::tolerance() const { return impl_->config.absolute_tolerance; }
const ResolvedConfiguration& Simulation::configuration() const { return impl_->config; }

ElementFields Simulation::fields() const { return compute_element_fields(impl_->mesh, impl_->materials, impl_->x); }

std::vector<Reaction> Simulation::reactions() const {
  return constraint_reactions(impl_->mesh, impl_->materials, impl_->constraints, impl_->x, impl_->force_applied);
}

}  // namespace snh
