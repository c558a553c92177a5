#!/usr/bin/env python3
"""End-to-end checks of animorph-cli bake's exports: mesh sequences and the animated glTF.

usage: export_checks.py MODE CLI PROJECT [ARGS...]
  sequence CLI PROJECT            --format ply,obj / --obj / --name: NAME_####.EXT files, OBJ read back
                                  with the PLY's vertex and face counts; bad --format/--name exit 2;
                                  --format none alone bakes for the report and writes nothing
  gltf CLI PROJECT                --gltf: one node per frame, at every frame exactly that frame's node
                                  has scale 1 (STEP keys evaluated), the same for KHR_node_visibility,
                                  vertex and triangle counts equal the PLY of the same frame, repeated
                                  frames share a mesh (and their PLYs are identical), --jobs 1 and 2
                                  write the same bytes, a failed write leaves no file
  validator CLI PROJECT TOOLS     the Khronos glTF-Validator reports 0 errors and 0 warnings
                                  (exit 77: skipped when Node/npm or the registry is unavailable)
  blender CLI PROJECT SCRIPT      Blender imports the glTF headless (SCRIPT runs inside it): the frame
                                  objects, one visible at each frame of the timeline, every frame's
                                  vertex count against its PLY (exit 77: skipped when blender is not
                                  installed)
"""
import json
import os
import struct
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_checks import fail, read_ply_header as ply_counts, run, blender_or_skip, run_blender  # noqa: E402 (the script beside this one)

FRAMES = (40, 215)  # collapse, morph, expand and target; the gear's 4 s turn repeats from frame 204
RES = "16"


def bake(cli, project, out_dir, *extra, frames=FRAMES):
    r = run(cli, "bake", project, "--frames", f"{frames[0]}:{frames[1]}", "--res", RES, *(("-o", out_dir) if out_dir else ()),
            *extra)
    if r.returncode != 0:
        fail(f"bake {' '.join(extra)}: exit {r.returncode}: {r.stderr}")
    return r.stdout


def obj_counts(path):
    v = vn = f = 0
    with open(path) as fh:
        for line in fh:
            tag, _, rest = line.partition(" ")
            if tag == "v":
                if len(rest.split()) not in (3, 6):
                    fail(f"{path}: vertex line {line.strip()!r}")
                v += 1
            elif tag == "vn":
                vn += 1
            elif tag == "f":
                corners = rest.split()
                if len(corners) != 3 or any(c.split("//")[0] != c.split("//")[-1] or "//" not in c for c in corners):
                    fail(f"{path}: face line {line.strip()!r} is not 'f a//a b//b c//c'")
                if any(not 1 <= int(c.split("//")[0]) <= v for c in corners):
                    fail(f"{path}: face {line.strip()!r} refers to a vertex that does not exist")
                f += 1
    if vn != v:
        fail(f"{path}: {vn} normals for {v} vertices")
    return v, f


def read_glb(path):
    with open(path, "rb") as f:
        b = f.read()
    magic, version, total = struct.unpack_from("<4sII", b, 0)
    if magic != b"glTF" or version != 2 or total != len(b):
        fail(f"{path}: bad GLB header {magic} {version} {total} ({len(b)} bytes)")
    jlen, jtype = struct.unpack_from("<I4s", b, 12)
    if jtype != b"JSON":
        fail(f"{path}: first chunk is {jtype}")
    doc = json.loads(b[20:20 + jlen])
    blen, btype = struct.unpack_from("<I4s", b, 20 + jlen)
    if btype != b"BIN\0":
        fail(f"{path}: second chunk is {btype}")
    return doc, b[28 + jlen:28 + jlen + blen]


def accessor_values(doc, binary, index):
    a = doc["accessors"][index]
    view = doc["bufferViews"][a["bufferView"]]
    fmt = {5126: "f", 5121: "B", 5123: "H", 5125: "I"}[a["componentType"]]
    comps = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}[a["type"]]
    start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
    flat = struct.unpack_from(f"<{a['count'] * comps}{fmt}", binary, start)
    return [flat[i * comps:(i + 1) * comps] for i in range(a["count"])]


