// Constraints, obstacles, solve options and the Simulation a Python program
// drives frame by frame (snh/simulation.h, fields.h, device.h).
#include "snh/simulation.h"

#include "callbacks.h"
#include "common.h"
#include "snh/checkpoint.h"
#include "snh/configuration.h"
#include "snh/device.h"
#include "snh/fields.h"

namespace snh_python {

namespace {

// An enum value, or its name as the C++ parser takes it.
template <class E>
E enum_or_name(py::handle value, E (*parse)(const std::string&)) {
  if (py::isinstance<py::str>(value)) return parse(value.cast<std::string>());
  return value.cast<E>();
}

// An unset option: None or 'automatic' (snh::kAutomatic) for empty, else
// an enum value or its name.
template <class E>
std::optional<E> optional_enum_or_name(py::handle value, E (*parse)(const std::string&)) {
  if (value.is_none()) return std::nullopt;
  if (py::isinstance<py::str>(value)) return snh::parse_optional(value.cast<std::string>(), parse);
  return value.cast<E>();
}

snh::Points optional_xyz(py::handle value, const char* what, py::ssize_t rows = -1) {
  if (value.is_none()) return {};
  return to_points(value, what, rows);
}

py::object xyz_or_none(const snh::Points& values) {
  if (values.empty()) return py::none();
  return xyz_array(values);
}

py::array_t<double> rotation_array(const snh::RigidTransform& t) {
  return copy_array(std::vector<double>(t.rotation.begin(), t.rotation.end()), {3, 3});  // both row-major
}

void set_rotation(snh::RigidTransform& t, py::handle rotation) {
  const std::vector<double> r = to_doubles(rotation, "rotation", 3, 3);
  for (int i = 0; i < 9; ++i) t.rotation[i] = r[i];  // both row-major
}

snh::ConstraintSet make_constraint_set(std::string name, py::handle vertices, const py::object& motion,
                                       std::array<bool, 3> components, const py::object& targets) {
  snh::ConstraintSet set;
  set.name = std::move(name);
  set.vertices = to_indices(vertices, "vertices", 0, -1);
  set.motion = transform_callback<snh::RigidTransform>(motion, "motion");
  if (!targets.is_none()) {
    auto held = hold(targets);
    const py::ssize_t rows = static_cast<py::ssize_t>(set.vertices.size());
    set.targets = [held, rows](double t, snh::Points& xyz) {
      py::gil_scoped_acquire gil;
      xyz = to_points((*held)(t), "targets", rows);
    };
  }
  set.components = components;
  return set;
}

// Index lists and per-vertex arrays against the mesh, as ValueErrors before
// the engine sees them.
void check_inputs(const snh::Mesh& mesh, const std::vector<snh::ConstraintSet>& sets,
                  const std::optional<snh::SolveOptions>& options) {
  const size_t n = mesh.vertex_count();
  for (const snh::ConstraintSet& set : sets)
    for (size_t i = 0; i < set.vertices.size(); ++i)
      if (static_cast<size_t>(set.vertices[i]) >= n)
        throw py::value_error("constraint set '" + set.name + "': vertex " + std::to_string(set.vertices[i]) +
                              " at position " + std::to_string(i) + " is outside [0, " + std::to_string(n) + ")");
  if (!options) return;
  const std::pair<const char*, const snh::Points*> arrays[] = {{"external_force", &options->external_force},
                                                               {"initial_positions", &options->initial_positions},
                                                               {"initial_velocities", &options->initial_velocities}};
  for (const auto& [name, values] : arrays)
    if (!values->empty() && values->size() != n)  // points
      throw py::value_error(std::string("SolveOptions.") + name + ": expected shape (" + std::to_string(n) +
                            ", 3), got (" + std::to_string(values->size()) + ", 3)");
}

const snh::ConstraintSet* find_set(const snh::Simulation& sim, const std::string& name) {
  for (const snh::ConstraintSet& set : sim.constraints())
    if (set.name == name) return &set;
  return nullptr;
}

}  // namespace

void bind_solver_enums(py::module_& m) {
  py::enum_<snh::Precision>(m, "Precision", "Working precision of the device kernels.")
      .value("single", snh::Precision::single)
      .value("double", snh::Precision::double_);
  py::enum_<snh::Preconditioner>(m, "Preconditioner", "Preconditioner of the conjugate gradient solves.")
      .value("none", snh::Preconditioner::none)
      .value("block_jacobi", snh::Preconditioner::block_jacobi)
      .value("multigrid", snh::Preconditioner::multigrid);
  py::enum_<snh::ProductVariant>(m, "ProductVariant", "How Hessian products are computed.")
      .value("cached", snh::ProductVariant::cached)
      .value("recompute", snh::ProductVariant::recompute)
      .value("element_matrices", snh::ProductVariant::element_matrices)
      .value("assembled", snh::ProductVariant::assembled);
  py::enum_<snh::HessianMode>(m, "HessianMode", "Projected Hessian always, or the true one near the solution.")
      .value("projected", snh::HessianMode::projected)
      .value("adaptive", snh::HessianMode::adaptive);
  py::enum_<snh::ChebyshevKind>(m, "ChebyshevKind", "Polynomial of the multigrid smoother.")
      .value("first", snh::ChebyshevKind::first)
      .value("fourth", snh::ChebyshevKind::fourth)
      .value("optimized_fourth", snh::ChebyshevKind::optimized_fourth);
  py::enum_<snh::ObstacleType>(m, "ObstacleType", "Kinematic obstacle shape.")
      .value("plane", snh::ObstacleType::plane)
      .value("sphere", snh::ObstacleType::sphere)
      .value("cylinder", snh::ObstacleType::cylinder);
}

namespace {

void bind_rigid_transform(py::module_& m) {
  py::class_<snh::RigidTransform>(m, "RigidTransform",
                                  "x = rotation (X - center) + center + translation; rotation a (3, 3) matrix.")
      .def(py::init([](py::object rotation, py::object translation, py::object center) {
             snh::RigidTransform t;
             if (!rotation.is_none()) set_rotation(t, rotation);
             if (!translation.is_none()) t.translation = to_vec3(translation, "translation");
             if (!center.is_none()) t.center = to_vec3(center, "center");
             return t;
           }),
           py::arg("rotation") = py::none(), py::arg("translation") = py::none(), py::arg("center") = py::none(),
           "Identity unless given: rotation (3, 3), translation (3,), center (3,).")
      .def_static("identity", &snh::RigidTransform::identity, "The identity.")
      .def_static("rotation_about", &snh::RigidTransform::rotation_about, py::arg("axis"), py::arg("angle"),
                  py::arg("center") = std::array<double, 3>{0, 0, 0},
                  "Rotation by angle (radians) about the unit axis through center.")
      .def_static("translation_by", &snh::RigidTransform::translation_by, py::arg("offset"), "A translation.")
      .def_property("rotation", &rotation_array, &set_rotation, "The rotation, float64 (3, 3) [row, column].")
      .def_property(
          "translation", [](const snh::RigidTransform& t) { return t.translation; },
          [](snh::RigidTransform& t, py::handle v) { t.translation = to_vec3(v, "translation"); }, "Translation (3,).")
      .def_property(
          "center", [](const snh::RigidTransform& t) { return t.center; },
          [](snh::RigidTransform& t, py::handle v) { t.center = to_vec3(v, "center"); }, "Rotation centre (3,).")
      .def(
          "apply",
          [](const snh::RigidTransform& t, py::handle points) {
            const py::array a = py::module_::import("numpy").attr("asarray")(points);
            const bool one = a.ndim() == 1;
            std::vector<double> x = to_doubles(one ? py::object(a.attr("reshape")(1, -1)) : py::object(a), "points", 3);
            for (size_t i = 0; i < x.size(); i += 3) {
              const auto y = t.apply({x[i], x[i + 1], x[i + 2]});
              x[i] = y[0], x[i + 1] = y[1], x[i + 2] = y[2];
            }
            const py::ssize_t n = static_cast<py::ssize_t>(x.size() / 3);
            return one ? to_array(std::move(x), {3}) : to_array(std::move(x), {n, 3});
          },
          py::arg("points"), "The map applied to a point (3,) or points (n, 3).")
      .def("__repr__", [](const snh::RigidTransform& t) {
        return "RigidTransform(translation=(" + std::to_string(t.translation[0]) + ", " +
               std::to_string(t.translation[1]) + ", " + std::to_string(t.translation[2]) + "))";
      });
}

void bind_constraint_sets(py::module_& m) {
  py::class_<snh::ConstraintSet>(m, "ConstraintSet",
                                 "Vertices whose positions are prescribed: at rest, or moved by motion(t) -> "
                                 "RigidTransform at load parameter t in (0, 1], or placed by targets(t) -> (k, 3).")
      .def(py::init(&make_constraint_set), py::arg("name"), py::arg("vertices"), py::arg("motion") = py::none(),
           py::arg("components") = std::array<bool, 3>{true, true, true}, py::arg("targets") = py::none(),
           "A named set of vertex indices; components says which of x, y, z it prescribes.")
      .def_readwrite("name", &snh::ConstraintSet::name, "Set name (used by Simulation.set_transform).")
      .def_property(
          "vertices",
          [](const snh::ConstraintSet& s) { return copy_array(s.vertices, {py::ssize_t(s.vertices.size())}); },
          [](snh::ConstraintSet& s, py::handle v) { s.vertices = to_indices(v, "vertices", 0, -1); },
          "Vertex indices, int32 (k,).")
      .def_property(
          "motion",
          [](const snh::ConstraintSet& s) -> py::object {
            if (!s.motion) return py::none();
            return py::cpp_function(s.motion, py::arg("t"));
          },
          [](snh::ConstraintSet& s, const py::object& f) {
            s.motion = transform_callback<snh::RigidTransform>(f, "motion");
          },
          "Callable t -> RigidTransform, or None (the set stays at rest).")
      .def_readwrite("components", &snh::ConstraintSet::components, "Which of x, y, z are prescribed.")
      .def("__repr__", [](const snh::ConstraintSet& s) {
        return "ConstraintSet('" + s.name + "', " + std::to_string(s.vertices.size()) + " vertices)";
      });
}

void bind_dynamics_options(py::module_& m) {
  py::class_<snh::DynamicsOptions>(m, "DynamicsOptions", "Implicit Euler time stepping.")
      .def(py::init([](const py::kwargs& kw) { return from_kwargs<snh::DynamicsOptions>(kw); }),
           "Keyword arguments set the fields (time_step, density, damping_mass, damping_stiffness, substeps).")
      .def_readwrite("time_step", &snh::DynamicsOptions::time_step, "Seconds per time step (> 0).")
      .def_readwrite("density", &snh::DynamicsOptions::density, "Mass per rest volume (> 0).")
      .def_property(
          "damping_mass", [](const snh::DynamicsOptions& d) { return d.damping.mass; },
          [](snh::DynamicsOptions& d, double v) { d.damping.mass = v; }, "Rayleigh mass damping a, 1/s.")
      .def_property(
          "damping_stiffness", [](const snh::DynamicsOptions& d) { return d.damping.stiffness; },
          [](snh::DynamicsOptions& d, double v) { d.damping.stiffness = v; }, "Rayleigh stiffness damping b, s.")
      .def_readwrite("substeps", &snh::DynamicsOptions::substeps, "Backward Euler steps per time step (>= 1).");
}

void bind_obstacles(py::module_& m) {
  py::class_<snh::Obstacle>(m, "Obstacle", "A kinematic plane, sphere or cylinder the body cannot enter.")
      .def(py::init([](const py::kwargs& kw) { return from_kwargs<snh::Obstacle>(kw); }),
           "Keyword arguments set the fields.")
      .def_static(
          "plane",
          [](const std::array<double, 3>& point, const std::array<double, 3>& normal, const py::object& motion,
             std::optional<double> friction) {
            snh::Obstacle o;
            o.type = snh::ObstacleType::plane, o.point = point, o.direction = normal, o.friction = friction;
            o.motion = transform_callback<snh::RigidTransform>(motion, "motion");
            return o;
          },
          py::arg("point"), py::arg("normal"), py::arg("motion") = py::none(), py::arg("friction") = py::none(),
          "A plane through point; normal points to the free side.")
      .def_static(
          "sphere",
          [](const std::array<double, 3>& center, double radius, const py::object& motion,
             std::optional<double> friction) {
            snh::Obstacle o;
            o.type = snh::ObstacleType::sphere, o.point = center, o.radius = radius, o.friction = friction;
            o.motion = transform_callback<snh::RigidTransform>(motion, "motion");
            return o;
          },
          py::arg("center"), py::arg("radius"), py::arg("motion") = py::none(), py::arg("friction") = py::none(),
          "A sphere.")
      .def_static(
          "cylinder",
          [](const std::array<double, 3>& point, const std::array<double, 3>& axis, double radius,
             const py::object& motion, std::optional<double> friction) {
            snh::Obstacle o;
            o.type = snh::ObstacleType::cylinder, o.point = point, o.direction = axis, o.radius = radius;
            o.friction = friction;
            o.motion = transform_callback<snh::RigidTransform>(motion, "motion");
            return o;
          },
          py::arg("point"), py::arg("axis"), py::arg("radius"), py::arg("motion") = py::none(),
          py::arg("friction") = py::none(), "An infinite cylinder about the axis through point.")
      .def_readwrite("type", &snh::Obstacle::type, "ObstacleType.")
      .def_readwrite("point", &snh::Obstacle::point, "Plane point, sphere centre or point on the axis.")
      .def_readwrite("direction", &snh::Obstacle::direction, "Plane normal or cylinder axis.")
      .def_readwrite("radius", &snh::Obstacle::radius, "Sphere or cylinder radius.")
      .def_property(
          "motion",
          [](const snh::Obstacle& o) -> py::object {
            if (!o.motion) return py::none();
            return py::cpp_function(o.motion, py::arg("t"));
          },
          [](snh::Obstacle& o, const py::object& f) {
            o.motion = transform_callback<snh::RigidTransform>(f, "motion");
          },
          "Callable t -> RigidTransform, or None.")
      .def_readwrite("friction", &snh::Obstacle::friction, "Coulomb coefficient, or None for ContactOptions'.");
}

void bind_contact_options(py::module_& m) {
  py::class_<snh::ContactOptions>(m, "ContactOptions", "Penalty contact with obstacles and self-contact.")
      .def(py::init([](const py::kwargs& kw) { return from_kwargs<snh::ContactOptions>(kw); }),
           "Keyword arguments set the fields.")
      .def_readwrite("stiffness", &snh::ContactOptions::stiffness, "Penalty stiffness per vertex (force/length).")
      .def_readwrite("thickness", &snh::ContactOptions::thickness, "Contact layer thickness.")
      .def_readwrite("self", &snh::ContactOptions::self, "Self-collision penalty on.")
      .def_readwrite("self_stiffness", &snh::ContactOptions::self_stiffness, "Penalty self-contact's; None: stiffness.")
      .def_readwrite("friction", &snh::ContactOptions::friction, "Default Coulomb coefficient.")
      .def_readwrite("friction_slip", &snh::ContactOptions::friction_slip,
                     "Stick-slip length; None: 1% of the vertex spacing.");
}

void bind_solve_options(py::module_& m) {
  py::class_<snh::SolveOptions>(m, "SolveOptions",
                                "What a solve does. Enum fields also take their names, e.g. precision='float'.")
      .def(py::init([](const py::kwargs& kw) { return from_kwargs<snh::SolveOptions>(kw); }),
           "Keyword arguments set the fields of the same names.")
      .def_property(
          "precision", [](const snh::SolveOptions& o) { return o.precision; },
          [](snh::SolveOptions& o, py::handle v) { o.precision = enum_or_name(v, &snh::parse_precision); },
          "Precision.double (default) or Precision.single ('double', 'float').")
      .def_property(
          "device", [](const snh::SolveOptions& o) { return o.device.match; },
          [](snh::SolveOptions& o, std::string match) { o.device.match = std::move(match); },
          "Case-insensitive substring of '<platform> / <device>'; '' for SNH_DEVICE, else the first GPU.")
      .def_readwrite("dynamics", &snh::SolveOptions::dynamics, "DynamicsOptions, or None for quasistatics.")
      .def_readwrite("obstacles", &snh::SolveOptions::obstacles, "Obstacle list (a copy: assign a new list).")
      .def_readwrite("contact", &snh::SolveOptions::contact, "ContactOptions (its fields can be set in place).")
      .def_readwrite("load_steps", &snh::SolveOptions::load_steps, "Load (or time) steps per solve.")
      .def_readwrite("max_newton_iterations", &snh::SolveOptions::max_newton_iterations)
      .def_readwrite("fail_on_inverted", &snh::SolveOptions::fail_on_inverted,
                     "A step ending with inverted elements fails (StepStatus.inverted_elements); later steps not run.")
      .def_readwrite("strain_tolerance", &snh::SolveOptions::strain_tolerance, "None: 1e-6 double, 1e-4 float.")
      .def_readwrite("absolute_tolerance", &snh::SolveOptions::absolute_tolerance)
      .def_readwrite("relative_tolerance", &snh::SolveOptions::relative_tolerance)
      .def_readwrite("max_cg_iterations", &snh::SolveOptions::max_cg_iterations)
      .def_readwrite("forcing_gamma", &snh::SolveOptions::forcing_gamma)
      .def_readwrite("forcing_max", &snh::SolveOptions::forcing_max)
      .def_property(
          "preconditioner", [](const snh::SolveOptions& o) { return o.preconditioner; },
          [](snh::SolveOptions& o, py::handle v) {
            o.preconditioner = optional_enum_or_name(v, &snh::parse_preconditioner);
          },
          "Preconditioner (or 'none', 'block-jacobi', 'multigrid'), or None ('automatic'): the measured choice.")
      .def_readwrite("line_search_halvings", &snh::SolveOptions::line_search_halvings)
      .def_property(
          "product", [](const snh::SolveOptions& o) { return o.product; },
          [](snh::SolveOptions& o, py::handle v) { o.product = optional_enum_or_name(v, &snh::parse_product_variant); },
          "ProductVariant (or its name), or None ('automatic'): the measured choice.")
      .def_property(
          "product_precision", [](const snh::SolveOptions& o) { return o.product_precision; },
          [](snh::SolveOptions& o, py::handle v) {
            if (v.is_none())
              o.product_precision.reset();
            else
              o.product_precision = enum_or_name(v, &snh::parse_precision);
          },
          "Precision of CG's products in double solves, or None (float).")
      .def_property(
          "hessian", [](const snh::SolveOptions& o) { return o.hessian; },
          [](snh::SolveOptions& o, py::handle v) { o.hessian = enum_or_name(v, &snh::parse_hessian_mode); },
          "HessianMode (or 'projected', 'adaptive').")
      .def_property(
          "external_force", [](const snh::SolveOptions& o) { return xyz_or_none(o.external_force); },
          [](snh::SolveOptions& o, py::handle v) { o.external_force = optional_xyz(v, "external_force"); },
          "Lumped force (n, 3) float64, or None.")
      .def_property(
          "body_force", [](const snh::SolveOptions& o) { return o.body_force; },
          [](snh::SolveOptions& o, py::handle v) { o.body_force = to_vec3(v, "body_force"); },
          "Body force per rest volume (3,).")
      .def_readwrite("ramp_loads", &snh::SolveOptions::ramp_loads, "Forces grow with the load steps.")
      .def_readwrite("fallback_to_double", &snh::SolveOptions::fallback_to_double)
      .def_property(
          "initial_positions", [](const snh::SolveOptions& o) { return xyz_or_none(o.initial_positions); },
          [](snh::SolveOptions& o, py::handle v) { o.initial_positions = optional_xyz(v, "initial_positions"); },
          "Starting positions (n, 3), or None for rest.")
      .def_property(
          "initial_velocities", [](const snh::SolveOptions& o) { return xyz_or_none(o.initial_velocities); },
          [](snh::SolveOptions& o, py::handle v) { o.initial_velocities = optional_xyz(v, "initial_velocities"); },
          "Starting velocities (n, 3) with dynamics, or None for zero.");
}

void bind_simulation_class(py::module_& m) {
  py::class_<snh::Simulation>(m, "Simulation",
                              "A simulation driven frame by frame: built once (kernels compiled, mesh uploaded), "
                              "then solved from its current state after new targets and loads.")
      .def(py::init([](snh::Mesh mesh, const snh::MaterialMap& materials, std::vector<snh::ConstraintSet> constraints,
                       std::optional<snh::SolveOptions> options) {
             check_inputs(mesh, constraints, options);
             py::gil_scoped_release release;
             return std::make_unique<snh::Simulation>(std::move(mesh), materials, std::move(constraints),
                                                      options.value_or(snh::SolveOptions{}));
           }),
           py::arg("mesh"), py::arg("materials"), py::arg("constraints") = std::vector<snh::ConstraintSet>{},
           py::arg("options") = py::none(), "With a MaterialMap (one material per element).")
      .def(py::init([](snh::Mesh mesh, const snh::Material& material, std::vector<snh::ConstraintSet> constraints,
                       std::optional<snh::SolveOptions> options) {
             check_inputs(mesh, constraints, options);
             py::gil_scoped_release release;
             return std::make_unique<snh::Simulation>(std::move(mesh), material, std::move(constraints),
                                                      options.value_or(snh::SolveOptions{}));
           }),
           py::arg("mesh"), py::arg("material"), py::arg("constraints") = std::vector<snh::ConstraintSet>{},
           py::arg("options") = py::none(),
           "Validates everything (snh.Error naming the input), builds the kernels and uploads the mesh.")
      .def("set_transform", &snh::Simulation::set_transform, py::arg("set"), py::arg("transform"),
           "The set's absolute target transform for the next solve.")
      .def(
          "set_positions",
          [](snh::Simulation& sim, const std::string& name, py::handle xyz) {
            const snh::ConstraintSet* set = find_set(sim, name);
            sim.set_positions(name, to_points(xyz, "positions of set '" + name + "'",
                                              set ? static_cast<py::ssize_t>(set->vertices.size()) : -1));
          },
          py::arg("set"), py::arg("positions"), "Absolute target positions (k, 3) of the set's vertices.")
      .def(
          "set_external_force",
          [](snh::Simulation& sim, py::handle force) {
            sim.set_external_force(optional_xyz(force, "external_force", sim.mesh().vertex_count()));
          },
          py::arg("force"), "Lumped force (n, 3), or None for none.")
      .def(
          "set_body_force", [](snh::Simulation& sim, py::handle f) { sim.set_body_force(to_vec3(f, "body_force")); },
          py::arg("force_per_rest_volume"), "Body force per rest volume (3,).")
      .def(
          "set_state",
          [](snh::Simulation& sim, py::handle x) {
            sim.set_state(to_points(x, "positions", sim.mesh().vertex_count()));
          },
          py::arg("positions"), "Replaces the state (n, 3).")
      .def(
          "set_velocities",
          [](snh::Simulation& sim, py::handle v) {
            sim.set_velocities(optional_xyz(v, "velocities", sim.mesh().vertex_count()));
          },
          py::arg("velocities"), "With dynamics: replaces the velocities (n, 3), or None for zero.")
      .def("restart", &snh::Simulation::restart, "Back to the initial state, callbacks and no force.")
      .def(
          "solve",
          [](snh::Simulation& sim, int load_steps, const py::object& progress, const py::object& on_step) {
            // Always observed, so that Ctrl-C (a pending signal) stops a long solve.
            std::shared_ptr<py::object> held_progress = progress.is_none() ? nullptr : hold(progress);
            const snh::ProgressCallback progress_callback = [held_progress](const snh::NewtonIteration& record) {
              py::gil_scoped_acquire gil;
              if (PyErr_CheckSignals() != 0) throw py::error_already_set();
              return held_progress ? keep_going((*held_progress)(record)) : true;
            };
            snh::StepCallback step_callback;
            if (!on_step.is_none()) {
              auto held = hold(on_step);
              step_callback = [held](int step, const snh::Points& x) {
                py::gil_scoped_acquire gil;
                (*held)(step, xyz_array(x));
              };
            }
            py::gil_scoped_release release;
            return sim.solve(load_steps, progress_callback, step_callback);
          },
          py::arg("load_steps") = 0, py::arg("progress") = py::none(), py::arg("on_step") = py::none(),
          "Moves the constrained vertices to their targets in load_steps (0: the options') and brings the body "
          "to equilibrium. progress(NewtonIteration) is called after each Newton update: return False to cancel "
          "(SolveResult.cancelled). on_step(step, positions) is called after each step. Exceptions raised in "
          "either propagate. Runs without the GIL.")
      .def_property_readonly(
          "positions", [](const snh::Simulation& sim) { return xyz_array(sim.positions()); },
          "Current positions, float64 (n, 3).")
      .def_property_readonly(
          "velocities", [](const snh::Simulation& sim) { return xyz_array(sim.velocities()); },
          "With dynamics: velocities, float64 (n, 3).")
      .def_property_readonly("time", &snh::Simulation::time, "With dynamics: simulated time.")
      .def("fields", &snh::Simulation::fields, "Per-element F, J, stresses and energy density (ElementFields).")
      .def("reactions", &snh::Simulation::reactions,
           "Per constraint set, the force and torque it exerts on the body (Reaction list).")
      .def_property_readonly(
          "applied_force", [](const snh::Simulation& sim) { return xyz_array(sim.applied_force()); },
          "The lumped external force of the last solve's final step, (n, 3).")
      .def_property_readonly(
          "mesh", [](const snh::Simulation& sim) { return snh::Mesh(sim.mesh()); }, "The mesh (a copy).")
      .def_property_readonly(
          "materials", [](const snh::Simulation& sim) { return snh::MaterialMap(sim.materials()); },
          "The MaterialMap (a copy).")
      .def_property_readonly("constraints", &snh::Simulation::constraints, "The constraint sets (copies).")
      .def_property_readonly("device", &snh::Simulation::device, "The OpenCL device (DeviceInfo).")
      .def_property_readonly("tolerance", &snh::Simulation::tolerance, "The absolute residual tolerance.")
      .def_property_readonly("configuration", &snh::Simulation::configuration,
                             "The ResolvedConfiguration: every automatic choice made, with its reason.")
      .def("checkpoint", &snh::Simulation::checkpoint,
           "The full state (SimulationState): positions, velocities, time, friction anchors, constraint targets "
           "and loads. The next solve rebuilds the preconditioner, as after restore, so that both continue "
           "identically.")
      .def(
          "restore",
          [](snh::Simulation& sim, const snh::SimulationState& state) {
            py::gil_scoped_release release;
            sim.restore(state);
          },
          py::arg("state"),
          "Replaces the state by a checkpoint of a simulation built from the same mesh, materials, constraint "
          "sets and options; the solves that follow give bitwise the results the original gave.");
}

void bind_checkpoints(py::module_& m) {
  py::class_<snh::SimulationState>(m, "SimulationState",
                                   "A simulation's full state (Simulation.checkpoint), to restore or to write with "
                                   "write_checkpoint.")
      .def_property_readonly(
          "positions", [](const snh::SimulationState& s) { return xyz_array(s.positions); }, "float64 (n, 3).")
      .def_property_readonly(
          "velocities", [](const snh::SimulationState& s) { return xyz_array(s.velocities); },
          "float64 (n, 3); empty without dynamics.")
      .def_readonly("time", &snh::SimulationState::time, "Simulated time.");
  m.def("write_checkpoint", &snh::write_checkpoint, py::arg("path"), py::arg("state"),
        "Writes a SimulationState to a versioned binary file (doubles bit for bit).");
  m.def("read_checkpoint", &snh::read_checkpoint, py::arg("path"),
        "Reads a checkpoint file; snh.Error names the file and the item for a damaged one.");
}

void bind_field_functions(py::module_& m) {
  m.def(
      "deformation_statistics",
      [](const snh::Mesh& mesh, py::handle x) {
        return snh::deformation_statistics(mesh, to_points(x, "positions", mesh.vertex_count()));
      },
      py::arg("mesh"), py::arg("positions"), "Volume ratio, J range and inverted elements at positions (n, 3).");
  m.def(
      "compute_element_fields",
      [](const snh::Mesh& mesh, const snh::MaterialMap& materials, py::handle x) {
        return snh::compute_element_fields(mesh, materials, to_points(x, "positions", mesh.vertex_count()));
      },
      py::arg("mesh"), py::arg("materials"), py::arg("positions"), "ElementFields at positions (n, 3).");
  m.def(
      "elastic_forces",
      [](const snh::Mesh& mesh, const snh::MaterialMap& materials, py::handle x) {
        return to_array(snh::elastic_forces(mesh, materials, to_points(x, "positions", mesh.vertex_count())));
      },
      py::arg("mesh"), py::arg("materials"), py::arg("positions"), "Elastic nodal forces -dE/dx, (n, 3).");
}

}  // namespace

void bind_simulation(py::module_& m) {
  m.def("list_devices", &snh::list_devices, "Every OpenCL device on this machine (DeviceInfo list).");
  bind_rigid_transform(m);
  bind_constraint_sets(m);
  bind_dynamics_options(m);
  bind_obstacles(m);
  bind_contact_options(m);
  bind_solve_options(m);
  bind_resolved_configuration(m);
  bind_checkpoints(m);  // before Simulation, whose checkpoint() returns a SimulationState
  bind_simulation_class(m);
  bind_field_functions(m);
}

}  // namespace snh_python
