"""Loads snh's point caches onto a character in Blender and checks them.

    blender -b --factory-startup --python tests/blender/check_cache.py -- \\
        --file CHAR --pc2 SIM.pc2 [--lbs LBS.pc2] --frames 0,5,10 --fps FPS --out report.json

The character is imported with Blender's own importer (by extension:
.gltf/.glb import_scene.gltf, .fbx import_scene.fbx, .dae
wm.collada_import) and the skinned mesh whose vertex count equals the
cache's point count is taken. The caches are in the file's coordinates;
Blender's importers change them:

  glTF  the importer turns +Y up into +Z up in the vertices themselves:
        (x, y, z) in the file is (x, -z, y) in obj.data.vertices. Mesh Cache:
        forward_axis POS_Z, up_axis NEG_Y (measured: the modifier applies
        its axis conversion the other way round from the importers'
        forward/up convention, so NEG_Z/POS_Y, the glTF importer's, gives
        (x, z, -y)).
  FBX   the importer keeps the control points as they are in
        obj.data.vertices and puts the axis conversion and the unit scale
        into the objects' transforms. Mesh Cache: forward_axis POS_Y,
        up_axis POS_Z (no conversion).
  DAE   the vertices are kept as in the file (seen on Blender's own Z_UP
        files; a Y_UP file is not covered here). Mesh Cache as FBX.

Frames: the scene's frame rate is set to --fps before importing, and glTF
and Collada keys land on frame = seconds x fps, so cache sample k is scene
frame start + k, start being the PC2 header's start frame (the first clip
frame). The FBX importer sets the scene's rate from the file instead (and
offsets its keys by anim_offset, given as 0 here): clip frame f is scene
frame f x scene fps / --fps. Mesh Cache: cache_format PC2, time_mode FRAME,
play_mode SCENE, frame_start = start, frame_scale = --fps / scene fps (1
when they agree), deform_mode OVERWRITE, interpolation LINEAR (the modifier
reads sample frame_scale x scene frame - frame_start, whatever the PC2
header's start frame says).

Checks, each relative to the rest mesh's bounding-box diagonal:
  (a) rest: the LBS cache's frame 0 (else the simulated cache's) against
      the imported mesh's rest vertices, vertex for vertex (<= 1e-5);
      where it fails, a nearest-point match tells an order problem from a
      shape problem.
  (b) mesh_cache: the simulated cache through a Mesh Cache modifier (the
      Armature modifier off), evaluated at each frame, against the cache's
      sample (<= 1e-5).
  (c) skinning: Blender's own Armature deformation at each frame (Mesh
      Cache off) against the LBS cache's sample (<= 1e-4).
The report (--out) holds every figure; the exit status is 1 when a check
fails or the mesh is not found.
"""

import argparse
import json
import math
import os
import struct
import sys
import warnings

import bpy
import numpy
from mathutils.kdtree import KDTree

# Blender 3.4's glTF importer uses numpy.bool, which numpy 1.24 (Debian 12's,
# which Debian's Blender runs with) removed: give it back as the builtin.
with warnings.catch_warnings():
    warnings.simplefilter("ignore", FutureWarning)
    if not hasattr(numpy, "bool"):
        numpy.bool = bool

TOL_REST = 1e-5
TOL_CACHE = 1e-5
TOL_SKIN = 1e-4

# cache (file) coordinates -> Blender object-local coordinates, and the
# Mesh Cache modifier's axes that do the same.
AXES = {
    "gltf": (lambda p: (p[0], -p[2], p[1]), "POS_Z", "NEG_Y"),
    "fbx": (lambda p: (p[0], p[1], p[2]), "POS_Y", "POS_Z"),
    "dae": (lambda p: (p[0], p[1], p[2]), "POS_Y", "POS_Z"),
}


def parse():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="check_cache.py")
    ap.add_argument("--file", required=True, help="the character file (.gltf, .glb, .fbx, .dae)")
    ap.add_argument("--pc2", help="the simulated surface's PC2 cache")
    ap.add_argument("--points", type=int,
                    help="without caches: only check that a skinned mesh of this many vertices is imported")
    ap.add_argument("--lbs", help="the linear-blend-skinned surface's PC2 cache")
    ap.add_argument("--frames", default="0", help="clip frames to check, comma separated")
    ap.add_argument("--fps", type=float, required=True, help="the frame rate the caches were sampled at")
    ap.add_argument("--out", required=True, help="the JSON report")
    return ap.parse_args(argv)


def read_pc2(path):
    with open(path, "rb") as f:
        data = f.read()
    magic, version, points, start, rate, samples = struct.unpack_from("<12siiffi", data, 0)
    if magic != b"POINTCACHE2\0" or version != 1:
        raise SystemExit(f"{path}: not a PC2 file")
    if len(data) != 32 + 12 * points * samples:
        raise SystemExit(f"{path}: {len(data)} bytes, expected {32 + 12 * points * samples}")
    flat = struct.unpack_from("<%df" % (3 * points * samples), data, 32)
    frames = [[flat[(s * points + i) * 3:(s * points + i) * 3 + 3] for i in range(points)] for s in range(samples)]
    return {"points": points, "start": start, "rate": rate, "samples": samples, "frames": frames}


