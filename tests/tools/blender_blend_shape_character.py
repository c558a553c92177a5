# Builds a small character with blend shapes in Blender (headless) and exports it, so the tests
# check our blend-shape playback against a real exporter and a real evaluator:
#
#   blender -b --factory-startup -P blender_blend_shape_character.py -- OUT_DIR
#
# writes into OUT_DIR:
#   blend_shape_character.glb  a tube on a two-bone armature with two shape keys ("bulge", "lean");
#                              the bone and both shape-key values are keyed over frames 0..24 (24 fps)
#                              and exported as one glTF animation (morph targets + weights channel)
#   blend_shape_static.glb     the same mesh with the shape keys held at 0.5 / 0.25 and no animation:
#                              the glTF mesh's default weights are what moves it
#   blend_shape_character.fbx,
#   blend_shape_static.fbx     the same two scenes through Blender's FBX exporter (shape keys as
#                              blend shape channels, their values as DeformPercent, the keyed values
#                              as the channels' animation curves)
#   blend_shape_character.dae,
#   blend_shape_static.dae     the same two scenes through Blender's Collada exporter (a <skin> of
#                              the base geometry beside a <morph> controller whose weights are the
#                              shape keys' values at export; Blender writes no shape animation)
#   blend_shape_reference.json Blender's own evaluated mesh (shape keys, then the armature) of both
#                              files: {"frames": [F...], "fps": 24, "rest": [[x,y,z]...],
#                              "animated": {"F": [[x,y,z]...]}, "static": [[x,y,z]...]}, world space in
#                              glTF axes (Y up), one row per Blender vertex; "rest" is the undeformed
#                              mesh, to match the glTF vertices to Blender's
import numpy
numpy.bool = bool  # Debian's numpy lacks the alias Blender 3.4's glTF add-on uses

import json
import math
import os
import sys

import bpy

RINGS = 9          # rings of vertices along the tube (z 0..2)
SEGMENTS = 12      # vertices per ring
HEIGHT = 2.0
RADIUS = 0.3
FRAMES = [0, 5, 10, 15, 20, 24]


def out_dir():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) != 1:
        sys.exit("usage: blender -b --factory-startup -P blender_blend_shape_character.py -- OUT_DIR")
    os.makedirs(argv[0], exist_ok=True)
    return argv[0]


def clear_scene():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.fps = 24
    scene.frame_start = 0
    scene.frame_end = 24
    return scene


