#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpora under tests/fuzz/corpus/ (committed; rerun after
changing this script or the demo files):

  corpus/gltf_json/  small .gltf files: a skinned, animated triangle (data: URI buffer, and
                     an external "mesh.bin" the target provides), sparse and shared accessors,
                     a node matrix, and hand-made malformed cases of the kinds the importer
                     must refuse (deep nesting, huge counts, 64-bit indices, bad enums)
  corpus/gltf_glb/   the same documents as GLB, plus broken GLB layouts
  corpus/project/    the demo projects (minified) and malformed projects
  corpus/blobtree_scene/  the demo BlobTree scene (minified), every node type, malformed scenes

usage: make_seeds.py [--source DIR]   (default: the repository holding this script)
"""
import argparse
import base64
import copy
import json
import os
import shutil
import struct


def minified(obj):
    return json.dumps(obj, separators=(",", ":"), sort_keys=True).encode()


def floats(*v):
    return struct.pack(f"<{len(v)}f", *v)


def skinned_triangle():
    """glTF dict + its BIN bytes: one skinned triangle, two joints, an animation with
    LINEAR, STEP and CUBICSPLINE samplers, u16 indices."""
    views, accessors, bin_ = [], [], bytearray()

    def add(data, ctype, count, type_, target=None, minmax=None):
        while len(bin_) % 4:
            bin_.append(0)
        view = {"buffer": 0, "byteOffset": len(bin_), "byteLength": len(data)}
        if target:
            view["target"] = target
        views.append(view)
        bin_.extend(data)
        acc = {"bufferView": len(views) - 1, "componentType": ctype, "count": count, "type": type_}
        if minmax:
            acc["min"], acc["max"] = minmax
        accessors.append(acc)
        return len(accessors) - 1

    pos = add(floats(0, 0, 0, 1, 0, 0, 0, 1, 0), 5126, 3, "VEC3", 34962, ([0, 0, 0], [1, 1, 0]))
    idx = add(struct.pack("<3H", 0, 1, 2), 5123, 3, "SCALAR", 34963)
    joints = add(bytes([0, 1, 0, 0] * 3), 5121, 3, "VEC4", 34962)
    weights = add(floats(1, 0, 0, 0, 0.5, 0.5, 0, 0, 0, 1, 0, 0), 5126, 3, "VEC4", 34962)
    ibm = add(floats(*([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] * 2)), 5126, 2, "MAT4")
    times = add(floats(0, 0.5, 1), 5126, 3, "SCALAR", None, ([0], [1]))
    rot = add(floats(0, 0, 0, 1, 0, 0, 0.383, 0.924, 0, 0, 0.707, 0.707), 5126, 3, "VEC4")
    trans = add(floats(0, 0, 0, 0, 1, 0, 0, 0, 0), 5126, 3, "VEC3")
    cubic = add(floats(*([0, 0, 0, 1, 1, 1, 0, 0, 0] * 3)), 5126, 9, "VEC3")
    gltf = {
        "asset": {"version": "2.0", "generator": "animorph tests/fuzz/make_seeds.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [
            {"name": "body", "mesh": 0, "skin": 0},
            {"name": "root", "children": [2], "translation": [0, 0.1, 0]},
            {"name": "tip", "rotation": [0, 0, 0, 1], "scale": [1, 1, 1]},
        ],
        "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": pos, "JOINTS_0": joints,
                                                                  "WEIGHTS_0": weights},
                                                   "indices": idx, "mode": 4}]}],
        "skins": [{"joints": [1, 2], "inverseBindMatrices": ibm, "skeleton": 1}],
        "animations": [{"name": "wave",
                        "samplers": [{"input": times, "output": rot, "interpolation": "LINEAR"},
                                     {"input": times, "output": trans, "interpolation": "STEP"},
                                     {"input": times, "output": cubic, "interpolation": "CUBICSPLINE"}],
                        "channels": [{"sampler": 0, "target": {"node": 2, "path": "rotation"}},
                                     {"sampler": 1, "target": {"node": 1, "path": "translation"}},
                                     {"sampler": 2, "target": {"node": 2, "path": "scale"}}]}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(bin_)}],
    }
    return gltf, bytes(bin_)


def with_data_uri(gltf, bin_):
    g = copy.deepcopy(gltf)
    g["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bin_).decode()
    return g


def glb(gltf, bin_):
    """A GLB container: header, JSON chunk (space-padded), BIN chunk (zero-padded)."""
    j = minified(gltf)
    j += b" " * (-len(j) % 4)
    b = bin_ + b"\0" * (-len(bin_) % 4)
    chunks = struct.pack("<I4s", len(j), b"JSON") + j
    if bin_:
        chunks += struct.pack("<I4s", len(b), b"BIN\0") + b
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def gltf_variants(base, bin_):
    """(name, gltf dict) pairs: valid shapes of a document, then malformed ones."""
    out = [("skinned_triangle", base)]
    g = copy.deepcopy(base)  # unindexed, node matrix, no animation
    del g["meshes"][0]["primitives"][0]["indices"]
    g["nodes"][1] = {"name": "root", "children": [2], "matrix": [1, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}
    del g["animations"]
    out.append(("matrix_unindexed", g))
    g = copy.deepcopy(base)  # sparse accessor over the positions
    g["accessors"].append({"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                           "sparse": {"count": 1, "indices": {"bufferView": 1, "componentType": 5123},
                                      "values": {"bufferView": 0}}})
    g["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = len(g["accessors"]) - 1
    out.append(("sparse_positions", g))
    g = copy.deepcopy(base)  # strided view, triangle strip, morph target
    g["bufferViews"][0]["byteStride"] = 12
    g["meshes"][0]["primitives"][0]["mode"] = 5
    g["meshes"][0]["primitives"][0]["targets"] = [{"POSITION": 0}]
    g["meshes"][0]["weights"] = [0.5]
    out.append(("strip_stride_target", g))
    malformed = {
        "huge_count_no_view": lambda g: g["accessors"].append({"componentType": 5126, "count": 67108864,
                                                                "type": "VEC3"}) or
        g["meshes"][0]["primitives"][0]["attributes"].update(POSITION=len(g["accessors"]) - 1),
        "index_beyond_32_bits": lambda g: g["meshes"][0]["primitives"][0].update(indices=4294967300),
        "view_minus_one": lambda g: g["accessors"][0].update(bufferView=4294967295),
        "bad_component_type": lambda g: g["accessors"][1].update(componentType=5130),
        "missing_type": lambda g: g["accessors"][0].pop("type"),
        "view_past_buffer": lambda g: g["bufferViews"][0].update(byteOffset=1 << 31),
        "negative_key_times": lambda g: g["accessors"][5].update(min=[-1]),
        "joint_out_of_range": lambda g: g["skins"][0].update(joints=[1, 99]),
        "cyclic_children": lambda g: g["nodes"][2].update(children=[1]),
        "deep_extras": lambda g: g.update(extras=json.loads("[" * 300 + "]" * 300)),
        "materials_not_objects": lambda g: g.update(materials=[1, [2]]),
        "external_buffer_missing": lambda g: g["buffers"][0].update(uri="nothing.bin"),
        "escaping_uri": lambda g: g["buffers"][0].update(uri="../../etc/passwd"),
    }
    for name, change in malformed.items():
        g = copy.deepcopy(base)
        change(g)
        out.append((name, g))
    return out


def write(path, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data)


def gltf_seeds(out):
    base, bin_ = skinned_triangle()
    for name, g in gltf_variants(base, bin_):
        write(f"{out}/gltf_json/{name}.gltf", minified(with_data_uri(g, bin_)))
        write(f"{out}/gltf_glb/{name}.glb", glb(g, bin_))
    ext = copy.deepcopy(base)  # the external buffer the fuzz target writes beside its input
    ext["accessors"] = [ext["accessors"][0]]
    ext["bufferViews"] = [{"buffer": 0, "byteLength": 36}]
    ext["buffers"] = [{"byteLength": 36, "uri": "mesh.bin"}]
    ext["meshes"] = [{"primitives": [{"attributes": {"POSITION": 0}}]}]
    for k in ("skins", "animations"):
        del ext[k]
    ext["nodes"] = [{"mesh": 0}]
    ext["scenes"] = [{"nodes": [0]}]
    write(f"{out}/gltf_json/external_buffer.gltf", minified(ext))
    good = glb(base, bin_)
    broken = {
        "truncated": good[: len(good) // 2],
        "length_too_big": good[:8] + struct.pack("<I", len(good) + 100) + good[12:],
        "json_chunk_too_long": good[:12] + struct.pack("<I", 1 << 30) + good[16:],
        "bin_chunk_short": good[:-8],
        "version_1": good[:4] + struct.pack("<I", 1) + good[8:],
        "no_bin_chunk": glb(base, b""),
    }
    for name, data in broken.items():
        write(f"{out}/gltf_glb/{name}.glb", data)


def json_seeds(source, out):
    demo = os.path.join(source, "resources", "demo")
    for name in ("demo.animorph", "blob_demo.animorph"):
        with open(os.path.join(demo, name)) as f:
            project = json.load(f)
        write(f"{out}/project/{name}", minified(project))
        malformed = {
            "version_wraps": lambda p: p.update(version=4294967297),
            "frame_end_huge": lambda p: p["timeline"].update(frame_end=4294967296),
            "fps_tiny": lambda p: p["timeline"].update(fps=1e-300),
            "clip_huge": lambda p: p["actors"][0].update(clip=2147483647),
            "actors_not_array": lambda p: p.update(actors={"a": 1}),
            "no_format": lambda p: p.pop("format"),
        }
        for key, change in malformed.items():
            p = copy.deepcopy(project)
            change(p)
            write(f"{out}/project/{name[:-9]}_{key}.animorph", minified(p))
    write(f"{out}/project/deep_nesting.animorph", b'{"format":"animorph","version":1,"x":' + b"[" * 400 + b"]" * 400 + b"}")
    write(f"{out}/project/syntax_error.animorph", b'{"format":"animorph",\n"version":1,\n"actors":[}')

    with open(os.path.join(demo, "blob_creature.json")) as f:
        scene = json.load(f)
    write(f"{out}/blobtree_scene/blob_creature.json", minified(scene))
    types = ["point", "segment", "triangle", "disc", "circle", "curve", "capsule", "cylinder", "cone",
             "union", "blend", "intersection", "difference", "frame", "twist", "taper", "bend", "map"]
    children = [{"id": i + 2, "type": t, "name": t, "params": {}, "children": []} for i, t in enumerate(types)]
    every = {"format": "animorph-blobtree", "version": 1, "threshold": 0.5,
             "root": {"id": 1, "type": "blend", "name": "root", "params": {}, "children": children}}
    write(f"{out}/blobtree_scene/every_type_no_params.json", minified(every))
    malformed = {
        "unknown_type": lambda s: s["root"].update(type="teapot"),
        "negative_threshold": lambda s: s.update(threshold=-1),
        "version_2": lambda s: s.update(version=2),
        "id_huge": lambda s: s["root"].update(id=1 << 40),
        "children_not_array": lambda s: s["root"].update(children=7),
    }
    for key, change in malformed.items():
        s = copy.deepcopy(scene)
        change(s)
        write(f"{out}/blobtree_scene/{key}.json", minified(s))
    deep = {"id": 1, "type": "point", "params": {"center": [0, 0, 0], "radius": 1}, "children": []}
    for i in range(2, 80):
        deep = {"id": i, "type": "frame", "params": {}, "children": [deep]}
    write(f"{out}/blobtree_scene/too_deep.json",
          minified({"format": "animorph-blobtree", "version": 1, "threshold": 1, "root": deep}))


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", default=os.path.dirname(os.path.dirname(here)))
    a = ap.parse_args()
    out = os.path.join(here, "corpus")
    shutil.rmtree(out, ignore_errors=True)
    gltf_seeds(out)
    json_seeds(a.source, out)
    for d in sorted(os.listdir(out)):
        print(f"{d}: {len(os.listdir(os.path.join(out, d)))} seeds")


if __name__ == "__main__":
    main()
