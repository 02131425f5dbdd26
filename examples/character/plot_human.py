#!/usr/bin/python3
"""Draws the human example from its point caches, seen from the front (glTF
+z, the character's left on the right): the simulated surface at rest, the
simulated surface at a frame coloured by its distance from the
linear-blend-skinned surface, the linear-blend-skinned surface at that
frame, and a close-up of the raised shoulder with both as wireframes.

    python3 plot_human.py human.glb human.pc2 human_lbs.pc2 out.png [frame]

The triangles come from the .glb (its first mesh's first primitive, whose
vertex order the caches follow); the frame is a sample index of the caches
(default: the last).
"""
import json
import struct
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
import numpy as np  # noqa: E402


def read_pc2(path):
    data = open(path, "rb").read()
    if data[:12] != b"POINTCACHE2\0":
        raise SystemExit(path + ": not a PC2 file")
    version, points, start, rate, samples = struct.unpack("<iiffi", data[12:32])
    xyz = np.frombuffer(data, dtype="<f4", offset=32, count=3 * points * samples)
    return start, rate, xyz.reshape(samples, points, 3)


def glb_triangles(path):
    """The first primitive's triangles and rest positions from a binary glTF."""
    data = open(path, "rb").read()
    magic, version, length = struct.unpack("<4sII", data[:12])
    if magic != b"glTF" or version != 2:
        raise SystemExit(path + ": not a binary glTF 2.0 file")
    chunks, at = {}, 12
    while at < length:
        size, kind = struct.unpack("<I4s", data[at:at + 8])
        chunks[kind] = data[at + 8:at + 8 + size]
        at += 8 + size
    doc = json.loads(chunks[b"JSON"])
    binary = chunks[b"BIN\0"]

    def accessor(index, dtype):
        a = doc["accessors"][index]
        view = doc["bufferViews"][a["bufferView"]]
        offset = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        width = {"SCALAR": 1, "VEC3": 3}[a["type"]]
        return np.frombuffer(binary, dtype=dtype, offset=offset, count=a["count"] * width)

    primitive = doc["meshes"][0]["primitives"][0]
    index_type = {5125: "<u4", 5123: "<u2", 5121: "u1"}[doc["accessors"][primitive["indices"]]["componentType"]]
    return (accessor(primitive["indices"], index_type).reshape(-1, 3),
            accessor(primitive["attributes"]["POSITION"], "<f4").reshape(-1, 3))


def draw(ax, xyz, triangles, values=None, cmap=None, vmax=None, color=(0.8, 0.8, 0.8)):
    """Flat-shaded triangles seen along -z, far ones first."""
    corners = xyz[triangles]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    normals /= np.linalg.norm(normals, axis=1, keepdims=True) + 1e-30
    light = np.array([-0.3, 0.4, 1.0])
    shade = 0.35 + 0.65 * np.clip(normals @ (light / np.linalg.norm(light)), 0.0, 1.0)
    if values is None:
        base = np.tile(np.array(color), (len(triangles), 1))
    else:
        base = np.asarray(cmap(np.clip(values[triangles].mean(axis=1) / vmax, 0.0, 1.0)))[:, :3]
    colors = base * shade[:, None]
    order = np.argsort(corners[:, :, 2].mean(axis=1))
    ax.add_collection(PolyCollection(corners[order][:, :, :2], facecolors=colors[order], edgecolors=colors[order],
                                     linewidths=0.2))
    ax.set_aspect("equal")
    ax.set_xlim(-0.85, 0.85)
    ax.set_ylim(-0.02, 2.05)
    ax.tick_params(labelsize=7)


def main():
    if len(sys.argv) < 5:
        raise SystemExit(__doc__)
    glb, simulated_path, skinned_path, out = sys.argv[1:5]
    triangles, rest = glb_triangles(glb)
    start, rate, simulated = read_pc2(simulated_path)
    _, _, skinned = read_pc2(skinned_path)
    if simulated.shape[1] != len(rest):
        raise SystemExit("%s has %d points, %s %d vertices" % (simulated_path, simulated.shape[1], glb, len(rest)))
    frame = int(sys.argv[5]) if len(sys.argv) > 5 else simulated.shape[0] - 1
    distance = np.linalg.norm(simulated[frame] - skinned[frame], axis=1)
    vmax = max(distance.max(), 1e-6)
    cmap = plt.get_cmap("inferno_r")
    fig, axes = plt.subplots(1, 4, figsize=(12.0, 4.2), gridspec_kw={"width_ratios": [1, 1.15, 1, 1.2]})
    draw(axes[0], simulated[0], triangles)
    axes[0].set_title("frame %d: simulated (rest)" % round(start), fontsize=8)
    draw(axes[1], simulated[frame], triangles, distance, cmap, vmax)
    axes[1].set_title("frame %d: simulated, coloured by distance\nfrom skinning (max %.1f mm)"
                      % (round(start + frame), 1000 * distance.max()), fontsize=8)
    draw(axes[2], skinned[frame], triangles, color=(0.75, 0.75, 0.8))
    axes[2].set_title("frame %d: linear blend skinning" % round(start + frame), fontsize=8)
    close = axes[3]
    close.triplot(skinned[frame, :, 0], skinned[frame, :, 1], triangles, color="0.6", linewidth=0.4)
    close.triplot(simulated[frame, :, 0], simulated[frame, :, 1], triangles, color="tab:red", linewidth=0.4)
    close.plot([], [], color="tab:red", label="simulated")
    close.plot([], [], color="0.6", label="linear blend skinning")
    close.legend(fontsize=7, loc="lower right")
    close.set_aspect("equal")
    close.set_xlim(-0.1, 0.45)
    close.set_ylim(1.25, 1.75)
    close.tick_params(labelsize=7)
    close.set_title("frame %d: the left shoulder and elbow" % round(start + frame), fontsize=8)
    bar = fig.colorbar(plt.cm.ScalarMappable(norm=plt.Normalize(0, 1000 * vmax), cmap=cmap), ax=axes[1],
                       fraction=0.04, pad=0.02)
    bar.set_label("mm", fontsize=7)
    bar.ax.tick_params(labelsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=90)


if __name__ == "__main__":
    main()
