"""A lost GPU device in the editor (a driver reset; simulated, since lavapipe never loses its
device: ANIMORPH_DEBUG_DEVICE_LOST_FILE makes the swapchain's wait report VK_ERROR_DEVICE_LOST once
the file exists). The unsaved work is autosaved at once, the editor remakes its whole Vulkan side
and goes on drawing the same picture, says so in the status bar, keeps the edit and its undo, and
quits cleanly with no validation errors.

usage: test_device_lost.py EDITOR_BIN DEMO_DIR"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
work, project, original = g.demo_copy(sys.argv[2], "animorph-gui-lost-")
# The editor loses its device at the first frame after this file appears.
trigger = os.environ["ANIMORPH_DEBUG_DEVICE_LOST_FILE"] = os.path.join(work, "lose-the-device")
ed = g.Editor(sys.argv[1], project, workdir=work).start()
try:
    actor = original["actors"][0]["id"]
    ed.click_widget(f"outliner/{actor}")
    sx0, sy0, sx1, sy1 = ed.widget("inspector/speed")
    ed.drag(sx0 + 10, (sy0 + sy1) / 2, sx0 + 110, (sy0 + sy1) / 2)
    m = ed.fresh_map()
    g.check(m["dirty"], "an unsaved edit (the first actor's speed)")
    autosave = project + ".autosave"
    # A timed autosave may already have run (5 s after the first edit, on a slow machine): remove
    # it, so the file checked below is the one written when the device is lost.
    if os.path.exists(autosave):
        os.remove(autosave)
    before = ed.screenshot(os.path.join(work, "before.png"))

    open(trigger, "w").close()
    ed.key("Right")
    ed.key("Left")  # back to the same frame: the same picture
    m = ed.wait_until(lambda m: "device was lost" in m.get("status", ""), "the status bar reports the lost device")
    g.check("renderer was recreated" in m["status"] and "autosaved" in m["status"], f"status: {m['status']!r}")
    g.check(os.path.exists(autosave), "the unsaved work was autosaved when the device was lost")
    g.check(m["dirty"] and m["selected"] == actor, "the document, its edit and the selection are kept")
    frames = m["frame_count"]
    after = ed.screenshot(os.path.join(work, "after.png"))
    g.check(ed.fresh_map()["frame_count"] > frames, "the editor draws frames on the new device")
    w, h = 1600, 900
    # Everything but the status bar (its message and timings differ) is drawn again as before.
    diff = g.differing_pixels(before, after, 0, 0, w, h - 24)
    g.check(diff < 0.01 * w * h, f"the window after recovery matches the one before ({diff} differing pixels)")
    mean, std = g.region_stats(after, *m["viewport"])
    g.check(std > 0.02, f"the viewport shows the scene (grey-level deviation {std:.3f})")
    ed.key("ctrl+z")
    g.check(not ed.fresh_map()["dirty"], "the undo history survived: Ctrl+Z undoes the edit")
    g.xdo("key", "--clearmodifiers", "ctrl+q")  # clean again: quits without a prompt
    rc = ed.wait_exit()
    g.check(rc == 0, f"the editor quits cleanly with no validation errors (exit {rc})")
    log = ed.read_log()
    g.check("the GPU device was lost" in log, "the log names the lost device")
finally:
    ed.kill()
