"""Conversions to and from meshio and PyVista, imported only when used."""

from __future__ import annotations

from typing import Any, Mapping, Optional

import numpy as np

from ._snh import ElementFields, ElementType, Mesh

_MESHIO_CELL = {ElementType.hex8: "hexahedron", ElementType.tet4: "tetra"}


def _cell_data(mesh: Mesh, fields: Any) -> dict:
    """Per-element arrays as meshio cell data (one block)."""
    if fields is None:
        return {}
    if isinstance(fields, ElementFields):
        fields = {
            "F": fields.deformation_gradient,
            "J": fields.j,
            "P": fields.pk1,
            "cauchy": fields.cauchy,
            "von_mises": fields.von_mises,
            "energy_density": fields.energy_density,
            "min_J": fields.min_j,
        }
    data = {}
    for name, values in fields.items():
        values = np.asarray(values)
        if values.shape[0] != mesh.element_count:
            raise ValueError(f"field '{name}': {values.shape[0]} rows for {mesh.element_count} elements")
        if values.ndim == 3:  # tensors as nine components, row-major (VTK's order)
            values = values.reshape(values.shape[0], -1)
        data[name] = [values]
    return data


def to_meshio(mesh: Mesh, positions: Optional[np.ndarray] = None, fields: Any = None):
    """The mesh as a meshio.Mesh at positions (n, 3) (default: rest).

    fields: an ElementFields (Simulation.fields()) or a {name: (m, ...)}
    mapping of per-element arrays, written as cell data. The mesh's own point
    and cell arrays go along as point and cell data.
    """
    import meshio

    points = mesh.positions if positions is None else np.asarray(positions, dtype=np.float64)
    if points.shape != (mesh.vertex_count, 3):
        raise ValueError(f"positions: expected shape ({mesh.vertex_count}, 3), got {points.shape}")
    point_data = {a.name: a.values for a in mesh.point_arrays}
    cell_data = {a.name: [a.values] for a in mesh.cell_arrays}
    cell_data.update(_cell_data(mesh, fields))
    return meshio.Mesh(points, [(_MESHIO_CELL[mesh.type], mesh.elements)], point_data=point_data, cell_data=cell_data)


def from_meshio(m: Any) -> Mesh:
    """An snh.Mesh from a meshio.Mesh's hexahedra or tetrahedra.

    Other cells (surfaces, lines) are skipped; a mesh mixing hexahedra and
    tetrahedra is refused. Point data and cell data of the volume cells come
    along as point and cell arrays.
    """
    blocks = [(i, b) for i, b in enumerate(m.cells) if b.type in ("hexahedron", "tetra")]
    kinds = {b.type for _, b in blocks}
    if not blocks:
        raise ValueError("from_meshio: the mesh has no hexahedron or tetra cells")
    if len(kinds) > 1:
        raise ValueError("from_meshio: the mesh mixes hexahedra and tetrahedra")
    elements = np.concatenate([b.data for _, b in blocks])
    mesh = Mesh(np.asarray(m.points, dtype=np.float64)[:, :3], elements)
    from ._snh import MeshArray

    def array(name, values):
        values = np.asarray(values, dtype=np.float64)
        a = MeshArray(name=name, components=1 if values.ndim == 1 else int(np.prod(values.shape[1:])))
        a.values = values.reshape(values.shape[0], -1) if values.ndim > 1 else values
        return a

    mesh.point_arrays = [array(k, v) for k, v in m.point_data.items() if np.asarray(v).dtype.kind in "biuf"]
    cell_arrays = []
    for name, per_block in m.cell_data.items():
        values = [np.asarray(per_block[i]) for i, _ in blocks]
        if all(v.dtype.kind in "biuf" for v in values):
            cell_arrays.append(array(name, np.concatenate(values)))
    mesh.cell_arrays = cell_arrays
    return mesh


def to_pyvista(mesh: Mesh, positions: Optional[np.ndarray] = None, fields: Any = None):
    """The mesh as a pyvista.UnstructuredGrid (needs PyVista installed)."""
    import pyvista

    return pyvista.from_meshio(to_meshio(mesh, positions, fields))