def step_value(times, values, t):
    """A STEP sampler at time t: the value of the last key at or before t (the first key before it)."""
    k = 0
    for i, key in enumerate(times):
        if key <= t:
            k = i
    return values[k]


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def mode_sequence(cli, project):
    with tempfile.TemporaryDirectory() as tmp:
        frames = (46, 50)  # collapse and morph frames
        out = os.path.join(tmp, "both")
        bake(cli, project, out, "--format", "ply,obj", frames=frames)
        expected = sorted(f"demo_{f:04d}.{e}" for f in range(frames[0], frames[1] + 1) for e in ("ply", "obj"))
        if sorted(os.listdir(out)) != expected:
            fail(f"--format ply,obj wrote {sorted(os.listdir(out))}, expected {expected}")
        for f in range(frames[0], frames[1] + 1):
            pv, pf = ply_counts(os.path.join(out, f"demo_{f:04d}.ply"))
            ov, of = obj_counts(os.path.join(out, f"demo_{f:04d}.obj"))
            if (pv, pf) != (ov, of) or pv <= 0:
                fail(f"frame {f}: OBJ has {ov} vertices, {of} faces; the PLY {pv}, {pf}")
        out2 = os.path.join(tmp, "obj")
        bake(cli, project, out2, "--obj", "--name", "creature_to_gear", frames=frames)
        expected = sorted(f"creature_to_gear_{f:04d}.obj" for f in range(frames[0], frames[1] + 1))
        if sorted(os.listdir(out2)) != expected:
            fail(f"--obj --name wrote {sorted(os.listdir(out2))}, expected {expected}")
        for f in range(frames[0], frames[1] + 1):
            with open(os.path.join(out, f"demo_{f:04d}.obj"), "rb") as a, \
                    open(os.path.join(out2, f"creature_to_gear_{f:04d}.obj"), "rb") as b:
                if a.read() != b.read():
                    fail(f"frame {f}: the OBJ of --obj differs from the one of --format ply,obj")
        for bad in (["--format", "stl"], ["--name", "a/b"], ["--name", "two words"]):
            r = run(cli, "bake", project, "--frames", "46:46", "--res", RES, "-o", os.path.join(tmp, "bad"), *bad)
            if r.returncode != 2:
                fail(f"bake {bad}: exit {r.returncode}, expected 2 ({r.stderr})")
        if os.path.exists(os.path.join(tmp, "bad")):
            fail("a refused bake created its output directory")
        check_format_none(cli, project, tmp, frames)


def check_format_none(cli, project, tmp, frames):
    """--format none with no other output bakes for its report and writes nothing (no -o needed)."""
    quiet = os.path.join(tmp, "quiet")
    os.mkdir(quiet)
    r = subprocess.run([os.path.abspath(cli), "bake", os.path.abspath(project), "--frames", f"{frames[0]}:{frames[1]}", "--res", RES,
                        "--format", "none"], capture_output=True, text=True, cwd=quiet)
    if r.returncode != 0:
        fail(f"bake --format none without -o: exit {r.returncode}, expected 0 ({r.stderr.strip()})")
    summary = f"baked frames {frames[0]}..{frames[1]} "
    if summary not in r.stdout or "into no files" not in r.stdout or "continuity:" not in r.stdout:
        fail(f"bake --format none: no summary '{summary}... into no files' and continuity report: {r.stdout}")
    if os.listdir(quiet):
        fail(f"bake --format none wrote {os.listdir(quiet)}")


