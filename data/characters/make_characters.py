"""Skinned, animated test characters made as an artist makes them in Blender.

    blender -b --factory-startup --python data/characters/make_characters.py -- OUTDIR

Each character is blocked out with a Skin modifier over a vertex skeleton
(a closed, manifold body), smoothed by one level of Subdivision Surface,
rigged with an armature whose weights come from Automatic Weights
(parent_set ARMATURE_AUTO), animated with one action (frames 0..20 at
24 fps: frame 0 is the rest pose, the arms bend 45 and 50 degrees, the
head nods 30) and written with Blender's own exporters. One file per defect
that real exported characters have (data/characters/README.md lists them):

    creature.gltf, .fbx, .dae    clean: closed, manifold, weights summing to 1
    inside_out.gltf              every face flipped (normals inwards)
    open_sheets.gltf             open eyelid caps, an open skirt, loose
                                 vertices and loose edges in the skinned mesh
    thin_tail.gltf               a tail thinner than a quarter of the body's
                                 radius whose bone runs out of the skin
    unnormalized.fbx, .gltf      weight sums 0.85..1.15, a few unweighted
                                 vertices
    centimetres.fbx              the creature in centimetres (unit scale 0.01)
    missing_joint.dae            a joint named by the skin absent from the
                                 node hierarchy
"""

import base64
import json
import math
import os
import re
import struct
import sys

import bmesh
import bpy
from mathutils import Vector

FPS = 24
LAST_FRAME = 20


def out_dir():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) != 1:
        raise SystemExit("usage: blender -b --factory-startup --python make_characters.py -- OUTDIR")
    os.makedirs(argv[0], exist_ok=True)
    return os.path.abspath(argv[0])


def clear_scene(unit_scale=1.0):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.fps = FPS
    scene.frame_start = 0
    scene.frame_end = LAST_FRAME
    scene.unit_settings.system = 'METRIC'
    scene.unit_settings.scale_length = unit_scale
    return scene


# The body's skeleton for the Skin modifier: (position, radius x, radius y),
# edges between them. Z is up, -Y is the front (Blender's convention).
BODY_VERTS = [
    ((0.0, 0.0, 0.00), 0.20, 0.16),   # 0 pelvis (root)
    ((0.0, 0.0, 0.45), 0.21, 0.17),   # 1 chest
    ((0.0, 0.0, 0.68), 0.08, 0.08),   # 2 neck
    ((0.0, 0.0, 0.82), 0.15, 0.15),   # 3 head
    ((0.0, 0.0, 1.00), 0.10, 0.10),   # 4 crown
    ((0.22, 0.0, 0.55), 0.08, 0.08),  # 5 shoulder.L
    ((0.48, 0.0, 0.55), 0.07, 0.07),  # 6 elbow.L
    ((0.76, 0.0, 0.55), 0.06, 0.06),  # 7 hand.L
    ((-0.22, 0.0, 0.55), 0.08, 0.08),  # 8 shoulder.R
    ((-0.48, 0.0, 0.55), 0.07, 0.07),  # 9 elbow.R
    ((-0.76, 0.0, 0.55), 0.06, 0.06),  # 10 hand.R
]
BODY_EDGES = [(0, 1), (1, 2), (2, 3), (3, 4), (1, 5), (5, 6), (6, 7), (1, 8), (8, 9), (9, 10)]

# A tail from the pelvis backwards (+Y), radius 0.035..0.03 against the pelvis's 0.16..0.2.
TAIL_VERTS = [((0.0, 0.30, 0.02), 0.035, 0.035), ((0.0, 0.55, 0.10), 0.03, 0.03)]
TAIL_EDGES = [(0, 11), (11, 12)]

# Bones: name, head, tail, parent, connected.
BONES = [
    ("hips", (0, 0, 0.10), (0, 0, 0.45), None, False),
    ("chest", (0, 0, 0.45), (0, 0, 0.68), "hips", True),
    ("head", (0, 0, 0.68), (0, 0, 0.94), "chest", True),
    ("upper_arm.L", (0.2, 0, 0.55), (0.48, 0, 0.55), "chest", False),
    ("lower_arm.L", (0.48, 0, 0.55), (0.74, 0, 0.55), "upper_arm.L", True),
    ("upper_arm.R", (-0.2, 0, 0.55), (-0.48, 0, 0.55), "chest", False),
    ("lower_arm.R", (-0.48, 0, 0.55), (-0.74, 0, 0.55), "upper_arm.R", True),
]
# The tail's bone is longer than the tail (0.75 against the mesh's 0.55) and
# bent upwards out of it: its far half runs outside the skin.
TAIL_BONE = ("tail", (0, 0.12, 0.0), (0, 0.75, 0.30), "hips", False)


