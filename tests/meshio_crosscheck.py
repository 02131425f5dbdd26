#!/usr/bin/python3
"""Reads every mesh under a folder with meshio and with snh (snh-mesh-info)
and compares the point count, the count of tetrahedra or hexahedra, and the
total volume. Usage: meshio_crosscheck.py SNH_MESH_INFO DATA_MESHES_DIR

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


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    tool, folder = sys.argv[1], sys.argv[2]
    files = sorted(f for f in os.listdir(folder) if f.endswith(EXTENSIONS))
    if not files:
        print(f"meshio_crosscheck: no meshes in {folder}")
        return 1
    failures = 0
    for name in files:
        path = os.path.join(folder, name)
        mesh = meshio.read(path)
        volume_cells = [(c.type, c.data) for c in mesh.cells if c.type in ("tetra", "hexahedron")]
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
        status = "FAIL" if problems else "ok"
        print(f"{status:4} {name}: {snh['vertices']} points, {snh['elements']} {snh['type']}, volume {snh['volume']:.15g}"
              + ("; " + "; ".join(problems) if problems else ""))
        failures += bool(problems)
    print(f"meshio_crosscheck: {len(files) - failures} of {len(files)} files agree with meshio {meshio.__version__}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
