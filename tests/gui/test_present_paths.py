"""The ways frames reach the X window: on a CPU Vulkan device (lavapipe) the
editor renders into its own images and puts them into the window through MIT-SHM
(Swapchain's host presentation; ANIMORPH_PRESENT=copy copies them into the shared
segments on the CPU instead of importing the segments); ANIMORPH_PRESENT=wsi keeps
the Vulkan WSI. The
widget map names the path in use; the window's pixels, read back from the X
server, show the same editor either way (outside the status bar's timings),
also after a resize. Zero Vulkan validation errors. On an X server without
MIT-SHM the host path cannot run: the other checks are made, then the test
exits 77 (ctest: skipped), since the MIT-SHM path it names was not shown.

usage: test_present_paths.py EDITOR_BIN DEMO_DIR"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
work, project, doc = g.demo_copy(demo_dir, "animorph-gui-present-")


def capture(env_present, name):
    if env_present:
        os.environ["ANIMORPH_PRESENT"] = env_present
    else:
        os.environ.pop("ANIMORPH_PRESENT", None)
    os.makedirs(os.path.join(work, name), exist_ok=True)
    ed = g.Editor(editor_bin, project, workdir=os.path.join(work, name)).start()
    try:
        m = ed.fresh_map(6)
        shot = ed.screenshot(os.path.join(work, name + ".png"))
        # A smaller window: the targets follow the window size.
        g.xdo("windowsize", "--sync", ed.window, 1000, 640)
        m2 = ed.fresh_map(10)
        small = ed.screenshot(os.path.join(work, name + "-small.png"))
        g.xdo("key", "--clearmodifiers", "ctrl+q")  # (ed.key would wait for frames after it)
        code = ed.wait_exit()
        log = ed.read_log()
    finally:
        ed.kill()
    g.check(code == 0, f"{name}: the editor exits cleanly (code {code})")
    g.check("validation error" not in log, f"{name}: no Vulkan validation errors")
    return m, shot, m2, small


m_host, shot_host, m2_host, small_host = capture(None, "default")
m_wsi, shot_wsi, m2_wsi, small_wsi = capture("wsi", "wsi")
m_copy, shot_copy, m2_copy, small_copy = capture("copy", "copy")
print("present paths:", m_host.get("present"), "|", m_wsi.get("present"), "|", m_copy.get("present"), flush=True)
g.check(m_wsi.get("present", "").startswith("Vulkan WSI"), "ANIMORPH_PRESENT=wsi keeps the Vulkan WSI")
# The tests run on lavapipe (a CPU device): the default is MIT-SHM unless this X server lacks it.
no_shm = "no MIT-SHM" in m_host.get("present", "")
if not no_shm:
    g.check(m_host.get("present", "").startswith("MIT-SHM (host"), "on a CPU device the default puts frames through MIT-SHM")
    g.check(m_copy.get("present") == "MIT-SHM (host, copied)", "ANIMORPH_PRESENT=copy copies frames into the segments")

# The window's pixels as the X server has them: the same editor either way. The status bar
# (bottom 24 px: fps, frame time) differs between runs; the rest may differ in a few pixels of
# anti-aliased text that moved by the timings' width, never in the layout.
for a, b, w, h in ((shot_host, shot_wsi, 1600, 900), (small_host, small_wsi, 1000, 640),
                   (shot_copy, shot_wsi, 1600, 900), (small_copy, small_wsi, 1000, 640)):
    mean, sd = g.region_stats(a, 0, 0, w, h - 24)
    g.check(sd > 0.05, f"{os.path.basename(a)} shows the editor, not a blank window (grey sd {sd:.3f})")
    diff = g.differing_pixels(a, b, 0, 0, w, h - 24)
    g.check(diff < 0.01 * w * h, f"{os.path.basename(a)} and the WSI window agree ({diff} differing pixels)")
if no_shm:
    print("SKIP: " + m_host["present"] + ": the MIT-SHM host path was not exercised (the WSI checks passed)",
          flush=True)
    sys.exit(77)
