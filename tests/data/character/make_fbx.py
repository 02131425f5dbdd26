# Makes bend.fbx (a skinned, animated tube: 3 bones, automatic weights, a
# clip that bends it over 10 frames) with Blender's own FBX exporter, then
# imports it again with Blender's FBX importer and writes what Blender reads
# to bend.json: the imported mesh's vertices (object-local coordinates, the
# file's control points), its raw vertex-group weights and the
# armature-deformed vertices at a few frames, in the mesh object's local
# space. It also writes bend_missing_bone.fbx: bend.fbx with the cluster of
# bone 'tip' disconnected from its bone node. tests/test_character_fbx.cpp
# compares snh's reader against these numbers.
#
#   blender -b --factory-startup --python tests/data/character/make_fbx.py -- tests/data/character
#
# Blender 3.4 wrote the committed files.
import math
import json
import os
import struct
import sys

import bmesh
import bpy

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
out_dir = os.path.abspath(argv[0] if argv else os.path.dirname(os.path.abspath(__file__)))
fbx_path = os.path.join(out_dir, "bend.fbx")
missing_path = os.path.join(out_dir, "bend_missing_bone.fbx")
json_path = os.path.join(out_dir, "bend.json")

FPS = 24
FRAME_START, FRAME_END = 1, 11  # the clip: 11 frames, the bend over 10
SNH_FRAMES = [0, 3, 5, 10]      # frames (from the clip's start) compared

# -- the character ----------------------------------------------------------
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.fps = FPS
scene.render.fps_base = 1.0
scene.frame_start, scene.frame_end = FRAME_START, FRAME_END

# A closed tube along z: 20 rings of 16 vertices, quads between the rings,
# a 16-sided polygon closing each end (triangulated by the reader), and one
# loose vertex that no face uses (weighted 0.5 to 'mid' alone below).
RINGS, AROUND, LENGTH = 20, 16, 3.0
bm = bmesh.new()
rings = []
for i in range(RINGS):
    z = LENGTH * i / (RINGS - 1)
    r = 0.3 + 0.04 * math.sin(2.0 * z)
    rings.append([bm.verts.new((r * math.cos(2 * math.pi * k / AROUND), r * math.sin(2 * math.pi * k / AROUND), z))
                  for k in range(AROUND)])
for i in range(RINGS - 1):
    for k in range(AROUND):
        k1 = (k + 1) % AROUND
        bm.faces.new((rings[i][k], rings[i][k1], rings[i + 1][k1], rings[i + 1][k]))
bm.faces.new(list(reversed(rings[0])))
bm.faces.new(rings[-1])
bm.verts.new((0.0, 0.0, 1.5))
LOOSE = RINGS * AROUND
mesh = bpy.data.meshes.new("Body")
bm.to_mesh(mesh)
bm.free()
body = bpy.data.objects.new("Body", mesh)
scene.collection.objects.link(body)
# Placed off the armature's origin, so that the mesh's own space is not the
# world's.
body.location = (0.05, -0.02, 0.1)
body.rotation_euler = (0.0, 0.0, math.radians(30.0))

arm_data = bpy.data.armatures.new("Rig")
rig = bpy.data.objects.new("Rig", arm_data)
scene.collection.objects.link(rig)
rig.location = (0.0, 0.0, 0.1)
bpy.context.view_layer.objects.active = rig
bpy.ops.object.mode_set(mode="EDIT")
parent = None
for name, z0 in (("root", 0.0), ("mid", 1.0), ("tip", 2.0)):
    b = arm_data.edit_bones.new(name)
    b.head, b.tail = (0.0, 0.0, z0), (0.0, 0.0, z0 + 1.0)
    if parent is not None:
        b.parent, b.use_connect = parent, True
    parent = b
bpy.ops.object.mode_set(mode="OBJECT")

bpy.ops.object.select_all(action="DESELECT")
body.select_set(True)
rig.select_set(True)
bpy.context.view_layer.objects.active = rig
bpy.ops.object.parent_set(type="ARMATURE_AUTO")
for g in body.vertex_groups:
    g.remove([LOOSE])
