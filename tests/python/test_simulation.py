"""Simulation: callbacks, cancelling, exceptions, options and state."""

import math

import numpy as np
import pytest

import snh
from conftest import status_name


def test_progress_callback_cancels(bar_problem):
    mesh, material, sets, options = bar_problem
    sim = snh.Simulation(mesh, material, sets, options)
    seen = []

    def progress(record):
        seen.append(record.iteration)
        return len(seen) < 3

    result = sim.solve(progress=progress)
    assert result.cancelled and not result.converged
    assert len(seen) == 3
    assert status_name(result.steps[-1].status) == "cancelled"


def test_exception_in_progress_propagates(bar_problem):
    class Stop(Exception):
        pass

    def progress(record):
        raise Stop("from the callback")

    sim = snh.Simulation(*bar_problem)
    with pytest.raises(Stop, match="from the callback"):
        sim.solve(progress=progress)


def test_exception_in_motion_propagates(bar_problem):
    mesh, material, sets, options = bar_problem

    def motion(t):
        raise KeyError("no such frame")

    sets[1].motion = motion
    sim = snh.Simulation(mesh, material, sets, options)
    with pytest.raises(KeyError, match="no such frame"):
        sim.solve()


def test_engine_errors_are_snh_errors(bar_problem):
    mesh, material, sets, options = bar_problem
    sim = snh.Simulation(mesh, material, sets, options)
    with pytest.raises(snh.Error, match="no constraint set named 'nope'"):
        sim.set_transform("nope", snh.RigidTransform())
    with pytest.raises(RuntimeError):
        snh.Simulation(mesh, material, [snh.ConstraintSet("a", [0]), snh.ConstraintSet("a", [1])])
    with pytest.raises(snh.Error):
        snh.read_mesh("/nonexistent/mesh.msh")


def test_options_keywords_and_names():
    options = snh.SolveOptions(precision="float", load_steps=3, preconditioner="block-jacobi")
    assert options.precision == snh.Precision.single
    assert options.preconditioner == snh.Preconditioner.block_jacobi
    assert options.load_steps == 3
    assert options.external_force is None
    with pytest.raises(AttributeError):
        snh.SolveOptions(no_such_option=1)
    options.dynamics = snh.DynamicsOptions(time_step=0.01, density=1000.0, damping_mass=0.5)
    assert options.dynamics.damping_mass == 0.5
    options.obstacles = [snh.Obstacle.plane((0, 0, -1), (0, 0, 1))]
    assert options.obstacles[0].type == snh.ObstacleType.plane


def test_unset_options_are_none():
    # Unset (the library chooses) is None; 'automatic' names it in strings.
    options = snh.SolveOptions()
    assert options.preconditioner is None
    assert options.product is None
    assert options.product_precision is None
    assert options.contact.self_stiffness is None
    assert options.contact.friction_slip is None
    assert not hasattr(snh.Preconditioner, "automatic")
    options.preconditioner = "multigrid"
    options.product = snh.ProductVariant.cached
    assert options.preconditioner == snh.Preconditioner.multigrid
    options.preconditioner = "automatic"
    options.product = None
    assert options.preconditioner is None and options.product is None
    contact = snh.ContactOptions(friction_slip=0.01)
    assert contact.friction_slip == 0.01
    contact.friction_slip = None
    assert contact.friction_slip is None
    assert snh.MaterialOptions().barrier is None
    assert snh.SceneParameters().resolution is None
    assert snh.CharacterReadOptions().last_frame is None
    automatic = snh.StableNeoHookean.from_youngs_modulus(1.0, 0.45, None)
    assert automatic.barrier == snh.StableNeoHookean.from_youngs_modulus(1.0, 0.45).barrier


