"""File > Export > Playblast... in the real editor: a short playblast of the demo morph (frames
40..51 at 640x360 with the burn-in) runs as a background job and writes an .mp4 that ffprobe reads
as 12 frames of 640x360, with the frame number and stage burnt into its corner; the settings are
saved in the project; a long playblast cancelled while its frames are being drawn and encoded
leaves no file (no .mp4, no temporary) and the editor stays responsive.

usage: test_playblast.py EDITOR_BIN DEMO_DIR"""
import json
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
if not shutil.which("ffmpeg") or not shutil.which("ffprobe"):
    print("SKIP: ffmpeg is not installed (run.sh installs it)")
    sys.exit(77)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
work, project, _ = g.demo_copy(demo_dir, "animorph-gui-playblast-")
out_dir = os.path.join(work, "out")
short_mp4 = os.path.join(out_dir, "short.mp4")
long_mp4 = os.path.join(out_dir, "long.mp4")


def open_playblast(ed):
    ed.click_widget("menu/File")
    ed.click_widget("menu/Export")
    ed.click_widget("menu/Playblast...")
    ed.widget("playblast/start")


def set_field(ed, key, text):
    ed.click_widget(key)
    ed.key("ctrl+a")
    ed.type_text(text)
    ed.key("Tab")


def probe(mp4):
    return subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                           "stream=width,height,nb_read_frames", "-of", "csv=p=0", mp4],
                          capture_output=True, text=True).stdout.strip()


ed = g.Editor(editor_bin, project, workdir=work).start()
try:
    ed.wait_until(lambda m: m["project"] == project, "the demo opens")
    open_playblast(ed)
    ed.click_widget("playblast/use_timeline")  # off: the frames below
    set_field(ed, "playblast/first", "40")
    set_field(ed, "playblast/last", "51")
    set_field(ed, "playblast/width", "640")
    set_field(ed, "playblast/height", "360")
    set_field(ed, "playblast/resolution", "24")
    set_field(ed, "playblast/output", short_mp4)
    ed.screenshot(os.path.join(os.environ.get("ANIMORPH_GUI_SHOTS", work), "playblast_dialog.png"))
    ed.click_widget("playblast/start")
    m = ed.wait_until(lambda m: m.get("job", "x") == "" and "Playblast:" in m["status"], "the playblast finishes",
                      timeout=180)
    got = probe(short_mp4)
    g.check(got == "640,360,12", f"{short_mp4}: ffprobe reads width,height,frames = {got!r}: {m['status']!r}")
    g.check(os.listdir(out_dir) == ["short.mp4"], f"nothing else in {out_dir}: {os.listdir(out_dir)}")
    # The first frame's corner holds the burn-in (white text on a dark box) and the rest does not.
    frame0 = os.path.join(work, "frame0.png")
    subprocess.run(["ffmpeg", "-v", "error", "-y", "-i", short_mp4, "-frames:v", "1", frame0], check=True)
    mean_corner, sd_corner = g.region_stats(frame0, 12, 12, 200, 20)
    g.check(sd_corner > 0.15, f"the corner of frame 40 has text in it (grey level sd {sd_corner:.2f})")
    ed.key("ctrl+s")
    with open(project) as f:
        saved = json.load(f)["playblast"]
    g.check(saved["first"] == 40 and saved["last"] == 51 and saved["width"] == 640 and saved["height"] == 360 and
            saved["output"] == short_mp4 and saved["burn_in"], f"the last settings are saved in the project: {saved}")

    # A long playblast (the whole demo at 1280x720) cancelled while frames are drawn and encoded.
    open_playblast(ed)
    g.check(ed.fresh_map()["widgets"].get("playblast/start") is not None, "the dialog opens with the saved settings")
    ed.click_widget("playblast/use_timeline")  # on: the timeline's 145 frames
    set_field(ed, "playblast/width", "1280")
    set_field(ed, "playblast/height", "720")
    set_field(ed, "playblast/resolution", "12")  # baking is quick: the cancel comes while drawing
    set_field(ed, "playblast/output", long_mp4)
    ed.click_widget("playblast/start")

    def drawing(m):
        parts = [f for f in os.listdir(out_dir) if f.startswith("long.mp4.part-")]
        return m.get("job") == "Playblast" and m["job_fraction"] > 0.0 and parts

    m = ed.wait_until(drawing, "the playblast draws and encodes frames (its temporary file exists)", timeout=120)
    g.check("job/cancel" in m["widgets"], f"the progress panel shows ({m['job_fraction']:.0%} done)")
    ed.screenshot(os.path.join(os.environ.get("ANIMORPH_GUI_SHOTS", work), "playblast_running.png"))
    ed.click_widget("job/cancel")
    m = ed.wait_until(lambda m: m.get("job", "x") == "", "the playblast ends after Cancel", timeout=60)
    g.check("cancelled" in m["status"], f"the status bar says so: {m['status']!r}")
    left = sorted(os.listdir(out_dir))
    g.check(left == ["short.mp4"], f"no file of the cancelled playblast is left in {out_dir}: {left}")
    before = m["current_frame"]
    ed.key("Right")
    m = ed.fresh_map()
    g.check(m["current_frame"] == before + 1, "the editor is responsive (Right steps a frame)")
    ed.key("ctrl+s")
    g.xdo("key", "--clearmodifiers", "ctrl+q")
    rc = ed.wait_exit()
    g.check(rc == 0, f"the editor quits cleanly with no validation errors (exit {rc})")
finally:
    ed.kill()
print("playblast: all checks passed")
