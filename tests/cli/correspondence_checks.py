"""Skeleton correspondence from the command line: `new` with two glTF
characters picks it; `correspond` prints the chain matching (text and JSON);
`bake --method` compares it with interpolation through B..C: no empty frame,
the largest frame-to-frame volume change under a stated bound and smaller than
interpolation's (both printed), on the demo pair; the committed demo uses it and
bakes through C without a volume jump; a bad --method fails naming the value.
With SHARED_ASSETS_DIR, only the comparison on the shared tentacle.glb ->
plate.glb (exit 77: skipped when they are not there).

usage: correspondence_checks.py CLI DEMO_DIR [SHARED_ASSETS_DIR]"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

cli, demo = sys.argv[1], sys.argv[2]
assets = sys.argv[3] if len(sys.argv) > 3 else None
work = tempfile.mkdtemp(prefix="animorph-cli-correspondence-")
for f in ("creature.glb", "gear.glb"):
    shutil.copy(os.path.join(demo, f), work)
BOUND = 0.12  # largest frame-to-frame volume change through B..C (measured 6.2 % and 7.9 % at 32^3)


def run(*args, code=0):
    r = subprocess.run([cli, *args], cwd=work, capture_output=True, text=True, timeout=300)
    if r.returncode != code:
        sys.exit(f"FAIL: {' '.join(args)}: exit {r.returncode}, wanted {code}\n{r.stdout}\n{r.stderr}")
    return r.stdout + r.stderr


def within_bc(project, method):
    out = run("bake", project, "--frames", "47:85", "--res", "32", "--format", "none", "--gltf",
              f"{method}.glb", "--method", method)
    assert not re.search(r"frame \d+: empty", out), out
    m = re.search(r"continuity: (\w+), largest .* within B\.\.C ([0-9.]+)% at frame (\d+)", out)
    assert m and m.group(1) == method, out
    return float(m.group(2)) / 100.0, int(m.group(3))


def compare(label, project):
    (ci, fi), (cc, fc) = within_bc(project, "interpolation"), within_bc(project, "skeleton_correspondence")
    print(f"{label}: largest volume change through B..C at 32^3: interpolation {100 * ci:.1f}% (frame {fi}), "
          f"skeleton correspondence {100 * cc:.1f}% (frame {fc}), bound {100 * BOUND:.0f}%")
    assert cc < BOUND, f"{label}: {cc} over {BOUND}"
    assert cc < ci, f"{label}: correspondence {cc} not below interpolation {ci}"


if assets is not None:
    tentacle, plate = os.path.join(assets, "tentacle.glb"), os.path.join(assets, "plate.glb")
    if not (os.path.exists(tentacle) and os.path.exists(plate)):
        shutil.rmtree(work, ignore_errors=True)
        print(f"SKIP: {assets} has no tentacle.glb / plate.glb (shared assets)")
        sys.exit(77)
    run("new", tentacle, plate, "-o", "tp.animorph")
    compare("tentacle -> plate", "tp.animorph")
    shutil.rmtree(work, ignore_errors=True)
    sys.exit(0)

out = run("new", "creature.glb", "gear.glb", "-o", "cg.animorph")
with open(os.path.join(work, "cg.animorph")) as f:
    assert json.load(f)["morph"]["method"] == "skeleton_correspondence", "the default with two rigs"
assert out.strip().endswith("skeleton_correspondence"), out

out = run("correspond", "cg.animorph")
assert "source chains:" in out and "target chains:" in out and "<->" in out, out
assert "shrinks into" in out, out  # the creature's limbs have no partner on the gear
j = json.loads(run("correspond", "cg.animorph", "--json"))
src, dst = j["source_chains"], j["target_chains"]
assert len(src) > len(dst) >= 1, (len(src), len(dst))
assert all(c["match"] >= 0 or c["anchor_chain"] >= 0 for c in src), src
assert sum(c["match"] >= 0 for c in src) == j["matched"] >= 1, j["matched"]
print(f"ok: correspond: {len(src)} source chains, {len(dst)} target chains, {j['matched']} matched")

compare("creature -> gear", "cg.animorph")

# The committed demo uses the method, and its seam at C no longer pops: the stand-in core
# joins the expansion to the morph (no frame around C changes volume by more than 20 %).
with open(os.path.join(demo, "demo.animorph")) as f:
    committed = json.load(f)["morph"]
assert committed["method"] == "skeleton_correspondence", committed["method"]
shutil.copy(os.path.join(demo, "demo.animorph"), work)
c = committed["markers"]["C"]
out = run("bake", "demo.animorph", "--frames", f"{c - 2}:{c + 6}", "--res", "32", "--format", "none", "--gltf", "seam.glb")
assert "continuity: 0 frames empty or changing volume by more than 20%" in out, out
print("ok: the demo uses skeleton correspondence; frames C-2..C+6:",
      [l for l in out.splitlines() if l.startswith("continuity: skeleton")][0])
out = run("bake", "cg.animorph", "--frames", "0:1", "--res", "8", "-o", "x", "--method", "blend", code=2)
assert "'blend'" in out, out
out = run("new", "creature.glb", "gear.glb", "-o", "y.animorph", "--correspondence-blend", "skeleton_correspondence",
          code=2)
assert "--correspondence-blend" in out, out
out = run("new", "creature.glb", "gear.glb", "-o", "st.animorph", "--correspondence-blend", "space_time")
with open(os.path.join(work, "st.animorph")) as f:
    assert json.load(f)["morph"]["correspondence_blend"] == "space_time"
print("ok: bad method values fail naming them; --correspondence-blend is saved")
shutil.rmtree(work, ignore_errors=True)