def skin_body(name, tail=False, size=1.0):
    verts = BODY_VERTS + (TAIL_VERTS if tail else [])
    edges = BODY_EDGES + (TAIL_EDGES if tail else [])
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([Vector(p) * size for p, _, _ in verts], edges, [])
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    skin = obj.modifiers.new("Skin", 'SKIN')
    skin.branch_smoothing = 0.5
    for i, (_, rx, ry) in enumerate(verts):
        sv = mesh.skin_vertices[0].data[i]
        sv.radius = (rx * size, ry * size)
        sv.use_root = (i == 0)
    bpy.ops.object.modifier_apply(modifier=skin.name)
    sub = obj.modifiers.new("Subdivision", 'SUBSURF')
    sub.levels = 1
    bpy.ops.object.modifier_apply(modifier=sub.name)
    bpy.ops.object.shade_smooth()
    return obj


def check_closed(obj):
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    open_edges = sum(1 for e in bm.edges if len(e.link_faces) != 2)
    bm.free()
    if open_edges:
        raise RuntimeError(f"{obj.name}: {open_edges} edges are not shared by exactly two faces")


def armature(name, tail=False, size=1.0):
    data = bpy.data.armatures.new(name)
    arm = bpy.data.objects.new(name, data)
    bpy.context.scene.collection.objects.link(arm)
    bpy.context.view_layer.objects.active = arm
    bpy.ops.object.mode_set(mode='EDIT')
    for bname, head, tail_pos, parent, connected in BONES + ([TAIL_BONE] if tail else []):
        b = data.edit_bones.new(bname)
        b.head = Vector(head) * size
        b.tail = Vector(tail_pos) * size
        if parent:
            b.parent = data.edit_bones[parent]
            b.use_connect = connected
    bpy.ops.object.mode_set(mode='OBJECT')
    return arm


def auto_weights(body, arm):
    bpy.ops.object.select_all(action='DESELECT')
    body.select_set(True)
    arm.select_set(True)
    bpy.context.view_layer.objects.active = arm
    bpy.ops.object.parent_set(type='ARMATURE_AUTO')


def animate(arm, tail=False):
    """One action: rest at frame 0, the arms and head bent at 10, and further at 20."""
    arm.animation_data_create()
    action = bpy.data.actions.new("wave")
    arm.animation_data.action = action
    bend = {  # bone: (axis index, degrees at frame 10, degrees at frame 20)
        "upper_arm.L": (1, 25, 45), "lower_arm.L": (0, 30, 50),
        "upper_arm.R": (1, -25, -45), "lower_arm.R": (0, -30, -50),
        "head": (0, 15, 30), "chest": (2, 10, 20),
    }
    if tail:
        bend["tail"] = (0, 20, 40)
    for bname, (axis, d10, d20) in bend.items():
        pb = arm.pose.bones[bname]
        pb.rotation_mode = 'XYZ'
        for frame, deg in ((0, 0.0), (10, d10), (20, d20)):
            rot = [0.0, 0.0, 0.0]
            rot[axis] = math.radians(deg)
            pb.rotation_euler = rot
            pb.keyframe_insert("rotation_euler", frame=frame)
    bpy.context.scene.frame_set(0)


def fill_unweighted(body):
    """Bone heat leaves the open parts far from every bone without weights
    (Blender reports "Bone Heat Weighting: failed to find solution"); give
    each such vertex the weights of the nearest weighted vertex, as one
    fixes it by hand with a weight transfer."""
    from mathutils.kdtree import KDTree
    verts = body.data.vertices
    weighted = [v.index for v in verts if v.groups]
    tree = KDTree(len(weighted))
    for i in weighted:
        tree.insert(verts[i].co, i)
    tree.balance()
    missing = [v.index for v in verts if not v.groups]
    for i in missing:
        _, j, _ = tree.find(verts[i].co)
        for ge in verts[j].groups:
            body.vertex_groups[ge.group].add([i], ge.weight, 'REPLACE')
    print(f"{body.name}: weights of the nearest weighted vertex given to {len(missing)} vertices")


