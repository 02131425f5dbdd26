#!/usr/bin/python3
"""Writes the meshio-made test meshes of data/meshes from the gmsh-made ones
(see README.md): VTK XML (ascii and base64 binary, uncompressed), VTK legacy
5.1 binary and a TetGen .node/.ele pair. Run from this folder with Debian's
python3 (python3-meshio)."""
import meshio


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
