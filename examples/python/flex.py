"""A limb of muscle wrapped in fat, held by two bones, flexed at the elbow.

Usage: python3 flex.py [output.png]

The upper bone stays; the lower one bends about the elbow frame by frame,
each frame solved from the previous one (warm start) under gravity. The
plot shows the von Mises stress of the bent limb's mid-plane elements and
the bones' reaction moments over the bend; it is written to a PNG.
"""

import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import snh  # noqa: E402

out = sys.argv[1] if len(sys.argv) > 1 else "flex.png"

# Lengths in m, forces in N, stresses in Pa: a 0.4 m limb, 0.1 m thick.
h = 0.025
limb = snh.make_box_lattice(16, 4, 4, h)
fat = snh.Material.from_youngs_modulus(2e4, 0.47)
muscle = snh.Material.from_youngs_modulus(1e5, 0.49)
core = snh.MaterialRegion("muscle", snh.elements_in_box(limb, (0, 0.025, 0.025), (0.4, 0.075, 0.075)), muscle)
materials = snh.make_material_map(limb, fat, [core])

# Bones: capsules along the limb's axis near each end.
elbow = (0.2, 0.05, 0.05)
bones = [
    snh.Bone("upper_bone", snh.Capsule((0.0, 0.05, 0.05), (0.15, 0.05, 0.05), 0.013)),
    snh.Bone("lower_bone", snh.Capsule((0.25, 0.05, 0.05), (0.4, 0.05, 0.05), 0.013)),
]
sets = snh.bone_constraints(limb, bones)
options = snh.SolveOptions(body_force=(0.0, 0.0, -1000.0 * 9.81))  # density times gravity
sim = snh.Simulation(limb, materials, sets, options)
print(f"device: {sim.device.name}, {limb.element_count} hexes")

angles, moments = [], []
frames = 6
for frame in range(frames + 1):
    angle = (math.pi / 3) * frame / frames
    sim.set_transform("lower_bone", snh.RigidTransform.rotation_about((0, 1, 0), -angle, elbow))
    result = sim.solve(load_steps=1 if frame == 0 else 2)
    upper = sim.reactions()[0]
    angles.append(math.degrees(angle))
    moments.append(upper.torque[1])
    print(f"frame {frame}: {angles[-1]:4.0f} deg, {result.steps[-1].status}, min J {result.min_j:.3f}")

# The bent limb's elements in the mid-plane y = 0.05, coloured by stress.
fields = sim.fields()
centroids = sim.positions[limb.elements].mean(axis=1)
mid = snh.elements_in_box(limb, (0, 0.025, 0), (0.4, 0.05, 0.1))
fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4))
points = ax0.scatter(centroids[mid, 0], centroids[mid, 2], c=fields.von_mises[mid] / 1e3, cmap="viridis", s=60, marker="s")
fig.colorbar(points, ax=ax0, label="von Mises stress (kPa)")
ax0.set_aspect("equal")
ax0.set_xlabel("x (m)")
ax0.set_ylabel("z (m)")
ax0.set_title(f"flexed {angles[-1]:.0f} degrees")
ax1.plot(angles, moments, "o-")
ax1.set_xlabel("elbow angle (degrees)")
ax1.set_ylabel("upper bone moment about y (N m)")
ax1.set_title("reaction at the upper bone")
fig.tight_layout()
fig.savefig(out, dpi=120)
print(f"wrote {out}")
