"""The continuity ratio of a morph from the command line (docs/morph.md, "Continuity"):
`bake` prints the largest frame-to-frame jump of the visible surface over A..D divided by
the characters' own largest per-frame motion; this holds it at 2 or less (no pop) on one
pair, printing the figure. By default a collapse or expansion frame is written as its
visible surface; --keep-inner-shell keeps the stand-in core as a second shell (said so).

usage: continuity_checks.py demo CLI DEMO_DIR
       continuity_checks.py tentacle-plate CLI SHARED_ASSETS_DIR
       continuity_checks.py exported CLI CHARACTER_SCRIPT
Exit 77 (skipped) when the pair's files or tools are missing."""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

BOUND = 2.0
RES = "32"  # the property holds at 32^3 (cells of 3-5 cm on these pairs), and CI runs on 2 cores


def fail(msg):
    sys.exit("FAIL: " + msg)


def skip(msg):
    print("SKIP: " + msg)
    sys.exit(77)


def run(cli, work, *args):
    r = subprocess.run([cli, *args], cwd=work, capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        fail(f"{' '.join(args)}: exit {r.returncode}\n{r.stdout}\n{r.stderr}")
    return r.stdout + r.stderr


def markers(cli, work, project):
    return json.loads(run(cli, work, "info", "--json", project))["markers"]


def ratio_of(cli, work, label, project, *extra):
    """Bakes A..D at RES, returns (ratio, the report line, the bake's output)."""
    m = markers(cli, work, project)
    out = run(cli, work, "bake", project, "--frames", f"{m['A']}:{m['D']}", "--res", RES, "--format", "none",
              "--gltf", "x.glb", "--jobs", "2", *extra)
    line = next((l for l in out.splitlines() if l.startswith("continuity ratio")), None)
    if not line:
        fail(f"{label}: bake printed no continuity ratio\n{out}")
    g = re.search(r": ([0-9.]+|inf)x: ([0-9.]+) m at frame (\d+) / own motion ([0-9.]+) m", line)
    if not g:
        fail(f"{label}: cannot read the ratio in: {line}")
    if "(A..D)" not in line:
        fail(f"{label}: the ratio is not over A..D: {line}")
    return float(g.group(1)), line, out


def hold(cli, work, label, project):
    r, line, _ = ratio_of(cli, work, label, project)
    print(f"{label} at {RES}^3: {line}")
    if not r <= BOUND:
        fail(f"{label}: continuity ratio {r} over {BOUND}")
    print(f"ok: {label}: continuity ratio {r:.2f} <= {BOUND}")


def mode_demo(cli, demo):
    work = tempfile.mkdtemp(prefix="animorph-continuity-")
    for f in ("creature.glb", "gear.glb", "demo.animorph"):
        shutil.copy(os.path.join(demo, f), work)
    hold(cli, work, "creature -> gear (the demo)", "demo.animorph")
    # The exported frames are what is seen: the first expansion frame as a PLY, with the stand-in
    # core cut away by default (fewer triangles, said so), both shells with --keep-inner-shell.
    c = markers(cli, work, "demo.animorph")["C"]
    counts = {}
    for mode, extra in (("visible", []), ("kept", ["--keep-inner-shell"])):
        out = run(cli, work, "bake", "demo.animorph", "--frames", f"{c + 1}:{c + 1}", "--res", RES, "-o", mode, *extra)
        note = "carry the stand-in core as a second closed shell" if extra else "written as their visible surface"
        if note not in out:
            fail(f"bake {' '.join(extra)}: no note '{note}'\n{out}")
        with open(os.path.join(work, mode, f"demo_{c + 1:04d}.ply"), "rb") as f:
            head = f.read(400).decode("latin-1")
        counts[mode] = int(re.search(r"element face (\d+)", head).group(1))
    if not counts["visible"] < counts["kept"]:
        fail(f"frame C+1: the visible surface has {counts['visible']} triangles, both shells {counts['kept']}")
    print(f"ok: frame C+1 written as its visible surface ({counts['visible']} triangles; both shells {counts['kept']})")
    shutil.rmtree(work, ignore_errors=True)


def mode_tentacle_plate(cli, assets):
    tentacle, plate = os.path.join(assets, "tentacle.glb"), os.path.join(assets, "plate.glb")
    if not (os.path.exists(tentacle) and os.path.exists(plate)):
        skip(f"{assets} has no tentacle.glb / plate.glb")
    work = tempfile.mkdtemp(prefix="animorph-continuity-")
    run(cli, work, "new", tentacle, plate, "-o", "tp.animorph")
    hold(cli, work, "tentacle -> plate", "tp.animorph")
    shutil.rmtree(work, ignore_errors=True)


def mode_exported(cli, script):
    if not os.path.exists(script):
        skip(f"{script} is not in this checkout: no characters made by a real exporter")
    if not shutil.which("blender"):
        skip("blender is not installed: no characters made by a real exporter")
    work = tempfile.mkdtemp(prefix="animorph-continuity-")
    r = subprocess.run([sys.executable, script, work], capture_output=True, text=True, timeout=600)
    if r.returncode == 77:
        skip(f"{script}: {r.stdout.strip()} {r.stderr.strip()}")
    if r.returncode != 0:
        fail(f"{script}: exit {r.returncode}\n{r.stdout}\n{r.stderr}")
    glbs = sorted(f for f in os.listdir(work) if f.endswith(".glb"))
    if len(glbs) < 2:
        fail(f"{script} made {glbs}: two characters needed")
    a, b = glbs[0], glbs[1]
    run(cli, work, "new", a, b, "-o", "ex.animorph")
    hold(cli, work, f"{a} -> {b} (exported by Blender)", "ex.animorph")
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    mode, cli, where = sys.argv[1], sys.argv[2], sys.argv[3]
    {"demo": mode_demo, "tentacle-plate": mode_tentacle_plate, "exported": mode_exported}[mode](cli, where)
