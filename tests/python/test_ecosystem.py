"""meshio and PyVista conversions, and mesh and ParaView files."""

import numpy as np
import pytest

import snh


def test_meshio_round_trip(bar_problem):
    meshio = pytest.importorskip("meshio")
    mesh, material, sets, options = bar_problem
    sim = snh.Simulation(mesh, material, sets, options)
    sim.solve()
    m = snh.to_meshio(mesh, sim.positions, sim.fields())
    assert isinstance(m, meshio.Mesh)
    assert m.cells[0].type == "hexahedron"
    assert m.cell_data["F"][0].shape == (mesh.element_count, 9)
    back = snh.from_meshio(m)
    assert np.array_equal(back.elements, mesh.elements)
    assert np.array_equal(back.positions, sim.positions)
    assert {a.name for a in back.cell_arrays} >= {"J", "von_mises"}


def test_written_files_read_back(tmp_path):
    meshio = pytest.importorskip("meshio")
    mesh = snh.make_tet_box(2, 1, 1, 0.5)
    for ext in (".msh", ".vtk", ".vtu", ".mesh"):
        path = str(tmp_path / ("bar" + ext))
        snh.write_mesh(path, mesh)
        again = snh.read_mesh(path)
        assert np.array_equal(again.positions, mesh.positions)
        assert np.array_equal(again.elements, mesh.elements)
    path = str(tmp_path / "fields.vtu")
    fields = snh.compute_element_fields(mesh, snh.uniform_material(mesh, snh.Material.from_youngs_modulus(1e4, 0.4)),
                                        mesh.positions)
    snh.write_vtu(path, mesh, point_fields={"u": np.zeros((mesh.vertex_count, 3))},
                  cell_fields={"F": fields.deformation_gradient, "J": fields.j})
    m = meshio.read(path)
    assert m.cell_data["F"][0].shape == (mesh.element_count, 9)
    assert np.allclose(m.cell_data["F"][0], np.eye(3).reshape(1, 9))


def test_pyvista_when_installed():
    pytest.importorskip("pyvista")
    grid = snh.to_pyvista(snh.make_box_lattice(1, 1, 1, 1.0))
    assert grid.n_cells == 1
