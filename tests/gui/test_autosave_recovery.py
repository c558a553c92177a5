"""Autosave and recovery in the real editor: an edit is autosaved a few seconds after it is made
(Document::kFirstAutosaveDelaySec, 5 s; not the minute of the autosave interval), the editor is
then killed (SIGKILL: a crash), and the next start on the same project offers the autosave;
Recover opens it with the edit, unsaved, while the project file itself is untouched.

usage: test_autosave_recovery.py EDITOR_BIN DEMO_DIR"""
import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
work, project, original = g.demo_copy(sys.argv[2], "animorph-gui-autosave-")
with open(project, "rb") as f:
    original_bytes = f.read()
autosave = project + ".autosave"
actor = original["actors"][0]["id"]
speed0 = original["actors"][0]["speed"]

ed = g.Editor(sys.argv[1], project, workdir=work).start()
try:
    ed.click_widget(f"outliner/{actor}")
    sx0, sy0, sx1, sy1 = ed.widget("inspector/speed")
    ed.drag(sx0 + 10, (sy0 + sy1) / 2, sx0 + 110, (sy0 + sy1) / 2)
    edited = time.monotonic()
    g.check(ed.fresh_map()["dirty"], "an unsaved edit (the first actor's speed)")
    while not os.path.exists(autosave) and time.monotonic() - edited < 40:
        time.sleep(0.1)
    waited = time.monotonic() - edited
    g.check(os.path.exists(autosave), f"the edit is autosaved ({waited:.1f} s after it)")
    g.check(waited < 15, f"the autosave comes a few seconds after the first unsaved edit, not a minute "
                         f"({waited:.1f} s)")
    time.sleep(0.5)  # the autosave is written atomically: once it exists it is whole
    with open(autosave) as f:
        saved = json.load(f)
    speed1 = saved["actors"][0]["speed"]
    g.check(speed1 != speed0, f"the autosave holds the edit (speed {speed0} -> {speed1})")
    ed.kill()  # SIGKILL: no chance to save or clean up
    g.check(os.path.exists(autosave), "the autosave outlives the killed editor")
    with open(project, "rb") as f:
        g.check(f.read() == original_bytes, "the project file is untouched")

    ed = g.Editor(sys.argv[1], project, workdir=work).start()
    ed.click_widget("prompt/recover")
    m = ed.wait_until(lambda m: "Recovered" in m.get("status", ""), "the editor recovers the autosave")
    g.check(m["dirty"], "the recovered project is unsaved (dirty)")
    ed.click_widget(f"outliner/{actor}")
    ed.key("ctrl+s")
    ed.wait_until(lambda m: not m["dirty"], "Ctrl+S saves the recovered project")
    with open(project) as f:
        g.check(json.load(f)["actors"][0]["speed"] == speed1, "saving keeps the recovered edit")
    g.xdo("key", "--clearmodifiers", "ctrl+q")
    rc = ed.wait_exit()
    g.check(rc == 0, f"the editor quits cleanly with no validation errors (exit {rc})")
    g.check(not os.path.exists(autosave), "no autosave is left once the project is saved")
finally:
    ed.kill()
