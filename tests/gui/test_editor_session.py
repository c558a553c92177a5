"""A person's first session with the editor, in a real window: open the demo
project, scrub the timeline, play and pause with Space, edit an actor in the
inspector, undo with Ctrl+Z, save with Ctrl+S, quit with Ctrl+Q. Judged by the
saved project, the editor's state and screenshots; the editor must exit with
zero Vulkan validation errors (it exits non-zero otherwise).

usage: test_editor_session.py EDITOR_BIN DEMO_DIR"""
import json
import os
import shutil
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

# Pixels of the scene (below the viewport's overlay line) that must change when scrubbing moves the
# characters. Measured: 29,363; with the scene frozen at frame 0, 0 (and 741 over the whole viewport,
# the frame number's digits, which the check counted before).
SCENE_MOVED = 5000

g.ensure_display(sys.argv)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
work = tempfile.mkdtemp(prefix="animorph-gui-session-")
for name in ("demo.animorph", "creature.glb", "gear.glb"):
    shutil.copy(os.path.join(demo_dir, name), work)
project = os.path.join(work, "demo.animorph")
with open(project) as f:
    original = json.load(f)
actor = original["actors"][0]["id"]

ed = g.Editor(editor_bin, project, workdir=work).start()
try:
    m = ed.fresh_map()
    g.check(m["project"] == os.path.realpath(project) or m["project"] == project, "the demo project is open")
    vx, vy, vw, vh = m["viewport"]
    shot0 = ed.screenshot(os.path.join(work, "start.png"))
    mean, sd = g.region_stats(shot0, vx + vw * 0.25, vy + vh * 0.25, vw * 0.5, vh * 0.5)
    g.check(sd > 0.03, f"the viewport shows the characters (grey-level sd {sd:.3f})")

    # Scrub: drag along the ruler from the left quarter to the middle.
    x0, y0, x1, y1 = ed.widget("timeline/ruler")
    ym = (y0 + y1) / 2
    ed.drag(x0 + (x1 - x0) * 0.2, ym, x0 + (x1 - x0) * 0.55, ym)
    f1 = ed.fresh_map()["current_frame"]
    ed.drag(x0 + (x1 - x0) * 0.55, ym, x0 + (x1 - x0) * 0.3, ym)
    f2 = ed.fresh_map()["current_frame"]
    g.check(f1 > f2 > 0, f"dragging the ruler scrubs (frame {f1} then {f2})")
    g.check(not ed.fresh_map()["dirty"], "scrubbing does not dirty the project")
    shot1 = ed.screenshot(os.path.join(work, "scrubbed.png"))
    # Below the viewport's overlay line: its frame number changed too, and must not count.
    moved = g.differing_pixels(shot0, shot1, *g.scene_region(m))
    g.check(moved > SCENE_MOVED, f"the characters moved between frames ({moved} pixels of the scene changed, "
                                 f"more than {SCENE_MOVED})")

    # Space plays, Space pauses.
    ed.move(vx + vw / 2, vy + vh / 2)
    ed.key("space")
    a = ed.fresh_map()["current_frame"]
    time.sleep(1.0)
    b = ed.fresh_map()["current_frame"]
    g.check(b != a, f"Space plays ({a} -> {b} after 1 s)")
    ed.key("space")
    c = ed.fresh_map()["current_frame"]
    time.sleep(0.6)
    d = ed.fresh_map()["current_frame"]
    g.check(c == d, f"Space pauses (frame stays at {d})")

    # Paused and left alone, the editor draws on demand: it waits for input instead of
    # redrawing (a frame a second for timers), and the next input is drawn at once.
    m0 = ed.wait_until(lambda m: m.get("idle", False) and not m.get("preview_busy", True), "the editor goes idle",
                       timeout=30)
    time.sleep(3.0)
    m1 = ed.ui_map()
    idle_frames = m1["frame_count"] - m0["frame_count"]
    g.check(idle_frames <= 6, f"an idle editor draws on demand ({idle_frames} frames in 3 s)")
    ed.key("Right")
    m2 = ed.fresh_map()
    g.check(m2["current_frame"] == d + 1 and m2["frame_count"] > m1["frame_count"],
            f"input wakes it: Right steps to frame {m2['current_frame']}")

    # Select the first actor in the outliner, drag its Speed field.
    ed.click_widget(f"outliner/{actor}")
    g.check(ed.fresh_map()["selected"] == actor, f"clicking '{actor}' in the outliner selects it")
    sx0, sy0, sx1, sy1 = ed.widget("inspector/speed")
    syc = (sy0 + sy1) / 2
    ed.drag(sx0 + 10, syc, sx0 + 110, syc)
    g.check(ed.fresh_map()["dirty"], "dragging Speed in the inspector makes the project dirty")
    ed.key("ctrl+z")
    g.check(not ed.fresh_map()["dirty"], "Ctrl+Z undoes the whole drag in one step")
    ed.key("ctrl+shift+z")
    g.check(ed.fresh_map()["dirty"], "Ctrl+Shift+Z redoes it")
    ed.key("ctrl+s")
    g.check(not ed.fresh_map()["dirty"], "Ctrl+S saves")
    with open(project) as f:
        saved = json.load(f)
    speed = next(x for x in saved["actors"] if x["id"] == actor)["speed"]
    g.check(speed > 1.0, f"the saved project has the new speed ({speed:.3f})")
    g.check(not os.path.exists(project + ".autosave"), "saving leaves no autosave behind")

    # An unsaved edit, then Ctrl+Q: the prompt appears; Don't Save quits.
    ed.drag(sx0 + 10, syc, sx0 + 60, syc)
    g.check(ed.fresh_map()["dirty"], "a second edit is unsaved")
    ed.key("ctrl+q")
    ed.widget("prompt/dont_save")
    shot2 = ed.screenshot(os.path.join(work, "quit_prompt.png"))
    g.check(os.path.getsize(shot2) > 0, "the unsaved-changes prompt is shown")
    ed.click_widget("prompt/dont_save", wait=False)
    rc = ed.wait_exit()
    g.check(rc == 0, f"the editor quits cleanly with no validation errors (exit {rc})")
    with open(project) as f:
        after = json.load(f)
    g.check(after == saved, "Don't Save leaves the saved project untouched")
finally:
    ed.kill()
print("editor session: all checks passed")
