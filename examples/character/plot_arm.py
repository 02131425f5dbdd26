#!/usr/bin/python3
"""Plots a skinned character's frames from its point caches: the simulated
surface over the linear-blend-skinned one, seen along -z.

    python3 plot_arm.py arm.gltf arm.pc2 arm_lbs.pc2 out.png [frame ...]

The triangles come from the glTF (its first primitive's indices, which the
caches' vertex order follows); frames are sample indices (default: first,
middle, last).
"""
import base64
import json
import struct
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_pc2(path):
    data = open(path, "rb").read()
    if data[:12] != b"POINTCACHE2\0":
        raise SystemExit(path + ": not a PC2 file")
    version, points, start, rate, samples = struct.unpack("<iiffi", data[12:32])
    xyz = np.frombuffer(data, dtype="<f4", offset=32, count=3 * points * samples)
    return start, xyz.reshape(samples, points, 3)


def gltf_triangles(path):
    doc = json.load(open(path))
    uri = doc["buffers"][0]["uri"]
    raw = base64.b64decode(uri.split(",", 1)[1])
    accessor = doc["accessors"][doc["meshes"][0]["primitives"][0]["indices"]]
    view = doc["bufferViews"][accessor["bufferView"]]
    dtype = {5125: "<u4", 5123: "<u2"}[accessor["componentType"]]
    offset = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
    return np.frombuffer(raw, dtype=dtype, offset=offset, count=accessor["count"]).reshape(-1, 3)


def main():
    if len(sys.argv) < 5:
        raise SystemExit(__doc__)
    gltf, simulated_path, skinned_path, out = sys.argv[1:5]
    triangles = gltf_triangles(gltf)
    start, simulated = read_pc2(simulated_path)
    _, skinned = read_pc2(skinned_path)
    n = simulated.shape[0]
    frames = [int(f) for f in sys.argv[5:]] or [0, n // 2, n - 1]
    fig, axes = plt.subplots(1, len(frames), figsize=(3.2 * len(frames), 3.2), squeeze=False)
    for ax, f in zip(axes[0], frames):
        ax.triplot(skinned[f, :, 0], skinned[f, :, 1], triangles, color="0.7", linewidth=0.4)
        ax.triplot(simulated[f, :, 0], simulated[f, :, 1], triangles, color="tab:red", linewidth=0.4)
        distance = np.linalg.norm(simulated[f] - skinned[f], axis=1)
        ax.set_title("frame %d: max %.1f mm from skinning" % (start + f, 1000 * distance.max()), fontsize=8)
        ax.set_aspect("equal")
        ax.set_xlim(-0.02, 0.45)
        ax.set_ylim(-0.08, 0.3)
        ax.tick_params(labelsize=7)
    axes[0][0].plot([], [], color="tab:red", label="simulated")
    axes[0][0].plot([], [], color="0.7", label="linear blend skinning")
    axes[0][0].legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    fig.savefig(out, dpi=80)


if __name__ == "__main__":
    main()
