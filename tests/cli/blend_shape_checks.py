#!/usr/bin/env python3
"""animorph-cli on a character with blend shapes made by Blender (the CTest fixture of
tests/tools/blender_blend_shape_character.py):

usage: blend_shape_checks.py CLI TOOLS FIXTURE_DIR
  * `new` morphs it into the demo gear and `bake --gltf` exports the morph; the frames before
    marker A (the source playing its clip, shape keys and bones) hold Blender's own evaluated
    mesh of the same frames, within 1e-4 of the diagonal;
  * the Khronos glTF-Validator reports 0 errors and 0 warnings on that bake and on the character
    exported back to glTF with its morph targets and weight animation (reexported.glb, written by
    the core round-trip test).
Exit 77 (skipped) when the fixture was not made (no Blender) or Node / the validator is missing.
"""
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_checks import fail, run  # noqa: E402
from export_checks import read_glb, accessor_values  # noqa: E402

FRAMES = (0, 20)


def diagonal(points):
    lo = [min(p[k] for p in points) for k in range(3)]
    hi = [max(p[k] for p in points) for k in range(3)]
    return math.dist(lo, hi)


def match(ours, blender, tol):
    """For each of our vertices, the Blender vertex at the same rest position."""
    out = []
    for i, p in enumerate(ours):
        best = min(range(len(blender)), key=lambda k: math.dist(p, blender[k]))
        if math.dist(p, blender[best]) > tol:
            fail(f"vertex {i} at {p} has no Blender vertex at its rest position (nearest {blender[best]})")
        out.append(best)
    return out


def frame_positions(doc, binary, name):
    node = next((n for n in doc["nodes"] if n.get("name") == name), None)
    if node is None or "mesh" not in node:
        fail(f"the baked glTF has no mesh node {name}")
    prim = doc["meshes"][node["mesh"]]["primitives"][0]
    return accessor_values(doc, binary, prim["attributes"]["POSITION"])


def main(cli, tools, fixture):
    source = os.path.join(fixture, "blend_shape_character.glb")
    if not os.path.exists(os.path.join(fixture, "blend_shape_reference.json")):
        print(f"{fixture}: no blend-shape character (Blender is not installed): skipped")
        sys.exit(77)
    with open(os.path.join(fixture, "blend_shape_reference.json")) as f:
        ref = json.load(f)
    src_doc, src_bin = read_glb(source)
    rest = accessor_values(src_doc, src_bin, src_doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"])
    diag = diagonal(ref["rest"])
    vmap = match(rest, ref["rest"], 1e-5 * diag)
    with tempfile.TemporaryDirectory() as tmp:
        r = run(cli, "make-demo", tmp)
        if r.returncode != 0:
            fail(f"make-demo: {r.stderr}")
        project = os.path.join(tmp, "tube.animorph")
        r = run(cli, "new", source, os.path.join(tmp, "gear.glb"), "-o", project, "--accept-poor-fit")
        if r.returncode != 0:
            fail(f"new: exit {r.returncode}: {r.stderr}")
        glb = os.path.join(tmp, "tube.glb")
        r = run(cli, "bake", project, "--frames", f"{FRAMES[0]}:{FRAMES[1]}", "--res", "16", "--format", "none",
                "--gltf", glb, "--name", "tube")
        if r.returncode != 0:
            fail(f"bake: exit {r.returncode}: {r.stderr}")
        doc, binary = read_glb(glb)
        for frame in (int(f) for f in ref["animated"] if FRAMES[0] <= int(f) <= FRAMES[1]):
            ours = frame_positions(doc, binary, f"tube_{frame:04d}")
            if len(ours) != len(vmap):
                fail(f"frame {frame}: {len(ours)} vertices, the character has {len(vmap)}")
            worst = max(math.dist(p, ref["animated"][str(frame)][vmap[i]]) for i, p in enumerate(ours))
            print(f"frame {frame}: worst distance to Blender's evaluated mesh {worst:.2e} ({worst / diag:.1e} of the diagonal)")
            if worst > 1e-4 * diag:
                fail(f"frame {frame}: the baked mesh is {worst} from Blender's (diagonal {diag})")

        r = subprocess.run([os.path.join(tools, "install_validator.sh"), tools], capture_output=True, text=True)
        if r.returncode != 0:
            print(r.stdout.strip())
            sys.exit(r.returncode)
        files = [glb, os.path.join(fixture, "reexported.glb")]
        if not os.path.exists(files[1]):
            fail(f"{files[1]} is missing: the core round-trip test writes it (fixture blend_shape_export)")
        r = subprocess.run(["node", os.path.join(tools, "validate_gltf.js"), *files], capture_output=True, text=True)
        print(r.stdout.strip())
        if r.returncode != 0 or r.stdout.count(" 0 errors, 0 warnings") != len(files):
            fail(f"the glTF-Validator did not accept the files: {r.stdout}{r.stderr}")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
