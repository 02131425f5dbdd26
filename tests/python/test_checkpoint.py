"""Checkpoints: a restored simulation continues bit for bit; the boundary surface."""

import numpy as np
import pytest

import snh


def _twisting_bar():
    mesh = snh.make_box_lattice(6, 2, 2, 0.1)
    material = snh.Material.from_youngs_modulus(1e5, 0.45)
    x = mesh.positions
    base = np.flatnonzero(x[:, 0] < 1e-9)
    tip = np.flatnonzero(x[:, 0] > 0.6 - 1e-9)
    sets = [snh.ConstraintSet("base", base), snh.ConstraintSet("tip", tip)]
    options = snh.SolveOptions(body_force=[0, 0, -1000 * 9.81])
    return mesh, material, sets, options


def _frames(sim, first, count):
    out = []
    for frame in range(first, first + count):
        sim.set_transform("tip", snh.RigidTransform.rotation_about([1, 0, 0], 0.2 * frame, [0.6, 0.1, 0.1]))
        result = sim.solve()
        out.append((sim.positions.copy(), [s.newton_iterations for s in result.steps]))
    return out


def test_restored_simulation_continues_bit_for_bit(tmp_path):
    problem = _twisting_bar()
    sim = snh.Simulation(*problem)
    _frames(sim, 1, 2)
    state = sim.checkpoint()
    path = tmp_path / "bar.snhcheckpoint"
    snh.write_checkpoint(str(path), state)
    original = _frames(sim, 3, 2)

    sim.restore(state)
    again = _frames(sim, 3, 2)
    fresh = snh.Simulation(*problem)
    fresh.restore(snh.read_checkpoint(str(path)))
    from_file = _frames(fresh, 3, 2)
    for (x0, n0), (x1, n1), (x2, n2) in zip(original, again, from_file):
        assert n0 == n1 == n2
        assert x0.tobytes() == x1.tobytes() == x2.tobytes()


def test_damaged_checkpoint_names_the_file(tmp_path):
    path = tmp_path / "short.snhcheckpoint"
    path.write_bytes(b"not a checkpoint")
    with pytest.raises(snh.Error, match="short.snhcheckpoint"):
        snh.read_checkpoint(str(path))


def test_checkpoint_of_another_mesh_is_refused():
    sim = snh.Simulation(*_twisting_bar())
    other = snh.Simulation(snh.make_box_lattice(2, 2, 2, 0.1),
                           snh.Material.from_youngs_modulus(1e5, 0.45))
    with pytest.raises(snh.Error):
        other.restore(sim.checkpoint())


def test_boundary_surface_of_a_box_is_closed_and_encloses_its_volume():
    mesh = snh.make_box_lattice(3, 2, 1, 0.5)
    surface, vertices = snh.boundary_surface(mesh)
    assert surface.triangles.shape == (2 * 2 * (3 * 2 + 3 * 1 + 2 * 1), 3)
    assert vertices.dtype == np.int32 and len(vertices) == surface.positions.shape[0]
    assert snh.enclosed_volume(surface) == pytest.approx(1.5 * 1.0 * 0.5, rel=1e-12)
