"""The kept viewport image (gpu/present/viewport_image.h): the editor renders the 3D scene only when
what it shows changed and copies the kept image under the UI otherwise. Through real input on the
demo: hovering UI buttons redraws the UI (the button's hover colour shows) without a scene pass; an
orbit drag and a new frame typed into the timeline each render the scene again, and the viewport's
pixels change with them. The kept image shows the same pixels as the scene drawn into every frame
(ANIMORPH_VIEWPORT_IMAGE=off), and neither run has Vulkan validation errors.

usage: test_kept_viewport.py EDITOR_BIN DEMO_DIR"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
work, project, doc = g.demo_copy(demo_dir, "animorph-gui-kept-")


def settled(ed):
    """The map of the editor gone idle with no preview computing."""
    ed.fresh_map(3)
    return ed.wait_until(lambda m: m.get("idle") and not m.get("preview_busy", False), "the editor settles", 60)


def finish(ed, name):
    g.xdo("key", "--clearmodifiers", "ctrl+q")
    code = ed.wait_exit()
    log = ed.read_log()
    g.check(code == 0, f"{name}: the editor exits cleanly (code {code})")
    g.check("validation error" not in log, f"{name}: no Vulkan validation errors")


os.environ.pop("ANIMORPH_VIEWPORT_IMAGE", None)
for sub in ("kept", "off"):
    os.makedirs(os.path.join(work, sub), exist_ok=True)
ed = g.Editor(editor_bin, project, workdir=os.path.join(work, "kept")).start()
try:
    m0 = settled(ed)
    region = g.scene_region(m0)
    shot0 = ed.screenshot(os.path.join(work, "start.png"))
    m0 = settled(ed)
    # UI only: the pointer over two outliner buttons, in turn (hover colours), then back.
    bx0, by0, bx1, by1 = ed.widget("outliner/import")
    cx0, cy0, cx1, cy1 = ed.widget("outliner/new_blob")
    ed.move((bx0 + bx1) / 2, (by0 + by1) / 2)
    m1 = ed.fresh_map(3)
    hover = ed.screenshot(os.path.join(work, "hover.png"))
    ed.move((cx0 + cx1) / 2, (cy0 + cy1) / 2)
    ed.fresh_map(3)
    ed.move(bx0 + 10, by1 + 300)  # the outliner's empty part: no tooltip over the viewport
    m1 = settled(ed)
    away = ed.screenshot(os.path.join(work, "away.png"))
    m1 = settled(ed)
    print("start:", m0["scene_passes"], "scene passes,", m0["kept_viewport_frames"], "kept; after hovering:",
          m1["scene_passes"], m1["kept_viewport_frames"], flush=True)
    g.check(m1["frame_count"] > m0["frame_count"], "hovering the buttons draws frames")
    g.check(m1["scene_passes"] == m0["scene_passes"],
            f"frames that only change the UI render no scene ({m1['scene_passes'] - m0['scene_passes']} passes)")
    g.check(m1["kept_viewport_frames"] > m0["kept_viewport_frames"], "they show the kept viewport image")
    w = int(bx1 - bx0)
    h = int(by1 - by0)
    g.check(g.differing_pixels(shot0, hover, bx0, by0, w, h) > 0, "the hovered button is redrawn (the UI still updates)")
    g.check(g.differing_pixels(shot0, away, *region) < 0.002 * region[2] * region[3],
            "the viewport shows the same scene while only the UI changed")
    # The camera moves: the scene is rendered again and the viewport shows the new view.
    vx, vy, vw, vh = m1["viewport"]
    ed.drag(vx + vw * 0.5, vy + vh * 0.5, vx + vw * 0.5 + 120, vy + vh * 0.5 + 20, modifiers=("alt",))  # Maya: Alt+LMB orbits
    m2 = settled(ed)
    orbit = ed.screenshot(os.path.join(work, "orbit.png"))
    g.check(m2["scene_passes"] > m1["scene_passes"],
            f"orbiting renders the scene ({m2['scene_passes'] - m1['scene_passes']} passes)")
    moved = g.differing_pixels(away, orbit, *region)
    g.check(moved > 0.01 * region[2] * region[3], f"the viewport shows the orbited view ({moved} pixels changed)")
    # A new time: the creature's pose changes.
    ed.set_frame(30)
    m3 = settled(ed)
    frame30 = ed.screenshot(os.path.join(work, "frame30.png"))
    g.check(m3["scene_passes"] > m2["scene_passes"], "a new frame renders the scene")
    posed = g.differing_pixels(orbit, frame30, *region)
    g.check(posed > 100, f"the viewport shows the creature at frame 30 ({posed} pixels changed)")
    finish(ed, "kept image")
finally:
    ed.kill()

# The same start drawn into every frame: the same viewport pixels.
os.environ["ANIMORPH_VIEWPORT_IMAGE"] = "off"
ref = g.Editor(editor_bin, project, workdir=os.path.join(work, "off")).start()
try:
    mr = settled(ref)
    shot_off = ref.screenshot(os.path.join(work, "start-off.png"))
    g.check(mr["kept_viewport_frames"] == 0, "ANIMORPH_VIEWPORT_IMAGE=off keeps no image")
    diff = g.differing_pixels(shot0, shot_off, *region)
    g.check(diff < 0.002 * region[2] * region[3],
            f"the kept image shows the pixels of the scene drawn into the frame ({diff} differ)")
    finish(ref, "drawn every frame")
finally:
    ref.kill()
print("kept viewport: ok")
