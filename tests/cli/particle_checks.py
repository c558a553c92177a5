#!/usr/bin/env python3
"""End-to-end checks of animorph-cli's particle commands.

usage: particle_checks.py CLI RESOURCES_DIR
  make-statue-demo writes resources/demo/statue.animorph byte for byte;
  simulate --convert --animorphosis --reform-into gathers a ball of particles into another ball;
  simulate --convert --animorphosis turns the blob demo's creature into
  particles, adds the gathering actor and the identity-linked animorphosis;
  simulate again with a seed is repeatable; a character's mesh and stand-in
  convert into a new particle actor; bad input fails naming the actor
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
        # Re-forming into another actor's shape: a ball of particles gathers into a second ball 3 m away.
        def ball(aid, centre, radius):
            return {"id": aid, "name": aid, "kind": "blobtree", "blobtree": {"threshold": 0.5, "root": {
                "id": 1, "name": "ball", "type": "point",
                "params": {"center": centre, "radius": radius, "intensity": 1.0, "stiffness": 2.0}}}}
        two = os.path.join(tmp, "two.animorph")
        json.dump({"format": "animorph", "version": 1, "name": "two balls",
                   "actors": [ball("a", [0, 0.6, 0], 0.5), ball("b", [3, 0.6, 0], 0.7)]}, open(two, "w"))
        reformed = os.path.join(tmp, "reformed.animorph")
        r = run(cli, "simulate", two, "--actor", "a", "--convert", "300", "--animorphosis", "--reform-into", "b",
                "--duration", "1", "-o", reformed)
        if r.returncode != 0 or "re-forms into 'b'" not in r.stdout:
            fail(f"simulate --reform-into exited {r.returncode}: {r.stdout} {r.stderr}")
        p = json.load(open(reformed))
        gathering = next(a for a in p["actors"] if a["id"] == p["animorphosis"]["target"])
        ends = []
        for n in gathering["blobtree"]["root"]["children"]:
            keys = n["params"]["center"]["keys"]
            ends.append(max(keys, key=lambda k: k["t"])["v"])
        # b's visible radius with threshold 0.5, stiffness 2: 0.7 * sqrt(1 - 0.5^(1/2)) = 0.38 m.
        far = max(((e[0] - 3) ** 2 + (e[1] - 0.6) ** 2 + e[2] ** 2) ** 0.5 for e in ends)
        if len(ends) < 250 or far > 0.4:
            fail(f"{len(ends)} particles gather into b, the farthest {far:.3f} m from its centre (expected <= 0.4)")
        r = run(cli, "simulate", two, "--actor", "a", "--reform-into", "b", "-o", os.path.join(tmp, "bad.animorph"))
        if r.returncode == 0 or "--animorphosis" not in r.stderr:
            fail(f"--reform-into without --animorphosis: exit {r.returncode}, {r.stderr!r}")
        # A character: its posed mesh, then its stand-in, fill a new particle actor; the character stays.
        demo = os.path.join(resources, "demo.animorph")
        before = json.load(open(demo))
        for source in ("mesh", "standin"):
            conv = os.path.join(tmp, f"{source}.animorph")
            r = run(cli, "simulate", demo, "--actor", "creature", "--convert", "500", "--from", source,
                    "--duration", "0.5", "-o", conv)
            if r.returncode != 0 or ("boundary edges" in r.stdout) != (source == "mesh"):
                fail(f"simulate --from {source} exited {r.returncode}: {r.stdout} {r.stderr}")
            p = json.load(open(conv))
            if p["actors"][:2] != before["actors"] or len(p["actors"]) != 3:
                fail(f"--from {source}: expected the two characters unchanged and one new actor")
            made = p["actors"][2]
            points = len(made["blobtree"]["root"]["children"])
            if made.get("kind") != "blobtree" or not 500 <= points <= 505:
                fail(f"--from {source}: {points} particles in {made['id']} (expected 500..505)")
        bad = os.path.join(tmp, "bad.animorph")
        r = run(cli, "simulate", demo, "--actor", "creature", "--convert", "500", "--from", "skin", "-o", bad)
        if r.returncode == 0 or "--from" not in r.stderr or os.path.exists(bad):
            fail(f"--from skin: exit {r.returncode}, {r.stderr!r}")
        r = run(cli, "simulate", demo, "--actor", "creature", "-o", bad)
        if r.returncode == 0 or "--convert" not in r.stderr or os.path.exists(bad):
            fail(f"a character without --convert: exit {r.returncode}, {r.stderr!r}")
        r = run(cli, "simulate", out, "--actor", "nobody", "-o", bad)
        if r.returncode == 0 or "nobody" not in r.stderr or os.path.exists(bad):
            fail(f"an unknown actor: exit {r.returncode}, {r.stderr!r}")
        r = run(cli, "simulate", out, "--actor", ids[0], "--restitution", "3", "-o", bad)
        if r.returncode == 0 or "restitution" not in r.stderr or os.path.exists(bad):
            fail(f"restitution 3: exit {r.returncode}, {r.stderr!r}")
    print("ok")


if __name__ == "__main__":
    main()
