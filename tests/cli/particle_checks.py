#!/usr/bin/env python3
"""End-to-end checks of animorph-cli's particle commands.

usage: particle_checks.py CLI RESOURCES_DIR
  make-statue-demo writes resources/demo/statue.animorph byte for byte;
  simulate --convert --animorphosis turns the blob demo's creature into
  particles, adds the gathering actor and the identity-linked animorphosis;
  simulate again with a seed is repeatable; bad input fails naming the actor
  and the reason, writing nothing."""
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
    with tempfile.TemporaryDirectory() as tmp:
        r = run(cli, "make-statue-demo", tmp)
        if r.returncode != 0:
            fail(f"make-statue-demo exited {r.returncode}: {r.stderr}")
        with open(os.path.join(tmp, "statue.animorph"), "rb") as a, \
                open(os.path.join(resources, "statue.animorph"), "rb") as b:
            if a.read() != b.read():
                fail("resources/demo/statue.animorph is stale; run animorph-cli make-statue-demo resources/demo")
        src = os.path.join(resources, "blob_demo.animorph")
        out = os.path.join(tmp, "p.animorph")
        r = run(cli, "simulate", src, "--actor", "creature", "--convert", "600", "--animorphosis",
                "--duration", "1", "-o", out)
        if r.returncode != 0:
            fail(f"simulate --animorphosis exited {r.returncode}: {r.stderr}")
        p = json.load(open(out))
        ids = [a["id"] for a in p["actors"]]
        if len(ids) != 2:
            fail(f"expected the creature and its gathering copy, got {ids}")
        links = p["animorphosis"]["links"] if "links" in p["animorphosis"] else p["animorphosis"]["graph"]["links"]
        points = len(p["actors"][0]["blobtree"]["root"]["children"])
        if not 570 <= points <= 630 or len(links) != points:
            fail(f"{points} particles, {len(links)} links (expected about 600, one link each)")
        outs = []
        for k in range(2):
            o2 = os.path.join(tmp, f"s{k}.animorph")
            r = run(cli, "simulate", out, "--actor", ids[0], "--seed", "5", "--noise", "2", "--duration", "1",
                    "-o", o2)
            if r.returncode != 0 or "simulated" not in r.stdout:
                fail(f"simulate exited {r.returncode}: {r.stdout} {r.stderr}")
            outs.append(open(o2, "rb").read())
        if outs[0] != outs[1]:
            fail("the same seed gave different projects")
        bad = os.path.join(tmp, "bad.animorph")
        r = run(cli, "simulate", out, "--actor", "nobody", "-o", bad)
        if r.returncode == 0 or "nobody" not in r.stderr or os.path.exists(bad):
            fail(f"an unknown actor: exit {r.returncode}, {r.stderr!r}")
        r = run(cli, "simulate", out, "--actor", ids[0], "--restitution", "3", "-o", bad)
        if r.returncode == 0 or "restitution" not in r.stderr or os.path.exists(bad):
            fail(f"restitution 3: exit {r.returncode}, {r.stderr!r}")
    print("ok")


if __name__ == "__main__":
    main()
