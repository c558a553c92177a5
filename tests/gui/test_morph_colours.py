"""Colour through the morph in the real editor: the demo morph at a frame between B and C
(the implicit stage) shows both sides' colours at once -- the creature's green scales on the
part of the surface still its stand-in's and the gear's bronze where the gear's stand-in grows
-- and the animorphosis demo's BlobTrees are drawn in their primitives' colours, not the clay
tone. Judged by counting the viewport's pixels by hue in screenshots (kept in the work folder).

usage: test_morph_colours.py EDITOR_BIN DEMO_DIR"""
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

# Pixels of one side's hue the mid-morph surface must show (measured: several thousand each).
MIN_PIXELS = 400

g.ensure_display(sys.argv)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
work, project, doc = g.demo_copy(demo_dir, "animorph-gui-morph-colours-")


def refined(m):
    p = m.get("preview", "")
    return not m.get("preview_busy", True) and "^3" in p and "(refining)" not in p


ed = g.Editor(editor_bin, project, workdir=work).start()
try:
    mk = doc["morph"]["markers"]
    m = ed.fresh_map()
    region = g.scene_region(m)
    best = None
    for frame in ((mk["B"] + mk["C"]) // 2, mk["B"] + (mk["C"] - mk["B"]) // 3):
        ed.set_frame(frame)
        m = ed.wait_until(refined, f"the refined preview of frame {frame}", timeout=120)
        shot = ed.screenshot(os.path.join(work, f"morph_colours_{frame}.png"))
        green, orange, clay, saturated = g.hue_counts(shot, region)
        print(f"frame {frame}: green {green}, orange {orange}, clay {clay}, saturated {saturated}; {m['preview']}",
              flush=True)
        if best is None or min(green, orange) > min(best[1], best[2]):
            best = (frame, green, orange, shot)
        if green > MIN_PIXELS and orange > MIN_PIXELS:
            break
    frame, green, orange, shot = best
    g.check(green > MIN_PIXELS and orange > MIN_PIXELS,
            f"mid-morph (frame {frame}, B={mk['B']}, C={mk['C']}) the surface shows the creature's green "
            f"({green} pixels) and the gear's bronze ({orange} pixels): {shot}")
    g.xdo("key", "--clearmodifiers", "ctrl+q")
    rc = ed.wait_exit()
    g.check(rc == 0, f"the editor exits cleanly, with no validation errors (exit {rc})")
finally:
    ed.kill()

# The animorphosis demo: its BlobTrees (dinosaur and dragon) in their colours, not clay.
project2 = os.path.join(work, "animorphosis.animorph")
shutil.copy(os.path.join(demo_dir, "animorphosis.animorph"), project2)
ed = g.Editor(editor_bin, project2, workdir=tempfile.mkdtemp(prefix="animorph-gui-blob-colours-")).start()
try:
    m = ed.wait_until(refined, "the animorphosis demo's refined preview", timeout=180)
    region = g.scene_region(m)
    shot = ed.screenshot(os.path.join(work, "animorphosis_colours.png"))
    green, orange, clay, saturated = g.hue_counts(shot, region)
    print(f"animorphosis: green {green}, orange {orange}, clay {clay}, saturated {saturated}; {m['preview']}",
          flush=True)
    g.check(green + orange > 2 * MIN_PIXELS and green + orange > clay,
            f"the BlobTrees are drawn in their colours ({green} green and {orange} orange pixels against {clay} "
            f"in the clay tone): {shot}")
    g.xdo("key", "--clearmodifiers", "ctrl+q")
    rc = ed.wait_exit()
    g.check(rc == 0, f"the editor exits cleanly, with no validation errors (exit {rc})")
finally:
    ed.kill()
print("morph colours: all checks passed")
