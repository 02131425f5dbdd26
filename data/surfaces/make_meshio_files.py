"""Writes sphere.ply (binary little endian) and sphere.obj from gmsh's sphere.stl with meshio.

STL stores corners by value: meshio keeps them unmerged, so the points are
merged here (exactly equal coordinates) before writing indexed formats.
Run from this folder with Debian's /usr/bin/python3 (python3-meshio).
"""
import meshio
import numpy as np

mesh = meshio.read("sphere.stl")
points, inverse = np.unique(mesh.points, axis=0, return_inverse=True)
triangles = inverse.reshape(-1)[mesh.cells_dict["triangle"]]
indexed = meshio.Mesh(points, [("triangle", triangles)])
meshio.write("sphere.ply", indexed, binary=True)
meshio.write("sphere.obj", indexed)
