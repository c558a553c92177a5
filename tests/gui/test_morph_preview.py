"""The morph's implicit stage in the real editor: scrub the demo into B..C by
dragging the ruler, then wait (through the widget map's `preview_busy` and
`preview` fields) for the refined preview of the stage; the status line names
the resolution, the device and why; the viewport header's preview button opens
the device/resolution popup, and choosing the CPU there is kept in the
preferences. Zero Vulkan validation errors at exit.

usage: test_morph_preview.py EDITOR_BIN DEMO_DIR"""
import json
import os
import re
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
work = tempfile.mkdtemp(prefix="animorph-gui-morph-preview-")
for name in ("demo.animorph", "creature.glb", "gear.glb"):
    shutil.copy(os.path.join(demo_dir, name), work)
project = os.path.join(work, "demo.animorph")
with open(project) as f:
    doc = json.load(f)
mk = doc["morph"]["markers"]
tl = doc["timeline"]
target = (mk["B"] + mk["C"]) // 2


def refined(m):
    p = m.get("preview", "")
    return not m.get("preview_busy", True) and "^3" in p and "(refining)" not in p


ed = g.Editor(editor_bin, project, workdir=work).start()
try:
    vx, vy, vw, vh = ed.fresh_map()["viewport"]
    x0, y0, x1, y1 = ed.widget("timeline/ruler")
    ym = (y0 + y1) / 2
    span = tl["frame_end"] - tl["frame_start"]
    xt = x0 + (x1 - x0) * (target - tl["frame_start"]) / span
    ed.drag(x0 + (x1 - x0) * 0.1, ym, xt, ym, steps=16)
    m = ed.fresh_map()
    f = m["current_frame"]
    g.check(mk["B"] < f < mk["C"], f"scrubbed into the morph stage (frame {f}, B={mk['B']}, C={mk['C']})")
    m = ed.wait_until(refined, "the morph stage's refined preview", timeout=120)
    status = m["preview"]
    g.check(re.search(r"preview 128\^3 (CPU|GPU) \d+ ms, \d+ tris", status) is not None,
            f"the status names the refined resolution, device, time and triangles: '{status}'")
    tris = int(re.search(r"(\d+) tris", status).group(1))
    g.check(tris > 1000, f"the morph stage has a surface ({tris} triangles)")
    g.check("auto" in status, f"the status says why the device was chosen: '{status}'")
    shot = ed.screenshot(os.path.join(work, "morph_stage.png"))
    mean, sd = g.region_stats(shot, vx + vw * 0.3, vy + vh * 0.3, vw * 0.4, vh * 0.4)
    g.check(sd > 0.03, f"the viewport shows the morph surface (grey-level sd {sd:.3f})")

    # The viewport header's preview button: choose the CPU explicitly.
    ed.click_widget("viewport/preview_button")
    ed.click_widget("preview/device_cpu")
    ed.click_widget("status/document")  # a click outside closes the popup
    m = ed.wait_until(lambda m: "CPU (preference)" in m.get("preview", ""), "the CPU preference in the status",
                      timeout=120)
    m = ed.wait_until(refined, "the refined CPU preview", timeout=120)
    g.check("CPU" in m["preview"], f"the preview runs on the CPU: '{m['preview']}'")
    g.xdo("key", "--clearmodifiers", "ctrl+q")  # not ed.key: the editor is gone before another frame
    rc = ed.wait_exit()
    g.check(rc == 0, f"the editor exits cleanly, no validation errors (status {rc})")
    prefs = os.path.join(work, "config", "animorph", "prefs.json")
    with open(prefs) as fp:
        saved = json.load(fp)
    g.check(saved.get("previewDevice") == "cpu", f"the device choice is saved ({saved.get('previewDevice')})")
    g.check(saved.get("previewCoarseResolution") == 96, "the interactive resolution defaults to 96")
    print("ok: morph preview session")
finally:
    ed.kill()
