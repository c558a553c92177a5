"""Weight painting in the real editor: open a copy of the demo project, select
the morph's source (the creature), enter Weight Paint mode with P, paint one
stroke over it with the mouse (xdotool: button down, move, up), save with
Ctrl+S and find the weights changed in the saved project (some vertices > 0,
the rest untouched), then Ctrl+Z and save again: the original map is back
exactly. The viewport must show the heat-colour overlay while painting, and
the editor must exit with zero Vulkan validation errors.

usage: test_weight_paint.py EDITOR_BIN DEMO_DIR"""
import base64
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
work = tempfile.mkdtemp(prefix="animorph-gui-paint-")
for name in ("demo.animorph", "creature.glb", "gear.glb"):
    shutil.copy(os.path.join(demo_dir, name), work)
project = os.path.join(work, "demo.animorph")
with open(project) as f:
    original = json.load(f)
source = original["morph"]["source"]


def morph_actor(doc, actor_id):
    return next(a for a in doc["morph"]["actors"] if a["id"] == actor_id)


def weight_map(doc, actor_id):
    text = morph_actor(doc, actor_id).get("weight_map")
    if text is None:
        return None
    raw = base64.b64decode(text)
    return list(struct.unpack("<%df" % (len(raw) // 4), raw))


def colour_counts(png, x, y, w, h):
    """Pixels of a region that are clearly blue (weight 0 in the heat ramp) and clearly warm (weight > 0.5)."""
    out = subprocess.run(["convert", png, "-crop", f"{int(w)}x{int(h)}+{int(x)}+{int(y)}", "+repage", "-depth", "8",
                          "txt:-"], capture_output=True, text=True, check=True).stdout
    blue = warm = 0
    for line in out.splitlines()[1:]:
        try:
            rgb = line.split("(")[1].split(")")[0].split(",")[:3]
            r, gg, b = (float(v) for v in rgb)
        except (IndexError, ValueError):
            continue
        if b > r + 60 and b > gg + 20:
            blue += 1
        if r > b + 60 and r > 120:
            warm += 1
    return blue, warm


original_map = weight_map(original, source)
ed = g.Editor(editor_bin, project, workdir=work).start()
try:
    ed.click_widget(f"outliner/{source}")
    g.check(ed.fresh_map()["selected"] == source, f"clicking '{source}' in the outliner selects it")
    vx, vy, vw, vh = ed.fresh_map()["viewport"]
    ed.move(vx + vw / 2, vy + vh / 2)
    ed.key("p")
    ed.widget("paint/panel")
    tx0, ty0, tx1, ty1 = ed.widget("paint/target")
    g.check(tx1 - tx0 > 40 and ty1 - ty0 > 40, f"the creature is on screen in paint mode ({tx1 - tx0:.0f} x {ty1 - ty0:.0f} px)")
    g.check("viewport/paint_note" in ed.fresh_map()["widgets"], "the viewport says it is in Weight Paint mode")
    before = ed.screenshot(os.path.join(work, "paint_before.png"))
    blue0, warm0 = colour_counts(before, tx0, ty0, tx1 - tx0, ty1 - ty0)
    g.check(blue0 > 200, f"the unpainted creature shows in the overlay's blue ({blue0} blue pixels)")

    # One stroke across the middle of the creature, left to right.
    cy = (ty0 + ty1) / 2
    ed.drag(tx0 + (tx1 - tx0) * 0.3, cy, tx0 + (tx1 - tx0) * 0.7, cy, steps=16)
    m = ed.fresh_map()
    g.check(m["dirty"], "the stroke changed the project")
    ed.move(tx0 + (tx1 - tx0) * 0.5, cy - 10)
    painted_png = ed.screenshot(os.path.join(work, "paint_after.png"))
    blue1, warm1 = colour_counts(painted_png, tx0, ty0, tx1 - tx0, ty1 - ty0)
    g.check(warm1 > warm0 + 50, f"the painted band shows in warm heat colours ({warm0} -> {warm1} warm pixels)")
    g.check("paint/brush" in ed.fresh_map()["widgets"], "the brush circle is drawn at the cursor")

    ed.key("ctrl+s")
    g.check(not ed.fresh_map()["dirty"], "Ctrl+S saves")
    with open(project) as f:
        saved = json.load(f)
    painted = weight_map(saved, source)
    g.check(painted is not None and len(painted) > 100, f"the saved project has a weight map for '{source}'")
    base = original_map or [0.0] * len(painted)
    changed = sum(1 for a, b in zip(painted, base) if a != b)
    g.check(changed > 0 and all(0.0 <= w <= 1.0 for w in painted), f"{changed} weights changed, all within [0, 1]")
    g.check(max(painted) > 0.0, f"painted weights are > 0 (max {max(painted):.3f})")
    g.check(len(painted) - changed > len(painted) // 4, f"{len(painted) - changed} of {len(painted)} vertices untouched")
    g.check(saved["morph"]["actors"] != original["morph"]["actors"], "the morph section changed")

    ed.key("ctrl+z")
    g.check(ed.fresh_map()["dirty"], "Ctrl+Z undoes the stroke")
    ed.key("ctrl+s")
    with open(project) as f:
        restored = json.load(f)
    g.check(weight_map(restored, source) == original_map, "after Ctrl+Z the saved map is the original exactly")
    g.check(restored["morph"] == original["morph"], "the whole morph section is as it was")

    g.xdo("key", "--clearmodifiers", "ctrl+q")  # nothing unsaved: the editor exits at once
    rc = ed.wait_exit()
    g.check(rc == 0, f"the editor quits cleanly with no validation errors (exit {rc})")
finally:
    ed.kill()
print("weight paint: all checks passed")
