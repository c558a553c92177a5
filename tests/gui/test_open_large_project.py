"""Opening a large project runs off the UI thread: while it loads, the editor keeps presenting
frames and shows the job's progress panel; Cancel stops it and the editor keeps its (empty)
project; opened again and left alone, a smaller copy opens. The project is generated here: the
BlobTree demo creature repeated as thousands of hidden actors (tens of MB of JSON) and hundreds of
glTF actors, each of its own file.

usage: test_open_large_project.py EDITOR_BIN DEMO_DIR"""
import json
import os
import shutil
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
work = tempfile.mkdtemp(prefix="animorph-gui-large-")
for sub in ("editor", "editor2"):
    os.makedirs(os.path.join(work, sub))


def write_project(path, copies, characters):
    """copies of the BlobTree creature and `characters` glTF actors, each of its own file (links to
    the demo's creature.glb: each is loaded on its own)."""
    with open(os.path.join(demo_dir, "blob_demo.animorph")) as f:
        demo = json.load(f)
    creature = next(a for a in demo["actors"] if a.get("kind") == "blobtree")
    creature["id"] = creature["name"] = "@ID@"
    creature["visible"] = False
    one = json.dumps(creature)
    demo["actors"] = []
    folder = os.path.dirname(path)
    for i in range(characters):
        name = f"character{i}.glb"
        if not os.path.exists(os.path.join(folder, name)):
            os.symlink(os.path.join(os.path.abspath(demo_dir), "creature.glb"), os.path.join(folder, name))
        demo["actors"].append({"id": f"character{i}", "asset": name, "visible": False})
    head = json.dumps(demo)
    cut = head.index('"actors": [') + len('"actors": [')
    with open(path, "w") as f:
        f.write(head[:cut])
        if characters:
            f.write(head[cut:head.index("]", cut)] + ",")
            cut = head.index("]", cut)
        f.write(",".join(one.replace("@ID@", f"blob{i}") for i in range(copies)))
        f.write(head[cut:])
    return os.path.getsize(path)


large = os.path.join(work, "large.animorph")
small = os.path.join(work, "small.animorph")
size = write_project(large, 3000, 400)
write_project(small, 30, 3)
print(f"generated {large}: {size / 1e6:.0f} MB", flush=True)

ed = g.Editor(editor_bin, large, workdir=os.path.join(work, "editor")).start()
try:
    # Past the start-up frames (drawn whatever happens), the frames come from the job's redraws.
    m = ed.wait_until(lambda m: m.get("job", "").startswith("Open large") and m["frame_count"] >= 12,
                      "the open job runs", timeout=30)
    f0, t0 = m["frame_count"], time.monotonic()
    m = ed.wait_until(lambda m: m["frame_count"] >= f0 + 5, "frames presented while the project loads", timeout=10)
    g.check(m.get("job", "") != "", f"{m['frame_count'] - f0} frames in {time.monotonic() - t0:.1f} s while the "
            f"job runs ({m['job_fraction']:.0%} done)")
    g.check("job/cancel" in m["widgets"] and "job/progress" in m["widgets"], "the progress panel shows with Cancel")
    ed.screenshot(os.path.join(work, "loading.png"))
    ed.click_widget("job/cancel")
    m = ed.wait_until(lambda m: m.get("job", "x") == "", "the job ends after Cancel", timeout=60)
    g.check("cancelled" in m["status"], f"the status bar says so: {m['status']!r}")
    g.check(m["project"] == "" and not m["dirty"], "the editor keeps its empty, untitled project")
    ed.key("ctrl+o")  # still responsive: Open shows the file browser
    ed.widget("file_browser/path")
    g.xdo("key", "--clearmodifiers", "Escape")
    ed.fresh_map()

    ed.kill()
    ed = g.Editor(editor_bin, small, workdir=os.path.join(work, "editor2")).start()
    m = ed.wait_until(lambda m: m["project"] == small, "the smaller project opens", timeout=60)
    g.check(m.get("job", "") == "" and "Opened" in m["status"], f"opened as a job: {m['status']!r}")
    g.xdo("key", "--clearmodifiers", "ctrl+q")
    rc = ed.wait_exit()
    g.check(rc == 0, f"the editor quits cleanly with no validation errors (exit {rc})")
finally:
    ed.kill()
shutil.rmtree(work, ignore_errors=True)
print("open large project: all checks passed")