def test_resolved_options_are_set(bar_problem):
    mesh, material, sets, options = bar_problem
    sim = snh.Simulation(mesh, material, sets, options)
    resolved = sim.configuration.options
    assert resolved.preconditioner is not None and resolved.product is not None
    result = sim.solve()
    assert result.preconditioner == resolved.preconditioner
    if result.preconditioner != snh.Preconditioner.multigrid:
        assert result.multigrid_smoother_degree is None and result.multigrid_chebyshev is None


def test_frame_by_frame_targets(bar_problem):
    mesh, material, sets, options = bar_problem
    sets[1].motion = None
    sim = snh.Simulation(mesh, material, sets, options)
    sim.set_transform("end", snh.RigidTransform.translation_by((0.1, 0, 0)))
    assert sim.solve().converged
    end = sets[1].vertices
    assert np.allclose(sim.positions[end], mesh.positions[end] + [0.1, 0, 0])
    target = mesh.positions[end] + [0.2, 0, 0]
    sim.set_positions("end", target)
    assert sim.solve(load_steps=1).converged
    assert np.allclose(sim.positions[end], target)
    sim.restart()
    assert np.array_equal(sim.positions, mesh.positions)
    sim.set_state(mesh.positions * 1.01)
    assert np.allclose(sim.positions, mesh.positions * 1.01)


def test_rigid_transform():
    t = snh.RigidTransform.rotation_about((0, 0, 1), math.pi / 2, (1, 0, 0))
    assert t.rotation.shape == (3, 3)
    assert np.allclose(t.rotation @ [1, 0, 0], [0, 1, 0])
    assert np.allclose(t.apply((2, 0, 0)), (1, 1, 0))
    assert t.apply(np.zeros((5, 3))).shape == (5, 3)
    u = snh.RigidTransform(rotation=t.rotation, translation=(1, 2, 3))
    assert np.array_equal(u.rotation, t.rotation)


def test_dynamics_time_and_velocities():
    mesh = snh.make_box_lattice(2, 1, 1, 0.5)
    held = snh.ConstraintSet("held", snh.vertices_on_plane(mesh, (0, 0, 0), (1, 0, 0)))
    options = snh.SolveOptions(
        dynamics=snh.DynamicsOptions(time_step=0.01, density=1000.0), body_force=(0, 0, -9810.0), load_steps=2
    )
    sim = snh.Simulation(mesh, snh.Material.from_youngs_modulus(1e5, 0.4), [held], options)
    sim.solve()
    assert sim.time == pytest.approx(0.02)
    assert sim.velocities.shape == (mesh.vertex_count, 3)
    assert sim.velocities[:, 2].min() < 0


def test_regions():
    mesh = snh.make_box_lattice(2, 1, 1, 1.0)
    soft = snh.Material.from_youngs_modulus(1e3, 0.4)
    stiff = snh.Material.from_youngs_modulus(1e5, 0.4, model="snh")
    region = snh.MaterialRegion("stiff", snh.elements_in_box(mesh, (1, 0, 0), (2, 1, 1)), stiff)
    materials = snh.make_material_map(mesh, soft, [region])
    assert materials.names == ["base", "stiff"]
    assert materials.element_material.tolist() == [0, 1]
    held = snh.ConstraintSet("held", snh.vertices_on_plane(mesh, (0, 0, 0), (1, 0, 0)))
    sim = snh.Simulation(mesh, materials, [held], snh.SolveOptions(body_force=(0, 0, -10)))
    assert sim.solve().converged


def test_obstacle_contact():
    block = snh.make_box_lattice(2, 2, 2, 0.5)
    top = snh.ConstraintSet(
        "top",
        snh.vertices_on_plane(block, (0, 0, 1), (0, 0, 1)),
        motion=lambda t: snh.RigidTransform.translation_by((0, 0, -0.3 * t)),
    )
    floor = snh.Obstacle.plane((0, 0, -0.1), (0, 0, 1))
    options = snh.SolveOptions(
        load_steps=2, obstacles=[floor], contact=snh.ContactOptions(stiffness=1e5, thickness=0.01)
    )
    sim = snh.Simulation(block, snh.Material.from_youngs_modulus(1e4, 0.4), [top], options)
    result = sim.solve()
    assert result.converged
    assert result.steps[-1].contacts > 0
    assert sim.positions[:, 2].min() > -0.1 - 0.05


