#!/usr/bin/python3
"""The drop scene seen along the cylinders' axes at a few frames, and its
shape measures over time (docs/validation.md).

    /usr/bin/python3 bench/plot_drop.py VTU_DIR SCENE.json OUT.png [FRAMES]

VTU_DIR and SCENE.json written by
`snh-gpu-bench scene drop --vtu VTU_DIR --json SCENE.json`; FRAMES a comma
list (default 18,27,36,60). Each of the first panels shows the body's
vertices (y, z) at that frame, coloured by the smallest J of their elements,
and the obstacles' cross-sections (drop_obstacles_NNNN.vtu); the last panel
the per-step volume ratio, smallest J and rigid-fit shape deviation.
"""
import json
import sys

import matplotlib
import meshio
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def cross_sections(surface):
    """Each obstacle's (y, z) outline: the vertices of one connected piece of
    the surface at the far end of the cylinders' axis (x largest), a tube's
    ordered around its centre and closed."""
    points, triangles = surface.points, surface.cells_dict["triangle"]
    parent = list(range(len(points)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for a, b, c in triangles:
        parent[find(b)] = find(a)
        parent[find(c)] = find(a)
    far = points[:, 0] > points[:, 0].max() - 1e-9
    pieces = {}
    for i in np.nonzero(far)[0]:
        pieces.setdefault(find(i), []).append(points[i, 1:3])
    out = []
    for section in pieces.values():
        section = np.array(section)
        if len(section) > 2:
            centre = section.mean(axis=0)
            order = np.argsort(np.arctan2(section[:, 1] - centre[1], section[:, 0] - centre[0]))
            section = np.vstack([section[order], section[order[:1]]])
        out.append(section)
    return out


def main():
    folder, scene_json, out = sys.argv[1:4]
    frames = [int(f) for f in (sys.argv[4] if len(sys.argv) > 4 else "18,27,36,60").split(",")]
    steps = json.load(open(scene_json))["steps"]
    fig, axes = plt.subplots(1, len(frames) + 1, figsize=(4 * (len(frames) + 1), 4))
    for ax, frame in zip(axes, frames):
        body = meshio.read(f"{folder}/drop_{frame:04d}.vtu")
        tets = body.cells_dict["tetra"]
        j = np.concatenate(body.cell_data["J"])
        vertex_j = np.full(len(body.points), np.inf)
        for k in range(4):
            np.minimum.at(vertex_j, tets[:, k], j)
        for section in cross_sections(meshio.read(f"{folder}/drop_obstacles_{frame:04d}.vtu")):
            ax.plot(section[:, 0], section[:, 1], "-", color="0.4", linewidth=1)
        sc = ax.scatter(body.points[:, 1], body.points[:, 2], c=vertex_j, s=3, cmap="viridis", vmin=-0.3, vmax=1.0)
        ax.set_xlim(-0.1, 0.1)
        ax.set_ylim(-0.1, 0.1)
        ax.set_aspect("equal")
        t = steps[frame - 1]["time"] if frame > 0 else 0.0
        ax.set_title(f"frame {frame}, t = {t:.2f} s")
        ax.set_xlabel("y (m)")
    axes[0].set_ylabel("z (m)")
    fig.colorbar(sc, ax=axes[len(frames) - 1], fraction=0.046, label="min J of the vertex's elements")
    ax = axes[-1]
    time = [s["time"] for s in steps]
    ax.plot(time, [s["volume_ratio"] for s in steps], label="volume / rest volume")
    ax.plot(time, [s["min_j"] for s in steps], label="min J")
    ax.plot(time, [s["rigid_fit_rms_relative"] for s in steps], label="shape deviation (rigid fit, / radius of gyration)")
    ax.set_xlabel("t (s)")
    ax.legend(fontsize=7, loc="lower left")
    ax.set_title("per frame")
    fig.tight_layout()
    fig.savefig(out, dpi=80)


if __name__ == "__main__":
    main()
