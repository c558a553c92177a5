"""Files dropped on the editor window from a file manager (XDND, as GLFW receives it): a glTF file
becomes a new actor, something else is refused with its name in the status bar, and a project
opens after the unsaved-changes prompt. The editor quits with no Vulkan validation errors.

usage: test_drop_files.py EDITOR_BIN DEMO_DIR"""
import json
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
work, project, original = g.demo_copy(demo_dir, "animorph-gui-drop-")
incoming = os.path.join(work, "incoming")
os.makedirs(incoming)
glb = shutil.copy(os.path.join(demo_dir, "gear.glb"), os.path.join(incoming, "Spare Gear.glb"))
notes = os.path.join(incoming, "notes.txt")
with open(notes, "w") as f:
    f.write("not a scene\n")
other = shutil.copy(project, os.path.join(work, "other.animorph"))

ed = g.Editor(editor_bin, project, workdir=work).start()
try:
    m = ed.fresh_map()
    vx, vy, vw, vh = m["viewport"]
    cx, cy = vx + vw / 2, vy + vh / 2
    actors_before = len(original["actors"])

    g.drop_files(ed.window, [glb], cx, cy)
    m = ed.wait_until(lambda m: m.get("dirty"), "the dropped glTF is imported")
    g.check(m["selected"] not in [a["id"] for a in original["actors"]],
            f"dropping a .glb adds and selects a new actor ({m['selected']})")
    g.check("Spare Gear.glb" in m.get("status", ""), f"the status bar names it: {m.get('status')!r}")
    ed.key("ctrl+s")
    with open(project) as f:
        saved = json.load(f)
    added = [a for a in saved["actors"] if a["id"] == m["selected"]]
    g.check(len(saved["actors"]) == actors_before + 1 and added and added[0]["asset"].endswith("Spare Gear.glb"),
            "the saved project has the actor, with the file's path (a name with a space survives the URI)")

    g.drop_files(ed.window, [notes], cx, cy)
    m = ed.wait_until(lambda m: "notes.txt" in m.get("status", ""), "the refusal in the status bar")
    g.check(not m["dirty"], f"a dropped text file changes nothing: {m['status']!r}")

    ed.drag(cx - 40, cy, cx + 40, cy)  # orbit: not an edit, the project stays clean
    ed.key("ctrl+z")                   # undo the import: now the project has unsaved changes
    g.check(ed.fresh_map()["dirty"], "undoing the import leaves unsaved changes")
    g.drop_files(ed.window, [other], cx, cy)
    ed.widget("prompt/dont_save")
    g.check(True, "dropping a project asks about the unsaved changes first")
    ed.click_widget("prompt/dont_save")
    m = ed.wait_until(lambda m: m.get("project", "").endswith("other.animorph"), "the dropped project opens")
    g.check(not m["dirty"], "the dropped project is open and clean")
    g.xdo("key", "--clearmodifiers", "ctrl+q")
    rc = ed.wait_exit()
    g.check(rc == 0, f"the editor quits cleanly with no validation errors (exit {rc})")
finally:
    ed.kill()
print("drop files: all checks passed")
