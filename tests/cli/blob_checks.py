#!/usr/bin/env python3
"""End-to-end checks of animorph-cli on BlobTree projects.

usage: blob_checks.py CLI RESOURCES_DIR
  make-blob-demo writes the scene and the project, identical to the committed
  resources/demo files; info shows the BlobTree actor's node counts;
  polygonize works on the project (--actor, world space, errors naming the
  actor) and still on a scene file."""
import json
import os
import subprocess
import sys
import tempfile


def run(cli, *args):
    return subprocess.run([cli, *args], capture_output=True, text=True, timeout=300)


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def obj_vertices(path):
    with open(path) as f:
        return [tuple(map(float, line.split()[1:4])) for line in f if line.startswith("v ")]


def main():
    cli, resources = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as tmp:
        r = run(cli, "make-blob-demo", tmp)
        if r.returncode != 0:
            fail(f"make-blob-demo exited {r.returncode}: {r.stderr}")
        for name in ("blob_creature.json", "blob_demo.animorph"):
            with open(os.path.join(tmp, name), "rb") as a, open(os.path.join(resources, name), "rb") as b:
                if a.read() != b.read():
                    fail(f"resources/demo/{name} is stale; run animorph-cli make-blob-demo resources/demo")
        project = os.path.join(tmp, "blob_demo.animorph")

        r = run(cli, "info", project, "--json")
        if r.returncode != 0:
            fail(f"info exited {r.returncode}: {r.stderr}")
        info = json.loads(r.stdout)
        actor = info["actors"][0]
        if actor.get("kind") != "blobtree" or actor["nodes"] != 30 or actor["primitives"] < 10 or actor["maps"] < 5:
            fail(f"info of the BlobTree actor: {actor}")
        if abs(actor["animation_end"] - 2.0) > 1e-9:
            fail(f"animation end {actor['animation_end']}")
        r = run(cli, "info", project)
        if "BlobTree: 30 nodes" not in r.stdout:
            fail(f"human summary: {r.stdout}")

        # The project's actor, moved: the mesh comes out in world space.
        with open(project) as f:
            p = json.load(f)
        p["actors"][0]["translation"] = [5.0, 0.0, 0.0]
        moved = os.path.join(tmp, "moved.animorph")
        with open(moved, "w") as f:
            json.dump(p, f)
        out_a = os.path.join(tmp, "a.obj")
        out_b = os.path.join(tmp, "b.obj")
        r = run(cli, "polygonize", project, "--actor", "creature", "--time", "0.5", "--res", "40", "-o", out_a)
        if r.returncode != 0 or "actor 'creature'" not in r.stdout:
            fail(f"polygonize --actor: {r.returncode} {r.stdout} {r.stderr}")
        r = run(cli, "polygonize", moved, "--time", "0.5", "--res", "40", "-o", out_b)
        if r.returncode != 0:
            fail(f"polygonize (the only BlobTree actor): {r.stderr}")
        va, vb = obj_vertices(out_a), obj_vertices(out_b)
        if not va or len(va) != len(vb):
            fail(f"vertex counts {len(va)} / {len(vb)}")
        dx = sum(b[0] - a[0] for a, b in zip(va, vb)) / len(va)
        if abs(dx - 5.0) > 1e-3:
            fail(f"the actor's translation is not applied (mean shift {dx})")
        r = run(cli, "polygonize", project, "--actor", "nobody", "-o", out_a)
        if r.returncode == 0 or "no actor 'nobody'" not in r.stderr:
            fail(f"unknown actor: {r.returncode} {r.stderr}")
        # A scene file still works, and --actor on it is a usage error.
        scene = os.path.join(tmp, "blob_creature.json")
        r = run(cli, "polygonize", scene, "--res", "24", "-o", out_a)
        if r.returncode != 0:
            fail(f"polygonize scene: {r.stderr}")
        if run(cli, "polygonize", scene, "--actor", "x", "-o", out_a).returncode != 2:
            fail("--actor on a scene file is not a usage error")
    print("ok")


if __name__ == "__main__":
    main()
