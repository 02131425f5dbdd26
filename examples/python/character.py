"""A skinned character from Python: the example arm (examples/character/arm.gltf)
read at 10 frames per second, rigged on a lattice, its first three frames run
and the simulated surface written as a PC2 point cache.

    PYTHONPATH=build/python python3 examples/python/character.py [arm.pc2] [--resolution N]

Without --resolution the lattice's cell is 0.025 m, as in
examples/character/arm.json; with it, N cells along the arm's longest side.
"""

import argparse
import pathlib

import snh

ARM = pathlib.Path(__file__).resolve().parents[1] / "character" / "arm.gltf"

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("pc2", nargs="?", default="arm.pc2", help="the point cache to write")
parser.add_argument("--resolution", type=int, help="cells along the longest side (default: cell 0.025)")
args = parser.parse_args()

character = snh.read_character(str(ARM), snh.CharacterReadOptions(clip="bend", fps=10, last_frame=2))
cell = snh.character_cell(character, args.resolution) if args.resolution else 0.025
rig = snh.prepare_character(character, cell, snh.CharacterBoneOptions(radius_fraction=0.5, exclude=["wrist"]))
print(
    f"{character.surface.vertex_count} vertices, {len(character.joints)} joints, "
    f"cell {cell:.4g}: {rig.voxels.lattice.element_count} hexes, bones {[b.name for b in rig.bones.bones]}"
)

material = snh.Material.from_youngs_modulus(2e4, 0.45)
simulation = snh.Simulation(rig.voxels.lattice, material, rig.constraints, snh.SolveOptions(load_steps=1))
cache = snh.CharacterCacheSeries(character, pc2=args.pc2)


def on_frame(frame, lattice, surface, skinned):
    cache.add(frame.record.frame, surface)
    print(
        f"frame {frame.record.frame}: {frame.record.newton_iterations} Newton iterations, "
        f"{'converged' if frame.record.converged else str(frame.record.status)}, "
        f"LBS distance max {frame.lbs.max_distance * 1e3:.3f} mm, mean {frame.lbs.mean_distance * 1e3:.3f} mm"
    )


frames = snh.run_character_frames(simulation, character, rig, on_frame=on_frame)
cache.finish()
converged = sum(f.record.converged for f in frames)
print(f"{converged} of {len(frames)} frames converged; wrote {args.pc2} ({snh.read_pc2(args.pc2).sample_count} samples)")
