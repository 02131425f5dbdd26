"""Skinned characters: reading, bones, the rigged lattice, frames against
linear blend skinning, point caches, and the surface per frame bit for bit
as `snh run` writes it."""

import json
import pathlib
import subprocess

import numpy as np
import pytest

import snh

ROOT = pathlib.Path(__file__).resolve().parents[2]
ARM = str(ROOT / "examples" / "character" / "arm.gltf")
BAD_WEIGHTS = str(ROOT / "tests" / "data" / "character" / "bad_weights.gltf")
CELL = 0.025  # examples/character/arm.json


def arm(last_frame=2):
    return snh.read_character(ARM, snh.CharacterReadOptions(clip="bend", fps=10, last_frame=last_frame))


def arm_bones():
    return snh.CharacterBoneOptions(radius_fraction=0.5, exclude=["wrist"])


def weight_sums(weights):
    rows = np.repeat(np.arange(weights.vertex_count), np.diff(weights.offset))
    return np.bincount(rows, weights=weights.weight, minlength=weights.vertex_count)


def arm_simulation(rig):
    material = snh.Material.from_youngs_modulus(2e4, 0.45)
    return snh.Simulation(rig.voxels.lattice, material, rig.constraints, snh.SolveOptions(load_steps=1))


def run_arm(character, rig, options=None):
    """The frames and, per frame, the callback's lattice, surface and skinned arrays."""
    seen = []
    frames = snh.run_character_frames(
        arm_simulation(rig), character, rig, options, on_frame=lambda f, x, s, k: seen.append((f, x, s, k))
    )
    return frames, seen


@pytest.fixture(scope="module")
def character():
    return arm()


@pytest.fixture(scope="module")
def rig(character):
    return snh.prepare_character(character, CELL, arm_bones())


def test_read_arm_shapes_and_weights(character):
    c = character
    assert c.file == ARM
    assert c.surface.positions.shape == (359, 3) and c.surface.positions.dtype == np.float64
    assert c.surface.triangles.dtype == np.int32
    # The seam is welded: fewer welded vertices, each at its surface vertices' position.
    assert c.welded.vertex_count < c.surface.vertex_count
    assert c.welded_index.shape == (359,) and c.welded_index.dtype == np.int32
    assert np.allclose(c.welded.positions[c.welded_index], c.surface.positions, atol=1e-9)
    assert [j.name for j in c.joints] == ["shoulder", "elbow", "wrist"]
    assert [j.parent for j in c.joints] == [-1, 0, 1]
    assert np.allclose([j.rest_position[0] for j in c.joints], [0.05, 0.2, 0.35])
    for j in c.joints:
        assert j.inverse_bind.shape == (4, 4)
        assert np.allclose(j.inverse_bind @ [*j.rest_position, 1.0], [0, 0, 0, 1])
    w = c.weights
    assert w.vertex_count == 359
    assert w.offset.shape == (360,) and w.offset.dtype == np.int32 and w.offset[0] == 0
    assert w.joint.dtype == np.int32 and w.weight.dtype == np.float64
    assert w.joint.shape == w.weight.shape == (w.offset[-1],)
    assert np.all((w.joint >= 0) & (w.joint < 3))
    assert np.allclose(weight_sums(w), 1.0, atol=1e-3)
    assert c.clip_names == ["bend"] and c.has_clip
    assert c.clip.name == "bend" and c.clip.index == 0 and c.clip.fps == 10.0 and c.clip.first_frame == 0
    assert c.clip.frame_count == 3
    assert np.allclose(c.clip.times, [0.0, 0.1, 0.2])
    assert c.clip.skinning.shape == (3, 3, 4, 4) and c.clip.skinning.dtype == np.float64
    assert c.warnings == []  # a clean file: nothing repaired


def test_linear_blend_skinning_bends_the_arm():
    c = arm(last_frame=None)  # the whole clip: 0 to 90 degrees over 1 s
    assert c.clip.frame_count == 11
    rest = c.surface.positions
    at_rest = snh.linear_blend_skinning(rest, c.weights, c.clip.skinning[0])
    assert np.allclose(at_rest, rest, atol=1e-9)
    bent = snh.linear_blend_skinning(rest, c.weights, c.clip.skinning[-1])
    assert bent.shape == (359, 3)
    assert np.allclose(bent[358], [0.2, 0.2, 0.0], atol=1e-5)  # the tip's centre
    with pytest.raises(ValueError, match="rest"):
        snh.linear_blend_skinning(rest[:-1], c.weights, c.clip.skinning[0])
    with pytest.raises(ValueError, match="matrices"):
        snh.linear_blend_skinning(rest, c.weights, c.clip.skinning[0][:, :3])
    with pytest.raises(snh.Error, match="names joint"):
        snh.linear_blend_skinning(rest, c.weights, c.clip.skinning[0][:2])