def mode_gltf(cli, project):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "ply")
        glb = os.path.join(tmp, "morph.glb")
        log = bake(cli, project, out, "--gltf", glb, "--jobs", "2")
        if "wrote " + glb not in log:
            fail(f"bake --gltf did not report the file: {log}")
        doc, binary = read_glb(glb)
        first, last = FRAMES
        count = last - first + 1
        fps = doc["scenes"][0]["extras"]["fps"]
        if fps != 24.0 or doc["scenes"][0]["extras"]["frameStart"] != first or doc["scenes"][0]["extras"]["frameEnd"] != last:
            fail(f"scene extras {doc['scenes'][0]['extras']}")
        nodes = doc["nodes"]
        frame_nodes = {n["name"]: i for i, n in enumerate(nodes) if n["name"].startswith("demo_")}
        if sorted(frame_nodes) != [f"demo_{f:04d}" for f in range(first, last + 1)]:
            fail(f"{len(frame_nodes)} frame nodes for {count} frames: {sorted(frame_nodes)[:3]}...")
        if doc.get("extensionsRequired"):
            fail(f"extensionsRequired {doc['extensionsRequired']}: the extensions must stay optional")

        # Evaluate the STEP keys (scale, and KHR_node_visibility through KHR_animation_pointer).
        anim = doc["animations"][0]
        scale = {}
        visible = {}
        for ch in anim["channels"]:
            s = anim["samplers"][ch["sampler"]]
            if s["interpolation"] != "STEP":
                fail(f"sampler {s} is not STEP")
            keys = ([t[0] for t in accessor_values(doc, binary, s["input"])], accessor_values(doc, binary, s["output"]))
            tgt = ch["target"]
            if tgt["path"] == "scale":
                scale[tgt["node"]] = keys
            elif tgt["path"] == "pointer":
                ptr = tgt["extensions"]["KHR_animation_pointer"]["pointer"]
                parts = ptr.split("/")
                if parts[3:] != ["extensions", "KHR_node_visibility", "visible"]:
                    fail(f"unexpected pointer {ptr}")
                visible[int(parts[2])] = keys
        if sorted(scale) != sorted(frame_nodes.values()) or sorted(visible) != sorted(frame_nodes.values()):
            fail(f"{len(scale)} scale and {len(visible)} visibility channels for {count} frame nodes")
        for f in range(first, last + 1):
            for t in (f32(f / fps), (f + 0.5) / fps):  # on the key, as importers read it, and mid-frame
                shown = [n for n, i in frame_nodes.items() if step_value(*scale[i], t) == (1.0, 1.0, 1.0)]
                hidden = [n for n, i in frame_nodes.items() if step_value(*scale[i], t) == (0.0, 0.0, 0.0)]
                if shown != [f"demo_{f:04d}"] or len(hidden) != count - 1:
                    fail(f"frame {f} (t={t}): scale 1 on {shown}, 0 on {len(hidden)} of {count} nodes")
                flags = [n for n, i in frame_nodes.items() if step_value(*visible[i], t) != (0,)]
                if flags != shown:
                    fail(f"frame {f}: KHR_node_visibility shows {flags}")

        # Geometry: every frame's mesh against the PLY of the same frame; repeats.
        by_mesh = {}
        for f in range(first, last + 1):
            node = nodes[frame_nodes[f"demo_{f:04d}"]]
            prim = doc["meshes"][node["mesh"]]["primitives"][0]
            verts = doc["accessors"][prim["attributes"]["POSITION"]]["count"]
            tris = doc["accessors"][prim["indices"]]["count"] // 3
            if (verts, tris) != ply_counts(os.path.join(out, f"demo_{f:04d}.ply")):
                fail(f"frame {f}: glTF {verts} vertices {tris} triangles, PLY {ply_counts(os.path.join(out, f'demo_{f:04d}.ply'))}")
            by_mesh.setdefault(node["mesh"], []).append(f)
        if len(by_mesh) != len(doc["meshes"]) or len(by_mesh) >= count:
            fail(f"{len(doc['meshes'])} meshes ({len(by_mesh)} used) for {count} frames: the repeated frames were not shared")
        plys = {}
        for mesh, fs in by_mesh.items():
            with open(os.path.join(out, f"demo_{fs[0]:04d}.ply"), "rb") as fh:
                data = fh.read()
            if data in plys:
                fail(f"frames {plys[data]} and {fs} are identical but have two meshes")
            plys[data] = fs
            for f in fs[1:]:
                with open(os.path.join(out, f"demo_{f:04d}.ply"), "rb") as fh:
                    if fh.read() != data:
                        fail(f"frames {fs[0]} and {f} share a mesh but their PLYs differ")
        print(f"{count} frames, {len(doc['meshes'])} meshes, {os.path.getsize(glb)} bytes")

        # The same bytes for any --jobs; --format none needs no -o.
        glb1 = os.path.join(tmp, "one.glb")
        bake(cli, project, None, "--format", "none", "--gltf", glb1, "--jobs", "1")
        with open(glb, "rb") as a, open(glb1, "rb") as b:
            if a.read() != b.read():
                fail("bake --gltf wrote different files for --jobs 1 and --jobs 2")
        # A write that fails leaves nothing behind (a file where the directory should be).
        blocker = os.path.join(tmp, "blocker")
        with open(blocker, "w") as fh:
            fh.write("x")
        r = run(cli, "bake", project, "--frames", "46:48", "--res", RES, "--format", "none",
                "--gltf", os.path.join(blocker, "x.glb"))
        if r.returncode == 0 or "x.glb" not in r.stderr:
            fail(f"bake --gltf into a file's path: exit {r.returncode}, stderr {r.stderr!r}")
        if sorted(os.listdir(tmp)) != ["blocker", "morph.glb", "one.glb", "ply"]:
            fail(f"left behind: {sorted(os.listdir(tmp))}")


