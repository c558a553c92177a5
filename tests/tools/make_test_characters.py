#!/usr/bin/env python3
"""Builds the test characters: real exporter output made by Blender from scripted meshes.

usage: python3 make_test_characters.py OUTDIR
       blender -b --factory-startup -P make_test_characters.py -- OUTDIR

Four characters -- a humanoid (face and finger bones, three meshes on one rig), a quadruped (a
wide ellipsoid body on ONE spine bone), a long tentacle (a chain of ten bones) and a thin flag
(a sheet 1 cm thick) -- each rigged with Blender's automatic weights, keyed over 40 frames, with
shape keys whose values are keyed, and with bones outside the mesh (a root on the ground, IK
targets, a pole and a prop bone without vertices). Each is exported to FBX, Collada and glTF
(.glb), in metres (NAME_m.EXT) and in centimetres (NAME_cm.EXT: the scene's unit scale 0.01,
the data 100x); some variants have a scaled armature (NAME_scaledroot: data in centimetres
under a 0.01 armature scale, as Mixamo-style rigs come; NAME_stretched: a non-uniform armature
scale). Blender's FBX files declare centimetres and carry the unit in a 100x root transform;
humanoid_fbxunits.fbx declares metres instead (the exporter's FBX_SCALE_UNITS).
OUTDIR/manifest.json lists every file: character, format, unit, metres per unit, world height
in metres, meshes, bones, shape keys, frames, and what it is meant to exercise.

Run with python3, the script runs Blender on itself and exits 77 (CTest's "skipped") when
Blender is not installed. It regenerates nothing when OUTDIR/manifest.json was written by this
very script (same content hash) and every file it lists exists.
"""
import hashlib
import json
import math
import os
import shutil
import subprocess
import sys

SCRIPT = os.path.abspath(__file__)
FRAMES = (1, 40)
FPS = 24


