#!/usr/bin/python3
"""Writes a skinned arm as glTF 2.0 (JSON with an embedded base64 buffer).

The arm is a closed tube along +x, 0.4 m long and 0.05 m in radius, capped
at both ends, with a texture seam (the first column of ring vertices is
repeated at 360 degrees, so positions repeat as they do in real assets).
Three joints inside the tube: shoulder (x = 0.05), elbow (x = 0.2), wrist
(x = 0.35); weights blended smoothly over x = 0.15..0.25 (shoulder to
elbow) and 0.3..0.37 (elbow to wrist). One clip,
"bend": the elbow turns about +z from 0 to 90 degrees over 1 s (keys at 0,
0.5 and 1 s), lifting the forearm towards +y.

    python3 make_arm.py arm.gltf

--case writes the small files of the character tests instead (see
tests/data/character/README.md): trs, no_skin, no_animation, nan_key,
bad_weights, and the repairs: inside_out (every face wound inwards),
unweighted (vertices 5 and 40 without weights), flap (an open fin sticking
out of the tube and two loose points), tail (a joint past the wrist, so
that the wrist's segment crosses the skin).
"""
import argparse
import base64
import json
import math
import struct

import numpy as np

LENGTH, RADIUS, SEGMENTS, RINGS = 0.4, 0.05, 16, 21
JOINT_X = [0.05, 0.2, 0.35]


class Buffer:
    """Binary chunks with their bufferViews and accessors."""

    def __init__(self):
        self.data = bytearray()
        self.views = []
        self.accessors = []

    def add(self, array, component, kind, target=None, bounds=False):
        array = np.ascontiguousarray(array)
        while len(self.data) % 4:
            self.data.append(0)
        view = {"buffer": 0, "byteOffset": len(self.data), "byteLength": array.nbytes}
        if target:
            view["target"] = target
        self.data += array.tobytes()
        self.views.append(view)
        count = array.shape[0]
        accessor = {"bufferView": len(self.views) - 1, "componentType": component, "count": count, "type": kind}
        if bounds:
            flat = array.reshape(count, -1)
            accessor["min"] = [float(v) for v in flat.min(axis=0)]
            accessor["max"] = [float(v) for v in flat.max(axis=0)]
        self.accessors.append(accessor)
        return len(self.accessors) - 1


FLOAT, USHORT, UINT = 5126, 5123, 5125


def smoothstep(t):
    t = np.clip(t, 0.0, 1.0)
    return t * t * (3 - 2 * t)


def arm_mesh():
    """Positions, triangles (outward) and per-vertex weights of (shoulder, elbow, wrist)."""
    xs = np.linspace(0.0, LENGTH, RINGS)
    positions = []
    for x in xs:
        for s in range(SEGMENTS + 1):  # s = SEGMENTS repeats s = 0: the seam
            a = 2 * math.pi * s / SEGMENTS
            positions.append((x, RADIUS * math.cos(a), RADIUS * math.sin(a)))
    ring = SEGMENTS + 1
    triangles = []
    for r in range(RINGS - 1):
        for s in range(SEGMENTS):
            a, b = r * ring + s, r * ring + s + 1
            c, d = a + ring, b + ring
            triangles += [(a, b, d), (a, d, c)]
    start = len(positions)
    positions += [(0.0, 0.0, 0.0), (LENGTH, 0.0, 0.0)]
    for s in range(SEGMENTS):  # caps, facing -x and +x
        triangles.append((start, s + 1, s))
        last = (RINGS - 1) * ring
        triangles.append((start + 1, last + s, last + s + 1))
    positions = np.array(positions, dtype=np.float32)
    x = positions[:, 0].astype(np.float64)
    to_elbow = smoothstep((x - 0.15) / 0.1)
    to_wrist = smoothstep((x - 0.3) / 0.07)
    weights = np.stack([1 - to_elbow, to_elbow * (1 - to_wrist), to_wrist], axis=1)
    return positions, np.array(triangles, dtype=np.uint32), weights.astype(np.float32)