def mode_validator(cli, project, tools):
    r = subprocess.run([os.path.join(tools, "install_validator.sh"), tools], capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout.strip())
        sys.exit(r.returncode)
    with tempfile.TemporaryDirectory() as tmp:
        glb = os.path.join(tmp, "morph.glb")
        bake(cli, project, None, "--format", "none", "--gltf", glb, "--jobs", "2")
        r = subprocess.run(["node", os.path.join(tools, "validate_gltf.js"), glb], capture_output=True, text=True)
        print(r.stdout.strip())
        if r.returncode != 0 or " 0 errors, 0 warnings" not in r.stdout:
            fail(f"the glTF-Validator did not accept the baked glTF: {r.stdout}{r.stderr}")


def mode_blender(cli, project, script):
    blender = blender_or_skip()
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "ply")
        glb = os.path.join(tmp, "morph.glb")
        bake(cli, project, out, "--gltf", glb, "--jobs", "2")
        result = os.path.join(tmp, "blender.json")
        r = run_blender(blender, script, glb, result)
        if r.returncode != 0 or not os.path.exists(result):
            fail(f"blender exited {r.returncode}: {r.stdout[-2000:]}{r.stderr[-2000:]}")
        with open(result) as fh:
            got = json.load(fh)
        first, last = FRAMES
        names = [f"demo_{f:04d}" for f in range(first, last + 1)]
        if sorted(got["frame_objects"]) != names:
            fail(f"Blender has {len(got['frame_objects'])} frame objects, expected {len(names)}")
        for f in range(first, last + 1):
            shown = got["visible"][str(f)]
            if shown != [f"demo_{f:04d}"]:
                fail(f"Blender frame {f}: visible {shown}")
        for f in range(first, last + 1):
            verts, _ = ply_counts(os.path.join(out, f"demo_{f:04d}.ply"))
            if got["vertices"][f"demo_{f:04d}"] != verts:
                fail(f"Blender frame {f}: {got['vertices'][f'demo_{f:04d}']} vertices, the PLY {verts}")
        print(f"Blender {got['version']}: {len(names)} frame objects, one visible per frame {first}..{last}, "
              f"scene {got['scene_range']} at {got['fps']} fps")


def main():
    if len(sys.argv) < 4:
        fail(__doc__)
    mode, args = sys.argv[1], sys.argv[2:]
    {"sequence": mode_sequence, "gltf": mode_gltf, "validator": mode_validator, "blender": mode_blender}[mode](*args)
    print("ok")


if __name__ == "__main__":
    main()
