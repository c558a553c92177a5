#!/usr/bin/env python3
"""animorph-cli bake --mp4: the playblast of the demo morph read back with ffprobe has one frame
per baked frame at the asked size; --burn-in draws the frame number into the top-left corner (the
corner differs from the playblast without it, the rest of the first frame does not change much);
an odd --size is refused. Offscreen, no X server.

usage: playblast_check.py CLI DEMO_DIR"""
import os
import shutil
import subprocess
import sys
import tempfile

cli, demo = sys.argv[1], sys.argv[2]
if not shutil.which("ffmpeg") or not shutil.which("ffprobe"):
    print("SKIP: ffmpeg is not installed (run.sh installs it)")
    sys.exit(77)
env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
env["ANIMORPH_VALIDATION"] = "1"
env.setdefault("VK_ICD_FILENAMES", "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json")
work = tempfile.mkdtemp(prefix="animorph-playblast-")


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def bake(out, *extra):
    r = subprocess.run([cli, "bake", os.path.join(demo, "demo.animorph"), "--frames", "40:51", "--res", "24",
                        "--format", "none", "--mp4", out, *extra], capture_output=True, text=True, env=env,
                       timeout=300)
    print(r.stdout.strip())
    return r


def first_frame(mp4, png):
    subprocess.run(["ffmpeg", "-v", "error", "-y", "-i", mp4, "-frames:v", "1", png], check=True)
    return png


plain, burnt = os.path.join(work, "out", "plain.mp4"), os.path.join(work, "burnt.mp4")
r = bake(plain, "--size", "320x180")
if r.returncode != 0:
    fail(f"bake --mp4 exited {r.returncode}: {r.stderr}")
probe = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                        "stream=nb_read_frames,width,height", "-of", "csv=p=0", plain],
                       capture_output=True, text=True, check=True).stdout.strip()
if probe != "320,180,12":
    fail(f"ffprobe says width,height,frames = {probe}, expected 320,180,12")
print(f"ok: {plain}: 12 frames at 320x180")
if [f for f in os.listdir(os.path.dirname(plain)) if f != "plain.mp4"]:
    fail(f"temporary files left beside the playblast: {os.listdir(os.path.dirname(plain))}")

r = bake(burnt, "--size", "320x180", "--burn-in")
if r.returncode != 0:
    fail(f"bake --mp4 --burn-in exited {r.returncode}: {r.stderr}")
a, b = first_frame(plain, os.path.join(work, "a.png")), first_frame(burnt, os.path.join(work, "b.png"))


def differing(crop):
    out = subprocess.run(["compare", "-metric", "AE", "-fuzz", "10%", f"{a}[{crop}]", f"{b}[{crop}]", "null:"],
                         capture_output=True, text=True)
    return int(float(out.stderr.split()[0]))


corner, rest = differing("120x24+0+0"), differing("320x140+0+40")
if corner < 100 or rest > 50:
    fail(f"--burn-in: {corner} pixels differ in the corner (expected the frame number) and {rest} elsewhere")
print(f"ok: --burn-in draws the frame number ({corner} pixels in the corner, {rest} elsewhere)")

r = bake(os.path.join(work, "odd.mp4"), "--size", "321x180")
if r.returncode != 2 or "--size" not in r.stderr:
    fail(f"an odd --size should be refused: exit {r.returncode}, {r.stderr!r}")
shutil.rmtree(work)
print("ok")
