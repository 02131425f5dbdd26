#!/usr/bin/python3
"""The shipped arm example (data/arm): a closed, outward-facing triangle
surface of an arm-like limb along +x and its elbow-flexion animation.

    /usr/bin/python3 make_arm.py    # writes arm.obj and arm_flexion.json here

The limb is a surface of revolution about the x axis, 4 long (x in [0, 4]):
its radius runs 0.5 at the shoulder, a biceps bulge, 0.42 at the elbow
(x = 2), 0.36 at the forearm's middle, 0.3 at the wrist, with rounded ends
(elliptic caps 0.35 long). Rings of vertices every 1/12 along x, 24 around,
one vertex closing each end. Units are free (the scene uses E = 1).

The animation has 25 frames (0 .. 24): the forearm bone rotates about the
elbow axis (the y axis through (2, 0, 0)) from 0 to 100 degrees of flexion
(its far end rises towards +z), eased in and out; the upper-arm bone is not
animated and stays at rest.
"""
import json
import math
import os

import numpy as np

LENGTH, CAP, RINGS, AROUND = 4.0, 0.35, 48, 24
ELBOW = (2.0, 0.0, 0.0)
FRAMES, MAX_DEGREES = 25, 100.0


def radius(x):
    """Radius of the limb at x (before the end caps round it off)."""
    base = np.interp(x, [0.0, 2.0, 3.0, 4.0], [0.5, 0.42, 0.36, 0.3])
    biceps = 0.06 * math.exp(-(((x - 1.0) / 0.45) ** 2))
    cap = 1.0
    if x < CAP:
        cap = math.sqrt(max(0.0, 1.0 - ((CAP - x) / CAP) ** 2))
    elif x > LENGTH - CAP:
        cap = math.sqrt(max(0.0, 1.0 - ((x - (LENGTH - CAP)) / CAP) ** 2))
    return (base + biceps) * cap


def surface():
    # Ring stations: denser in the caps (cosine spacing) so their tips are round.
    s = np.linspace(0.0, 1.0, RINGS + 1)[1:-1]
    xs = LENGTH * (1.0 - np.cos(math.pi * s)) / 2.0
    vertices = [(0.0, 0.0, 0.0)]
    for x in xs:
        r = radius(x)
        for k in range(AROUND):
            a = 2.0 * math.pi * k / AROUND
            vertices.append((x, r * math.cos(a), r * math.sin(a)))
    vertices.append((LENGTH, 0.0, 0.0))
    last = len(vertices) - 1
    ring = lambda i, k: 1 + i * AROUND + (k % AROUND)
    triangles = []
    # Outward normals: counter-clockwise seen from outside. Going around
    # (y, z) with increasing angle is counter-clockwise seen from +x.
    for k in range(AROUND):
        triangles.append((0, ring(0, k + 1), ring(0, k)))
    for i in range(len(xs) - 1):
        for k in range(AROUND):
            a, b = ring(i, k), ring(i, k + 1)
            c, d = ring(i + 1, k), ring(i + 1, k + 1)
            triangles.append((a, b, d))
            triangles.append((a, d, c))
    n = len(xs) - 1
    for k in range(AROUND):
        triangles.append((last, ring(n, k), ring(n, k + 1)))
    return vertices, triangles


def write_obj(path, vertices, triangles):
    with open(path, "w") as f:
        f.write("# arm-like limb along +x, made by make_arm.py\n")
        for v in vertices:
            f.write("v %.9g %.9g %.9g\n" % v)
        for t in triangles:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


def flexion(degrees):
    """Row-major 4x4: rotation about the y axis through the elbow by -degrees
    (the forearm's +x end goes towards +z)."""
    a = -math.radians(degrees)
    r = np.array([[math.cos(a), 0.0, math.sin(a)], [0.0, 1.0, 0.0], [-math.sin(a), 0.0, math.cos(a)]])
    p = np.array(ELBOW)
    m = np.eye(4)
    m[:3, :3] = r
    m[:3, 3] = p - r @ p
    m[np.abs(m) < 1e-15] = 0.0
    return [[round(float(v), 12) for v in row] for row in m]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    vertices, triangles = surface()
    write_obj(os.path.join(here, "arm.obj"), vertices, triangles)
    frames = []
    for f in range(FRAMES):
        s = f / (FRAMES - 1)
        degrees = MAX_DEGREES * (1.0 - math.cos(math.pi * s)) / 2.0  # eased in and out
        frames.append({"time": f, "bones": {"forearm": flexion(degrees)}})
    with open(os.path.join(here, "arm_flexion.json"), "w") as f:
        f.write('{"frames": [\n')
        f.write(",\n".join("  " + json.dumps(fr) for fr in frames))
        f.write("\n]}\n")
    print("arm.obj: %d vertices, %d triangles; arm_flexion.json: %d frames" % (len(vertices), len(triangles), FRAMES))


if __name__ == "__main__":
    main()
