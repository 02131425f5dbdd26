#!/usr/bin/python3
"""The arm example's surface at rest and flexed, side by side (docs/user-guide.md).

    /usr/bin/python3 bench/plot_arm.py REST.obj FLEXED.obj OUT.png [MID.obj]

e.g. data/arm/arm.obj and arm-out/surface_0024.obj written by
`snh-gpu-bench scene --file data/scenes/arm.json`. Each panel looks at the
arm from the side (-y), the elbow's hinge axis pointing at the viewer, with
flat shading from a fixed light.
"""
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402


def read_obj(path):
    vertices, faces = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                vertices.append([float(p) for p in parts[1:4]])
            elif parts[0] == "f":
                faces.append([int(p.split("/")[0]) - 1 for p in parts[1:4]])
    return np.array(vertices), np.array(faces)


def draw(ax, vertices, faces, title, limits):
    triangles = vertices[faces]
    normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    normals /= np.linalg.norm(normals, axis=1, keepdims=True) + 1e-30
    light = np.array([-0.4, -0.8, 0.6])
    light /= np.linalg.norm(light)
    shade = 0.35 + 0.65 * np.clip(normals @ light, 0.0, 1.0)
    colors = np.outer(shade, [0.93, 0.72, 0.62])
    ax.add_collection3d(Poly3DCollection(triangles, facecolors=colors, edgecolors="none"))
    ax.set_xlim(*limits[0])
    ax.set_ylim(*limits[1])
    ax.set_zlim(*limits[2])
    ax.set_box_aspect([limits[d][1] - limits[d][0] for d in range(3)])
    ax.view_init(elev=12, azim=-90)
    ax.set_title(title)
    ax.set_axis_off()


def main():
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    shapes = [("rest", sys.argv[1]), ("flexed (last frame)", sys.argv[2])]
    if len(sys.argv) == 5:
        shapes.insert(1, ("half way", sys.argv[4]))
    meshes = [(title, *read_obj(path)) for title, path in shapes]
    everything = np.vstack([m[1] for m in meshes])
    lo, hi = everything.min(axis=0), everything.max(axis=0)
    pad = 0.05 * (hi - lo).max()
    limits = [(lo[d] - pad, hi[d] + pad) for d in range(3)]
    fig = plt.figure(figsize=(4.2 * len(meshes), 4.2))
    for i, (title, vertices, faces) in enumerate(meshes):
        draw(fig.add_subplot(1, len(meshes), i + 1, projection="3d"), vertices, faces, title, limits)
    fig.suptitle("snh arm example: embedded surface, elbow flexion 0 to 100 degrees")
    fig.tight_layout()
    fig.savefig(sys.argv[3], dpi=110)
    print("wrote", sys.argv[3])


if __name__ == "__main__":
    main()
