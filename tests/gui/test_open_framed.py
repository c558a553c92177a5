"""Opening a character frames it, as F does, whatever its units, size and place: `animorph FILE`
with an FBX thousands of units tall (assimp-testmodels' animation_with_skeleton.fbx, 7,000 cm
across), a Blender FBX in centimetres and a glTF 1,800 units tall standing 36 km from the origin
(a Blender glTF of the test characters under a root scaled 1000x and moved away). For each, the
character's pixels -- the screenshot against the same view with the actor hidden -- touch no
border of the viewport and cover at least 0.5 % of it, with a bounding box at least 40 % of the
viewport's height or width; the timeline spans the character's clip.

usage: test_open_framed.py EDITOR_BIN DEMO_DIR [TEST_CHARACTERS_DIR]
(default: BUILD/test_characters, where the fixture writes them, BUILD holding app/animorph)"""
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
characters = sys.argv[3] if len(sys.argv) > 3 else \
    os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(editor_bin))), "test_characters")
models = "/usr/share/assimp/models"
fbx = os.path.join(models, "FBX", "animation_with_skeleton.fbx")
humanoid_glb = os.path.join(characters, "humanoid_m.glb")
humanoid_cm = os.path.join(characters, "humanoid_cm.fbx")
for needed in (fbx, humanoid_glb, humanoid_cm):
    if not os.path.exists(needed):
        print(f"SKIP: {needed} is missing (assimp-testmodels, or the test characters made with Blender)")
        sys.exit(77)
work = tempfile.mkdtemp(prefix="animorph-gui-open-framed-")


def far_and_tall(src, dst, scale, offset):
    """A copy of a GLB whose scene hangs under a new root node scaled and moved (JSON chunk rewritten)."""
    data = open(src, "rb").read()
    json_len = struct.unpack_from("<I", data, 12)[0]
    doc = json.loads(data[20:20 + json_len])
    rest = data[20 + json_len:]
    scene = doc["scenes"][doc.get("scene", 0)]
    doc["nodes"].append({"name": "far_root", "scale": [scale] * 3, "translation": offset,
                         "children": scene["nodes"]})
    scene["nodes"] = [len(doc["nodes"]) - 1]
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    out = struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(text) + len(rest)) + struct.pack("<I4s", len(text), b"JSON")
    with open(dst, "wb") as f:
        f.write(out + text + rest)
    return dst


def character_mask(shot, empty, vx, vy, vw, vh, inset=3):
    """Pixels of the viewport (less an inset for its frame) that differ between the two shots:
    (count, (x, y, w, h) of their bounding box, pixels on the inset border)."""
    x, y, w, h = int(vx) + inset, int(vy) + inset, int(vw) - 2 * inset, int(vh) - 2 * inset
    mask = shot + ".mask.png"
    subprocess.run(["convert", shot, empty, "-crop", f"{w}x{h}+{x}+{y}", "+repage", "-compose", "difference",
                    "-composite", "-colorspace", "Gray", "-threshold", "4%", mask], check=True)
    out = subprocess.run(["convert", mask, "-format", "%[fx:mean*w*h] %@", "info:"], capture_output=True, text=True,
                         check=True).stdout.split()
    count = int(float(out[0]))
    bw, rest = out[1].split("x")
    bh, bx, by = rest.split("+")
    border = 0
    for crop in (f"{w}x2+0+0", f"{w}x2+0+{h - 2}", f"2x{h}+0+0", f"2x{h}+{w - 2}+0"):
        s = subprocess.run(["convert", mask, "-crop", crop, "+repage", "-format", "%[fx:mean*w*h]", "info:"],
                           capture_output=True, text=True, check=True).stdout
        border += int(float(s))
    return count, (int(bx), int(by), int(bw), int(bh)), border, (w, h)


def check_framed(path, label, clip_seconds=None):
    name = os.path.basename(path)
    os.makedirs(os.path.join(work, label))
    ed = g.Editor(editor_bin, path, workdir=os.path.join(work, label)).start()
    try:
        m = ed.wait_until(lambda m: name in m.get("status", "") and m.get("selected", "") != "",
                          f"{name} is imported and selected", timeout=60)
        vx, vy, vw, vh = m["viewport"]
        if clip_seconds:
            fps, end = m.get("fps", 24), m.get("frame_end", 0)
            g.check(abs(end - clip_seconds * fps) <= 1.5,
                    f"{label}: the timeline spans the clip ({end} frames at {fps} fps for {clip_seconds} s)")
        shot = ed.screenshot(os.path.join(work, label + ".png"))
        # The same view without the character: its outliner eye hides it (the camera stays).
        ed.click_widget(f"outliner/{m['selected']}/visible")
        empty = ed.screenshot(os.path.join(work, label + "_empty.png"))
        count, box, border, (w, h) = character_mask(shot, empty, vx, vy, vw, vh)
        share = count / float(w * h)
        print(f"{label}: {count} character pixels ({100 * share:.1f} % of the viewport {w}x{h}), box {box}, "
              f"{border} on the border")
        g.check(border == 0, f"{label}: the character touches no border of the viewport ({border} pixels do)")
        # Framed, not a speck: a thin character (animation_with_skeleton.fbx is a long tube) covers
        # little area, so the share is of pixels and of the viewport's width or height its box spans.
        g.check(share >= 0.005, f"{label}: the character covers at least 0.5 % of the viewport ({100 * share:.1f} %)")
        g.check(box[3] >= 0.4 * h or box[2] >= 0.4 * w,
                f"{label}: its bounding box spans 40 % of the viewport's height or width ({box} in {w}x{h})")
        ed.key("ctrl+q")
        ed.widget("prompt/dont_save")
        ed.click_widget("prompt/dont_save", wait=False)
        rc = ed.wait_exit()
        g.check(rc == 0, f"{label}: the editor quits cleanly with no validation errors (exit {rc})")
    finally:
        ed.kill()


far = far_and_tall(humanoid_glb, os.path.join(work, "far_giant.glb"), 1000.0, [30000.0, 2000.0, -20000.0])
check_framed(fbx, "fbx_7000_units", clip_seconds=20 / 24)
check_framed(shutil.copy(humanoid_cm, os.path.join(work, "humanoid_cm.fbx")), "fbx_centimetres", clip_seconds=39 / 24)
check_framed(far, "glb_far_and_tall")
shutil.rmtree(work, ignore_errors=True)
print("open framed: all checks passed")
