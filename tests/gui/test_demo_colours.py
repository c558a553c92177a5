"""The demo's characters are drawn in their materials' colours, not one grey: open
the demo project, take a screenshot at the first frame and at a frame where the
gear shows, and count the scene's pixels by hue. The creature's scales (green)
and the gear's bronze (orange) must each cover a good part of the scene, and the
background and grid (grey) must not be all there is.

usage: test_demo_colours.py EDITOR_BIN DEMO_DIR"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

# Pixels of a hue that a character must cover in a 1600x900 window's scene (measured: the
# creature about 11,000 green pixels at frame 0; any one-grey drawing gives 0).
MIN_PIXELS = 1500

g.ensure_display(sys.argv)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
work, project, doc = g.demo_copy(demo_dir, "animorph-gui-colours-")


ed = g.Editor(editor_bin, project, workdir=work).start()
try:
    m = ed.fresh_map()
    region = g.scene_region(m)
    shot0 = ed.screenshot(os.path.join(tempfile.gettempdir(), "animorph_demo_colours_start.png"))
    green, orange, _, saturated = g.hue_counts(shot0, region)
    g.check(green > MIN_PIXELS, f"the creature is drawn in its green scales ({green} green pixels, "
                                f"{saturated} saturated, at frame {m['current_frame']})")
    # After marker D the morph's target, the gear, is drawn in its place.
    d_frame = doc["morph"]["markers"]["D"]
    end = doc["timeline"]["frame_end"]
    best = (0, None, None)
    for frame in (min(end, d_frame + 12), end):
        ed.set_frame(frame)
        shot = ed.screenshot(os.path.join(tempfile.gettempdir(), f"animorph_demo_colours_{frame}.png"))
        orange = g.hue_counts(shot, region)[1]
        if orange > best[0]:
            best = (orange, frame, shot)
        if orange > MIN_PIXELS:
            break
    g.check(best[0] > MIN_PIXELS, f"the gear is drawn in its bronze ({best[0]} orange pixels at frame {best[1]}, "
                                  f"{best[2]})")
    g.xdo("key", "--clearmodifiers", "ctrl+q")
    rc = ed.wait_exit()
    g.check(rc == 0, f"the editor exits cleanly, with no validation errors (exit {rc})")
finally:
    ed.kill()
print("demo colours: all checks passed")
