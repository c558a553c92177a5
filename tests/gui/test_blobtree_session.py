"""Building and animating an implicit shape in a real window: start from an
empty project, add a BlobTree actor (outliner button), add a point primitive
under its root (Create menu), key the point's centre at frames 0 and 24
(key button in the inspector), move it at frame 24 with the translate gizmo,
scrub the timeline, save with Ctrl+S and quit. Judged by the saved project
(the point and its two keys), screenshots (the polygonised surface is in the
viewport and moves when scrubbing) and the exit status (no Vulkan validation
errors).

usage: test_blobtree_session.py EDITOR_BIN"""
import json
import os
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

# Pixels of the scene (below the viewport's overlay line) that must change when the surface follows
# the point back from frame 24 to 0: more than the moved gizmo's arrows alone. Measured: 77,611; with
# the scene frozen at frame 0, 2,023 (the gizmo; 2,564 over the whole viewport with the frame number,
# where the check passed at 300 before).
SURFACE_MOVED = 10000

g.ensure_display(sys.argv)
editor_bin = sys.argv[1]
work = tempfile.mkdtemp(prefix="animorph-gui-blob-")
project = os.path.join(work, "blob.animorph")
with open(project, "w") as f:
    json.dump({"format": "animorph", "version": 1, "name": "blob test", "actors": [],
               "timeline": {"fps": 24, "frame_start": 0, "frame_end": 48}}, f)


def set_frame(ed, frame):
    ed.click_widget("timeline/frame")
    ed.key("ctrl+a")
    ed.type_text(str(frame))
    ed.key("Return")
    got = ed.fresh_map()["current_frame"]
    g.check(got == frame, f"the current frame is {frame}")


def settle_preview(ed):
    # The surface is polygonised off the UI thread: wait until the worker has
    # delivered the refined level (the editor reports it in the UI map).
    ed.fresh_map(3)
    ed.wait_until(lambda m: not m.get("preview_busy", False) and "^3" in m.get("preview", ""),
                  "the preview is refined", timeout=60)
    ed.fresh_map(6)


ed = g.Editor(editor_bin, project, workdir=work).start()
try:
    m = ed.fresh_map()
    vx, vy, vw, vh = m["viewport"]
    empty = ed.screenshot(os.path.join(work, "empty.png"))

    # A new BlobTree actor: a blend of one sphere, selected.
    ed.click_widget("outliner/new_blob")
    m = ed.fresh_map()
    g.check(m["selected"] == "blob", "the outliner button adds and selects a BlobTree actor")
    settle_preview(ed)
    sphere = ed.screenshot(os.path.join(work, "sphere.png"))
    changed = g.differing_pixels(empty, sphere, vx, vy, vw, vh)
    g.check(changed > 2000, f"the sphere's surface is drawn in the viewport ({changed} pixels differ from empty)")

    # Select the root blend and add a point under it from the Create menu.
    ed.click_widget("outliner/blob/blob/1")
    ed.click_widget("menu/Create")
    ed.move(*ed.center("menu/Add/Primitive"))
    ed.fresh_map()
    ed.click_widget("menu/Add/point")
    point = None
    m = ed.fresh_map()
    for key in m["widgets"]:
        if key.startswith("outliner/blob/blob/") and key.count("/") == 3 and key.split("/")[3] not in ("1", "2"):
            point = int(key.split("/")[3])
    g.check(point is not None, f"the point appears in the outliner (node {point})")

    # Key its centre at frame 0, then at 24, then drag the gizmo's X arrow at 24.
    set_frame(ed, 0)
    ed.click_widget("inspector/blob/center/key")
    set_frame(ed, 24)
    ed.click_widget("inspector/blob/center/key")
    gx, gy = ed.center("gizmo/x")
    ox, oy = ed.center("gizmo/origin")
    length = max(1.0, ((gx - ox) ** 2 + (gy - oy) ** 2) ** 0.5)
    ed.drag(gx, gy, gx + (gx - ox) / length * 140, gy + (gy - oy) / length * 140, steps=14)
    settle_preview(ed)
    at24 = ed.screenshot(os.path.join(work, "frame24.png"))

    # Scrub back to the start: the point (and the surface around it) moves back.
    x0, y0, x1, y1 = ed.widget("timeline/ruler")
    ym = (y0 + y1) / 2
    fx = lambda f: x0 + (x1 - x0) * (f + 1.44) / (48 + 2 * 1.44)  # the ruler fits the range with a 3% margin
    ed.drag(fx(24), ym, fx(0), ym)
    m = ed.fresh_map()
    g.check(m["current_frame"] <= 1, f"scrubbing the ruler goes back to the start (frame {m['current_frame']})")
    settle_preview(ed)
    at0 = ed.screenshot(os.path.join(work, "frame0.png"))
    # Below the viewport's overlay line (its frame number changed too), more than the gizmo's
    # arrows, which moved with the point, could change.
    moved = g.differing_pixels(at24, at0, *g.scene_region(m))
    g.check(moved > SURFACE_MOVED, f"the surface follows the keyed point when scrubbing ({moved} pixels of the "
                                   f"scene changed, more than {SURFACE_MOVED})")
    mean, sd = g.region_stats(at0, vx + vw * 0.3, vy + vh * 0.3, vw * 0.4, vh * 0.4)
    g.check(sd > 0.03, f"the viewport centre shows a shaded surface (grey-level sd {sd:.3f})")

    # Save and check the document.
    ed.key("ctrl+s")
    g.check(not ed.fresh_map()["dirty"], "Ctrl+S saves")
    with open(project) as f:
        saved = json.load(f)
    actor = next(a for a in saved["actors"] if a["id"] == "blob")
    g.check(actor.get("kind") == "blobtree", "the saved actor is a BlobTree")

    pnode = g.find_node(actor["blobtree"]["root"], point)
    g.check(pnode is not None and pnode["type"] == "point", "the saved tree holds the point")
    center = pnode["params"]["center"]
    g.check(isinstance(center, dict) and len(center["keys"]) == 2, "the point's centre has two keys")
    k0, k1 = center["keys"]
    g.check(abs(k0["t"] - 0.0) < 1e-6 and abs(k1["t"] - 1.0) < 1e-6, "the keys sit at frames 0 and 24 (0 s and 1 s)")
    g.check(k1["v"][0] - k0["v"][0] > 0.05, f"the gizmo drag moved the key at 24 along +X ({k0['v'][0]:.3f} -> {k1['v'][0]:.3f})")
    g.check(abs(k1["v"][1] - k0["v"][1]) < 1e-6 and abs(k1["v"][2] - k0["v"][2]) < 1e-6, "only X changed")

    g.xdo("key", "--clearmodifiers", "ctrl+q")  # saved: quits at once, no prompt
    rc = ed.wait_exit()
    g.check(rc == 0, f"the editor quits cleanly with no validation errors (exit {rc})")
finally:
    ed.kill()
print("BlobTree session: all checks passed")
