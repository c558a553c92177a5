#!/usr/bin/env python3
"""Writes the FBX and Collada fuzz targets' seed corpora (committed; rerun after changing this
script): a tiny skinned, animated rig -- a box of 8 vertices on two bones, keyed over 6 frames,
with a material and a shape key held at 0.35 (an FBX blend shape channel with its DeformPercent, a
Collada <morph> controller) -- as Blender exports it, and a few hand-broken variants.

  corpus/fbx/      rig.fbx (Blender's binary FBX 7.4), rig_ascii.fbx (the same scene as ASCII FBX,
                   written by the `assimp` command), rig_cut.fbx (truncated), rig_big_count.fbx
                   (an array that claims 2^30 elements)
  corpus/collada/  rig.dae (Blender's Collada), rig_cut.dae, rig_big_count.dae, rig_weights.dae
                   (rig.dae with the shape's weight animated as OpenCOLLADA writes it: STEP,
                   BEZIER and LINEAR keys; Blender writes no weight animation)

usage: make_assimp_seeds.py [--source DIR]   (runs Blender headless on itself; needs blender
       and assimp-utils)
       make_assimp_seeds.py --weights-only [--source DIR]   (rig_weights.dae from rig.dae only)
"""
import os
import subprocess
import sys
import tempfile


def in_blender(out_fbx, out_dae):
    import bpy
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, 6
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0, 0, 0.5))
    box = bpy.context.object
    box.scale = (0.3, 0.3, 1.0)
    bpy.ops.object.transform_apply(scale=True)
    mat = bpy.data.materials.new("seed_red")
    mat.diffuse_color = (0.8, 0.1, 0.1, 1.0)
    box.data.materials.append(mat)
    box.shape_key_add(name="Basis", from_mix=False)
    squash = box.shape_key_add(name="squash", from_mix=False)
    for point in squash.data:
        point.co.z *= 0.8
    squash.value = 0.35
    bpy.ops.object.armature_add(location=(0, 0, 0))
    arm = bpy.context.object
    bpy.ops.object.mode_set(mode="EDIT")
    lower = arm.data.edit_bones[0]
    lower.name, lower.head, lower.tail = "lower", (0, 0, 0), (0, 0, 0.5)
    upper = arm.data.edit_bones.new("upper")
    upper.head, upper.tail, upper.parent = (0, 0, 0.5), (0, 0, 1.0), lower
    bpy.ops.object.mode_set(mode="OBJECT")
    box.select_set(True)
    arm.select_set(True)
    bpy.context.view_layer.objects.active = arm
    bpy.ops.object.parent_set(type="ARMATURE_AUTO")
    bpy.ops.object.mode_set(mode="POSE")
    bone = arm.pose.bones["upper"]
    bone.rotation_mode = "XYZ"
    for frame, angle in ((1, 0.0), (6, 0.8)):
        bone.rotation_euler = (angle, 0.0, 0.0)
        bone.keyframe_insert("rotation_euler", frame=frame)
    bpy.ops.object.mode_set(mode="OBJECT")
    bpy.ops.export_scene.fbx(filepath=out_fbx, object_types={"ARMATURE", "MESH"}, bake_anim=True,
                             bake_anim_simplify_factor=0.0, add_leaf_bones=False)
    bpy.ops.wm.collada_export(filepath=out_dae, include_armatures=True, include_shapekeys=True, include_animations=True,
                              triangulate=True)


def broken(path, data, cut_to, marker, replacement):
    with open(path.replace(".", "_cut.", 1), "wb") as f:
        f.write(data[:cut_to])
    at = data.find(marker)
    if at < 0:
        raise RuntimeError(f"{path}: no {marker!r} to patch")
    with open(path.replace(".", "_big_count.", 1), "wb") as f:
        f.write(data[:at] + replacement + data[at + len(replacement):])


