"""Surfaces, voxelization, embedding, bones and the frame driver."""

import numpy as np

import snh

CUBE_TRIANGLES = [
    [0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4],
    [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5],
]  # fmt: skip


def unit_cube():
    corners = [[x, y, z] for z in (0.0, 1.0) for y in (0.0, 1.0) for x in (0.0, 1.0)]
    return snh.TriangleSurface(corners, CUBE_TRIANGLES)


def test_voxelize_and_embed():
    cube = unit_cube()
    snh.validate_closed_surface(cube)
    assert snh.enclosed_volume(cube) == 1.0
    voxels = snh.voxelize(cube, 0.25)
    assert voxels.lattice.element_count == 64
    assert tuple(voxels.dims) == (4, 4, 4)
    assert voxels.element_cell.shape == (64, 3)
    embedding = snh.embed(voxels, cube)
    assert embedding.weights.shape == (8, 8)
    at_rest = snh.embedded_positions(embedding, voxels.lattice, voxels.lattice.positions)
    assert np.allclose(at_rest, cube.positions)


def test_bones_and_frames():
    lattice = snh.make_box_lattice(4, 1, 1, 0.25)
    bones = [
        snh.Bone("root", snh.Capsule((0, 0.125, 0.125), (0.01, 0.125, 0.125), 0.2)),
        snh.Bone("tip", snh.Capsule((0.99, 0.125, 0.125), (1, 0.125, 0.125), 0.2)),
    ]
    sets = snh.bone_constraints(lattice, bones)
    assert [s.name for s in sets] == ["root", "tip"]
    moved = snh.identity_matrix4()
    moved[0, 3] = 0.05
    animation = snh.Animation(["tip"], [0.0, 1.0], np.stack([snh.identity_matrix4(), moved])[:, None])
    assert animation.transforms.shape == (2, 1, 4, 4)
    sim = snh.Simulation(lattice, snh.Material.from_youngs_modulus(1e4, 0.4), sets)
    seen = []
    records = snh.run_frames(sim, animation, on_frame=lambda r, x, s: seen.append(x.shape) or True)
    assert [r.converged for r in records] == [True, True]
    assert seen == [(lattice.vertex_count, 3)] * 2
    tip = sets[1].vertices
    assert np.allclose(sim.positions[tip, 0], lattice.positions[tip, 0] + 0.05)
