#!/usr/bin/env python3
"""End-to-end checks of animorph-cli on animorphosis projects.

usage: animorph_checks.py CLI RESOURCES_DIR
  animorph makes a project from two BlobTree scenes (--auto proposes the graph),
  correspond prints it (text and --json), bake-keys writes a key-frame BlobTree
  scene that polygonize reads; bake writes frames, the same for any --jobs, and by
  default on one grid with temporal coherence; bad inputs fail naming the file and the reason."""
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


def main():
    cli, resources = sys.argv[1], sys.argv[2]
    creature = os.path.join(resources, "blob_creature.json")
    with tempfile.TemporaryDirectory() as tmp:
        project = os.path.join(tmp, "self.animorph")
        r = run(cli, "animorph", creature, creature, "-o", project, "--auto", "--start", "12", "--end", "36")
        if r.returncode != 0:
            fail(f"animorph exited {r.returncode}: {r.stderr}")
        if "links (automatic)" not in r.stdout:
            fail(f"animorph output: {r.stdout}")

        r = run(cli, "correspond", project, "--json")
        if r.returncode != 0:
            fail(f"correspond --json exited {r.returncode}: {r.stderr}")
        graph = json.loads(r.stdout)
        links = graph["links"]
        # A creature against itself: every node but the root links to itself.
        if len(links) != 29 or any(l["a"] != l["b"] for l in links):
            fail(f"auto-map of a creature onto itself: {links}")
        if any(l["artist"] or not 0.0 <= l["confidence"] <= 1.0 for l in links):
            fail(f"link flags: {links}")
        if graph["generic_tree"].get("nodes") != 30 or abs(graph["start"] - 0.5) > 1e-12:
            fail(f"generic tree / interval: {graph}")

        r = run(cli, "correspond", project)
        if r.returncode != 0 or "confidence" not in r.stdout or "generic tree: 30 nodes" not in r.stdout:
            fail(f"correspond text: {r.returncode} {r.stdout} {r.stderr}")

        baked = os.path.join(tmp, "baked.json")
        r = run(cli, "bake-keys", project, "-o", baked)
        if r.returncode != 0:
            fail(f"bake-keys exited {r.returncode}: {r.stderr}")
        if "keys" not in r.stdout or "largest deviation" not in r.stdout:
            fail(f"bake-keys output: {r.stdout}")
        with open(baked) as f:
            scene = json.load(f)
        if scene.get("format") != "animorph-blobtree":
            fail(f"baked scene format: {scene.get('format')}")
        mesh = os.path.join(tmp, "mid.obj")
        r = run(cli, "polygonize", baked, "--time", "1.0", "--res", "32", "-o", mesh)
        if r.returncode != 0 or not os.path.getsize(mesh):
            fail(f"polygonize of the baked tree: {r.returncode} {r.stderr}")

        # polygonize --animorphosis: C(t) of the project; before the interval it is the source.
        before, during = os.path.join(tmp, "before.obj"), os.path.join(tmp, "during.obj")
        source_mesh = os.path.join(tmp, "source.obj")
        for t, out in (("0.25", before), ("1.0", during)):
            r = run(cli, "polygonize", project, "--animorphosis", "--time", t, "--res", "32", "-o", out)
            if r.returncode != 0 or "animorphosis" not in r.stdout:
                fail(f"polygonize --animorphosis at {t}: {r.returncode} {r.stdout} {r.stderr}")
        r = run(cli, "polygonize", creature, "--time", "0.25", "--res", "32", "-o", source_mesh)
        if r.returncode != 0:
            fail(f"polygonize of the source: {r.stderr}")
        with open(before) as a, open(source_mesh) as b:
            if [l for l in a if l.startswith("v ")] != [l for l in b if l.startswith("v ")]:
                fail("before the interval the animorphosis is not the source")
        r = run(cli, "polygonize", creature, "--animorphosis", "--res", "32", "-o", before)
        if r.returncode != 2 or "project" not in r.stderr:
            fail(f"--animorphosis on a scene file: {r.returncode} {r.stderr}")

        # bake: the animorphosis frame by frame, the same for any --jobs (each frame on its own grid).
        outs = []
        for jobs in ("1", "2"):
            out = os.path.join(tmp, "frames" + jobs)
            r = run(cli, "bake", project, "--frames", "10:14", "--res", "24", "-o", out, "--jobs", jobs,
                    "--coherence", "0")
            if r.returncode != 0 or "baked the animorphosis" not in r.stdout:
                fail(f"bake --jobs {jobs}: {r.returncode} {r.stdout} {r.stderr}")
            outs.append(out)
        for f in range(10, 15):
            # NAME_####.ply, NAME the project's name (bake --name changes it)
            names = [n for n in os.listdir(outs[0]) if n.endswith(f"_{f:04d}.ply")]
            if len(names) != 1:
                fail(f"bake wrote {names} for frame {f}, expected one NAME_{f:04d}.ply")
            name = names[0]
            with open(os.path.join(outs[0], name), "rb") as a, open(os.path.join(outs[1], name), "rb") as b:
                if a.read() != b.read():
                    fail(f"bake {name} differs between --jobs 1 and 2")

        # By default the frames share one grid with temporal coherence, and the bake says what it reused.
        out = os.path.join(tmp, "coherent")
        r = run(cli, "bake", project, "--frames", "10:14", "--res", "24", "-o", out)
        if r.returncode != 0 or "temporal coherence (0.10 cell)" not in r.stdout or "blocks reused" not in r.stdout:
            fail(f"bake with coherence: {r.returncode} {r.stdout} {r.stderr}")
        if len([n for n in os.listdir(out) if n.endswith(".ply")]) != 5:
            fail(f"bake with coherence wrote {sorted(os.listdir(out))}, expected 5 frames")
        r = run(cli, "bake", project, "--frames", "10:14", "--res", "24", "-o", out, "--coherence", "2")
        if r.returncode != 2 or "--coherence" not in r.stderr:
            fail(f"bake --coherence 2: {r.returncode} {r.stderr}")

        # Errors name the file and the reason.
        r = run(cli, "correspond", os.path.join(resources, "blob_demo.animorph"))
        if r.returncode == 0 or "blob_demo.animorph" not in r.stderr or "animorphosis" not in r.stderr:
            fail(f"correspond without an animorphosis: {r.returncode} {r.stderr}")
        r = run(cli, "animorph", creature, os.path.join(tmp, "missing.json"), "-o", project)
        if r.returncode == 0 or "missing.json" not in r.stderr:
            fail(f"animorph with a missing target: {r.returncode} {r.stderr}")
        r = run(cli, "animorph", creature, creature, "-o", project, "--start", "30", "--end", "10")
        if r.returncode == 0 or "--end" not in r.stderr:
            fail(f"animorph with end before start: {r.returncode} {r.stderr}")
    print("ok")


if __name__ == "__main__":
    main()
