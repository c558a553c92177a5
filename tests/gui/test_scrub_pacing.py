"""Scrubbing the animorphosis demo (dinosaur -> dragon) in a real window with the CPU preview of
C(t) at 96^3: while the worker computes, the frame loop is paced (scene/scrub_pacing.h: a frame
per new mesh, the cursor's motion at most once a project frame) instead of redrawing on every
motion, yet the playhead follows the cursor, new C(t) meshes keep appearing while the button is
held, and the preview refines once it is released. The particle view is on (the default): the
demo's creatures are made of meta-primitives, not particles, so their surface is what is scrubbed.

usage: test_scrub_pacing.py EDITOR_BIN DEMO_DIR"""
import json
import os
import shutil
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
work = tempfile.mkdtemp(prefix="animorph-gui-scrub-pacing-")
print(f"work directory: {work}")
project = os.path.join(work, "animorphosis.animorph")
shutil.copy(os.path.join(demo_dir, "animorphosis.animorph"), project)
os.makedirs(os.path.join(work, "config", "animorph"))
with open(os.path.join(work, "config", "animorph", "prefs.json"), "w") as f:
    json.dump({"previewDevice": "cpu"}, f)

ed = g.Editor(editor_bin, project, workdir=work).start()
try:
    ed.set_frame(90)  # inside the interval (frames 48..144): C(t) is previewed
    ed.wait_until(lambda m: not m.get("preview_busy", False) and "^3" in m.get("preview", ""),
                  "the preview of C(t) is refined", timeout=120)
    x0, y0, x1, y1 = ed.widget("timeline/ruler")
    ym = (y0 + y1) / 2
    # From the ruler's middle (frame ~96) to the right, a motion every ~30 ms for ~4 s.
    xa, xb, steps = x0 + (x1 - x0) * 0.5, x0 + (x1 - x0) * 0.62, 120
    ed.move(xa, ym)
    time.sleep(0.05)
    g.xdo("mousedown", 1)
    start = ed.fresh_map(2)
    f_start, frames_start, t_start = start["current_frame"], start["frame_count"], time.monotonic()
    paced, previews, frames_seen = 0, set(), set()
    for i in range(1, steps + 1):
        ed.move(xa + (xb - xa) * i / steps, ym)
        time.sleep(0.02)
        m = ed.ui_map()
        paced += bool(m.get("paced", False))
        frames_seen.add(m.get("current_frame"))
        if m.get("preview", "").startswith("preview 96^3"):
            previews.add(m["preview"])
    held = ed.fresh_map(2)
    drawn, seconds = held["frame_count"] - frames_start, time.monotonic() - t_start
    vx, vy, vw, vh = held["viewport"]
    shot = ed.screenshot(os.path.join(work, "held.png"))  # the button still held: the 96^3 mesh
    mean, sd = g.region_stats(shot, vx + vw * 0.2, vy + vh * 0.2, vw * 0.6, vh * 0.6)
    g.check(sd > 0.03, f"while scrubbing the viewport shows C(t) (grey-level sd {sd:.3f})")
    g.xdo("mouseup", 1)
    f_end = held["current_frame"]
    print(f"scrubbed frames {f_start} -> {f_end} in {seconds:.1f} s: {drawn} frames drawn "
          f"({drawn / seconds:.1f} a second), {len(previews)} different 96^3 preview lines, "
          f"{paced} of {steps} maps paced", flush=True)
    g.check(f_end - f_start >= 10, f"the playhead followed the cursor (frame {f_start} -> {f_end})")
    g.check(len(frames_seen) >= 8, f"the playhead moved while the button was held ({len(frames_seen)} frames seen)")
    g.check(paced > 0, "the frame loop was paced while the preview of C(t) computed")
    g.check(len(previews) >= 2, f"new C(t) meshes were shown while scrubbing ({len(previews)} preview lines)")
    m = ed.wait_until(lambda m: not m.get("preview_busy", False) and not m.get("paced", True)
                      and "^3" in m.get("preview", "") and "refining" not in m["preview"],
                      "the preview refines after the release", timeout=120)
    g.check(m["current_frame"] == f_end, "releasing the button keeps the frame")
    shot = ed.screenshot(os.path.join(work, "scrubbed.png"))
    mean, sd = g.region_stats(shot, vx + vw * 0.2, vy + vh * 0.2, vw * 0.6, vh * 0.6)
    g.check(sd > 0.03, f"the viewport shows C(t) (grey-level sd {sd:.3f})")
    g.check(not ed.fresh_map()["dirty"], "scrubbing leaves the project unmodified")
    g.xdo("key", "--clearmodifiers", "ctrl+q")
    g.check(ed.wait_exit() == 0, "the editor quits cleanly (no validation errors)")
finally:
    ed.kill()
print("scrub pacing: all checks passed")