def test_device_is_selectable(bar_problem):
    mesh, material, sets, options = bar_problem
    options.device = "no such device anywhere"
    with pytest.raises(snh.Error):
        snh.Simulation(mesh, material, sets, options)
    assert snh.list_devices()


def test_interrupt_stops_a_long_solve(bar_problem):
    import _thread
    import threading

    sim = snh.Simulation(*bar_problem)
    timer = threading.Timer(0.2, _thread.interrupt_main)
    with pytest.raises(KeyboardInterrupt):
        timer.start()
        sim.solve(load_steps=400)
    timer.join()


def test_simulation_mesh_and_materials_are_copies(bar_problem):
    sim = snh.Simulation(*bar_problem)
    mesh = sim.mesh
    mesh.positions = mesh.positions + 1.0
    assert np.array_equal(sim.mesh.positions, bar_problem[0].positions)
    materials = sim.materials
    materials.names = ["changed"]
    assert sim.materials.names == ["base"]


def test_targets_and_step_callbacks(bar_problem):
    mesh, material, sets, options = bar_problem
    end = sets[1].vertices
    rest = mesh.positions[end]
    sets[1] = snh.ConstraintSet("end", end, targets=lambda t: rest + [0.1 * t, 0, 0])
    sim = snh.Simulation(mesh, material, sets, options)
    steps = []
    result = sim.solve(on_step=lambda step, x: steps.append((step, x.shape)))
    assert result.converged
    assert steps == [(1, (mesh.vertex_count, 3)), (2, (mesh.vertex_count, 3))]
    assert np.allclose(sim.positions[end], rest + [0.1, 0, 0])


def test_wrong_targets_shape_is_a_value_error(bar_problem):
    mesh, material, sets, options = bar_problem
    sets[1] = snh.ConstraintSet("end", sets[1].vertices, targets=lambda t: np.zeros((1, 3)))
    sim = snh.Simulation(mesh, material, sets, options)
    with pytest.raises(ValueError, match="targets: expected shape"):
        sim.solve()


def test_moving_obstacle():
    block = snh.make_box_lattice(2, 2, 1, 0.5)
    held = snh.ConstraintSet("held", snh.vertices_on_plane(block, (0, 0, 0.5), (0, 0, 1)))
    calls = []

    def rise(t):
        calls.append(t)
        return snh.RigidTransform.translation_by((0, 0, 0.15 * t))

    floor = snh.Obstacle.plane((0, 0, -0.1), (0, 0, 1), motion=rise)
    options = snh.SolveOptions(
        load_steps=2, obstacles=[floor], contact=snh.ContactOptions(stiffness=1e5, thickness=0.01)
    )
    sim = snh.Simulation(block, snh.Material.from_youngs_modulus(1e4, 0.4), [held], options)
    result = sim.solve()
    assert result.converged and calls
    assert result.steps[-1].contacts > 0


def test_configuration_reports_each_choice_and_the_run_uses_it(bar_problem):
    mesh, material, sets, options = bar_problem
    sim = snh.Simulation(mesh, material, sets, options)
    config = sim.configuration
    names = [s.name for s in config.settings]
    assert "preconditioner" in names and "absolute_tolerance" in names
    assert all(s.value and s.reason for s in config.settings)
    chosen = config.as_dict()
    assert chosen["preconditioner"][0] == config.setting("preconditioner").value
    result = sim.solve()
    assert result.preconditioner == config.options.preconditioner
    assert result.tolerance == config.absolute_tolerance
    with pytest.raises(snh.Error, match="no setting named"):
        config.setting("no_such_setting")
