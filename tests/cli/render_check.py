#!/usr/bin/env python3
"""animorph-cli render end to end: offscreen, with no X server (DISPLAY removed).

usage: render_check.py CLI DEMO_DIR
Renders the demo project at two frames and checks the pictures: the right size, the
characters visible (many pixels differ from the background), the two frames different
(the walk moves), zero validation errors (ANIMORPH_VALIDATION=1 makes them fail the
command). The BlobTree demo and the animorphosis demo show their BlobTrees (the picture differs
from the same scene with the actors hidden). A malformed project fails with its name on stderr."""
import os
import shutil
import subprocess
import sys
import tempfile

cli, demo = sys.argv[1], sys.argv[2]
env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
env["ANIMORPH_VALIDATION"] = "1"
env.setdefault("VK_ICD_FILENAMES", "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json")
work = tempfile.mkdtemp(prefix="animorph-render-")


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def render(frame, out, project=os.path.join(demo, "demo.animorph")):
    r = subprocess.run([cli, "render", project, "--frame", str(frame), "--size",
                        "320x180", "-o", out], capture_output=True, text=True, env=env, timeout=120)
    if r.returncode != 0:
        fail(f"render --frame {frame} exited {r.returncode}: {r.stderr}")
    print(r.stdout.strip())



a, b = os.path.join(work, "a.png"), os.path.join(work, "b.png")
render(0, a)
render(6, b)
size = subprocess.run(["identify", "-format", "%wx%h", a], capture_output=True, text=True).stdout
if size != "320x180":
    fail(f"picture is {size}, expected 320x180")
# The viewport background is one flat colour: count the pixels that are not it.
bg = subprocess.run(["convert", a, "-crop", "1x1+2+2", "-depth", "8", "-format", "%[hex:p{0,0}]", "info:"],
                    capture_output=True, text=True).stdout.strip()
fg = subprocess.run(["convert", a, "-fuzz", "4%", "-fill", "black", "-opaque", f"#{bg}", "-fill", "white",
                     "+opaque", "black", "-format", "%[fx:mean*w*h]", "info:"], capture_output=True, text=True).stdout
if float(fg or 0) < 0.05 * 320 * 180:
    fail(f"only {fg} pixels differ from the background #{bg}: the characters are not visible")
diff = subprocess.run(["compare", "-metric", "AE", "-fuzz", "3%", a, b, "null:"], capture_output=True, text=True)
changed = int(float(diff.stderr.split()[0]))
if changed < 100:
    fail(f"frames 0 and 6 differ in only {changed} pixels: the animation does not play")
print(f"ok: {float(fg):.0f} foreground pixels, {changed} pixels changed between frames")

# BlobTree actors and an animorphosis' C(t) are drawn: each picture differs from the same project
# with its actors hidden.
import json  # noqa: E402
for name, frame in (("blob_demo.animorph", 12), ("animorphosis.animorph", 96)):
    with open(os.path.join(demo, name)) as f:
        p = json.load(f)
    for a in p["actors"]:
        a["visible"] = False
    hidden = os.path.join(work, "hidden_" + name)
    with open(hidden, "w") as f:
        json.dump(p, f)
    shown_png, hidden_png = os.path.join(work, name + ".png"), os.path.join(work, name + ".hidden.png")
    render(frame, shown_png, os.path.join(demo, name))
    render(frame, hidden_png, hidden)
    diff = subprocess.run(["compare", "-metric", "AE", "-fuzz", "3%", shown_png, hidden_png, "null:"],
                          capture_output=True, text=True)
    drawn = int(float(diff.stderr.split()[0]))
    if drawn < 0.03 * 320 * 180:
        fail(f"{name}: only {drawn} pixels differ from the scene without its actors: the BlobTree is not drawn")
    # Drawn as the editor draws them: the blob creature (no colours of its own) in the clay tone
    # (blue over red), the animorphosis demo's dinosaur and dragon in their primitives' warm
    # colours (red over blue), neither in the grey of imported meshes: the mean colour of the lit pixels the actors cover (brighter than the
    # background and the grid, which the framing moves when the actors are hidden).
    mask = os.path.join(work, name + ".mask.png")
    subprocess.run(["convert", "(", shown_png, hidden_png, "-compose", "difference", "-composite", "-colorspace",
                    "gray", "-threshold", "3%", ")", "(", shown_png, "-colorspace", "gray", "-threshold", "45%", ")",
                    "-compose", "multiply", "-composite", mask], check=True)
    covered = float(subprocess.run(["convert", mask, "-format", "%[fx:mean]", "info:"], capture_output=True,
                                   text=True).stdout)
    rgb = subprocess.run(["convert", shown_png, mask, "-compose", "multiply", "-composite", "-format",
                          "%[fx:mean.r] %[fx:mean.g] %[fx:mean.b]", "info:"], capture_output=True, text=True).stdout
    r_, g_, b_ = (float(v) / max(covered, 1e-9) for v in rgb.split())
    coloured = name == "animorphosis.animorph"
    if not (r_ > 1.15 * b_ if coloured else b_ > 1.15 * r_):
        fail(f"{name}: the BlobTree surface's mean colour is r {r_:.2f} g {g_:.2f} b {b_:.2f}: "
             f"{'not its primitives colours' if coloured else 'not the clay tone'}")
    print(f"ok: {name} frame {frame}: the BlobTree actors cover {drawn} pixels, mean colour "
          f"r {r_:.2f} g {g_:.2f} b {b_:.2f}")

bad = os.path.join(work, "bad.animorph")
with open(bad, "w") as f:
    f.write('{"format": "animorph", "version": 1, "actors": [{"id": "x"}]}')
r = subprocess.run([cli, "render", bad, "-o", os.path.join(work, "c.png")], capture_output=True, text=True, env=env)
if r.returncode == 0 or "bad.animorph" not in r.stderr:
    fail(f"a malformed project should fail naming it: exit {r.returncode}, stderr {r.stderr!r}")
shutil.rmtree(work)
print("ok")