body.vertex_groups["mid"].add([LOOSE], 0.5, "REPLACE")

# The clip: 'mid' bends 60 degrees about its x axis, 'tip' bends back and
# twists, from frame 1 (the rest pose) to frame 11.
for name, rest, bent in (("mid", (0, 0, 0), (60, 0, 0)), ("tip", (0, 0, 0), (-40, 45, 0))):
    pb = rig.pose.bones[name]
    pb.rotation_mode = "XYZ"
    for frame, angles in ((FRAME_START, rest), (FRAME_END, bent)):
        pb.rotation_euler = [math.radians(a) for a in angles]
        pb.keyframe_insert("rotation_euler", frame=frame)
rig.animation_data.action.name = "bend"

bpy.ops.object.select_all(action="SELECT")
bpy.ops.export_scene.fbx(filepath=fbx_path, object_types={"ARMATURE", "MESH"}, use_mesh_modifiers=False,
                         mesh_smooth_type="OFF", add_leaf_bones=False, bake_anim=True,
                         bake_anim_use_all_actions=False, bake_anim_use_nla_strips=False,
                         bake_anim_simplify_factor=0.0)

# -- the same file with the cluster of 'tip' not connected to its bone ---------
# The connection (Model 'tip', Deformer 'tip') is pointed at an id no object
# has: a same-length byte patch of the binary file.
from io_scene_fbx import parse_fbx  # noqa: E402  (Blender's own FBX add-on)

root, _version = parse_fbx.parse(fbx_path)
ids = {}
for top in root.elems:
    if top.id == b"Objects":
        for o in top.elems:
            ids[(o.id, o.props[1].split(b"\x00")[0], o.props[2])] = o.props[0]
model = ids[(b"Model", b"tip", b"LimbNode")]
cluster = ids[(b"Deformer", b"tip", b"Cluster")]
data = open(fbx_path, "rb").read()
link = b"L" + struct.pack("<q", model) + b"L" + struct.pack("<q", cluster)
assert data.count(link) == 1, "the connection from bone 'tip' to its cluster"
unused = max(ids.values()) + 1
data = data.replace(link, b"L" + struct.pack("<q", unused) + b"L" + struct.pack("<q", cluster))
open(missing_path, "wb").write(data)

# -- what Blender's importer reads -----------------------------------------------
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.fbx(filepath=fbx_path)  # defaults: anim_offset 1, no space baking
scene = bpy.context.scene
meshes = [o for o in scene.objects if o.type == "MESH"]
assert len(meshes) == 1
body = meshes[0]
fps = scene.render.fps / scene.render.fps_base
assert abs(fps - FPS) < 1e-9
groups = {g.index: g.name for g in body.vertex_groups}
out = {
    "generator": "Blender %s, tests/data/character/make_fbx.py" % bpy.app.version_string,
    "fps": fps,
    "vertex_count": len(body.data.vertices),
    "loose_vertex": LOOSE,
    "positions": [[round(c, 9) for c in v.co] for v in body.data.vertices],
    "weights": [{groups[g.group]: round(g.weight, 9) for g in v.groups if g.weight > 0.0} for v in body.data.vertices],
    "frames": [],
}
# The exporter writes frame k at k / fps seconds (the clip starts at
# FRAME_START / fps); the importer puts time t at frame t * fps + 1.
for f in SNH_FRAMES:
    blender_frame = FRAME_START + f + 1
    scene.frame_set(blender_frame)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    evaluated = body.evaluated_get(depsgraph)
    deformed = evaluated.to_mesh()
    out["frames"].append({"frame": f, "blender_frame": blender_frame,
                          "positions": [[round(c, 9) for c in v.co] for v in deformed.vertices]})
    evaluated.to_mesh_clear()
with open(json_path, "w") as f:
    json.dump(out, f, separators=(",", ":"))
    f.write("\n")
print("wrote", fbx_path, missing_path, json_path)