def fmt_of(path):
    ext = os.path.splitext(path)[1].lower()
    return {".gltf": "gltf", ".glb": "gltf", ".fbx": "fbx", ".dae": "dae"}.get(ext)


def import_file(path, fmt, fps):
    scene = bpy.context.scene
    scene.render.fps = int(round(fps))
    scene.render.fps_base = scene.render.fps / fps
    if fmt == "gltf":
        bpy.ops.import_scene.gltf(filepath=path)
    elif fmt == "fbx":
        # The FBX importer sets the scene's rate from the file and puts its
        # keys at seconds x that rate + anim_offset (default 1).
        bpy.ops.import_scene.fbx(filepath=path, anim_offset=0.0)
    else:
        bpy.ops.wm.collada_import(filepath=path)


def max_diff(a, b):
    worst, at = 0.0, -1
    for i, (p, q) in enumerate(zip(a, b)):
        d = math.dist(p, q)
        if d > worst:
            worst, at = d, i
    return worst, at


def evaluated(obj):
    depsgraph = bpy.context.evaluated_depsgraph_get()
    ev = obj.evaluated_get(depsgraph)
    mesh = ev.to_mesh()
    co = [tuple(v.co) for v in mesh.vertices]
    ev.to_mesh_clear()
    return co


def main():
    args = parse()
    fmt = fmt_of(args.file)
    report = {"file": os.path.abspath(args.file), "format": fmt, "pc2": os.path.abspath(args.pc2) if args.pc2 else None,
              "lbs": os.path.abspath(args.lbs) if args.lbs else None, "fps": args.fps,
              "blender": bpy.app.version_string, "checks": {}, "passed": False}

    def finish(ok, error=None):
        report["passed"] = ok
        if error:
            report["error"] = error
            print("check_cache:", error, file=sys.stderr)
        with open(args.out, "w") as f:
            json.dump(report, f, indent=1)
        print(json.dumps({k: v for k, v in report.items() if k != "frames"}, indent=1))
        sys.stdout.flush()
        sys.exit(0 if ok else 1)

    if fmt is None:
        finish(False, f"{args.file}: unknown extension (.gltf, .glb, .fbx, .dae)")
    if args.points is not None and not args.pc2:
        bpy.ops.wm.read_factory_settings(use_empty=True)
        import_file(args.file, fmt, args.fps)
        counts = {o.name: len(o.data.vertices) for o in bpy.context.scene.objects if o.type == 'MESH'}
        report.update({"points": args.points, "meshes": counts})
        found = [o for o in bpy.context.scene.objects if o.type == 'MESH' and len(o.data.vertices) == args.points
                 and any(m.type == 'ARMATURE' for m in o.modifiers)]
        if not found:
            finish(False, f"no skinned mesh with {args.points} vertices in {args.file} as Blender imports it; "
                          f"the imported meshes' vertex counts: {counts}")
        finish(True)
    if not args.pc2:
        finish(False, "give --pc2 (or --points)")
    sim = read_pc2(args.pc2)
    lbs = read_pc2(args.lbs) if args.lbs else None
    if lbs and (lbs["points"] != sim["points"] or lbs["samples"] != sim["samples"] or lbs["start"] != sim["start"]):
        finish(False, f"the caches differ in points, samples or start: {args.pc2} and {args.lbs}")
    start = int(round(sim["start"]))
    frames = [int(f) for f in args.frames.split(",") if f.strip()]
    for f in frames:
        if not start <= f < start + sim["samples"]:
            finish(False, f"frame {f} is outside the cache's frames {start}..{start + sim['samples'] - 1}")
    report.update({"points": sim["points"], "samples": sim["samples"], "start_frame": start, "frames": frames})

    bpy.ops.wm.read_factory_settings(use_empty=True)
    import_file(args.file, fmt, args.fps)
    meshes = [o for o in bpy.context.scene.objects if o.type == 'MESH']
    counts = {o.name: len(o.data.vertices) for o in meshes}
    report["meshes"] = counts
    matching = [o for o in meshes if len(o.data.vertices) == sim["points"]]
    skinned = [o for o in matching if any(m.type == 'ARMATURE' for m in o.modifiers)]
    if not skinned:
        finish(False, f"no skinned mesh with the cache's {sim['points']} points in {args.file}; "
                      f"the imported meshes' vertex counts: {counts}")
    obj = skinned[0]
    report["object"] = obj.name
    to_local, forward, up = AXES[fmt]
    rest = [tuple(v.co) for v in obj.data.vertices]
    lo = [min(p[k] for p in rest) for k in range(3)]
    hi = [max(p[k] for p in rest) for k in range(3)]
    diag = math.dist(lo, hi)
    report["bbox_diagonal"] = diag
    report["mesh_cache_settings"] = {"cache_format": "PC2", "forward_axis": forward, "up_axis": up,
                                     "flip_axis": [], "deform_mode": "OVERWRITE", "time_mode": "FRAME",
                                     "play_mode": "SCENE", "frame_start": float(start), "frame_scale": 1.0,
                                     "interpolation": "LINEAR"}
    ok = True

    # (a) rest
    ref = lbs if lbs else sim
    first = [to_local(p) for p in ref["frames"][0]]
    d, at = max_diff(rest, first)
    a = {"cache": "lbs" if lbs else "pc2", "max_diff": d, "relative": d / diag, "vertex": at,
         "tolerance": TOL_REST, "passed": d / diag <= TOL_REST}
    if lbs:
        ds, _ = max_diff(rest, [to_local(p) for p in sim["frames"][0]])
        a["simulated_frame0_max_diff"] = ds
        a["simulated_frame0_relative"] = ds / diag
    if not a["passed"]:
        tree = KDTree(len(rest))
        for i, p in enumerate(rest):
            tree.insert(p, i)
        tree.balance()
        nearest = [tree.find(p) for p in first]
        a["nearest_point_max_diff"] = max(n[2] for n in nearest)
        a["vertices_matched_elsewhere"] = sum(1 for i, n in enumerate(nearest) if n[1] != i)
    report["checks"]["rest"] = a
    ok &= a["passed"]

    scene = bpy.context.scene
    # Clip frame f (at --fps) is scene frame f x ratio.
    ratio = scene.render.fps / scene.render.fps_base / args.fps
    report["scene_fps"] = scene.render.fps / scene.render.fps_base
    report["mesh_cache_settings"]["frame_scale"] = 1.0 / ratio

    def set_frame(f):
        t = f * ratio
        whole = math.floor(t + 1e-9)
        scene.frame_set(int(whole), subframe=max(0.0, t - whole))

    armature_mods = [m for m in obj.modifiers if m.type == 'ARMATURE']

    # (b) the simulated cache through a Mesh Cache modifier
    mc = obj.modifiers.new("snh_cache", 'MESH_CACHE')
    mc.cache_format = 'PC2'
    mc.filepath = os.path.abspath(args.pc2)
    mc.forward_axis = forward
    mc.up_axis = up
    mc.flip_axis = set()
    mc.deform_mode = 'OVERWRITE'
    mc.time_mode = 'FRAME'
    mc.play_mode = 'SCENE'
    mc.frame_start = float(start)
    mc.frame_scale = 1.0 / ratio
    mc.interpolation = 'LINEAR'
    for m in armature_mods:
        m.show_viewport = False
        m.show_render = False
    b = {"per_frame": {}, "tolerance": TOL_CACHE}
    worst = 0.0
    for f in frames:
        set_frame(f)
        co = evaluated(obj)
        want = [to_local(p) for p in sim["frames"][f - start]]
        d, at = max_diff(co, want)
        moved, _ = max_diff(co, rest)
        b["per_frame"][str(f)] = {"max_diff": d, "relative": d / diag, "vertex": at, "moved_from_rest": moved}
        worst = max(worst, d)
    b["max_relative"] = worst / diag
    b["passed"] = worst / diag <= TOL_CACHE
    report["checks"]["mesh_cache"] = b
    ok &= b["passed"]

    # (c) Blender's skinning against the LBS cache
    if lbs:
        mc.show_viewport = False
        mc.show_render = False
        for m in armature_mods:
            m.show_viewport = True
            m.show_render = True
        # Blender interpolates a rotation's keys component by component
        # (a normalized lerp) where glTF's LINEAR means slerp: between keys
        # further apart than a few degrees its skinning departs from the
        # file's. Each frame says whether it falls on a key.
        keys = set()
        for o in bpy.context.scene.objects:
            ad = o.animation_data
            if o.type == 'ARMATURE' and ad and ad.action:
                for fc in ad.action.fcurves:
                    keys.update(round(k.co[0], 3) for k in fc.keyframe_points)
        c = {"per_frame": {}, "tolerance": TOL_SKIN}
        worst = 0.0
        for f in frames:
            set_frame(f)
            co = evaluated(obj)
            want = [to_local(p) for p in lbs["frames"][f - start]]
            d, at = max_diff(co, want)
            moved, _ = max_diff(co, rest)
            c["per_frame"][str(f)] = {"max_diff": d, "relative": d / diag, "vertex": at,
                                      "blender_moved_from_rest": moved, "on_key": round(f * ratio, 3) in keys}
            worst = max(worst, d)
        c["max_relative"] = worst / diag
        c["passed"] = worst / diag <= TOL_SKIN
        report["checks"]["skinning"] = c
        ok &= c["passed"]

    finish(bool(ok))


try:
    main()
except SystemExit:
    raise
except Exception as e:  # an importer's or Blender's error: report it and fail
    import traceback
    traceback.print_exc()
    sys.exit(1)
