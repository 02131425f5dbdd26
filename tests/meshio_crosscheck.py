#!/usr/bin/python3
"""Reads every mesh under a folder with meshio and with snh (snh-mesh-info)
and compares the point count, the count of tetrahedra or hexahedra, the
total volume, the named Gmsh physical groups (vertex and element counts) and
the point and cell arrays (components and sum of values). Gmsh 2.2 writes an
element once per physical group it is in: identical volume cells count once.
Usage: meshio_crosscheck.py SNH_MESH_INFO DATA_MESHES_DIR [--written TMP_DIR]

With --written, every mesh is first written by snh's write_mesh
(snh-mesh-info MESH --write ...) to TMP_DIR in each format (TetGen for tets
too), and those files are checked instead: meshio must read what snh writes,
and agree with snh on it.

Exits 1 on any disagreement, and when meshio cannot be imported (Debian's
python3-meshio, installed by scripts/setup.sh)."""
import json
import os
import subprocess
import sys

try:
    import numpy as np
    import meshio
except ImportError as error:
    print(f"meshio_crosscheck: cannot import meshio ({error}); install python3-meshio (scripts/setup.sh)")
    sys.exit(1)

EXTENSIONS = (".msh", ".vtk", ".vtu", ".mesh", ".node")
# Corner signs of the hexahedron nodes in VTK order; 2x2x2 Gauss points.
SIGNS = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                  [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)


def tet_volume(points, cells):
    p = points[cells]
    d = np.einsum("ij,ij->i", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), p[:, 3] - p[:, 0])
    return float(np.sum(np.abs(d)) / 6.0)


def hex_volume(points, cells):
    p = points[cells]  # (n, 8, 3)
    g = 1.0 / np.sqrt(3.0)
    total = np.zeros(len(cells))
    for q in SIGNS * g:
        f = 1.0 + SIGNS * q  # (8, 3)
        dn = np.stack([SIGNS[:, 0] * f[:, 1] * f[:, 2], f[:, 0] * SIGNS[:, 1] * f[:, 2],
                       f[:, 0] * f[:, 1] * SIGNS[:, 2]], axis=1) / 8.0  # (8, 3): dN_a/dxi_r
        j = np.einsum("nad,ar->nrd", p, dn)
        total += np.linalg.det(j)
    return float(np.sum(np.abs(total)))


DIMENSION = {"vertex": 0, "line": 1, "triangle": 2, "quad": 2, "tetra": 3, "hexahedron": 3}


def unique_cells(data):
    """Volume cells without the copies gmsh 2.2 writes for overlapping groups."""
    return np.unique(data, axis=0) if len(data) else data


def meshio_groups(mesh):
    """{(name, tag, dimension): (vertices, elements)} for the named physical groups."""
    groups = {}
    physical = mesh.cell_data.get("gmsh:physical")
    for name, (tag, dimension) in mesh.field_data.items():
        if name in (mesh.cell_sets or {}):  # 4.1: sets by name, one index array per block
            blocks = [c.data[np.asarray(idx, dtype=int)] for c, idx in zip(mesh.cells, mesh.cell_sets[name])
                      if idx is not None and len(idx) and DIMENSION.get(c.type) == dimension]
        elif physical is not None:  # 2.2: each cell's physical tag
            blocks = [c.data[p == tag] for c, p in zip(mesh.cells, physical) if DIMENSION.get(c.type) == dimension]
        else:
            continue
        blocks = [b for b in blocks if len(b)]
        vertices = len(np.unique(np.concatenate([b.ravel() for b in blocks]))) if blocks else 0
        elements = sum(len(unique_cells(b)) for b in blocks) if dimension == 3 else 0
        groups[(name, int(tag), int(dimension))] = (vertices, elements)
    return groups


def meshio_arrays(data, cells):
    """[(name, components, sum)] over the volume cells (cell data) or points."""
    out = []
    for name, value in data.items():
        if name.startswith("gmsh:"):
            continue
        if cells is not None:
            value = np.concatenate([v for v, c in zip(value, cells) if c.type in ("tetra", "hexahedron")])
        value = np.asarray(value, dtype=float)
        out.append((name, 1 if value.ndim == 1 else value.shape[1], float(value.sum())))
    return sorted(out)