def creature(tail=False, size=1.0, extra=None, flip=False):
    body = skin_body("body", tail=tail, size=size)
    check_closed(body)
    if extra:
        extra(body, size)
    if flip:
        bpy.context.view_layer.objects.active = body
        bpy.ops.object.mode_set(mode='EDIT')
        bpy.ops.mesh.select_all(action='SELECT')
        bpy.ops.mesh.flip_normals()
        bpy.ops.object.mode_set(mode='OBJECT')
    arm = armature("rig", tail=tail, size=size)
    auto_weights(body, arm)
    if extra:
        fill_unweighted(body)
    animate(arm, tail=tail)
    unweighted = [v.index for v in body.data.vertices if not v.groups]
    print(f"{body.name}: {len(body.data.vertices)} vertices, {len(unweighted)} without weights")
    return body, arm


def add_open_sheets(body, size):
    """Eyelids (open half spheres in front of the head), a skirt (an open
    cylinder around the hips, flaring away from the body), three loose
    vertices and two loose edges, all in the body's mesh."""
    bm = bmesh.new()
    bm.from_mesh(body.data)
    for x in (-0.055, 0.055):
        geom = bmesh.ops.create_uvsphere(bm, u_segments=10, v_segments=6, radius=0.035 * size)
        verts = geom["verts"]
        # Keep the front half (-Y): delete the back half's vertices.
        bmesh.ops.delete(bm, geom=[v for v in verts if v.co.y > 1e-6], context='VERTS')
        for v in verts:
            if v.is_valid:
                v.co += Vector((x, -0.13, 0.85)) * size
    rings, sides = 4, 24
    ring_verts = []
    for r in range(rings):
        z = (0.10 - 0.12 * r) * size
        rad = (0.26 + 0.05 * r) * size
        ring_verts.append([bm.verts.new((rad * math.cos(2 * math.pi * s / sides),
                                         rad * 0.85 * math.sin(2 * math.pi * s / sides), z))
                           for s in range(sides)])
    for r in range(rings - 1):
        for s in range(sides):
            a, b = ring_verts[r][s], ring_verts[r][(s + 1) % sides]
            c, d = ring_verts[r + 1][(s + 1) % sides], ring_verts[r + 1][s]
            bm.faces.new((a, b, c, d))
    for p in ((0.3, -0.3, 0.2), (-0.3, -0.3, 0.2), (0.0, -0.35, 1.1)):
        bm.verts.new(Vector(p) * size)
    for p, q in (((0.1, -0.3, 0.9), (0.15, -0.35, 0.95)), ((-0.1, -0.3, 0.9), (-0.15, -0.35, 0.95))):
        bm.edges.new((bm.verts.new(Vector(p) * size), bm.verts.new(Vector(q) * size)))
    bm.to_mesh(body.data)
    bm.free()
    for poly in body.data.polygons:
        poly.use_smooth = True


def unnormalize(body, arm):
    """Scale each bone's vertex group by a factor 0.85..1.15 (no
    normalization afterwards) and take every weight off a few vertices."""
    factors = [0.85, 1.15, 0.9, 1.1, 0.95, 1.05, 0.88]
    for g, f in zip(body.vertex_groups, factors):
        for v in body.data.vertices:
            for ge in v.groups:
                if ge.group == g.index:
                    g.add([v.index], min(ge.weight * f, 1.0), 'REPLACE')
    unweighted = [7, 77, 177]
    for g in body.vertex_groups:
        g.remove(unweighted)
    return unweighted


def export_gltf(path):
    bpy.ops.export_scene.gltf(filepath=path, export_format='GLTF_EMBEDDED', export_animations=True,
                              export_skins=True, export_yup=True, use_mesh_edges=True, use_mesh_vertices=True)
    print("wrote", path, os.path.getsize(path), "bytes")


def export_fbx(path, **kw):
    bpy.ops.export_scene.fbx(filepath=path, bake_anim=True, **kw)
    print("wrote", path, os.path.getsize(path), "bytes")


def export_dae(path):
    bpy.ops.wm.collada_export(filepath=path, include_animations=True, sampling_rate=1,
                              include_all_actions=False)
    print("wrote", path, os.path.getsize(path), "bytes")


def gltf_buffer(doc):
    uri = doc["buffers"][0]["uri"]
    head, data = uri.split(",", 1)
    return head, bytearray(base64.b64decode(data))