def script_hash():
    with open(SCRIPT, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def up_to_date(outdir):
    try:
        with open(os.path.join(outdir, "manifest.json")) as f:
            manifest = json.load(f)
    except (OSError, ValueError):
        return False
    return manifest.get("generator_sha256") == script_hash() and all(
        os.path.isfile(os.path.join(outdir, e["file"])) for e in manifest.get("files", []))


def run_blender(outdir):
    """Outside Blender: run Blender headless on this script (exit 77 when it is missing)."""
    if up_to_date(outdir):
        print(f"{outdir}: test characters up to date")
        return 0
    blender = shutil.which("blender")
    if not blender:
        print("blender not installed (Debian package blender): test characters not made, skipped")
        return 77
    os.makedirs(outdir, exist_ok=True)
    # Blender embeds the system's Python and takes its standard library from the first python3.11 on
    # PATH: a Python installed elsewhere (pyenv, a venv) first on PATH hides Debian's numpy from it.
    here = os.path.dirname(os.path.realpath(sys.executable))
    path = [p for p in os.environ.get("PATH", "").split(os.pathsep)
            if p and ".pyenv" not in p and (os.path.realpath(p) != here or here in ("/usr/bin", "/bin"))]
    env = dict(os.environ, PATH=os.pathsep.join(path))
    r = subprocess.run([blender, "-b", "--factory-startup", "-noaudio", "-P", SCRIPT, "--", outdir],
                       capture_output=True, text=True, timeout=600, env=env)
    if r.returncode != 0 or not up_to_date(outdir):
        sys.stdout.write(r.stdout[-4000:])
        sys.stderr.write(r.stderr[-4000:])
        print(f"blender failed making the test characters in {outdir} (exit {r.returncode})")
        return 1
    for line in r.stdout.splitlines():
        if line.startswith("test characters:"):
            print(line)
    return 0


if __name__ == "__main__" and "--" not in sys.argv:
    if len(sys.argv) != 2:
        print(__doc__)
        sys.exit(2)
    sys.exit(run_blender(os.path.abspath(sys.argv[1])))

# ---------------------------------------------------------------- inside Blender from here on
import numpy  # noqa: E402

numpy.bool = bool  # Debian's numpy dropped the alias Blender 3.4's glTF add-on still uses
import bmesh  # noqa: E402
import bpy  # noqa: E402
from mathutils import Matrix, Vector  # noqa: E402


def reset_scene(scale_length):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.unit_settings.system = "METRIC"
    scene.unit_settings.scale_length = scale_length
    scene.unit_settings.length_unit = "CENTIMETERS" if scale_length < 0.1 else "METERS"
    scene.frame_start, scene.frame_end = FRAMES
    scene.render.fps = FPS
    return scene


# ---------------------------------------------------------------- geometry (bmesh, metres x s)

def add_ellipsoid(bm, centre, radii, s, segs=(24, 14)):
    m = Matrix.Translation(Vector(centre) * s) @ Matrix.Diagonal((*(Vector(radii) * s), 1.0))
    bmesh.ops.create_uvsphere(bm, u_segments=segs[0], v_segments=segs[1], radius=1.0, matrix=m)


def add_capsule(bm, a, b, r, s, segs=16):
    """A cylinder from a to b capped by spheres: voxel remeshing fuses the parts into one."""
    a, b = Vector(a) * s, Vector(b) * s
    d = b - a
    rot = d.to_track_quat("Z", "Y").to_matrix().to_4x4()
    m = Matrix.Translation((a + b) * 0.5) @ rot
    bmesh.ops.create_cone(bm, cap_ends=True, segments=segs, radius1=r * s, radius2=r * s, depth=d.length, matrix=m)
    for p in (a, b):
        bmesh.ops.create_uvsphere(bm, u_segments=segs, v_segments=segs // 2, radius=r * s,
                                  matrix=Matrix.Translation(p))


def add_tube(bm, points, radii, s, segs=16):
    """A closed tube through points (metres) with a radius per point, capped by pole vertices."""
    pts = [Vector(p) * s for p in points]
    rings = []
    for i, p in enumerate(pts):
        t = (pts[min(i + 1, len(pts) - 1)] - pts[max(i - 1, 0)]).normalized()
        u = t.orthogonal().normalized()
        v = t.cross(u)
        ring = []
        for k in range(segs):
            ang = 2.0 * math.pi * k / segs
            ring.append(bm.verts.new(p + (u * math.cos(ang) + v * math.sin(ang)) * radii[i] * s))
        rings.append(ring)
    for r0, r1 in zip(rings, rings[1:]):
        for k in range(segs):
            bm.faces.new((r0[k], r0[(k + 1) % segs], r1[(k + 1) % segs], r1[k]))
    first, last = pts[0], pts[-1]
    cap0 = bm.verts.new(first + (first - pts[1]).normalized() * radii[0] * s * 0.5)
    cap1 = bm.verts.new(last + (last - pts[-2]).normalized() * radii[-1] * s * 0.5)
    for k in range(segs):
        bm.faces.new((rings[0][(k + 1) % segs], rings[0][k], cap0))
        bm.faces.new((rings[-1][k], rings[-1][(k + 1) % segs], cap1))


def mesh_object(name, bm, voxel=None):
    """Links a mesh object made of bm; voxel remeshing (size in scene units) fuses overlapping parts."""
    me = bpy.data.meshes.new(name + "_parts")
    bm.to_mesh(me)
    bm.free()
    obj = bpy.data.objects.new(name, me)
    bpy.context.scene.collection.objects.link(obj)
    if voxel:
        mod = obj.modifiers.new("remesh", "REMESH")
        mod.mode = "VOXEL"
        mod.voxel_size = voxel
        mod.use_smooth_shade = True
        depsgraph = bpy.context.evaluated_depsgraph_get()
        fused = bpy.data.meshes.new_from_object(obj.evaluated_get(depsgraph))
        fused.name = name
        obj.modifiers.clear()
        obj.data = fused
        bpy.data.meshes.remove(me)
    for poly in obj.data.polygons:
        poly.use_smooth = True
    return obj


# ---------------------------------------------------------------- rigs

def make_armature(name, bones, s):
    """bones: (name, head, tail, parent, deform) in metres; returns the armature object."""
    data = bpy.data.armatures.new(name)
    arm = bpy.data.objects.new(name, data)
    bpy.context.scene.collection.objects.link(arm)
    bpy.context.view_layer.objects.active = arm
    bpy.ops.object.mode_set(mode="EDIT")
    for bname, head, tail, parent, deform in bones:
        eb = data.edit_bones.new(bname)
        eb.head, eb.tail = Vector(head) * s, Vector(tail) * s
        eb.use_deform = deform
        if parent:
            eb.parent = data.edit_bones[parent]
            eb.use_connect = (eb.parent.tail - eb.head).length < 1e-6
    bpy.ops.object.mode_set(mode="OBJECT")
    return arm


def bind_automatic(arm, meshes):
    """Parents the meshes to the armature with automatic (bone heat) weights, as a user would."""
    bpy.ops.object.select_all(action="DESELECT")
    for m in meshes:
        m.select_set(True)
    arm.select_set(True)
    bpy.context.view_layer.objects.active = arm
    bpy.ops.object.parent_set(type="ARMATURE_AUTO")
    for m in meshes:
        unweighted = sum(1 for v in m.data.vertices if not v.groups)
        if unweighted:
            raise RuntimeError(f"{m.name}: {unweighted} vertices got no automatic weight")


def key_pose(arm, keys):
    """keys: {bone: [(frame, (x, y, z) degrees), ...]} on rotation_euler; loc/scale keys as ('loc'|'scale', ...)."""
    for bname, frames in keys.items():
        pb = arm.pose.bones[bname]
        pb.rotation_mode = "XYZ"
        for frame, value, *kind in frames:
            if kind and kind[0] == "scale":
                pb.scale = value
                pb.keyframe_insert("scale", frame=frame)
            else:
                pb.rotation_euler = [math.radians(a) for a in value]
                pb.keyframe_insert("rotation_euler", frame=frame)
    arm.animation_data.action.name = arm.name + "Action"


def swing(angle_axis, amplitude, phase=0.0):
    """Three keys (frames 1, 20, 40) swinging about one axis and back: a loop."""
    out = []
    for frame, w in ((1, -1.0), (20, 1.0), (40, -1.0)):
        rot = [0.0, 0.0, 0.0]
        rot[angle_axis] = amplitude * (w if phase == 0.0 else math.cos(math.pi * (frame - 1) / 19.5 + phase))
        out.append((frame, tuple(rot)))
    return out


def add_shape_key(obj, name, move, frames):
    """A shape key moving each vertex by move(co) (scene units), its value keyed at frames {frame: value}."""
    if obj.data.shape_keys is None:
        obj.shape_key_add(name="Basis", from_mix=False)
    key = obj.shape_key_add(name=name, from_mix=False)
    moved = 0
    for i, v in enumerate(obj.data.vertices):
        d = move(v.co)
        if d.length > 0.0:
            key.data[i].co = v.co + d
            moved += 1
    if moved == 0:
        raise RuntimeError(f"{obj.name}: shape key {name} moves no vertex")
    for frame, value in frames.items():
        key.value = value
        key.keyframe_insert("value", frame=frame)
    obj.data.shape_keys.animation_data.action.name = obj.name + "ShapeKeys"
    return moved


def falloff(co, centre, radius, s):
    d = (co - Vector(centre) * s).length / (radius * s)
    return max(0.0, 1.0 - d) ** 2


# ---------------------------------------------------------------- the characters

def build_humanoid(s):
    bm = bmesh.new()
    add_ellipsoid(bm, (0, 0, 1.2), (0.18, 0.11, 0.27), s)
    add_ellipsoid(bm, (0, 0, 0.96), (0.16, 0.10, 0.12), s)
    add_capsule(bm, (0, 0, 1.38), (0, 0, 1.56), 0.05, s)
    add_ellipsoid(bm, (0, -0.01, 1.65), (0.09, 0.10, 0.12), s)
    for side in (1, -1):
        add_capsule(bm, (0.10 * side, 0, 1.40), (0.42 * side, 0, 1.40), 0.045, s)
        add_capsule(bm, (0.42 * side, 0, 1.40), (0.66 * side, 0, 1.40), 0.037, s)
        add_ellipsoid(bm, (0.71 * side, 0, 1.40), (0.05, 0.045, 0.017), s)
        for y in (-0.028, 0.0, 0.028):  # three fingers
            add_capsule(bm, (0.74 * side, y, 1.40), (0.83 * side, y, 1.40), 0.012, s, segs=10)
        add_capsule(bm, (0.10 * side, 0, 0.95), (0.10 * side, 0, 0.50), 0.07, s)
        add_capsule(bm, (0.10 * side, 0, 0.50), (0.10 * side, 0, 0.07), 0.05, s)
        add_capsule(bm, (0.10 * side, 0.02, 0.04), (0.10 * side, -0.15, 0.035), 0.035, s)
    body = mesh_object("Body", bm, voxel=0.011 * s)
    bm = bmesh.new()
    add_ellipsoid(bm, (0, -0.01, 1.75), (0.105, 0.115, 0.045), s, segs=(20, 10))
    hat = mesh_object("Hat", bm)
    bm = bmesh.new()
    add_ellipsoid(bm, (0.19, 0.02, 0.95), (0.05, 0.09, 0.08), s, segs=(16, 10))
    bag = mesh_object("Bag", bm)

    bones = [("root", (0, 0, 0), (0, 0.15, 0), None, False),  # on the ground between the feet
             ("hips", (0, 0, 0.92), (0, 0, 1.05), "root", True),
             ("spine", (0, 0, 1.05), (0, 0, 1.22), "hips", True),
             ("chest", (0, 0, 1.22), (0, 0, 1.42), "spine", True),
             ("neck", (0, 0, 1.42), (0, 0, 1.53), "chest", True),
             ("head", (0, 0, 1.53), (0, 0, 1.77), "neck", True),
             ("jaw", (0, -0.02, 1.59), (0, -0.09, 1.57), "head", True),
             ("eye_L", (0.035, -0.06, 1.67), (0.035, -0.10, 1.67), "head", True),
             ("eye_R", (-0.035, -0.06, 1.67), (-0.035, -0.10, 1.67), "head", True),
             ("brow", (0, -0.07, 1.71), (0, -0.105, 1.72), "head", True)]
    for sfx, x in (("L", 1), ("R", -1)):
        bones += [(f"shoulder_{sfx}", (0.03 * x, 0, 1.40), (0.15 * x, 0, 1.40), "chest", True),
                  (f"upperarm_{sfx}", (0.15 * x, 0, 1.40), (0.42 * x, 0, 1.40), f"shoulder_{sfx}", True),
                  (f"forearm_{sfx}", (0.42 * x, 0, 1.40), (0.66 * x, 0, 1.40), f"upperarm_{sfx}", True),
                  (f"hand_{sfx}", (0.66 * x, 0, 1.40), (0.74 * x, 0, 1.40), f"forearm_{sfx}", True),
                  (f"prop_{sfx}", (0.72 * x, -0.05, 1.40), (0.72 * x, -0.30, 1.40), f"hand_{sfx}", False),
                  (f"thigh_{sfx}", (0.10 * x, 0, 0.95), (0.10 * x, 0, 0.50), "hips", True),
                  (f"shin_{sfx}", (0.10 * x, 0, 0.50), (0.10 * x, 0, 0.07), f"thigh_{sfx}", True),
                  (f"foot_{sfx}", (0.10 * x, 0, 0.07), (0.10 * x, -0.16, 0.03), f"shin_{sfx}", True),
                  (f"foot_ik_{sfx}", (0.10 * x, 0.12, 0.0), (0.10 * x, 0.27, 0.0), "root", False),
                  (f"knee_pole_{sfx}", (0.10 * x, -0.55, 0.50), (0.10 * x, -0.65, 0.50), "root", False)]
        for k, y in enumerate((-0.028, 0.0, 0.028)):
            bones += [(f"finger{k}a_{sfx}", (0.74 * x, y, 1.40), (0.785 * x, y, 1.40), f"hand_{sfx}", True),
                      (f"finger{k}b_{sfx}", (0.785 * x, y, 1.40), (0.83 * x, y, 1.40), f"finger{k}a_{sfx}", True)]
    arm = make_armature("Armature", bones, s)
    bind_automatic(arm, [body, hat, bag])
    keys = {"spine": swing(2, 12), "head": swing(0, 10), "jaw": [(1, (0, 0, 0)), (20, (20, 0, 0)), (40, (0, 0, 0))],
            "upperarm_L": swing(1, 35), "upperarm_R": swing(1, 35), "forearm_L": swing(2, 30),
            "thigh_L": swing(0, 30), "thigh_R": swing(0, -30), "shin_L": swing(0, 20)}
    for k in range(3):
        keys[f"finger{k}a_L"] = swing(1, 40)
        keys[f"finger{k}b_L"] = swing(1, 40)
    key_pose(arm, keys)
    mouth = add_shape_key(body, "Smile",
                          lambda co: Vector((0, -0.012, 0.006)) * s * falloff(co, (0, -0.1, 1.6), 0.06, s),
                          {1: 0.0, 20: 1.0, 40: 0.0})
    chest = add_shape_key(body, "Breathe",
                          lambda co: (co - Vector((0, 0, 1.2)) * s) * 0.06 * falloff(co, (0, 0, 1.22), 0.3, s),
                          {1: 0.0, 10: 1.0, 30: 0.0, 40: 0.0})
    return arm, [body, hat, bag], {"Smile": mouth, "Breathe": chest}


def build_quadruped(s):
    bm = bmesh.new()
    add_ellipsoid(bm, (0, 0, 0.76), (0.38, 0.62, 0.24), s, segs=(32, 18))  # wide body, one spine bone
    add_capsule(bm, (0, -0.50, 0.82), (0, -0.76, 1.04), 0.10, s)
    add_ellipsoid(bm, (0, -0.90, 1.08), (0.11, 0.17, 0.10), s)
    tail = [(0, 0.55, 0.80), (0, 0.85, 0.85), (0, 1.10, 0.80), (0, 1.30, 0.70)]
    for (a, b, r) in zip(tail, tail[1:], (0.07, 0.05, 0.035)):
        add_capsule(bm, a, b, r, s)
    for x in (0.22, -0.22):
        for y in (0.38, -0.38):
            add_capsule(bm, (x, y, 0.66), (x, y, 0.33), 0.08, s)
            add_capsule(bm, (x, y, 0.33), (x, y, 0.05), 0.06, s)
    body = mesh_object("Body", bm, voxel=0.022 * s)
    bones = [("root", (0, 0, 0), (0, 0, 0.2), None, False),
             ("spine", (0, 0.55, 0.78), (0, -0.50, 0.80), "root", True),
             ("neck", (0, -0.50, 0.82), (0, -0.76, 1.04), "spine", True),
             ("head", (0, -0.76, 1.04), (0, -1.05, 1.10), "neck", True),
             ("tail1", (0, 0.55, 0.80), (0, 0.85, 0.85), "spine", True),
             ("tail2", (0, 0.85, 0.85), (0, 1.10, 0.80), "tail1", True),
             ("tail3", (0, 1.10, 0.80), (0, 1.30, 0.70), "tail2", True)]
    for x, sx in ((0.22, "L"), (-0.22, "R")):
        for y, sy in ((0.38, "hind"), (-0.38, "front")):
            n = f"{sy}_{sx}"
            bones += [(f"{n}_upper", (x, y, 0.66), (x, y, 0.33), "spine", True),
                      (f"{n}_lower", (x, y, 0.33), (x, y, 0.05), f"{n}_upper", True),
                      (f"{n}_ik", (x, y + 0.15, 0.0), (x, y + 0.30, 0.0), "root", False)]
    arm = make_armature("Armature", bones, s)
    bind_automatic(arm, [body])
    key_pose(arm, {"front_L_upper": swing(0, 25), "front_R_upper": swing(0, -25), "hind_L_upper": swing(0, -25),
                   "hind_R_upper": swing(0, 25), "tail1": swing(2, 25), "tail2": swing(2, 25), "head": swing(2, 15),
                   "spine": swing(1, 4)})
    moved = add_shape_key(body, "Breathe",
                          lambda co: Vector((co.x, 0, co.z - 0.76 * s)) * 0.08 * falloff(co, (0, 0, 0.76), 0.6, s),
                          {1: 0.0, 20: 1.0, 40: 0.0})
    return arm, [body], {"Breathe": moved}


def build_tentacle(s):
    n = 80
    pts = [(0.04 * math.sin(3.0 * i / n), 0.0, 2.0 * i / n) for i in range(n + 1)]
    radii = [0.12 + (0.015 - 0.12) * (i / n) ** 0.8 for i in range(n + 1)]
    bm = bmesh.new()
    add_tube(bm, pts, radii, s)
    body = mesh_object("Tentacle", bm)
    bones = [("root", (0, 0, -0.25), (0, 0, -0.05), None, False),  # below the base, outside the mesh
             ("ctrl_mid", (0.45, 0, 1.0), (0.55, 0, 1.0), "root", False),  # a control beside it
             ("tip_ik", (0, 0.3, 2.15), (0, 0.45, 2.15), "root", False)]
    parent = "root"
    for k in range(10):
        z0, z1 = 0.2 * k, 0.2 * (k + 1)
        name = f"seg{k:02d}"
        bones.append((name, (0, 0, z0), (0, 0, z1), parent, True))
        parent = name
    arm = make_armature("Armature", bones, s)
    bind_automatic(arm, [body])
    keys = {f"seg{k:02d}": [(1, (0, 0, 0)), (20, (0, 12 * math.sin(k * 0.7), 0)), (40, (0, 0, 0))] for k in range(10)}
    keys["seg09"] = [(1, (1, 1, 1), "scale"), (20, (1.4, 1.0, 1.4), "scale"), (40, (1, 1, 1), "scale")]
    key_pose(arm, keys)
    moved = add_shape_key(body, "Bulge",
                          lambda co: Vector((co.x, co.y, 0)) * 0.5 * falloff(co, (0, 0, 1.4), 0.3, s),
                          {1: 0.0, 20: 1.0, 40: 0.0})
    return arm, [body], {"Bulge": moved}


def build_flag(s):
    bm = bmesh.new()
    bmesh.ops.create_grid(bm, x_segments=48, y_segments=32, size=1.0,
                          matrix=Matrix.Translation(Vector((0.6, 0, 1.6)) * s) @ Matrix.Rotation(math.radians(90), 4, "X")
                          @ Matrix.Diagonal((0.6 * s, 0.4 * s, 1.0, 1.0)))
    sheet = mesh_object("Flag_sheet", bm)
    mod = sheet.modifiers.new("thickness", "SOLIDIFY")
    mod.thickness = 0.01 * s  # 1 cm thin
    mod.offset = 0.0
    depsgraph = bpy.context.evaluated_depsgraph_get()
    solid = bpy.data.meshes.new_from_object(sheet.evaluated_get(depsgraph))
    sheet.modifiers.clear()
    old = sheet.data
    sheet.data = solid
    bpy.data.meshes.remove(old)
    sheet.name = solid.name = "Flag"
    bones = [("root", (0, 0, 0), (0, 0, 0.3), None, False)]
    parent = "root"
    for k in range(4):
        name = f"flag{k}"
        bones.append((name, (0.3 * k, 0, 1.6), (0.3 * (k + 1), 0, 1.6), parent, True))
        parent = name
    arm = make_armature("Armature", bones, s)
    bind_automatic(arm, [sheet])
    key_pose(arm, {f"flag{k}": swing(2, 15, phase=0.9 * k) for k in range(4)})
    moved = add_shape_key(sheet, "Ripple",
                          lambda co: Vector((0, 0.04 * s * math.sin(co.x / s * 12.0), 0)) * min(1.0, co.x / s),
                          {1: 0.0, 20: 1.0, 40: 0.0})
    return arm, [sheet], {"Ripple": moved}


CHARACTERS = {"humanoid": (build_humanoid, "three meshes on one rig (body, hat, bag), face bones (jaw, eyes, brow) "
                                           "inside the head, three two-bone fingers per hand, arms in T-pose"),
              "quadruped": (build_quadruped, "a wide ellipsoid body (0.76 x 1.24 m) on ONE spine bone, "
                                             "two-bone legs, neck, head, a three-bone tail"),
              "tentacle": (build_tentacle, "a tapered tube 2 m long on a chain of ten bones, the tip bone "
                                           "scaled by the animation"),
              "flag": (build_flag, "a sheet 1.2 x 0.8 m and 1 cm thick on a chain of four bones")}

# Every character also has bones outside its mesh that carry no vertices.
EXTRA_BONES = {"humanoid": ["root", "foot_ik_L", "foot_ik_R", "knee_pole_L", "knee_pole_R", "prop_L", "prop_R"],
               "quadruped": ["root", "front_L_ik", "front_R_ik", "hind_L_ik", "hind_R_ik"],
               "tentacle": ["root", "ctrl_mid", "tip_ik"],
               "flag": ["root"]}

# (variant, scene unit: metres per Blender unit, data scale, armature object scale, formats, FBX scale option).
# Blender's FBX exporter by default (FBX_SCALE_NONE) declares centimetres and puts the unit
# conversion into the root objects' transforms (the 100x armature scale of Blender FBX files);
# FBX_SCALE_UNITS declares the scene's own unit instead (metres) with no scaled root.
VARIANTS = [("m", 1.0, 1.0, (1, 1, 1), ("fbx", "dae", "glb"), "FBX_SCALE_NONE"),
            ("cm", 0.01, 100.0, (1, 1, 1), ("fbx", "dae", "glb"), "FBX_SCALE_NONE")]
EXTRA_VARIANTS = {"humanoid": [("scaledroot", 1.0, 100.0, (0.01, 0.01, 0.01), ("fbx", "dae", "glb"), "FBX_SCALE_NONE"),
                               ("fbxunits", 1.0, 1.0, (1, 1, 1), ("fbx",), "FBX_SCALE_UNITS")],
                  "quadruped": [("stretched", 1.0, 1.0, (1.0, 1.3, 0.9), ("fbx", "glb"), "FBX_SCALE_NONE")],
                  "tentacle": [("scaledroot", 1.0, 100.0, (0.01, 0.01, 0.01), ("fbx", "glb"), "FBX_SCALE_NONE")]}


def export(path, fmt, fbx_scale_option):
    if fmt == "glb":
        bpy.ops.export_scene.gltf(filepath=path, export_format="GLB", export_animations=True, export_skins=True,
                                  export_morph=True, export_morph_normal=True, export_nla_strips=False,
                                  export_force_sampling=True, export_def_bones=False, export_materials="NONE")
    elif fmt == "fbx":
        # Every frame baked (simplify 0): FBX curves are Bezier, and importers that read their keys
        # linearly (assimp) play a simplified curve's keys, not Blender's curve between them.
        bpy.ops.export_scene.fbx(filepath=path, apply_unit_scale=True, apply_scale_options=fbx_scale_option,
                                 add_leaf_bones=True, bake_anim=True, bake_anim_simplify_factor=0.0,
                                 bake_anim_use_nla_strips=False,
                                 bake_anim_use_all_actions=False, object_types={"ARMATURE", "MESH"})
    else:
        bpy.ops.wm.collada_export(filepath=path, include_armatures=True, include_shapekeys=True,
                                  include_animations=True, include_all_actions=False, apply_modifiers=False,
                                  triangulate=True)
    if not os.path.isfile(path):
        raise RuntimeError(f"{path}: the {fmt} exporter wrote nothing")


def pieces(mesh):
    """Connected components of a mesh's edge graph."""
    parent = list(range(len(mesh.vertices)))

    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x
    for e in mesh.edges:
        a, b = find(e.vertices[0]), find(e.vertices[1])
        parent[a] = b
    return len({find(i) for i in range(len(parent))})


def world_height_m(meshes, metres_per_unit):
    bpy.context.scene.frame_set(FRAMES[0])
    zs = [(m.matrix_world @ v.co).z for m in meshes for v in m.data.vertices]
    return (max(zs) - min(zs)) * metres_per_unit


def make_variant(outdir, name, variant, files):
    vname, unit_m, data_scale, arm_scale, formats, fbx_option = variant
    build, what = CHARACTERS[name]
    reset_scene(unit_m)
    arm, meshes, shape_keys = build(data_scale)
    arm.scale = arm_scale
    bpy.context.view_layer.update()
    height = world_height_m(meshes, unit_m)
    deform = [b.name for b in arm.data.bones if b.use_deform]
    for m in meshes:  # the tests expect a one-piece stand-in for each of these
        if pieces(m.data) != 1:
            raise RuntimeError(f"{name}_{vname}: mesh {m.name} is in {pieces(m.data)} pieces, not one")
    for fmt in formats:
        fname = f"{name}_{vname}.{fmt}"
        export(os.path.join(outdir, fname), fmt, fbx_option)
        # The unit the file declares, and the character's height in the numbers the file holds.
        if fmt == "glb":  # glTF is metres by definition: Blender writes its numbers as they are
            unit = "m"
            height_file = height / unit_m
        elif fmt == "fbx":
            unit = "cm" if fbx_option == "FBX_SCALE_NONE" or unit_m < 0.1 else "m"
            height_file = height * (100.0 if unit == "cm" else 1.0)
        else:
            unit = "cm" if unit_m < 0.1 else "m"
            height_file = height / unit_m
        files.append({
            "file": fname, "character": name, "variant": vname, "format": fmt, "unit": unit,
            "height_file_units": round(height_file, 4), "height_m": round(height_file * (0.01 if unit == "cm" else 1.0), 4),
            "scene_unit_scale": unit_m, "fbx_scale_option": fbx_option if fmt == "fbx" else None,
            "data_scale": data_scale, "armature_scale": list(arm_scale),
            "meshes": [m.name for m in meshes], "vertices": sum(len(m.data.vertices) for m in meshes),
            "bones": len(arm.data.bones), "deform_bones": deform, "bones_without_vertices": EXTRA_BONES[name],
            "shape_keys": shape_keys, "frames": list(FRAMES), "fps": FPS,
            "one_piece_meshes": [m.name for m in meshes], "contains": what})


def main():
    outdir = os.path.abspath(sys.argv[sys.argv.index("--") + 1])
    os.makedirs(outdir, exist_ok=True)
    manifest_path = os.path.join(outdir, "manifest.json")
    if os.path.exists(manifest_path):
        os.remove(manifest_path)
    files = []
    for name in CHARACTERS:
        for variant in VARIANTS + EXTRA_VARIANTS.get(name, []):
            make_variant(outdir, name, variant, files)
    manifest = {"generator": "tests/tools/make_test_characters.py", "generator_sha256": script_hash(),
                "blender": bpy.app.version_string, "files": files,
                "notes": ["unit: the unit the file declares (glTF: metres by definition, its numbers as Blender "
                          "wrote them); height_m: the character's height in metres when read in that unit",
                          "every mesh of every character is one connected piece"]}
    with open(manifest_path + ".tmp", "w") as f:
        json.dump(manifest, f, indent=1)
    os.replace(manifest_path + ".tmp", manifest_path)
    print(f"test characters: {len(files)} files in {outdir}")


main()
