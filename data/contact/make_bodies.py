#!/usr/bin/env python3
"""Writes the closed surfaces of the self-contact scenes (data/scenes/
limbs_pressed.json, hand_head.json) as OBJ: capsules and a sphere as
latitude-longitude meshes, outward facing. Run from this folder:
/usr/bin/python3 make_bodies.py
With --spheres N PATH instead: two interpenetrating spheres of N rings and
2N meridians each (about 8 N^2 triangles in all) to PATH, for timing
`snh intersections` (docs/performance.md)."""
import math
import sys


def capsule(a, b, radius, around=16, cap_rings=4, length_rings=6):
    """A capsule from a to b along x (a[0] < b[0], same y and z)."""
    rings = []  # (x, ring radius)
    for i in range(1, cap_rings + 1):  # the cap at a, from its pole outwards
        t = math.pi / 2 * i / cap_rings
        rings.append((a[0] - radius * math.cos(t), radius * math.sin(t)))
    for i in range(1, length_rings):
        rings.append((a[0] + (b[0] - a[0]) * i / length_rings, radius))
    for i in range(cap_rings, 0, -1):
        t = math.pi / 2 * i / cap_rings
        rings.append((b[0] + radius * math.cos(t), radius * math.sin(t)))
    return lathe((a[0] - radius, a[1], a[2]), (b[0] + radius, b[1], b[2]), rings, around)


def sphere(center, radius, around=20, rings=10):
    pts = []
    for i in range(1, rings):
        t = math.pi * i / rings
        pts.append((center[0] - radius * math.cos(t), radius * math.sin(t)))
    return lathe((center[0] - radius, center[1], center[2]), (center[0] + radius, center[1], center[2]), pts, around)


def lathe(pole0, pole1, rings, around):
    """Rings (x, r) about the x axis through the poles' y and z."""
    y0, z0 = pole0[1], pole0[2]
    v = [pole0]
    for x, r in rings:
        for k in range(around):
            p = 2 * math.pi * k / around
            v.append((x, y0 + r * math.cos(p), z0 + r * math.sin(p)))
    v.append(pole1)
    f = []
    n = len(rings)
    ring = lambda i, k: 1 + i * around + k % around
    for k in range(around):
        f.append((0, ring(0, k + 1), ring(0, k)))
    for i in range(n - 1):
        for k in range(around):
            f.append((ring(i, k), ring(i, k + 1), ring(i + 1, k + 1)))
            f.append((ring(i, k), ring(i + 1, k + 1), ring(i + 1, k)))
    last = len(v) - 1
    for k in range(around):
        f.append((last, ring(n - 1, k), ring(n - 1, k + 1)))
    return v, f


def volume(v, f):
    s = 0.0
    for a, b, c in f:
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = v[a], v[b], v[c]
        s += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)
    return s / 6


def write(path, shells, comment):
    with open(path, "w") as out:
        out.write("# " + comment + " (make_bodies.py)\n")
        base = 1
        for v, f in shells:
            assert volume(v, f) > 0, path
            for p in v:
                out.write("v %.9g %.9g %.9g\n" % p)
            for a, b, c in f:
                out.write("f %d %d %d\n" % (a + base, b + base, c + base))
            base += len(v)


if len(sys.argv) == 4 and sys.argv[1] == "--spheres":
    n = int(sys.argv[2])
    write(sys.argv[3], [sphere((0.0, 0.0, 0.0), 1.0, 2 * n, n), sphere((1.2, 0.1, 0.05), 0.9, 2 * n, n)],
          "two interpenetrating spheres")
    sys.exit(0)
# Two parallel limbs 0.2 apart, radius 0.2, 1.2 long between their caps' centres.
write("two_limbs.obj", [capsule((0.0, -0.3, 0.0), (1.2, -0.3, 0.0), 0.2), capsule((0.0, 0.3, 0.0), (1.2, 0.3, 0.0), 0.2)],
      "two limbs side by side")
# A head-sized sphere (radius 0.5 at the origin) and a hand 0.15 from it.
write("hand_head.obj", [sphere((0.0, 0.0, 0.0), 0.5), capsule((0.8, 0.0, 0.0), (1.3, 0.0, 0.0), 0.15, around=12)],
      "a head and a hand")
