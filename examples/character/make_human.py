"""Builds a simple human-sized skinned character in Blender and exports it as glTF binary.

    blender -b --factory-startup --python make_human.py -- human.glb

Made as an artist would: a stick figure of vertices and edges (pelvis,
spine, chest, neck, head, shoulders, arms, hands, thighs, shins, feet) with a
radius per vertex, the Skin modifier and one level of Subdivision Surface,
applied, which gives one closed mesh about 1.75 m tall (metres, Z up, facing
-Y, arms in an A pose 40 degrees below the horizontal). An armature is built
by hand along the stick figure and bound with automatic (bone heat) weights.
One action, "raise_arm", frames 0..24 at 24 fps: the left arm (+X) rises
100 degrees sideways, up towards the head, the left elbow bends 60 degrees in
the same plane and the left knee bends 35 degrees.

The glTF exporter writes Y up (Blender's Z becomes glTF's Y, Blender's -Y
glTF's Z), so the character stands along +Y and faces +Z in the file.
"""
import math
import sys

import bpy
from mathutils import Matrix, Vector

FPS, LAST_FRAME = 24, 24
ARM_DOWN = math.radians(40)  # A pose: arms this far below the horizontal
RAISE, ELBOW, KNEE = math.radians(100), math.radians(60), math.radians(35)


def arm_point(side, distance):
    """A point on the straight arm, `distance` from the shoulder (side +1 left, -1 right)."""
    return (side * (0.19 + distance * math.cos(ARM_DOWN)), 0.0, 1.40 - distance * math.sin(ARM_DOWN))


def stick_figure():
    """Vertices (name, position, skin radius) and edges of the stick figure; the first vertex is the root."""
    v = [("pelvis", (0, 0, 0.93), (0.15, 0.11)),
         ("waist", (0, 0, 1.08), (0.13, 0.10)),
         ("chest", (0, 0, 1.25), (0.15, 0.11)),
         ("upper_chest", (0, 0, 1.40), (0.13, 0.10)),
         ("neck", (0, 0, 1.50), (0.05, 0.05)),
         ("jaw", (0, 0, 1.58), (0.075, 0.08)),
         ("head", (0, 0, 1.66), (0.09, 0.10)),
         ("crown", (0, 0, 1.76), (0.07, 0.075))]
    e = [(0, 1), (1, 2), (2, 3), (3, 4), (4, 5), (5, 6), (6, 7)]
    for side, tag in ((1, "L"), (-1, "R")):
        arm = [("clavicle", (side * 0.10, 0, 1.41), 0.06),
               ("shoulder", arm_point(side, 0.0), 0.055),
               ("biceps", arm_point(side, 0.14), 0.048),
               ("elbow", arm_point(side, 0.28), 0.038),
               ("forearm", arm_point(side, 0.39), 0.04),
               ("wrist", arm_point(side, 0.52), 0.032),
               ("hand", arm_point(side, 0.60), 0.035),
               ("fingers", arm_point(side, 0.69), 0.025)]
        leg = [("hip", (side * 0.11, 0, 0.88), 0.09),
               ("thigh", (side * 0.11, 0, 0.70), 0.08),
               ("knee", (side * 0.11, 0, 0.49), 0.055),
               ("calf", (side * 0.11, 0.01, 0.36), 0.06),
               ("ankle", (side * 0.11, 0.01, 0.10), 0.05),
               ("toe", (side * 0.11, -0.15, 0.035), 0.033)]
        for chain, parent in ((arm, 3), (leg, 0)):
            previous = parent
            for name, p, r in chain:
                v.append((name + "." + tag, p, (r, r)))
                e.append((previous, len(v) - 1))
                previous = len(v) - 1
    return v, e


def bones():
    """(name, head, tail, parent) of the armature, parents first."""
    out = [("hips", (0, 0, 0.93), (0, 0, 1.08), None),
           ("spine", (0, 0, 1.08), (0, 0, 1.25), "hips"),
           ("chest", (0, 0, 1.25), (0, 0, 1.40), "spine"),
           ("neck", (0, 0, 1.40), (0, 0, 1.56), "chest"),
           ("head", (0, 0, 1.56), (0, 0, 1.75), "neck")]
    for side, tag in ((1, "L"), (-1, "R")):
        out += [("shoulder." + tag, (side * 0.03, 0, 1.40), arm_point(side, 0.0), "chest"),
                ("upper_arm." + tag, arm_point(side, 0.0), arm_point(side, 0.28), "shoulder." + tag),
                ("forearm." + tag, arm_point(side, 0.28), arm_point(side, 0.52), "upper_arm." + tag),
                ("hand." + tag, arm_point(side, 0.52), arm_point(side, 0.68), "forearm." + tag),
                ("thigh." + tag, (side * 0.11, 0, 0.88), (side * 0.11, 0, 0.49), "hips"),
                ("shin." + tag, (side * 0.11, 0, 0.49), (side * 0.11, 0, 0.10), "thigh." + tag),
                ("foot." + tag, (side * 0.11, 0, 0.10), (side * 0.11, -0.15, 0.035), "shin." + tag)]
    return out


