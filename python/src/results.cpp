// What the engine reports back: solver records, results, profiles, element
// fields and reactions, as read-only Python objects. Every result field is
// bound here and nowhere else.
#include "common.h"
#include "snh/configuration.h"
#include "snh/fields.h"
#include "snh/frames.h"
#include "snh/scene.h"
#include "snh/simulation.h"

namespace snh_python {

namespace {

void bind_device_info(py::module_& m) {
  py::class_<snh::DeviceInfo>(m, "DeviceInfo", "An OpenCL device.")
      .def_readonly("platform", &snh::DeviceInfo::platform, "Platform name.")
      .def_readonly("name", &snh::DeviceInfo::name, "Device name.")
      .def_readonly("version", &snh::DeviceInfo::version, "OpenCL version string.")
      .def_readonly("is_gpu", &snh::DeviceInfo::is_gpu, "Whether the device is a GPU.")
      .def_readonly("has_fp64", &snh::DeviceInfo::has_fp64, "Whether it supports double precision.")
      .def_readonly("compute_units", &snh::DeviceInfo::compute_units, "Compute units.")
      .def_readonly("global_memory_bytes", &snh::DeviceInfo::global_memory_bytes, "Global memory in bytes.")
      .def("__repr__", [](const snh::DeviceInfo& d) { return "DeviceInfo('" + d.platform + " / " + d.name + "')"; });
}

void bind_status_enums(py::module_& m) {
  auto step_status = py::enum_<snh::StepStatus>(m, "StepStatus", "How a load or time step's Newton solve ended.")
                         .value("none", snh::StepStatus::none)
                         .value("converged", snh::StepStatus::converged)
                         .value("max_newton_iterations", snh::StepStatus::max_newton_iterations)
                         .value("line_search_failed", snh::StepStatus::line_search_failed)
                         .value("stagnated", snh::StepStatus::stagnated)
                         .value("non_finite_state", snh::StepStatus::non_finite_state)
                         .value("cancelled", snh::StepStatus::cancelled)
                         .value("inverted_elements", snh::StepStatus::inverted_elements);
  step_status.attr("__str__") =
      py::cpp_function([](snh::StepStatus s) { return std::string(snh::to_string(s)); }, py::is_method(step_status));
  auto cg_stop = py::enum_<snh::CgStop>(m, "CgStop", "Why a Newton iteration's conjugate gradient solve stopped.")
                     .value("none", snh::CgStop::none)
                     .value("converged", snh::CgStop::converged)
                     .value("max_iterations", snh::CgStop::max_iterations)
                     .value("negative_curvature", snh::CgStop::negative_curvature)
                     .value("breakdown", snh::CgStop::breakdown);
  cg_stop.attr("__str__") =
      py::cpp_function([](snh::CgStop s) { return std::string(snh::to_string(s)); }, py::is_method(cg_stop));
  auto recovery_action =
      py::enum_<snh::RecoveryAction>(m, "RecoveryAction", "What the Newton solver did to get past trouble.")
          .value("cg_breakdown_steepest_descent", snh::RecoveryAction::cg_breakdown_steepest_descent)
          .value("non_finite_direction_steepest_descent", snh::RecoveryAction::non_finite_direction_steepest_descent)
          .value("non_descent_steepest_descent", snh::RecoveryAction::non_descent_steepest_descent)
          .value("cg_breakdown_partial_direction", snh::RecoveryAction::cg_breakdown_partial_direction)
          .value("line_search_steepest_descent", snh::RecoveryAction::line_search_steepest_descent)
          .value("line_search_steepest_descent_failed", snh::RecoveryAction::line_search_steepest_descent_failed)
          .value("shorter_step", snh::RecoveryAction::shorter_step)
          .value("extended_step", snh::RecoveryAction::extended_step)
          .value("double_fallback", snh::RecoveryAction::double_fallback)
          .value("inverted_equilibrium_perturbed", snh::RecoveryAction::inverted_equilibrium_perturbed)
          .value("inverted_equilibrium_kept", snh::RecoveryAction::inverted_equilibrium_kept);
  recovery_action.attr("__str__") = py::cpp_function(
      [](snh::RecoveryAction a) { return std::string(snh::to_string(a)); }, py::is_method(recovery_action));
}

void bind_newton_records(py::module_& m) {
  py::class_<snh::Recovery>(m, "Recovery", "One recovery of a Newton iteration (read-only).")
      .def_readonly("action", &snh::Recovery::action)
      .def_readonly("factor", &snh::Recovery::factor, "extended_step: the step's factor.")
      .def_readonly("float_status", &snh::Recovery::float_status, "double_fallback: how the float solve ended.")
      .def("__str__", [](const snh::Recovery& r) { return snh::to_string(r); })
      .def("__repr__", [](const snh::Recovery& r) { return "Recovery('" + snh::to_string(r) + "')"; });

  py::class_<snh::NewtonIteration>(m, "NewtonIteration", "One Newton iteration's record (read-only).")
      .def_readonly("step", &snh::NewtonIteration::step, "Load or time step.")
      .def_readonly("iteration", &snh::NewtonIteration::iteration, "Iteration within the step.")
      .def_readonly("residual_norm", &snh::NewtonIteration::residual_norm, "Residual before this update.")
      .def_readonly("energy", &snh::NewtonIteration::energy, "Energy.")
      .def_readonly("step_length", &snh::NewtonIteration::step_length, "Line-search alpha accepted (0 if none).")
      .def_readonly("cg_iterations", &snh::NewtonIteration::cg_iterations, "CG iterations of this solve.")
      .def_readonly("cg_relative_residual", &snh::NewtonIteration::cg_relative_residual, "CG's relative residual.")
      .def_readonly("cg_stop", &snh::NewtonIteration::cg_stop, "Why CG stopped (CgStop).")
      .def_readonly("steepest_descent", &snh::NewtonIteration::steepest_descent,
                    "Whether the preconditioned steepest descent replaced CG's direction.")
      .def_readonly("projected", &snh::NewtonIteration::projected, "Whether the Hessian was the PSD projection.")
      .def_readonly("seconds", &snh::NewtonIteration::seconds, "Wall time since the solve began.")
      .def_readonly("recovery", &snh::NewtonIteration::recovery,
                    "What the solver did to get past trouble: a list of Recovery, empty if nothing.")
      .def_property_readonly(
          "recovery_text", [](const snh::NewtonIteration& r) { return snh::to_string(r.recovery); },
          "The recoveries as text (the names of the JSON output), or ''.")
      .def("__repr__", [](const snh::NewtonIteration& r) {
        return "NewtonIteration(step=" + std::to_string(r.step) + ", iteration=" + std::to_string(r.iteration) +
               ", residual_norm=" + std::to_string(r.residual_norm) + ")";
      });
}

void bind_solve_profile(py::module_& m) {
  py::class_<snh::SolveProfile>(m, "SolveProfile", "Where a solve's time went, in seconds (read-only).")
      .def_readonly("linearization", &snh::SolveProfile::linearization)
      .def_readonly("products", &snh::SolveProfile::products)
      .def_readonly("preconditioner_setup", &snh::SolveProfile::preconditioner_setup)
      .def_readonly("preconditioner_apply", &snh::SolveProfile::preconditioner_apply)
      .def_readonly("cg_vector_work", &snh::SolveProfile::cg_vector_work)
      .def_readonly("line_search_energies", &snh::SolveProfile::line_search_energies)
      .def_readonly("transfers", &snh::SolveProfile::transfers)
      .def_readonly("other", &snh::SolveProfile::other)
      .def_readonly("kernels", &snh::SolveProfile::kernels, "Seconds per OpenCL kernel, by name.")
      .def_readonly("total", &snh::SolveProfile::total, "Wall time less the callbacks.")
      .def_readonly("kernel_launches", &snh::SolveProfile::kernel_launches, "Kernels queued on the device.")
      .def_readonly("blocking_readbacks", &snh::SolveProfile::blocking_readbacks,
                    "Reads from the device the host waited for.")
      .def_readonly("bytes_to_host", &snh::SolveProfile::bytes_to_host)
      .def_readonly("bytes_to_device", &snh::SolveProfile::bytes_to_device)
      .def_readonly("cg_iterations_past_convergence", &snh::SolveProfile::cg_iterations_past_convergence);
}

void bind_solve_results(py::module_& m) {
  py::class_<snh::StepResult>(m, "StepResult", "One load or time step's outcome (read-only).")
      .def_readonly("step", &snh::StepResult::step)
      .def_readonly("newton_iterations", &snh::StepResult::newton_iterations)
      .def_readonly("cg_iterations", &snh::StepResult::cg_iterations)
      .def_readonly("converged", &snh::StepResult::converged)
      .def_readonly("residual_norm", &snh::StepResult::residual_norm)
      .def_readonly("status", &snh::StepResult::status, "A StepStatus; str() gives its name.")
      .def_readonly("seconds", &snh::StepResult::seconds)
      .def_readonly("precision_used", &snh::StepResult::precision_used,
                    "The Precision of the solve this result reports.")
      .def_readonly("fallback", &snh::StepResult::fallback, "What fallback_to_double did, or ''.")
      .def_readonly("profile", &snh::StepResult::profile)
      .def_readonly("time", &snh::StepResult::time, "With dynamics: simulated time at the step's end.")
      .def_readonly("contacts", &snh::StepResult::contacts)
      .def_readonly("max_penetration", &snh::StepResult::max_penetration)
      .def_readonly("self_contacts", &snh::StepResult::self_contacts)
      .def_readonly("max_self_penetration", &snh::StepResult::max_self_penetration)
      .def_readonly("preconditioner_builds", &snh::StepResult::preconditioner_builds)
      .def_readonly("min_j", &snh::StepResult::min_j, "The smallest J at the step's end.")
      .def_readonly("inverted_elements", &snh::StepResult::inverted_elements, "Elements with J <= 0 at the step's end.")
      .def_readonly("warnings", &snh::StepResult::warnings, "Damage the step shows (empty: a clean step).")
      .def("__repr__", [](const snh::StepResult& s) {
        return "StepResult(step=" + std::to_string(s.step) + ", status='" + snh::to_string(s.status) + "')";
      });

  py::class_<snh::SolveResult>(m, "SolveResult", "A solve's outcome (read-only).")
      .def_property_readonly(
          "positions", [](const snh::SolveResult& r) { return xyz_array(r.positions); },
          "Positions after the last step, float64 (n, 3).")
      .def_readonly("history", &snh::SolveResult::history, "NewtonIteration records.")
      .def_readonly("steps", &snh::SolveResult::steps, "StepResult per step.")
      .def_readonly("converged", &snh::SolveResult::converged)
      .def_readonly("cancelled", &snh::SolveResult::cancelled, "The progress callback stopped the solve.")
      .def_readonly("final_residual_norm", &snh::SolveResult::final_residual_norm)
      .def_readonly("tolerance", &snh::SolveResult::tolerance, "The absolute residual norm Newton stopped at.")
      .def_readonly("volume_ratio", &snh::SolveResult::volume_ratio)
      .def_readonly("min_j", &snh::SolveResult::min_j)
      .def_readonly("max_j", &snh::SolveResult::max_j)
      .def_readonly("inverted_elements", &snh::SolveResult::inverted_elements)
      .def_readonly("seconds", &snh::SolveResult::seconds)
      .def_readonly("profile", &snh::SolveResult::profile)
      .def_readonly("device_memory_bytes", &snh::SolveResult::device_memory_bytes)
      .def_readonly("device", &snh::SolveResult::device)
      .def_readonly("kernel_specialization", &snh::SolveResult::kernel_specialization)
      .def_readonly("product", &snh::SolveResult::product)
      .def_readonly("preconditioner", &snh::SolveResult::preconditioner)
      .def_readonly("product_precision", &snh::SolveResult::product_precision)
      .def_readonly("multigrid_smoother_degree", &snh::SolveResult::multigrid_smoother_degree)
      .def_readonly("multigrid_chebyshev", &snh::SolveResult::multigrid_chebyshev)
      .def_readonly("multigrid_float_cycle", &snh::SolveResult::multigrid_float_cycle)
      .def_readonly("warnings", &snh::SolveResult::warnings)
      .def("__repr__", [](const snh::SolveResult& r) {
        return std::string("SolveResult(converged=") + (r.converged ? "True" : "False") +
               ", cancelled=" + (r.cancelled ? "True" : "False") + ", steps=" + std::to_string(r.steps.size()) +
               ", newton_iterations=" + std::to_string(r.history.size()) + ")";
      });
}

void bind_field_results(py::module_& m) {
  py::class_<snh::DeformationStatistics>(m, "DeformationStatistics", "Volume ratio and J range of positions.")
      .def_readonly("volume_ratio", &snh::DeformationStatistics::volume_ratio)
      .def_readonly("min_j", &snh::DeformationStatistics::min_j)
      .def_readonly("max_j", &snh::DeformationStatistics::max_j)
      .def_readonly("inverted_elements", &snh::DeformationStatistics::inverted_elements);

  py::class_<snh::ElementFields>(m, "ElementFields",
                                 "Per-element fields averaged over each element's quadrature points (read-only). "
                                 "Tensors are (m, 3, 3) indexed [element, row, column]; scalars (m,).")
      .def_property_readonly(
          "deformation_gradient", [](const snh::ElementFields& f) { return matrices_array(f.deformation_gradient); },
          "F, (m, 3, 3).")
      .def_property_readonly(
          "j", [](const snh::ElementFields& f) { return copy_array(f.j, {py::ssize_t(f.j.size())}); },
          "det F (deformed / rest element volume), (m,).")
      .def_property_readonly(
          "pk1", [](const snh::ElementFields& f) { return matrices_array(f.pk1); },
          "First Piola-Kirchhoff stress P, (m, 3, 3).")
      .def_property_readonly(
          "cauchy", [](const snh::ElementFields& f) { return matrices_array(f.cauchy); },
          "Cauchy stress averaged over the deformed element, (m, 3, 3); NaN where J <= 0.")
      .def_property_readonly(
          "von_mises",
          [](const snh::ElementFields& f) { return copy_array(f.von_mises, {py::ssize_t(f.von_mises.size())}); },
          "von Mises stress of `cauchy`, (m,); NaN where J <= 0.")
      .def_property_readonly(
          "energy_density",
          [](const snh::ElementFields& f) {
            return copy_array(f.energy_density, {py::ssize_t(f.energy_density.size())});
          },
          "psi per rest volume, (m,).")
      .def_property_readonly(
          "min_j", [](const snh::ElementFields& f) { return copy_array(f.min_j, {py::ssize_t(f.min_j.size())}); },
          "Smallest det F over each element's points, (m,).");

  py::class_<snh::Reaction>(m, "Reaction", "The force and torque a constraint set exerts on the body (read-only).")
      .def_readonly("name", &snh::Reaction::name)
      .def_readonly("force", &snh::Reaction::force)
      .def_readonly("torque", &snh::Reaction::torque)
      .def_readonly("about", &snh::Reaction::about, "The torque's reference point.")
      .def("__repr__", [](const snh::Reaction& r) { return "Reaction('" + r.name + "')"; });
}

void bind_frame_record(py::module_& m) {
  py::class_<snh::FrameRecord>(m, "FrameRecord", "One animation frame's solve (read-only).")
      .def_readonly("frame", &snh::FrameRecord::frame)
      .def_readonly("time", &snh::FrameRecord::time)
      .def_readonly("converged", &snh::FrameRecord::converged)
      .def_readonly("status", &snh::FrameRecord::status, "The last load step's status.")
      .def_readonly("newton_iterations", &snh::FrameRecord::newton_iterations)
      .def_readonly("cg_iterations", &snh::FrameRecord::cg_iterations)
      .def_readonly("residual_norm", &snh::FrameRecord::residual_norm)
      .def_readonly("seconds", &snh::FrameRecord::seconds)
      .def_readonly("profile", &snh::FrameRecord::profile)
      .def_readonly("volume_ratio", &snh::FrameRecord::volume_ratio)
      .def_readonly("min_j", &snh::FrameRecord::min_j)
      .def_readonly("inverted_elements", &snh::FrameRecord::inverted_elements)
      .def_readonly("warnings", &snh::FrameRecord::warnings, "Damage the frame shows (empty: a clean frame).")
      .def_readonly("reactions", &snh::FrameRecord::reactions, "Reaction per constraint set at the frame's end.")
      .def_readonly("history", &snh::FrameRecord::history);
}

}  // namespace

// Registered by bind_simulation, between SolveOptions (which it holds) and
// Simulation (which returns it).
void bind_resolved_configuration(py::module_& m) {
  py::class_<snh::ResolvedSetting>(m, "ResolvedSetting", "One resolved setting: its name, value and reason.")
      .def_readonly("name", &snh::ResolvedSetting::name, "The option's name (as in scene files).")
      .def_readonly("value", &snh::ResolvedSetting::value, "Its value as printed.")
      .def_readonly("reason", &snh::ResolvedSetting::reason, "'given', 'default', or the rule that chose it.")
      .def("__repr__", [](const snh::ResolvedSetting& s) {
        return "ResolvedSetting('" + s.name + "', '" + s.value + "', '" + s.reason + "')";
      });
  py::class_<snh::ResolvedConfiguration>(
      m, "ResolvedConfiguration", "The options with every automatic choice made, each with its reason (read-only).")
      .def_readonly("options", &snh::ResolvedConfiguration::options, "The resolved SolveOptions.")
      .def_readonly("barrier_stiffness", &snh::ResolvedConfiguration::barrier_stiffness,
                    "Barrier self-contact's kappa (0 without the barrier).")
      .def_readonly("absolute_tolerance", &snh::ResolvedConfiguration::absolute_tolerance,
                    "The stopping test's absolute part.")
      .def_readonly("relative_tolerance", &snh::ResolvedConfiguration::relative_tolerance,
                    "The stopping test's relative part.")
      .def_readonly("settings", &snh::ResolvedConfiguration::settings, "Every setting, in a fixed order.")
      .def("setting", &snh::ResolvedConfiguration::setting, py::arg("name"),
           "The setting named `name`; raises snh.Error when there is none.")
      .def(
          "as_dict",
          [](const snh::ResolvedConfiguration& c) {
            py::dict d;
            for (const snh::ResolvedSetting& s : c.settings) d[py::str(s.name)] = py::make_tuple(s.value, s.reason);
            return d;
          },
          "{name: (value, reason)} in order.");
}

void bind_results(py::module_& m) {
  bind_device_info(m);
  bind_status_enums(m);
  bind_newton_records(m);
  bind_solve_profile(m);
  bind_solve_results(m);
  bind_field_results(m);
  bind_frame_record(m);
}

// After SolveOptions (simulation.cpp), which a SceneRun holds.
void bind_scene_results(py::module_& m) {
  py::class_<snh::SceneProgress>(m, "SceneProgress", "A scene run's progress after a step or frame (read-only).")
      .def_readonly("frame", &snh::SceneProgress::frame, "True for a rig's frame, False for a load step.")
      .def_readonly("index", &snh::SceneProgress::index, "1-based.")
      .def_readonly("count", &snh::SceneProgress::count)
      .def_readonly("newton_iterations", &snh::SceneProgress::newton_iterations)
      .def_readonly("cg_iterations", &snh::SceneProgress::cg_iterations)
      .def_readonly("residual_norm", &snh::SceneProgress::residual_norm)
      .def_readonly("status", &snh::SceneProgress::status)
      .def_readonly("seconds", &snh::SceneProgress::seconds)
      .def_readonly("time", &snh::SceneProgress::time)
      .def_readonly("min_j", &snh::SceneProgress::min_j);

  py::class_<snh::SceneStep>(m, "SceneStep", "What a scene run measured after a step or frame (read-only).")
      .def_property_readonly(
          "shape_defined", [](const snh::SceneStep& s) { return s.shape.defined; }, "Whether the shape was measured.")
      .def_property_readonly("volume_ratio", [](const snh::SceneStep& s) { return s.shape.volume_ratio; })
      .def_property_readonly("min_j", [](const snh::SceneStep& s) { return s.shape.min_j; })
      .def_property_readonly("rigid_fit_rms", [](const snh::SceneStep& s) { return s.shape.rigid_fit_rms; })
      .def_property_readonly("rigid_fit_rms_relative",
                             [](const snh::SceneStep& s) { return s.shape.rigid_fit_rms_relative; })
      .def_readonly("self_contact_measured", &snh::SceneStep::self_contact_measured)
      .def_readonly("unresolved_self_contacts", &snh::SceneStep::unresolved_self_contacts)
      .def_readonly("max_self_penetration", &snh::SceneStep::max_self_penetration)
      .def_readonly("reactions", &snh::SceneStep::reactions, "Reaction list, or None.");

  py::class_<snh::SceneRun>(m, "SceneRun", "A scene run's outcome (read-only).")
      .def_readonly("options", &snh::SceneRun::options, "The SolveOptions as run.")
      .def_readonly("result", &snh::SceneRun::result, "The SolveResult (load or time steps).")
      .def_readonly("steps", &snh::SceneRun::steps, "SceneStep per step or frame.")
      .def_readonly("frames", &snh::SceneRun::frames, "FrameRecord per frame of a rig.")
      .def_readonly("device", &snh::SceneRun::device)
      .def_readonly("resolved", &snh::SceneRun::resolved, "The ResolvedConfiguration it ran with.")
      .def_readonly("converged", &snh::SceneRun::converged, "Every step or frame converged.")
      .def_readonly("warnings", &snh::SceneRun::warnings);
}

}  // namespace snh_python