def quat_z(degrees):
    h = math.radians(degrees) / 2
    return [0.0, 0.0, math.sin(h), math.cos(h)]  # glTF order x, y, z, w


def translation_inverse(x):
    m = np.eye(4, dtype=np.float32)
    m[0, 3] = -x
    return m.T.reshape(-1)  # glTF matrices are column-major


def skinned_gltf(positions, triangles, joints4, weights4, nodes, joint_nodes, inverse_binds, animations,
                 with_skin=True):
    buf = Buffer()
    attributes = {"POSITION": buf.add(positions, FLOAT, "VEC3", 34962, bounds=True)}
    if with_skin:
        attributes["JOINTS_0"] = buf.add(joints4.astype(np.uint16), USHORT, "VEC4", 34962)
        attributes["WEIGHTS_0"] = buf.add(weights4.astype(np.float32), FLOAT, "VEC4", 34962)
    indices = buf.add(triangles.reshape(-1), UINT, "SCALAR", 34963)
    doc = {
        "asset": {"version": "2.0", "generator": "snh make_arm.py"},
        "scene": 0,
        "scenes": [{"nodes": [0] + [n for n in range(1, len(nodes)) if nodes[n].pop("root", False)]}],
        "nodes": nodes,
        "meshes": [{"name": "skin", "primitives": [{"attributes": attributes, "indices": indices, "mode": 4}]}],
    }
    if with_skin:
        doc["skins"] = [{"joints": joint_nodes,
                         "inverseBindMatrices": buf.add(np.array(inverse_binds, dtype=np.float32), FLOAT, "MAT4")}]
        nodes[0]["skin"] = 0
    if animations:
        doc["animations"] = []
        for name, channels in animations:
            samplers, chans = [], []
            for node, path, times, values, interpolation in channels:
                t = buf.add(np.array(times, dtype=np.float32), FLOAT, "SCALAR", bounds=True)
                kind = "VEC4" if path == "rotation" else "VEC3"
                v = buf.add(np.array(values, dtype=np.float32), FLOAT, kind)
                samplers.append({"input": t, "output": v, "interpolation": interpolation})
                chans.append({"sampler": len(samplers) - 1, "target": {"node": node, "path": path}})
            doc["animations"].append({"name": name, "samplers": samplers, "channels": chans})
    doc["accessors"] = buf.accessors
    doc["bufferViews"] = buf.views
    doc["buffers"] = [{"byteLength": len(buf.data),
                       "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buf.data)).decode()}]
    return doc


def arm(case=None):
    positions, triangles, weights = arm_mesh()
    joints4 = np.tile(np.array([0, 1, 2, 0], dtype=np.uint16), (len(positions), 1))
    weights4 = np.concatenate([weights, np.zeros((len(positions), 1), np.float32)], axis=1)
    weights4 /= weights4.sum(axis=1, keepdims=True)
    nodes = [{"name": "arm", "mesh": 0},
             {"name": "shoulder", "translation": [0.05, 0.0, 0.0], "children": [2], "root": True},
             {"name": "elbow", "translation": [0.15, 0.0, 0.0], "children": [3]},
             {"name": "wrist", "translation": [0.15, 0.0, 0.0]}]
    keys = [quat_z(0), quat_z(45), quat_z(90)]
    if case == "nan_key":
        keys[1] = [0.0, 0.0, float("nan"), 1.0]
    animations = [("bend", [(2, "rotation", [0.0, 0.5, 1.0], keys, "LINEAR")])]
    if case == "bad_weights":
        weights4[7] *= 0.5  # vertex 7's weights sum to 0.5
    if case == "no_animation":
        animations = []
    if case == "inside_out":
        triangles = triangles[:, ::-1].copy()
    if case == "unweighted":
        weights4[[5, 40]] = 0.0
    if case == "flap":
        # A one-sided fin at x = 0.25..0.32 in the plane z = 0 from the tube's
        # side (y = 0.05) out to y = 0.11, and two loose points near the tube.
        n = len(positions)
        fin = [(0.25, 0.05, 0.0), (0.32, 0.05, 0.0), (0.25, 0.11, 0.0), (0.32, 0.11, 0.0)]
        loose = [(0.1, 0.0, 0.09), (0.3, -0.085, 0.0)]
        positions = np.concatenate([positions, np.array(fin + loose, dtype=np.float32)])
        triangles = np.concatenate([triangles, np.array([[n, n + 1, n + 3], [n, n + 3, n + 2]], dtype=np.uint32)])
        x = positions[n:, 0]
        extra = np.zeros((len(x), 4), np.float32)
        extra[:, 1] = 1.0  # the elbow's
        joints4 = np.concatenate([joints4, np.tile(joints4[:1], (len(x), 1))])
        weights4 = np.concatenate([weights4, extra])
    joint_nodes, binds = [1, 2, 3], [translation_inverse(x) for x in JOINT_X]
    if case == "tail":
        nodes[3]["children"] = [4]
        nodes.append({"name": "tail", "translation": [0.12, 0.0, 0.0]})
        joint_nodes.append(4)
        binds.append(translation_inverse(0.47))
    return skinned_gltf(positions, triangles, joints4, weights4, nodes, joint_nodes, binds, animations,
                        with_skin=(case != "no_skin"))


def trs_chain():
    """Two joints with known T, R, S (identity inverse binds, so skinning matrices are world matrices): root
    T (1, 2, 3), R 90 degrees about z, S 2 (no channel: the node's own); tip keys at 0 and 1 s: T (0.5, 0, 0) to
    (1.5, 0, 0), R 0 to 90 degrees about x, S 1 to 3 (clip "move"); the same translations as STEP keys (clip
    "jump"). A tetrahedron weighted 3:1 to root and tip."""
    positions = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float32)
    triangles = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.uint32)
    joints4 = np.tile(np.array([0, 1, 0, 0], dtype=np.uint16), (4, 1))
    weights4 = np.tile(np.array([0.75, 0.25, 0, 0], dtype=np.float32), (4, 1))
    h = math.radians(90) / 2
    nodes = [{"name": "mesh", "mesh": 0},
             {"name": "root", "translation": [1.0, 2.0, 3.0], "rotation": [0.0, 0.0, math.sin(h), math.cos(h)],
              "scale": [2.0, 2.0, 2.0], "children": [2], "root": True},
             {"name": "tip", "translation": [0.5, 0.0, 0.0]}]
    identity = np.eye(4, dtype=np.float32).reshape(-1)
    animations = [("idle", [(2, "translation", [0.0, 1.0], [[0, 0, 0], [0, 0, 0]], "LINEAR")]),
                  ("move", [(2, "translation", [0.0, 1.0], [[0.5, 0, 0], [1.5, 0, 0]], "LINEAR"),
                            (2, "rotation", [0.0, 1.0], [[0, 0, 0, 1], [math.sin(h), 0, 0, math.cos(h)]], "LINEAR"),
                            (2, "scale", [0.0, 1.0], [[1, 1, 1], [3, 3, 3]], "LINEAR")]),
                  ("jump", [(2, "translation", [0.0, 1.0], [[0.5, 0, 0], [1.5, 0, 0]], "STEP")])]
    return skinned_gltf(positions, triangles, joints4, weights4, nodes, [1, 2], [identity, identity], animations)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", help="the .gltf to write")
    parser.add_argument("--case", choices=["trs", "no_skin", "no_animation", "nan_key", "bad_weights", "inside_out",
                                               "unweighted", "flap", "tail"])
    args = parser.parse_args()
    doc = trs_chain() if args.case == "trs" else arm(args.case)
    with open(args.out, "w") as f:
        json.dump(doc, f, separators=(",", ":"))
        f.write("\n")


if __name__ == "__main__":
    main()