def test_skin_weights_from_arrays():
    w = snh.SkinWeights([0, 1, 3], [0, 0, 1], [1.0, 0.25, 0.75])
    assert w.vertex_count == 2
    shift = np.eye(4)
    shift[0, 3] = 1.0
    out = snh.linear_blend_skinning([[0, 0, 0], [0, 1, 0]], w, np.stack([np.eye(4), shift]))
    assert np.allclose(out, [[0, 0, 0], [0.75, 1, 0]])
    with pytest.raises(ValueError, match="offset"):
        snh.SkinWeights([1, 2], [0], [1.0])
    with pytest.raises(ValueError, match="offset"):
        snh.SkinWeights([0, 2, 1], [0, 0], [1.0, 1.0])
    with pytest.raises(ValueError, match="last offset"):
        snh.SkinWeights([0, 2], [0, 0], [1.0])


def test_unknown_clip_names_the_file_and_the_clips():
    with pytest.raises(snh.Error) as error:
        snh.read_character(ARM, snh.CharacterReadOptions(clip="wave"))
    message = str(error.value)
    assert ARM in message and "no animation clip named 'wave'" in message and "'bend'" in message
    with pytest.raises(AttributeError):
        snh.CharacterReadOptions(clips="wave")


def test_weight_policy():
    strict = snh.CharacterReadOptions(weights=snh.WeightPolicy.strict)
    assert strict.weights == snh.WeightPolicy.strict
    with pytest.raises(snh.Error) as error:
        snh.read_character(BAD_WEIGHTS, strict)
    assert BAD_WEIGHTS in str(error.value) and "vertex 7" in str(error.value)
    c = snh.read_character(BAD_WEIGHTS, snh.CharacterReadOptions(weights=snh.WeightPolicy.normalize))
    sums = weight_sums(c.weights)
    assert sums[7] == pytest.approx(1.0, abs=1e-12)
    assert np.allclose(sums, 1.0, atol=1e-3)
    assert snh.CharacterReadOptions().weights == snh.WeightPolicy.normalize
    assert len(c.warnings) == 1 and "1 of 359 vertices" in c.warnings[0] and "worst sum 0.5" in c.warnings[0]


def test_prepare_character(character, rig):
    c = character
    assert rig.voxels.cell == CELL
    assert rig.voxels.lattice.element_count == 192  # docs/characters.md
    n = rig.voxels.lattice.vertex_count
    assert [s.name for s in rig.constraints] == ["shoulder", "elbow"]
    assert [b.name for b in rig.bones.bones] == ["shoulder", "elbow"]
    assert rig.bones.joint.tolist() == [0, 1]
    assert rig.bones.animation.frame_count == c.clip.frame_count
    assert rig.bones.animation.transforms.shape == (3, 2, 4, 4)
    assert np.array_equal(rig.bones.animation.transforms[:, 1], c.clip.skinning[:, 1])
    assert rig.embedding.element.shape == (359,)
    at_rest = snh.embedded_positions(rig.embedding, rig.voxels.lattice, rig.voxels.lattice.positions)
    assert np.allclose(at_rest, c.surface.positions, atol=1e-9)
    assert rig.lattice_weights.vertex_count == n
    assert np.allclose(weight_sums(rig.lattice_weights), 1.0, atol=1e-9)
    assert rig.cell == CELL
    assert rig.vertices_outside == 0 and rig.max_outside_distance == 0.0
    assert rig.warnings == [] and rig.bones.warnings == []
    assert snh.CharacterPrepareOptions().pieces == "attach"
    # Both overloads, and the options object set in place, give the same rig.
    options = snh.CharacterPrepareOptions()
    options.bones.exclude = ["wrist"]
    options.voxelize.name = "arm"
    assert options.bones.exclude == ["wrist"] and options.voxelize.name == "arm"
    for other in (
        snh.prepare_character(c, CELL, options),
        snh.prepare_character(c, CELL, bones=arm_bones(), voxelize=snh.VoxelizeOptions()),
    ):
        assert np.array_equal(other.voxels.lattice.positions, rig.voxels.lattice.positions)
        assert [s.vertices.tolist() for s in other.constraints] == [s.vertices.tolist() for s in rig.constraints]
    # Without exclusions the wrist, a leaf, gets a bone from the skin it weighs
    # most (leaf_from_skin), and none without that.
    default = snh.prepare_character(c, CELL)
    assert [s.name for s in default.constraints] == ["shoulder", "elbow", "wrist"]
    no_leaves = snh.prepare_character(c, CELL, bones=snh.CharacterBoneOptions(leaf_from_skin=False))
    assert [s.name for s in no_leaves.constraints] == ["shoulder", "elbow"]