def make_tube():
    verts, faces = [], []
    for r in range(RINGS):
        z = HEIGHT * r / (RINGS - 1)
        for s in range(SEGMENTS):
            a = 2.0 * math.pi * s / SEGMENTS
            verts.append((RADIUS * math.cos(a), RADIUS * math.sin(a), z))
    for r in range(RINGS - 1):
        for s in range(SEGMENTS):
            a, b = r * SEGMENTS + s, r * SEGMENTS + (s + 1) % SEGMENTS
            faces.append((a, b, b + SEGMENTS, a + SEGMENTS))
    bottom, top = len(verts), len(verts) + 1
    verts += [(0.0, 0.0, 0.0), (0.0, 0.0, HEIGHT)]
    for s in range(SEGMENTS):
        n = (s + 1) % SEGMENTS
        faces.append((bottom, n, s))
        last = (RINGS - 1) * SEGMENTS
        faces.append((top, last + s, last + n))
    mesh = bpy.data.meshes.new("Tube")
    mesh.from_pydata(verts, [], faces)
    mesh.update()
    for p in mesh.polygons:
        p.use_smooth = True  # shared vertices: one glTF vertex per Blender vertex
    obj = bpy.data.objects.new("Tube", mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def make_armature():
    data = bpy.data.armatures.new("Armature")
    arm = bpy.data.objects.new("Armature", data)
    bpy.context.scene.collection.objects.link(arm)
    bpy.context.view_layer.objects.active = arm
    bpy.ops.object.mode_set(mode="EDIT")
    lower = data.edit_bones.new("lower")
    lower.head, lower.tail = (0, 0, 0), (0, 0, 1)
    upper = data.edit_bones.new("upper")
    upper.head, upper.tail = (0, 0, 1), (0, 0, 2)
    upper.parent = lower
    upper.use_connect = True
    bpy.ops.object.mode_set(mode="OBJECT")
    return arm


def bind(tube, arm):
    # Weights by height, blended over the middle third: deterministic, unlike heat weighting.
    lower = tube.vertex_groups.new(name="lower")
    upper = tube.vertex_groups.new(name="upper")
    for v in tube.data.vertices:
        t = min(1.0, max(0.0, (v.co.z - 0.7) / 0.6))
        if t < 1.0:
            lower.add([v.index], 1.0 - t, "REPLACE")
        if t > 0.0:
            upper.add([v.index], t, "REPLACE")
    mod = tube.modifiers.new("Armature", "ARMATURE")
    mod.object = arm  # not parented: a skinned mesh node at the root, as the glTF-Validator wants it


def add_shape_keys(tube):
    tube.shape_key_add(name="Basis", from_mix=False)
    bulge = tube.shape_key_add(name="bulge", from_mix=False)
    lean = tube.shape_key_add(name="lean", from_mix=False)
    for i, v in enumerate(tube.data.vertices):
        co = v.co
        w = math.sin(math.pi * co.z / HEIGHT)  # widest in the middle
        radial = (co.x, co.y, 0.0)
        bulge.data[i].co = (co.x + 0.6 * w * radial[0], co.y + 0.6 * w * radial[1], co.z)
        lean.data[i].co = (co.x + 0.4 * (co.z / HEIGHT) ** 2, co.y, co.z + 0.1 * co.z / HEIGHT)
    return bulge, lean


def key_animation(tube, arm, bulge, lean):
    for frame, value in [(0, 0.0), (10, 1.0), (24, 0.2)]:
        bulge.value = value
        bulge.keyframe_insert("value", frame=frame)
    for frame, value in [(0, 0.0), (8, 0.0), (20, 0.9), (24, 0.6)]:
        lean.value = value
        lean.keyframe_insert("value", frame=frame)
    bone = arm.pose.bones["upper"]
    bone.rotation_mode = "XYZ"
    for frame, angle in [(0, 0.0), (12, 0.8), (24, -0.3)]:
        bone.rotation_euler = (angle, 0.0, 0.0)
        bone.keyframe_insert("rotation_euler", frame=frame)
    # One glTF animation for both: the exporter merges actions pushed to NLA tracks of one name.
    for owner, action in [(arm, arm.animation_data.action), (tube.data.shape_keys, tube.data.shape_keys.animation_data.action)]:
        action.name = "Motion"
        track = owner.animation_data.nla_tracks.new()
        track.name = "Motion"
        track.strips.new("Motion", 0, action)
        owner.animation_data.action = None


def to_gltf_axes(co):
    return [co[0], co[2], -co[1]]  # Blender Z-up to glTF Y-up, as the exporter converts


def evaluated_positions(tube):
    dg = bpy.context.evaluated_depsgraph_get()
    ev = tube.evaluated_get(dg)
    mesh = ev.to_mesh()
    out = [to_gltf_axes(ev.matrix_world @ v.co) for v in mesh.vertices]
    ev.to_mesh_clear()
    return out


def export(path, animations):
    bpy.ops.export_scene.gltf(filepath=path, export_format="GLB", export_animations=animations,
                              export_morph=True, export_morph_normal=True, export_skins=True,
                              export_apply=False)


def export_fbx(path, animations):
    bpy.ops.export_scene.fbx(filepath=path, bake_anim=animations, add_leaf_bones=False)


def export_dae(path, animations):
    bpy.ops.wm.collada_export(filepath=path, include_armatures=True, include_shapekeys=True,
                              include_animations=animations, triangulate=True)


def main():
    out = out_dir()
    scene = clear_scene()
    tube = make_tube()
    arm = make_armature()
    bind(tube, arm)
    bulge, lean = add_shape_keys(tube)
    ref = {"fps": 24, "frames": FRAMES}
    scene.frame_set(0)
    ref["rest"] = [to_gltf_axes(tube.matrix_world @ v.co) for v in tube.data.vertices]

    # The static file first: shape keys held, no animation data at all.
    bulge.value, lean.value = 0.5, 0.25
    scene.frame_set(0)
    ref["static"] = evaluated_positions(tube)
    export(os.path.join(out, "blend_shape_static.glb"), False)
    export_fbx(os.path.join(out, "blend_shape_static.fbx"), False)
    export_dae(os.path.join(out, "blend_shape_static.dae"), False)

    key_animation(tube, arm, bulge, lean)
    ref["animated"] = {}
    for f in FRAMES:
        scene.frame_set(f)
        ref["animated"][str(f)] = evaluated_positions(tube)
    export(os.path.join(out, "blend_shape_character.glb"), True)
    export_fbx(os.path.join(out, "blend_shape_character.fbx"), True)
    export_dae(os.path.join(out, "blend_shape_character.dae"), True)
    with open(os.path.join(out, "blend_shape_reference.json"), "w") as f:
        json.dump(ref, f)
    print("wrote", out)


main()