def main():
    if len(sys.argv) not in (3, 5) or (len(sys.argv) == 5 and sys.argv[3] != "--written"):
        print(__doc__)
        return 2
    tool, folder = sys.argv[1], sys.argv[2]
    files = sorted(f for f in os.listdir(folder) if f.endswith(EXTENSIONS))
    if not files:
        print(f"meshio_crosscheck: no meshes in {folder}")
        return 1
    if len(sys.argv) == 5:
        written = sys.argv[4]
        os.makedirs(written, exist_ok=True)
        for name in files:
            stem = os.path.join(written, name.replace(".", "_"))
            outputs = [stem + ext for ext in (".msh", ".vtk", ".vtu", ".mesh")]
            if json.loads(subprocess.run([tool, os.path.join(folder, name)], capture_output=True,
                                         text=True, check=True).stdout)["type"] == "tet4":
                outputs.append(stem + ".node")
            subprocess.run([tool, os.path.join(folder, name), "--write"] + outputs, capture_output=True, check=True)
        folder = written
        files = sorted(f for f in os.listdir(folder) if f.endswith(EXTENSIONS))
    failures = 0
    for name in files:
        path = os.path.join(folder, name)
        mesh = meshio.read(path)
        volume_cells = [(c.type, unique_cells(c.data)) for c in mesh.cells if c.type in ("tetra", "hexahedron")]
        count = sum(len(data) for _, data in volume_cells)
        volume = sum(tet_volume(mesh.points, data) if kind == "tetra" else hex_volume(mesh.points, data)
                     for kind, data in volume_cells)
        run = subprocess.run([tool, path], capture_output=True, text=True)
        if run.returncode != 0:
            print(f"FAIL {name}: snh-mesh-info exited {run.returncode}: {run.stderr.strip()}")
            failures += 1
            continue
        snh = json.loads(run.stdout)
        problems = []
        if snh["vertices"] != len(mesh.points):
            problems.append(f"points: snh {snh['vertices']}, meshio {len(mesh.points)}")
        if snh["elements"] != count:
            problems.append(f"cells: snh {snh['elements']}, meshio {count}")
        if abs(snh["volume"] - volume) > 1e-9 * max(1.0, abs(volume)):
            problems.append(f"volume: snh {snh['volume']!r}, meshio {volume!r}")
        if name.endswith(".msh"):
            # meshio keys groups by name (field_data): a name used in several
            # dimensions (Medit references written as .msh) keeps only one.
            names = [g["name"] for g in snh["groups"]]
            theirs = {k: v for k, v in meshio_groups(mesh).items() if names.count(k[0]) == 1}
            ours = {(g["name"], g["tag"], g["dimension"]): (g["vertices"], g["elements"])
                    for g in snh["groups"] if g["name"] and names.count(g["name"]) == 1}
            if ours != theirs:
                problems.append(f"groups: snh {ours}, meshio {theirs}")
        for kind, data, cells in (("point_arrays", mesh.point_data, None), ("cell_arrays", mesh.cell_data, mesh.cells)):
            if name.endswith((".vtu", ".vtk")):
                theirs = meshio_arrays(data, cells)
                ours = sorted((a["name"], a["components"], a["sum"]) for a in snh[kind])
                if [(n, c) for n, c, _ in ours] != [(n, c) for n, c, _ in theirs] or any(
                        abs(a[2] - b[2]) > 1e-9 * max(1.0, abs(b[2])) for a, b in zip(ours, theirs)):
                    problems.append(f"{kind}: snh {ours}, meshio {theirs}")
        status = "FAIL" if problems else "ok"
        extras = f", {len(snh['groups'])} groups" if snh["groups"] else ""
        extras += f", {len(snh['point_arrays'])} + {len(snh['cell_arrays'])} arrays" if (
            snh["point_arrays"] or snh["cell_arrays"]) else ""
        print(f"{status:4} {name}: {snh['vertices']} points, {snh['elements']} {snh['type']}, volume {snh['volume']:.15g}"
              + extras
              + ("; " + "; ".join(problems) if problems else ""))
        failures += bool(problems)
    print(f"meshio_crosscheck: {len(files) - failures} of {len(files)} files agree with meshio {meshio.__version__}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
