#!/usr/bin/env python3
"""End-to-end checks of animorph-cli info / make-demo.

usage: cli_checks.py MODE CLI [ARGS...]
  info-json CLI FILE JOINTS CLIP DURATION   info --json on a glTF: counts, clip and report
  info-bad CLI FILE                         info on a malformed file: non-zero exit, file named on stderr
  make-demo CLI RESOURCES_DIR               make-demo into a temp dir, then info on what it wrote;
                                            the committed resources/demo must match the generator
"""
import json
import os
import subprocess
import sys
import tempfile


def run(cli, *args):
    return subprocess.run([cli, *args], capture_output=True, text=True, timeout=120)


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def info_json(cli, path):
    r = run(cli, "info", path, "--json")
    if r.returncode != 0:
        fail(f"info --json {path} exited {r.returncode}: {r.stderr}")
    try:
        return json.loads(r.stdout)
    except json.JSONDecodeError as e:
        fail(f"info --json {path} printed invalid JSON ({e}): {r.stdout[:200]}")


def check_character_json(d, path):
    for key in ("vertices", "triangles", "joints", "meshes", "skins", "animations", "report"):
        if key not in d:
            fail(f"{path}: JSON lacks '{key}'")
    for key in ("warnings", "unsupported", "weights_normalised"):
        if key not in d["report"]:
            fail(f"{path}: JSON report lacks '{key}'")
    if d["vertices"] <= 0 or d["triangles"] <= 0:
        fail(f"{path}: no geometry: {d['vertices']} vertices, {d['triangles']} triangles")


def mode_info_json(cli, path, joints, clip, duration):
    d = info_json(cli, path)
    check_character_json(d, path)
    if d["joints"] != int(joints):
        fail(f"{path}: {d['joints']} joints, expected {joints}")
    names = [a["name"] for a in d["animations"]]
    if clip not in names:
        fail(f"{path}: clips {names}, expected {clip}")
    got = next(a["duration"] for a in d["animations"] if a["name"] == clip)
    if abs(got - float(duration)) > 1e-3:
        fail(f"{path}: {clip} lasts {got} s, expected {duration}")
    # The human summary names the same figures.
    r = run(cli, "info", path)
    if r.returncode != 0 or f"{d['triangles']} triangles" not in r.stdout or clip not in r.stdout:
        fail(f"human summary of {path} is missing figures: {r.stdout}")


def mode_info_bad(cli, path):
    r = run(cli, "info", path)
    if r.returncode == 0:
        fail(f"info {path} succeeded on a malformed file")
    if os.path.basename(path) not in r.stderr:
        fail(f"stderr does not name the file: {r.stderr!r}")
    if r.stdout.strip():
        fail(f"error output went to stdout: {r.stdout!r}")
    print(r.stderr.strip())


def mode_make_demo(cli, resources):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "demo")
        r = run(cli, "make-demo", out)
        if r.returncode != 0:
            fail(f"make-demo exited {r.returncode}: {r.stderr}")
        for name in ("creature.glb", "gear.glb", "demo.animorph"):
            if not os.path.isfile(os.path.join(out, name)):
                fail(f"make-demo did not write {name}")
        creature = info_json(cli, os.path.join(out, "creature.glb"))
        check_character_json(creature, "creature.glb")
        if creature["joints"] < 10 or [a["name"] for a in creature["animations"]] != ["walk"]:
            fail(f"creature: {creature['joints']} joints, clips {creature['animations']}")
        gear = info_json(cli, os.path.join(out, "gear.glb"))
        check_character_json(gear, "gear.glb")
        if gear["joints"] < 2 or gear["report"]["warnings"]:
            fail(f"gear: {gear}")
        project = info_json(cli, os.path.join(out, "demo.animorph"))
        if project["fps"] != 24 or project["frame_start"] != 0:
            fail(f"project timeline: {project}")
        walk = creature["animations"][0]["duration"]
        span = (project["frame_end"] - project["frame_start"]) / project["fps"]
        if span < 2 * walk - 1e-6:
            fail(f"timeline covers {span} s, less than two walk cycles of {walk} s")
        actors = {a["id"]: a for a in project["actors"]}
        if set(actors) != {"creature", "gear"} or not all(a["loads"] for a in actors.values()):
            fail(f"project actors: {project['actors']}")
        r = run(cli, "info", os.path.join(out, "demo.animorph"))
        if r.returncode != 0 or "creature.glb" not in r.stdout or "24 fps" not in r.stdout:
            fail(f"human project summary: {r.stdout}")
        # The committed demo must be what the generator writes today.
        for name, fresh in (("creature.glb", creature), ("gear.glb", gear)):
            committed = info_json(cli, os.path.join(resources, name))
            for key in ("vertices", "triangles", "joints", "animations"):
                if committed[key] != fresh[key]:
                    fail(f"resources/demo/{name} is stale ({key}: {committed[key]} vs {fresh[key]}); "
                         "run animorph-cli make-demo resources/demo")
        committed = info_json(cli, os.path.join(resources, "demo.animorph"))
        if not all(a["loads"] for a in committed["actors"]):
            fail(f"resources/demo/demo.animorph has actors that do not load: {committed['actors']}")
        # A missing directory argument is a usage error.
        if run(cli, "make-demo").returncode == 0:
            fail("make-demo without DIR succeeded")


def main():
    if len(sys.argv) < 3:
        fail(__doc__)
    mode, cli, args = sys.argv[1], sys.argv[2], sys.argv[3:]
    {"info-json": mode_info_json, "info-bad": mode_info_bad, "make-demo": mode_make_demo}[mode](cli, *args)
    print("ok")


if __name__ == "__main__":
    main()
