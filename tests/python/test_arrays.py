"""Arrays in and out: documented shapes and dtypes, and bad input refused."""

import numpy as np
import pytest

import snh
from conftest import status_name


def test_mesh_arrays():
    mesh = snh.make_box_lattice(3, 2, 1, 0.5)
    assert mesh.type == snh.ElementType.hex8
    assert mesh.positions.shape == (24, 3) and mesh.positions.dtype == np.float64
    assert mesh.elements.shape == (6, 8) and mesh.elements.dtype == np.int32
    tets = snh.make_tet_box(1, 1, 1, 1.0)
    assert tets.elements.shape == (6, 4) and tets.type == snh.ElementType.tet4
    again = snh.Mesh(mesh.positions, mesh.elements.astype(np.int64))
    assert np.array_equal(again.positions, mesh.positions)
    assert np.array_equal(again.elements, mesh.elements)
    assert again.type == snh.ElementType.hex8
    assert again.validate() == []
    assert again.volume() == pytest.approx(1.5 * 1.0 * 0.5)


def test_mesh_from_lists_converts_safely():
    mesh = snh.Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], [[0, 1, 2, 3]])
    assert mesh.type == snh.ElementType.tet4
    assert mesh.positions.dtype == np.float64
    assert mesh.volume() == pytest.approx(1 / 6)


def test_selections_are_sorted_int32():
    mesh = snh.make_box_lattice(2, 2, 2, 1.0)
    v = snh.vertices_in_box(mesh, (-0.1, -0.1, -0.1), (0.1, 2.1, 2.1))
    assert v.dtype == np.int32 and v.shape == (9,) and np.all(np.diff(v) > 0)
    assert snh.vertices_on_plane(mesh, (0, 0, 2), (0, 0, 1)).shape == (9,)
    assert snh.vertices_in_sphere(mesh, (1, 1, 1), 0.1).tolist() == [13]
    assert snh.elements_in_box(mesh, (0, 0, 0), (1, 1, 1)).tolist() == [0]
    assert snh.elements_in_sphere(mesh, (0.5, 0.5, 0.5), 0.1).tolist() == [0]


def test_simulation_arrays(bar_problem):
    mesh, material, sets, options = bar_problem
    sim = snh.Simulation(mesh, material, sets, options)
    result = sim.solve()
    n, m = mesh.vertex_count, mesh.element_count
    assert sim.positions.shape == (n, 3) and sim.positions.dtype == np.float64
    assert result.positions.shape == (n, 3)
    assert sim.velocities.shape == (0, 3)
    assert sim.applied_force.shape == (n, 3)
    fields = sim.fields()
    for name in ("deformation_gradient", "pk1", "cauchy"):
        assert getattr(fields, name).shape == (m, 3, 3)
    for name in ("j", "von_mises", "energy_density", "min_j"):
        assert getattr(fields, name).shape == (m,)
    # F is indexed [element, row, column]: J is its determinant for an affine map.
    rest = snh.compute_element_fields(mesh, sim.materials, mesh.positions)
    assert np.allclose(rest.deformation_gradient, np.eye(3))
    stretched = mesh.positions * np.array([2.0, 1.0, 1.0])
    f = snh.compute_element_fields(mesh, sim.materials, stretched).deformation_gradient
    assert np.allclose(f[:, 0, 0], 2.0) and np.allclose(f[:, 1, 1], 1.0)
    reactions = sim.reactions()
    assert [r.name for r in reactions] == ["held", "end"]
    assert len(reactions[0].force) == 3
    assert snh.elastic_forces(mesh, sim.materials, sim.positions).shape == (n, 3)
    assert isinstance(result.history[0], snh.NewtonIteration)
    assert status_name(result.steps[-1].status) == "converged"


BAD_MESHES = [
    (np.zeros((4, 2)), [[0, 1, 2, 3]], "expected shape"),
    (np.zeros((4, 3), dtype=complex), [[0, 1, 2, 3]], "cannot be converted safely"),
    (np.array([["a", "b", "c"]] * 4), [[0, 1, 2, 3]], "cannot be converted safely"),
    ([[0, 0, np.nan], [1, 0, 0], [0, 1, 0], [0, 0, 1]], [[0, 1, 2, 3]], "non-finite"),
    ([[0, 0, np.inf], [1, 0, 0], [0, 1, 0], [0, 0, 1]], [[0, 1, 2, 3]], "non-finite"),
    (np.eye(4, 3), [[0, 1, 2, 4]], "outside [0, 4)"),
    (np.eye(4, 3), [[0, 1, 2, -1]], "index -1"),
    (np.eye(4, 3), [[0.0, 1.0, 2.0, 3.0]], "integer array"),
    (np.eye(4, 3), [[0, 1, 2]], "8 (hex8) or 4 (tet4)"),
    (np.eye(4, 3), [0, 1, 2, 3], "2-D array"),
]


@pytest.mark.parametrize("positions,elements,message", BAD_MESHES)
def test_bad_mesh_arrays_raise_value_error(positions, elements, message):
    with pytest.raises(ValueError, match=message.replace("[", r"\[").replace("(", r"\(").replace(")", r"\)")):
        snh.Mesh(positions, elements)


def test_bad_simulation_arrays_raise_value_error(bar_problem):
    mesh, material, sets, options = bar_problem
    sim = snh.Simulation(mesh, material, sets, options)
    n = mesh.vertex_count
    with pytest.raises(ValueError, match="expected shape"):
        sim.set_state(np.zeros((n - 1, 3)))
    with pytest.raises(ValueError, match="non-finite"):
        sim.set_state(np.full((n, 3), np.nan))
    with pytest.raises(ValueError, match="expected shape"):
        sim.set_external_force(np.zeros(3 * n))
    with pytest.raises(ValueError, match="expected shape"):
        sim.set_positions("end", np.zeros((1, 3)))
    with pytest.raises(ValueError, match="integer array"):
        snh.ConstraintSet("x", [0.5, 1.5])
    with pytest.raises(ValueError, match="negative"):
        snh.ConstraintSet("x", [-1])
    with pytest.raises(ValueError, match="expected shape"):
        snh.SolveOptions(initial_positions=np.zeros((n, 2)))


def test_simulation_inputs_checked_against_the_mesh(bar_problem):
    mesh, material, sets, options = bar_problem
    n = mesh.vertex_count
    with pytest.raises(ValueError, match=rf"constraint set 'far': vertex {n} at position 1 is outside \[0, {n}\)"):
        snh.Simulation(mesh, material, [snh.ConstraintSet("far", [0, n])])
    options.initial_positions = np.zeros((n + 1, 3))
    with pytest.raises(ValueError, match="SolveOptions.initial_positions"):
        snh.Simulation(mesh, material, sets, options)


def test_nested_options_set_in_place():
    options = snh.SolveOptions(dynamics=snh.DynamicsOptions(time_step=0.01, density=1.0))
    options.contact.stiffness = 5.0
    options.dynamics.substeps = 3
    assert options.contact.stiffness == 5.0
    assert options.dynamics.substeps == 3
