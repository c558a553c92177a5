"""Animorphosis > Bake to Key-frame Actor in a real window: open a copy of the
animorphosis demo (dinosaur -> dragon), bake through the menu, the outliner
lists the new BlobTree actor and the status bar gives the key counts, Ctrl+S
saves it, Ctrl+Z removes it (the outliner row goes), Ctrl+S again: the saved
project has only the two creatures.

usage: test_bake_key_actor.py EDITOR_BIN DEMO_DIR"""
import json
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
work = tempfile.mkdtemp(prefix="animorph-gui-bake-keys-")
print(f"work directory: {work}")
project = os.path.join(work, "animorphosis.animorph")
shutil.copy(os.path.join(demo_dir, "animorphosis.animorph"), project)
BAKED = "dinosaur_to_dragon"


def saved_actor_ids():
    with open(project) as f:
        return [a["id"] for a in json.load(f)["actors"]]


ed = g.Editor(editor_bin, project, workdir=work).start()
try:
    ed.widget("outliner/dinosaur/visible", timeout=120)  # the project opens in the background
    ed.click_widget("menu/Animorphosis")
    ed.click_widget("menu/Bake to Key-frame Actor")
    # The bake runs as a background job; the outliner gets the actor when it is applied.
    m = ed.wait_until(lambda m: f"outliner/{BAKED}/visible" in m["widgets"], "the baked actor is in the outliner",
                      timeout=120)
    status = m.get("status", "")
    print(f"status: {status}")
    g.check("nA + nB + ns" in status and "largest deviation" in status,
            f"the status bar reports the key counts and the deviation ({status})")
    g.check(m["selected"] == BAKED, "the baked actor is selected")
    g.check(m["dirty"], "the bake is an unsaved edit")
    ed.key("ctrl+s")
    g.check(not ed.fresh_map()["dirty"], "Ctrl+S saves")
    g.check(BAKED in saved_actor_ids(), f"the saved project holds the baked actor ({saved_actor_ids()})")

    ed.key("ctrl+z")
    m = ed.wait_until(lambda m: f"outliner/{BAKED}/visible" not in m["widgets"], "Ctrl+Z removes the baked actor")
    ed.key("ctrl+s")
    g.check(not ed.fresh_map()["dirty"], "Ctrl+S saves again")
    g.check(saved_actor_ids() == ["dinosaur", "dragon"], f"undone, the saved project has the two creatures ({saved_actor_ids()})")
    g.xdo("key", "--clearmodifiers", "ctrl+q")
    rc = ed.wait_exit()
    g.check(rc == 0, f"the editor quits cleanly (exit {rc})")
finally:
    ed.kill()
print("bake to key-frame actor: all checks passed")
