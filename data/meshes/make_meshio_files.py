#!/usr/bin/python3
"""Writes the meshio-made test meshes of data/meshes from the gmsh-made ones
(see README.md): VTK XML (ascii and base64 binary, uncompressed), VTK legacy
5.1 binary and a TetGen .node/.ele pair; and box_groups with point and cell
arrays in VTK XML and legacy form. Run from this folder with Debian's python3
(python3-meshio)."""
import meshio
import numpy as np


def volume_only(path):
    m = meshio.read(path)
    cells = [(c.type, c.data) for c in m.cells if c.type in ("tetra", "hexahedron")]
    return meshio.Mesh(m.points, cells)


box = volume_only("box_tet.msh41.msh")
hexes = volume_only("hex_box.msh")
meshio.write("box_tet.vtu", box, binary=False)
meshio.write("box_tet_base64.vtu", box, binary=True, compression=None)
meshio.write("hex_box.vtu", hexes, binary=False)
meshio.write("box_tet_meshio_binary.vtk", box, binary=True)
meshio.write("box_tet.node", box, file_format="tetgen")


# Arrays on the two-volume box: point arrays "temperature" = x + 2 y and
# "displacement" = 0.1 (x, y, z); cell arrays "material" = the gmsh volume
# (1 left, 2 right, Int32) and "stiffness" = 1 + x of the cell's centroid.
groups = meshio.read("box_groups.msh41.msh")
tets = [c for c in groups.cells if c.type == "tetra"]
points = groups.points
material = np.concatenate([groups.cell_data["gmsh:geometrical"][i] for i, c in enumerate(groups.cells)
                           if c.type == "tetra"]).astype(np.int32)
cells = np.concatenate([c.data for c in tets])
arrays = meshio.Mesh(points, [("tetra", cells)],
                     point_data={"temperature": points[:, 0] + 2 * points[:, 1], "displacement": 0.1 * points},
                     cell_data={"material": [material], "stiffness": [1 + points[cells].mean(axis=1)[:, 0]]})
arrays.write("box_groups_arrays.vtu", binary=False)
arrays.write("box_groups_arrays_base64.vtu", binary=True, compression=None)
arrays.write("box_groups_arrays.vtk", binary=False)
arrays.write("box_groups_arrays_binary.vtk", binary=True)
