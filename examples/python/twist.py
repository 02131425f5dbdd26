"""A soft bar held at one end while the other end turns half a turn.

Usage: python3 twist.py [output.vtu]

Solves the twist in load steps, prints each Newton iteration's residual as
it runs, and writes the deformed bar with its stress and energy density for
ParaView.
"""

import math
import sys

import numpy as np

import snh

out = sys.argv[1] if len(sys.argv) > 1 else "twist.vtu"

# A 2 x 0.5 x 0.5 bar of 16 x 4 x 4 hexahedra; lengths in m, stresses in Pa.
bar = snh.make_box_lattice(16, 4, 4, 0.125)
held = snh.ConstraintSet("held", snh.vertices_on_plane(bar, (0, 0, 0), (1, 0, 0)))
turned = snh.ConstraintSet(
    "turned",
    snh.vertices_on_plane(bar, (2, 0, 0), (1, 0, 0)),
    # At load parameter t the end has turned t * 180 degrees about the bar's axis.
    motion=lambda t: snh.RigidTransform.rotation_about((1, 0, 0), t * math.pi, (2, 0.25, 0.25)),
)
flesh = snh.Material.from_youngs_modulus(1e5, 0.45)
options = snh.SolveOptions(load_steps=6, relative_tolerance=1e-6)
sim = snh.Simulation(bar, flesh, [held, turned], options)
print(f"device: {sim.device.name}, {bar.element_count} hexes, {3 * bar.vertex_count} DOF")


def progress(record):
    print(f"  step {record.step} iteration {record.iteration}: |r| = {record.residual_norm:.3e}")
    return True  # False would cancel the solve


result = sim.solve(progress=progress)
print(f"converged: {result.converged}, {len(result.history)} Newton iterations, {result.seconds:.2f} s")
print(f"volume ratio {result.volume_ratio:.4f}, min J {result.min_j:.3f}")

fields = sim.fields()
print(f"largest von Mises stress: {np.nanmax(fields.von_mises):.4g} Pa")
for r in sim.reactions():
    print(f"  {r.name:7s} torque about x: {r.torque[0]:.4g} N m")
snh.write_vtu(out, bar, sim.positions, cell_fields=snh.element_fields_for_vtu(fields, sim.materials))
print(f"wrote {out}")
sys.exit(0 if result.converged else 1)
