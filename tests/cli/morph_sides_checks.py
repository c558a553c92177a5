"""animorph-cli new with a BlobTree on either side (a BlobTree scene, an actor of
another project), then bake: exit 0, every frame written, the continuity
report printed; the glTF -> BlobTree morph has no expansion (C = D), the
BlobTree -> glTF morph no collapse (A = B); bad sides fail naming the path.

usage: morph_sides_checks.py CLI DEMO_DIR"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

cli, demo = sys.argv[1], sys.argv[2]
work = tempfile.mkdtemp(prefix="animorph-cli-morph-sides-")
for f in ("creature.glb", "gear.glb", "demo.animorph", "blob_creature.json"):
    shutil.copy(os.path.join(demo, f), work)


def run(*args, code=0):
    r = subprocess.run([cli, *args], cwd=work, capture_output=True, text=True, timeout=300)
    if r.returncode != code:
        sys.exit(f"FAIL: {' '.join(args)}: exit {r.returncode}, wanted {code}\n{r.stdout}\n{r.stderr}")
    return r.stdout + r.stderr


def markers(project):
    with open(os.path.join(work, project)) as f:
        p = json.load(f)
    return p["morph"], {a["id"]: a for a in p["actors"]}


out = run("new", "creature.glb", "blob_creature.json", "-o", "c2b.animorph")
m, actors = markers("c2b.animorph")
k = m["markers"]
assert actors["blob_creature"]["kind"] == "blobtree", actors["blob_creature"].get("kind")
assert k["A"] < k["B"] < k["C"] == k["D"], f"glTF -> BlobTree: C = D ({k})"
assert any(a["id"] == "creature" and a["standin"]["segments"] for a in m["actors"]), "the creature's stand-in"
print("ok: new glTF -> BlobTree scene:", out.strip().splitlines()[-1])

out = run("bake", "c2b.animorph", "--frames", "0:100", "--res", "24", "-o", "c2b")
assert "baked frames 0..100" in out, out
assert "continuity:" in out, out
assert len([f for f in os.listdir(os.path.join(work, "c2b")) if f.endswith(".ply")]) == 101
print("ok: bake glTF -> BlobTree:", [l for l in out.splitlines() if l.startswith("continuity")][0])

out = run("new", "c2b.animorph:blob_creature", "demo.animorph:gear", "-o", "b2g.animorph")
m, actors = markers("b2g.animorph")
k = m["markers"]
assert k["A"] == k["B"] < k["C"] < k["D"], f"BlobTree -> glTF: A = B ({k})"
assert actors["gear"]["asset"] == "gear.glb", actors["gear"]
out = run("bake", "b2g.animorph", "--frames", "0:120", "--res", "24", "-o", "b2g")
assert "0 collapse" in out and "continuity:" in out, out
print("ok: new and bake BlobTree -> glTF (project actors):", out.strip().splitlines()[0])

out = run("new", "missing.json", "creature.glb", "-o", "x.animorph", code=1)
assert "missing.json" in out, out
out = run("new", "demo.animorph:nobody", "creature.glb", "-o", "x.animorph", code=1)
assert "no actor with id 'nobody'" in out, out
print("ok: bad sides fail naming the path and the actor")
shutil.rmtree(work)
