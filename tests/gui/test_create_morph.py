"""Create > Morph... in a real window with a glTF character and a BlobTree
actor (the demo creature and the demo BlobTree creature beside it, no morph
yet): pick the glTF as source and the BlobTree as target, create (one undo
step), scrub into B..C: the viewport names the morph stage, the refined
preview has a surface, and the picture differs from the source alone before
A; the saved project holds the morph with C = D (no expansion on a BlobTree
side); Ctrl+Z removes it.

usage: test_create_morph.py EDITOR_BIN DEMO_DIR"""
import json
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
work = tempfile.mkdtemp(prefix="animorph-gui-create-morph-")
print(f"work directory: {work}")
shutil.copy(os.path.join(demo_dir, "creature.glb"), work)
with open(os.path.join(demo_dir, "demo.animorph")) as f:
    doc = json.load(f)
with open(os.path.join(demo_dir, "blob_demo.animorph")) as f:
    blob = next(a for a in json.load(f)["actors"] if a.get("kind") == "blobtree")
creature = next(a for a in doc["actors"] if a["id"] == "creature")
blob["id"], blob["name"] = "blobc", "Blob creature"
doc["actors"] = [creature, blob]
doc.pop("morph", None)
doc["name"] = "create morph test"
doc["timeline"].update({"frame_start": 0, "frame_end": 96, "current_frame": 0})
project = os.path.join(work, "create_morph.animorph")
with open(project, "w") as f:
    json.dump(doc, f)


def refined(m):
    p = m.get("preview", "")
    return not m.get("preview_busy", True) and "^3" in p and "(refining)" not in p


ed = g.Editor(editor_bin, project, workdir=work).start()
try:
    vx, vy, vw, vh = ed.fresh_map()["viewport"]
    ed.click(vx + vw - 40, vy + 60)  # nothing selected
    ed.set_frame(4)
    ed.fresh_map(6)
    before = ed.screenshot(os.path.join(work, "before.png"))

    ed.click_widget("menu/Create")
    ed.click_widget("menu/Morph...")
    ed.widget("morph/create/create")
    ed.click_widget("morph/create/source")
    ed.click_widget("morph/create/source/0")  # the creature (glTF)
    ed.click_widget("morph/create/target")
    ed.click_widget("morph/create/target/1")  # the blob creature (BlobTree)
    ed.click_widget("morph/create/create")
    m = ed.fresh_map()
    g.check(m["dirty"], "creating the morph is an unsaved edit")
    g.check("morph/create/create" not in m["widgets"], f"the modal closed ({m['status']})")
    g.check("Create morph creature -> blobc" in m["status"], f"the status names the morph: '{m['status']}'")

    ed.key("ctrl+s")
    with open(project) as f:
        morph = json.load(f).get("morph", {})
    g.check(morph.get("source") == "creature" and morph.get("target") == "blobc",
            f"the saved morph is creature -> blobc ({morph.get('source')} -> {morph.get('target')})")
    mk = morph["markers"]
    g.check(mk["A"] < mk["B"] < mk["C"] == mk["D"], f"markers A < B < C = D on a BlobTree target ({mk})")

    ed.set_frame((mk["B"] + mk["C"]) // 2)
    m = ed.wait_until(refined, "the morph stage's refined preview", timeout=120)
    g.check(m.get("viewport_note", "").startswith("morph: morph "),
            f"the viewport names the morph stage: '{m.get('viewport_note')}'")
    g.check("error" not in m.get("viewport_note", ""), "the morph evaluates (no error in the viewport)")
    tris = int(m["preview"].split(" tris")[0].split()[-1])
    g.check(tris > 1000, f"the morph stage has a surface ({tris} triangles)")
    ed.fresh_map(6)
    during = ed.screenshot(os.path.join(work, "morph.png"))
    changed = g.differing_pixels(before, during, vx, vy, vw, vh)
    g.check(changed > 2000, f"the viewport shows the morph, not the creature alone ({changed} pixels differ)")

    ed.key("ctrl+z")
    m = ed.fresh_map()
    g.check(not m.get("viewport_note", ""), f"Ctrl+Z removes the morph ('{m.get('viewport_note')}')")
finally:
    ed.kill()
print("create morph: all checks passed")