def weight_animation(name, target, times, values, interpolation):
    """An <animation> for a morph's weights as OpenCOLLADA writes it."""
    def source(kind, array, count, param, ptype):
        return (f'<source id="{name}-{kind}">{array}<technique_common><accessor source="#{name}-{kind}-array" '
                f'count="{count}" stride="1"><param name="{param}" type="{ptype}"/></accessor></technique_common>'
                '</source>\n')
    n = len(times)
    return (f'<animation id="{name}">\n'
            + source("input", f'<float_array id="{name}-input-array" count="{n}">{" ".join(times)}</float_array>',
                     n, "TIME", "float")
            + source("output", f'<float_array id="{name}-output-array" count="{n}">{" ".join(values)}</float_array>',
                     n, "WEIGHT", "float")
            + source("interpolation", f'<Name_array id="{name}-interpolation-array" count="{n}">'
                     f'{" ".join(interpolation)}</Name_array>', n, "INTERPOLATION", "name")
            + f'<sampler id="{name}-sampler"><input semantic="INPUT" source="#{name}-input"/>'
            f'<input semantic="OUTPUT" source="#{name}-output"/>'
            f'<input semantic="INTERPOLATION" source="#{name}-interpolation"/></sampler>\n'
            f'<channel source="#{name}-sampler" target="{target}"/>\n</animation>\n')


def write_weights_seed(dae):
    """rig_weights.dae: rig.dae with its morph's weight animated (CONTROLLER/SID(k) addressing)."""
    text = open(dae, encoding="utf-8").read()
    controller = text[text.index('<controller id="', text.index("<morph") - 200):].split('"')[1]
    weights = text[text.index("<morph"):].split('semantic="MORPH_WEIGHT" source="#')[1].split('"')[0]
    xml = weight_animation("w", f"{controller}/MorphWeights(0)", ["0.04", "0.125", "0.25", "0.4"],
                           ["0", "1", "0.5", "0.8"], ["STEP", "BEZIER", "LINEAR", "LINEAR"])
    # The weights source's own id, as OpenCOLLADA addresses it, in a comment for the fuzzer to splice.
    xml += f"<!-- {weights}(0) -->\n"
    open(dae.replace(".", "_weights.", 1), "w", encoding="utf-8").write(
        text.replace("<library_animations>", "<library_animations>\n" + xml, 1))


def main():
    if "--" in sys.argv:  # inside Blender
        in_blender(*sys.argv[sys.argv.index("--") + 1:])
        return
    source = sys.argv[sys.argv.index("--source") + 1] if "--source" in sys.argv else \
        os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    corpus = os.path.join(source, "tests", "fuzz", "corpus")
    fbx_dir, dae_dir = os.path.join(corpus, "fbx"), os.path.join(corpus, "collada")
    os.makedirs(fbx_dir, exist_ok=True)
    os.makedirs(dae_dir, exist_ok=True)
    fbx, dae = os.path.join(fbx_dir, "rig.fbx"), os.path.join(dae_dir, "rig.dae")
    if "--weights-only" in sys.argv:
        write_weights_seed(dae)
        return
    subprocess.run(["blender", "-b", "--factory-startup", "--python-exit-code", "1", "-P", os.path.abspath(__file__),
                    "--", fbx, dae], check=True,
                   env={k: v for k, v in os.environ.items() if not k.startswith("PYTHON")})
    with tempfile.TemporaryDirectory() as tmp:  # assimp writes a sidecar .mtl-free ASCII FBX
        subprocess.run(["assimp", "export", fbx, os.path.join(fbx_dir, "rig_ascii.fbx"), "-ffbxa"],
                       check=True, stdout=subprocess.DEVNULL, cwd=tmp)
    data = open(fbx, "rb").read()
    # 'Vertices' then the array type 'd' and its u32 count: claim 2^30 elements.
    at = data.find(b"Vertices")
    broken(fbx, data, len(data) // 2, data[at:at + 13], data[at:at + 9] + b"\x00\x00\x00\x40")
    text = open(dae, "rb").read()
    broken(dae, text, len(text) // 2, b'count="', b'count="4000000000')
    write_weights_seed(dae)
    print("seeds written to", corpus)


main()