def build_body():
    vertices, edges = stick_figure()
    mesh = bpy.data.meshes.new("human")
    mesh.from_pydata([p for _, p, _ in vertices], edges, [])
    body = bpy.data.objects.new("human", mesh)
    bpy.context.collection.objects.link(body)
    bpy.context.view_layer.objects.active = body
    body.select_set(True)
    bpy.ops.object.modifier_add(type='SKIN')
    skin = body.data.skin_vertices[0].data
    for i, (_, _, radius) in enumerate(vertices):
        skin[i].radius = radius
        skin[i].use_root = (i == 0)
    body.modifiers["Skin"].use_smooth_shade = True
    bpy.ops.object.modifier_add(type='SUBSURF')
    body.modifiers["Subdivision"].levels = 1
    body.modifiers["Subdivision"].render_levels = 1
    bpy.ops.object.modifier_apply(modifier="Skin")
    bpy.ops.object.modifier_apply(modifier="Subdivision")
    bpy.ops.object.shade_smooth()
    bpy.ops.object.mode_set(mode='EDIT')  # the Skin modifier can leave a few vertices in no face
    bpy.ops.mesh.select_all(action='SELECT')
    bpy.ops.mesh.delete_loose(use_verts=True, use_edges=True, use_faces=False)
    bpy.ops.object.mode_set(mode='OBJECT')
    return body


def check_closed(body):
    """Every edge shared by exactly two faces: one closed manifold surface."""
    mesh = body.data
    count = {}
    for polygon in mesh.polygons:
        for key in polygon.edge_keys:
            count[key] = count.get(key, 0) + 1
    bad = [k for k, n in count.items() if n != 2]
    if bad or len(count) != len(mesh.edges):
        raise SystemExit("make_human.py: the skin is not closed: %d edges not shared by two faces" % len(bad))
    euler = len(mesh.vertices) - len(mesh.edges) + len(mesh.polygons)
    if euler != 2:
        raise SystemExit("make_human.py: the skin's Euler characteristic is %d, not 2 (one closed shell)" % euler)
    print("make_human.py: skin %d vertices, %d faces, closed, Euler characteristic %d"
          % (len(mesh.vertices), len(mesh.polygons), euler))


def build_armature():
    data = bpy.data.armatures.new("skeleton")
    rig = bpy.data.objects.new("skeleton", data)
    bpy.context.collection.objects.link(rig)
    bpy.context.view_layer.objects.active = rig
    bpy.ops.object.mode_set(mode='EDIT')
    made = {}
    for name, head, tail, parent in bones():
        b = data.edit_bones.new(name)
        b.head, b.tail = Vector(head), Vector(tail)
        b.roll = 0.0
        if parent:
            b.parent = made[parent]
            b.use_connect = (Vector(head) - made[parent].tail).length < 1e-6
        made[name] = b
    bpy.ops.object.mode_set(mode='OBJECT')
    return rig


def bind(body, rig):
    bpy.ops.object.select_all(action='DESELECT')
    body.select_set(True)
    rig.select_set(True)
    bpy.context.view_layer.objects.active = rig
    bpy.ops.object.parent_set(type='ARMATURE_AUTO')
    unweighted = [v.index for v in body.data.vertices if sum(g.weight for g in v.groups) <= 0.0]
    if unweighted:
        raise SystemExit("make_human.py: %d vertices got no weight (first %d)" % (len(unweighted), unweighted[0]))


def key_rotation(rig, bone, world_rotation, frame):
    """Keys `bone` at `frame` turned by a rotation given in armature space, about the bone's head, relative
    to its parent."""
    rest = rig.data.bones[bone].matrix_local.to_3x3()
    local = rest.inverted() @ world_rotation @ rest
    pose = rig.pose.bones[bone]
    pose.rotation_mode = 'QUATERNION'
    pose.rotation_quaternion = local.to_quaternion()
    pose.keyframe_insert("rotation_quaternion", frame=frame)


def animate(rig):
    scene = bpy.context.scene
    scene.render.fps = FPS
    scene.frame_start, scene.frame_end = 0, LAST_FRAME
    rig.animation_data_create()
    action = bpy.data.actions.new("raise_arm")
    rig.animation_data.action = action
    up = Vector((0, -1, 0))  # about -Y (the view axis from the front) the +X arm turns up
    motion = {"upper_arm.L": Matrix.Rotation(RAISE, 3, up),
              "forearm.L": Matrix.Rotation(ELBOW, 3, up),
              "shin.L": Matrix.Rotation(KNEE, 3, Vector((1, 0, 0)))}  # the foot goes back (+Y)
    for bone, rotation in motion.items():
        key_rotation(rig, bone, Matrix.Identity(3), 0)
        key_rotation(rig, bone, rotation, LAST_FRAME)
    scene.frame_set(0)


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) != 1:
        raise SystemExit("usage: blender -b --factory-startup --python make_human.py -- out.glb")
    bpy.ops.object.select_all(action='SELECT')
    bpy.ops.object.delete()
    body = build_body()
    check_closed(body)
    low = min((body.matrix_world @ v.co).z for v in body.data.vertices)
    high = max((body.matrix_world @ v.co).z for v in body.data.vertices)
    print("make_human.py: height %.3f m (z %.3f to %.3f)" % (high - low, low, high))
    rig = build_armature()
    bind(body, rig)
    animate(rig)
    bpy.ops.export_scene.gltf(filepath=argv[0], export_format='GLB', export_animations=True, export_skins=True,
                              export_frame_range=True, export_force_sampling=True, export_def_bones=False,
                              export_texcoords=False, export_normals=False, export_colors=False,
                              export_materials='NONE', export_yup=True, export_apply=False)


main()
