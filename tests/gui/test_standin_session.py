"""Stand-in editing in a real window: open the demo morph, turn on the
Stand-in edit mode with E, click a capsule to select its segment, drag the
segment's radius handle outwards, save with Ctrl+S and find the radius grown in
the saved project (and nothing else of the stand-in changed); Ctrl+Z then
restores it, and the editor quits with no Vulkan validation errors.

usage: test_standin_session.py EDITOR_BIN DEMO_DIR"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
work, project, original = g.demo_copy(demo_dir, "animorph-gui-standin-")


def segments(doc, actor):
    for a in doc["morph"]["actors"]:
        if a["id"] == actor:
            return a["standin"]["segments"]
    g.fail(f"no morph actor {actor} in the project")


ed = g.Editor(editor_bin, project, workdir=work).start()
try:
    m = ed.fresh_map()
    vx, vy, vw, vh = m["viewport"]
    ed.move(vx + vw / 2, vy + vh / 2)
    ed.key("e")
    m = ed.fresh_map()
    keys = [k for k in m["widgets"] if k.startswith("standin/segment/")]
    g.check(len(keys) > 5, f"E turns on the stand-in edit mode and shows the segments ({len(keys)} on screen)")
    shot0 = ed.screenshot(os.path.join(work, "standins.png"))

    # Click the middle of a segment of the source actor.
    source = original["morph"]["source"]
    mine = sorted(k for k in keys if k.startswith(f"standin/segment/{source}/"))
    g.check(len(mine) > 0, "the source's segments are on screen")
    target_key = mine[len(mine) // 2]
    ed.click_widget(target_key)
    m = ed.fresh_map()
    seg = m["standin_segment"]
    actor = m["selected"]
    g.check(seg >= 0 and actor, f"clicking a capsule selects a segment ({actor} #{seg})")
    g.check(not m["dirty"], "selecting a segment is not an edit")

    # Drag the radius handle 40 px further from the segment's axis.
    hx, hy = ed.center("standin/radius")
    mx, my = ed.center(f"standin/segment/{actor}/{seg}")
    dx, dy = hx - mx, hy - my
    n = math.hypot(dx, dy) or 1.0
    ed.drag(hx, hy, hx + 40 * dx / n, hy + 40 * dy / n)
    m = ed.fresh_map()
    g.check(m["dirty"], "dragging the radius handle edits the project")
    shot1 = ed.screenshot(os.path.join(work, "radius.png"))
    changed = g.differing_pixels(shot0, shot1, vx, vy, vw, vh)
    g.check(changed > 100, f"the capsule outline grew on screen ({changed} viewport pixels changed)")

    ed.key("ctrl+s")
    ed.wait_until(lambda mm: not mm["dirty"], "the project is saved")
    with open(project) as f:
        saved = json.load(f)
    before, after = segments(original, actor), segments(saved, actor)
    g.check(len(before) == len(after), "the segment count is unchanged")
    r0, r1 = before[seg]["radius"], after[seg]["radius"]
    g.check(r1 > r0 * 1.05, f"the saved radius of segment {seg} grew ({r0:.4f} -> {r1:.4f} m)")
    others = [i for i in range(len(before)) if i != seg and before[i] != after[i]]
    g.check(not others and before[seg]["a"] == after[seg]["a"], "nothing else of the stand-in changed")

    ed.key("ctrl+z")
    m = ed.fresh_map()
    g.check(m["dirty"], "Ctrl+Z undoes the radius drag (unsaved again)")
    ed.key("ctrl+s")
    ed.wait_until(lambda mm: not mm["dirty"], "saved again")
    with open(project) as f:
        undone = json.load(f)
    g.check(abs(segments(undone, actor)[seg]["radius"] - r0) < 1e-6, "the undone radius is the original one")

    g.xdo("key", "--clearmodifiers", "ctrl+q")  # no fresh map: the editor is gone
    rc = ed.wait_exit()
    g.check(rc == 0, f"the editor quits cleanly with no validation errors (exit {rc})")
finally:
    ed.kill()
print("stand-in session: all checks passed")
