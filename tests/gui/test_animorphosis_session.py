"""An animorphosis shaped by hand in a real window: open a project whose two
BlobTree actors (the demo creature and a copy of it raised and shrunk) are in
an animorphosis with no links yet, scrub into the interval, open View >
Correspondence Editor, drag a wire from the source's torso onto the target's
torso, see the viewport change (the two half-grown torsos become one torso
half-way), Ctrl+Z (the picture comes back), redo, save, reopen: the link is
in the file and drawn in the correspondence editor.

usage: test_animorphosis_session.py EDITOR_BIN DEMO_DIR"""
import copy
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
work = tempfile.mkdtemp(prefix="animorph-gui-animorphosis-")
print(f"work directory: {work}")
project = os.path.join(work, "animorphosis.animorph")

with open(os.path.join(demo_dir, "blob_demo.animorph")) as f:
    demo = json.load(f)
source = next(a for a in demo["actors"] if a.get("kind") == "blobtree")
source["id"], source["name"] = "creature", "Creature"
target = copy.deepcopy(source)
target["id"], target["name"] = "raised", "Raised"


def shift(value, d):
    if isinstance(value, dict):
        for k in value["keys"]:
            k["v"] = [a + b for a, b in zip(k["v"], d)]
        return value
    return [a + b for a, b in zip(value, d)]


# The target's body frame is raised and shrunk: its torso is elsewhere, so linking the torsos moves it.
body = g.find_node(target["blobtree"]["root"], 2)
body["params"]["translation"] = shift(body["params"].get("translation", [0.0, 0.0, 0.0]), [0.0, 0.45, 0.0])
body["params"]["scale"] = [0.8, 0.8, 0.8]
TORSO = 3
g.check(g.find_node(source["blobtree"]["root"], TORSO)["name"] == "torso", "the demo creature's node 3 is its torso")
demo["actors"] = [source, target]
demo["name"] = "animorphosis test"
demo["timeline"].update({"fps": 24, "frame_start": 0, "frame_end": 48})
demo["animorphosis"] = {"source": "creature", "target": "raised", "start": 0.5, "end": 1.5, "graph": {"links": []}}
with open(project, "w") as f:
    json.dump(demo, f)


def settle_preview(ed):
    ed.fresh_map(3)
    ed.wait_until(lambda m: not m.get("preview_busy", False) and "^3" in m.get("preview", ""),
                  "the preview is refined", timeout=90)
    ed.fresh_map(6)


def show_correspondence_editor(ed, shown):
    """View > Correspondence Editor until the window is shown (or gone). On a loaded machine the
    menu item's click can land while the menu is still opening; the state is then checked and the
    menu used again, at most three times."""
    for _ in range(3):
        ed.click_widget("menu/View")
        ed.click_widget("menu/Correspondence Editor")
        if ("corr/window" in ed.fresh_map().get("widgets", {})) == shown:
            return
    g.check(False, f"View > Correspondence Editor {'shows' if shown else 'hides'} the editor")


ed = g.Editor(editor_bin, project, workdir=work).start()
try:
    m = ed.fresh_map()
    vx, vy, vw, vh = m["viewport"]
    ed.set_frame(24)  # u = 0.5: both half-way
    settle_preview(ed)
    unlinked = ed.screenshot(os.path.join(work, "unlinked.png"))

    show_correspondence_editor(ed, True)
    ed.widget("corr/window")
    ax, ay = ed.center(f"corr/a/{TORSO}")
    bx, by = ed.center(f"corr/b/{TORSO}")
    ed.drag(ax, ay, bx, by, steps=16)
    m = ed.fresh_map()
    link = f"corr/link/{TORSO}-{TORSO}"
    g.check(link in m["widgets"], "dragging from the source's torso onto the target's draws a wire")
    g.check(m["dirty"], "the link is an unsaved edit")
    ed.screenshot(os.path.join(work, "wire.png"))
    show_correspondence_editor(ed, False)
    # Pressing the torso's row selected it: a click on empty ground clears the selection (and its
    # highlight), so the pictures differ by the link alone.
    ed.click(vx + vw - 40, vy + 60)
    g.check(not ed.fresh_map().get("selected"), "a click on empty ground clears the selection")
    settle_preview(ed)
    linked = ed.screenshot(os.path.join(work, "linked.png"))
    changed = g.differing_pixels(unlinked, linked, vx, vy, vw, vh)
    g.check(changed > 300, f"the viewport shows the linked torsos half-way ({changed} pixels changed)")

    ed.key("ctrl+z")
    settle_preview(ed)
    undone = ed.screenshot(os.path.join(work, "undone.png"))
    back = g.differing_pixels(unlinked, undone, vx, vy, vw, vh)
    g.check(back < changed / 4, f"Ctrl+Z brings the unlinked picture back ({back} pixels differ, against {changed})")
    ed.key("ctrl+shift+z")
    ed.key("ctrl+s")
    g.check(not ed.fresh_map()["dirty"], "Ctrl+S saves")
    g.xdo("key", "--clearmodifiers", "ctrl+q")
    rc = ed.wait_exit()
    g.check(rc == 0, f"the editor quits cleanly with no validation errors (exit {rc})")
finally:
    ed.kill()

with open(project) as f:
    saved = json.load(f)
links = saved["animorphosis"]["graph"]["links"]
g.check(any(l["a"] == TORSO and l["b"] == TORSO and l.get("artist", True) for l in links),
        f"the saved project holds the artist link torso -> torso ({links})")

ed = g.Editor(editor_bin, project, workdir=work).start()
try:
    show_correspondence_editor(ed, True)
    ed.widget(f"corr/link/{TORSO}-{TORSO}")
    g.check(True, "reopened, the correspondence editor draws the link")
    g.xdo("key", "--clearmodifiers", "ctrl+q")
    rc = ed.wait_exit()
    g.check(rc == 0, f"the reopened editor quits cleanly (exit {rc})")
finally:
    ed.kill()
print("animorphosis session: all checks passed")
