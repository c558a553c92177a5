#!/usr/bin/env python3
"""End-to-end checks of animorph-cli on the dinosaur -> dragon demo.

usage: animorph_demo_checks.py CLI RESOURCES_DIR
  make-animorphosis-demo writes the committed project again, byte for byte, and
  with --scenes the two creatures, which animorph reads;
  bake of the committed project writes a few PLY frames across the interval;
  correspond lists the artist's graph with its s overrides."""
import filecmp
import json
import os
import sys
import tempfile

from animorph_checks import fail, run


def ply_faces(path):
    with open(path, "rb") as f:
        header = f.read(4096).split(b"end_header")[0].decode("ascii", "replace")
    for line in header.splitlines():
        if line.startswith("element face"):
            return int(line.split()[2])
    return 0


def main():
    cli, resources = sys.argv[1], sys.argv[2]
    project = os.path.join(resources, "animorphosis.animorph")
    with tempfile.TemporaryDirectory() as tmp:
        made = os.path.join(tmp, "made")
        r = run(cli, "make-animorphosis-demo", made, "--scenes")
        if r.returncode != 0 or "generic tree of" not in r.stdout:
            fail(f"make-animorphosis-demo: {r.returncode} {r.stdout} {r.stderr}")
        if not filecmp.cmp(os.path.join(made, "animorphosis.animorph"), project, shallow=False):
            fail("the committed project differs from what make-animorphosis-demo writes")
        # The scenes make the same project through `animorph`.
        remade = os.path.join(tmp, "remade.animorph")
        r = run(cli, "animorph", os.path.join(made, "dinosaur.json"), os.path.join(made, "dragon.json"), "-o", remade)
        if r.returncode != 0:
            fail(f"animorph of the demo scenes: {r.returncode} {r.stderr}")

        out = os.path.join(tmp, "frames")
        # Frames 47..49 straddle the start of the interval (frame 48 = 2 s), 96 is its middle.
        for frames in ("47:49", "96:96"):
            r = run(cli, "bake", project, "--frames", frames, "--res", "32", "-o", out, "--name", "frame")
            if r.returncode != 0 or "baked the animorphosis" not in r.stdout:
                fail(f"bake --frames {frames}: {r.returncode} {r.stdout} {r.stderr}")
        for f in (47, 48, 49, 96):
            path = os.path.join(out, f"frame_{f:04d}.ply")
            if not os.path.exists(path):
                fail(f"bake did not write {path}")
            if ply_faces(path) < 500:
                fail(f"{path}: only {ply_faces(path)} faces")

        r = run(cli, "correspond", project, "--json")
        if r.returncode != 0:
            fail(f"correspond --json: {r.returncode} {r.stderr}")
        links = json.loads(r.stdout)["links"]
        if len(links) < 1000:
            fail(f"correspond: {len(links)} links")
    print("ok")


if __name__ == "__main__":
    main()