def unnormalize_gltf(path, body, unweighted):
    """The glTF exporter divides every vertex's weights by their sum (and a
    vertex without weights by 0). Post-edit the WEIGHTS_0 buffer: multiply
    each vertex's weights by a factor 0.85..1.15 that follows its position,
    and write 0 for the vertices that Blender had no weight for."""
    with open(path) as f:
        doc = json.load(f)
    head, buf = gltf_buffer(doc)
    rest = {tuple(round(c, 4) for c in v.co): v.index for v in body.data.vertices}
    unweighted_pos = [tuple(round(c, 4) for c in body.data.vertices[i].co) for i in unweighted]
    for mesh in doc["meshes"]:
        for prim in mesh["primitives"]:
            attrs = prim["attributes"]
            if "WEIGHTS_0" not in attrs:
                continue
            pos_acc = doc["accessors"][attrs["POSITION"]]
            w_acc = doc["accessors"][attrs["WEIGHTS_0"]]
            assert w_acc["componentType"] == 5126
            pv = doc["bufferViews"][pos_acc["bufferView"]]
            wv = doc["bufferViews"][w_acc["bufferView"]]
            p0 = pv.get("byteOffset", 0) + pos_acc.get("byteOffset", 0)
            w0 = wv.get("byteOffset", 0) + w_acc.get("byteOffset", 0)
            for i in range(w_acc["count"]):
                x, y, z = struct.unpack_from("<3f", buf, p0 + 12 * i)
                blender_pos = (round(x, 4), round(-z, 4), round(y, 4))  # glTF +Y up -> Blender +Z up
                w = struct.unpack_from("<4f", buf, w0 + 16 * i)
                if blender_pos in unweighted_pos or any(math.isnan(c) for c in w):
                    w = (0.0, 0.0, 0.0, 0.0)
                else:
                    f = 1.0 + 0.15 * math.sin(7.0 * x + 5.0 * y + 3.0 * z)
                    w = tuple(c * f for c in w)
                struct.pack_into("<4f", buf, w0 + 16 * i, *w)
    doc["buffers"][0]["uri"] = head + "," + base64.b64encode(bytes(buf)).decode("ascii")
    with open(path, "w") as f:
        json.dump(doc, f, separators=(",", ":"))
    print("post-edited weights of", path)


def missing_joint_dae(path, joint="head"):
    """Blender's Collada export names each joint node by the bone (id
    rig_<bone>, name and sid <bone>) and the controller's Name_array by the
    sid. Rename the node of `joint` (id, name, sid and the animation
    channels that target it) so that the skin's joint name matches no
    node of the hierarchy."""
    with open(path) as f:
        text = f.read()
    node = re.search(r'<node id="([^"]*)" name="%s" sid="%s" type="JOINT">' % (re.escape(joint), re.escape(joint)),
                     text)
    if not node:
        raise RuntimeError(f"{path}: no joint node named {joint}")
    old_id = node.group(1)
    new = joint + "_renamed"
    text = text.replace(node.group(0), f'<node id="{old_id}_renamed" name="{new}" sid="{new}" type="JOINT">')
    text = text.replace(f'target="{old_id}/', f'target="{old_id}_renamed/')
    with open(path, "w") as f:
        f.write(text)
    print("renamed joint node", joint, "->", new, "in", path)


def main():
    out = out_dir()

    clear_scene()
    creature()
    export_gltf(os.path.join(out, "creature.gltf"))
    export_fbx(os.path.join(out, "creature.fbx"))
    export_dae(os.path.join(out, "creature.dae"))
    path = os.path.join(out, "missing_joint.dae")
    export_dae(path)
    missing_joint_dae(path)

    clear_scene()
    creature(flip=True)
    export_gltf(os.path.join(out, "inside_out.gltf"))

    clear_scene()
    creature(extra=add_open_sheets)
    export_gltf(os.path.join(out, "open_sheets.gltf"))

    clear_scene()
    creature(tail=True)
    export_gltf(os.path.join(out, "thin_tail.gltf"))

    clear_scene()
    body, arm = creature()
    unweighted = unnormalize(body, arm)
    export_fbx(os.path.join(out, "unnormalized.fbx"))
    export_gltf(os.path.join(out, "unnormalized.gltf"))
    unnormalize_gltf(os.path.join(out, "unnormalized.gltf"), body, unweighted)

    # Centimetres: the scene's unit scale 0.01 (one Blender unit is 1 cm)
    # and the creature built 100 times larger, so the FBX file's numbers
    # are centimetres (UnitScaleFactor 1).
    clear_scene(unit_scale=0.01)
    creature(size=100.0)
    export_fbx(os.path.join(out, "centimetres.fbx"))


main()