def test_character_cell(character):
    # The arm is 0.4 m long: 16 cells along it.
    cell = snh.character_cell(character, 16)
    assert cell == pytest.approx(0.025, rel=1e-6)
    rig = snh.prepare_character(character, cell, arm_bones())
    assert rig.voxels.cell == cell
    with pytest.raises(snh.Error, match="resolution"):
        snh.character_cell(character, 0)
    bones = snh.character_bones(character, arm_bones())
    assert [b.name for b in bones.bones] == ["shoulder", "elbow"]
    with pytest.raises(snh.Error):
        snh.character_bones(character, snh.CharacterBoneOptions(radius={"knee": 0.01}))


def test_run_frames_with_callback(character, rig):
    c = character
    frames, seen = run_arm(c, rig)
    assert [f.record.frame for f in frames] == [0, 1, 2]
    assert [f.record.time for f in frames] == pytest.approx([0.0, 0.1, 0.2])
    assert all(f.record.converged for f in frames)
    assert frames[0].lbs.max_distance < 1e-3
    assert frames[2].lbs.max_distance > frames[1].lbs.max_distance > 0.0
    n = rig.voxels.lattice.vertex_count
    for f, (record, lattice, surface, skinned) in enumerate(seen):
        assert record.record.frame == f
        assert lattice.shape == (n, 3) and surface.shape == skinned.shape == (359, 3)
        assert surface.dtype == skinned.dtype == np.float64
        lbs = snh.linear_blend_skinning(c.surface.positions, c.weights, c.clip.skinning[f])
        assert np.array_equal(skinned, lbs)
        distance = np.linalg.norm(surface - skinned, axis=1)
        assert record.lbs.max_distance == pytest.approx(distance.max(), rel=1e-12, abs=1e-15)
        assert record.lbs.mean_distance == pytest.approx(distance.mean(), rel=1e-12, abs=1e-15)
        assert np.allclose(snh.embedded_positions(rig.embedding, rig.voxels.lattice, lattice), surface)


def test_run_frames_stops_and_propagates(character, rig):
    sim = arm_simulation(rig)
    frames = snh.run_character_frames(sim, character, rig, on_frame=lambda f, x, s, k: f.record.frame < 1)
    assert [f.record.frame for f in frames] == [0, 1]

    def fail(f, x, s, k):
        raise KeyError("from the callback")

    with pytest.raises(KeyError, match="from the callback"):
        snh.run_character_frames(arm_simulation(rig), character, rig, on_frame=fail)
    with pytest.raises(TypeError, match="on_frame"):
        snh.run_character_frames(arm_simulation(rig), character, rig, on_frame=3)
    other = snh.Simulation(snh.make_box_lattice(2, 1, 1, 0.1), snh.Material.from_youngs_modulus(2e4, 0.45))
    with pytest.raises(ValueError, match="rig's lattice"):
        snh.run_character_frames(other, character, rig)
    options = snh.CharacterFrameOptions(skinned_guess=True)
    options.frames.load_steps = 1
    frames = snh.run_character_frames(arm_simulation(rig), character, rig, options)
    assert len(frames) == 3 and all(f.record.converged for f in frames)


def test_frames_are_deterministic(character, rig):
    first = run_arm(character, rig)[1]
    second = run_arm(character, rig)[1]
    for a, b in zip(first, second):
        assert np.array_equal(a[1], b[1]) and np.array_equal(a[2], b[2])


