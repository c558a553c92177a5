"""A glTF given on the command line, as a new user does (`animorph walker.glb`): the editor opens a
new untitled project with that character imported and drawn; a file named .glb that is not a glTF
binary gives an error naming the file and the reason, and the editor keeps running with an empty
project. Both quit cleanly with no Vulkan validation errors.

usage: test_open_gltf.py EDITOR_BIN DEMO_DIR"""
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
work = tempfile.mkdtemp(prefix="animorph-gui-open-gltf-")
walker = shutil.copy(os.path.join(demo_dir, "creature.glb"), os.path.join(work, "Walker.glb"))
fake = os.path.join(work, "renamed.glb")
with open(fake, "wb") as f:
    f.write(b"PK\x03\x04" + b"\0" * 60)


def quit_without_saving(ed, dirty):
    if dirty:
        ed.key("ctrl+q")
        ed.widget("prompt/dont_save")
        ed.click_widget("prompt/dont_save", wait=False)
    else:
        g.xdo("key", "--clearmodifiers", "ctrl+q")  # not ed.key: the editor is gone before another frame
    rc = ed.wait_exit()
    g.check(rc == 0, f"the editor quits cleanly with no validation errors (exit {rc})")


os.makedirs(os.path.join(work, "a"))
os.makedirs(os.path.join(work, "b"))
ed = g.Editor(editor_bin, walker, workdir=os.path.join(work, "a")).start()
try:
    m = ed.wait_until(lambda m: "Walker.glb" in m.get("status", ""), "the character is imported")
    g.check(m["project"] == "" and m["dirty"], f"a new untitled project with unsaved changes: {m['status']!r}")
    g.check(m["selected"] != "", f"the imported actor is selected ({m['selected']})")
    vx, vy, vw, vh = m["viewport"]
    shot_ok = ed.screenshot(os.path.join(work, "walker.png"))
    quit_without_saving(ed, dirty=True)
finally:
    ed.kill()

ed = g.Editor(editor_bin, fake, workdir=os.path.join(work, "b")).start()
try:
    m = ed.wait_until(lambda m: "not a glTF binary" in m.get("status", ""), "the refusal")
    g.check(fake in m["status"] and "'PK\\x03\\x04'" in m["status"],
            f"the error names the path as given and the bytes found: {m['status']!r}")
    ed.widget("error/ok")
    g.check(m["project"] == "" and not m["dirty"], "the editor keeps running with an empty, clean project")
    ed.click_widget("error/ok")
    shot_empty = ed.screenshot(os.path.join(work, "empty.png"))
    quit_without_saving(ed, dirty=False)
finally:
    ed.kill()

# The character is drawn: the viewport's centre differs from the empty project's.
cx, cy = vx + vw / 4, vy + vh / 4
changed = g.differing_pixels(shot_ok, shot_empty, cx, cy, vw / 2, vh / 2)
g.check(changed > 2000, f"the character is drawn in the viewport ({changed} pixels differ from an empty scene)")
shutil.rmtree(work, ignore_errors=True)
print("open glTF: all checks passed")