def test_point_caches_round_trip(tmp_path, character, rig):
    c = character
    frames, seen = run_arm(c, rig)
    series = snh.CharacterCacheSeries(
        c, pc2=str(tmp_path / "arm.pc2"), mdd=str(tmp_path / "arm.mdd"), lbs=str(tmp_path / "lbs.pc2")
    )
    for record, _, surface, _ in seen:
        series.add(record.record.frame, surface)
    with pytest.raises(snh.Error, match="not among the sampled frames"):
        series.add(7, seen[0][2])
    series.finish()
    pc2 = snh.read_pc2(str(tmp_path / "arm.pc2"))
    assert pc2.point_count == 359 and pc2.sample_count == 3
    assert pc2.start_frame == 0.0 and pc2.sample_rate == 1.0
    assert pc2.samples.dtype == np.float32 and pc2.samples.shape == (3, 359, 3)
    assert np.array_equal(pc2.samples, np.stack([s for _, _, s, _ in seen]).astype(np.float32))
    mdd = snh.read_mdd(str(tmp_path / "arm.mdd"))
    assert np.array_equal(mdd.samples, pc2.samples)
    assert np.allclose(mdd.times, c.clip.times)
    lbs = snh.read_pc2(str(tmp_path / "lbs.pc2"))
    assert np.array_equal(lbs.samples, np.stack([k for _, _, _, k in seen]).astype(np.float32))

    # A cache built in Python, through both formats.
    samples = np.random.default_rng(1).normal(size=(4, 5, 3))
    cache = snh.PointCache(samples=samples, start_frame=2.0, sample_rate=0.5, times=[0.0, 0.1, 0.2, 0.3])
    assert cache.point_count == 5
    snh.write_pc2(str(tmp_path / "a.pc2"), cache)
    snh.write_point_cache(str(tmp_path / "a.MDD"), cache)
    back = snh.read_pc2(str(tmp_path / "a.pc2"))
    assert np.array_equal(back.samples, samples.astype(np.float32))
    assert (back.start_frame, back.sample_rate) == (2.0, 0.5)
    assert (tmp_path / "a.pc2").read_bytes()[:12] == b"POINTCACHE2\0"
    back = snh.read_mdd(str(tmp_path / "a.MDD"))
    assert np.array_equal(back.samples, samples.astype(np.float32))
    assert np.array_equal(back.times, np.float32([0.0, 0.1, 0.2, 0.3]))
    with pytest.raises(snh.Error, match="a.obj"):
        snh.write_point_cache(str(tmp_path / "a.obj"), cache)
    cache.times = [0.0]
    with pytest.raises(snh.Error):
        snh.write_mdd(str(tmp_path / "b.mdd"), cache)
    (tmp_path / "short.pc2").write_bytes(b"POINTCACHE2\0\1\0")
    with pytest.raises(snh.Error, match="short.pc2"):
        snh.read_pc2(str(tmp_path / "short.pc2"))
    with pytest.raises(ValueError, match="samples"):
        snh.PointCache(samples=np.zeros((2, 5)))


def test_write_surface_ply(tmp_path, character):
    c = character
    path = tmp_path / "arm.ply"
    moved = c.surface.positions + [1.0, 0.0, 0.0]
    snh.write_surface_ply(str(path), c.surface, moved)
    data = path.read_bytes()
    header, body = data.split(b"end_header\n", 1)
    assert b"binary_little_endian" in header and b"element vertex 359" in header
    xyz = np.frombuffer(body[: 359 * 12], dtype="<f4").reshape(359, 3)
    assert np.array_equal(xyz, moved.astype(np.float32))
    with pytest.raises(ValueError, match="positions"):
        snh.write_surface_ply(str(path), c.surface, moved[:-1])


def test_surface_matches_snh_run(tmp_path, cli_program):
    """The arm example's first frames through `snh run` and through Python:
    the same PC2 samples, bit for bit."""
    scene = json.loads((ROOT / "examples" / "character" / "arm.json").read_text())
    scene["character"]["file"] = ARM
    scene["character"]["frames"] = [0, 2]
    scene["output"] = {"pc2": "cli.pc2"}
    path = tmp_path / "arm.json"
    path.write_text(json.dumps(scene))
    subprocess.run([cli_program, "run", str(path), "--quiet"], cwd=tmp_path, check=True, capture_output=True)
    cli = snh.read_pc2(str(tmp_path / "cli.pc2"))

    # The same simulation built in Python: the scene file gives the solve
    # options (with its self-contact surface) and the materials.
    loaded = snh.load_scene(str(path))
    c = snh.read_character(ARM, snh.CharacterReadOptions(clip="bend", fps=10, first_frame=0, last_frame=2))
    rig = snh.prepare_character(c, scene["character"]["cell"], arm_bones())
    sim = snh.Simulation(rig.voxels.lattice, loaded.materials, rig.constraints, loaded.scene.options)
    options = snh.CharacterFrameOptions(skinned_guess=False)
    options.frames.load_steps = loaded.scene.options.load_steps
    surfaces = []
    frames = snh.run_character_frames(sim, c, rig, options, lambda f, x, s, k: surfaces.append(s))
    assert [f.record.frame for f in frames] == [0, 1, 2]
    assert cli.sample_count == 3
    assert np.array_equal(cli.samples, np.stack(surfaces).astype(np.float32))
