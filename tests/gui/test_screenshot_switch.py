"""The command-line switches a script uses to capture the editor (--frame N --screenshot FILE
--quit) wait for the project given on the command line, which opens as a background job: the
screenshot shows that project at frame N, not the empty editor of the first frames."""
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
editor, demo_dir = sys.argv[1], sys.argv[2]
project = os.path.join(demo_dir, "animorphosis.animorph")
work = tempfile.mkdtemp(prefix="animorph-gui-shot-")


def capture(frame):
    png = os.path.join(work, f"frame{frame}.png")
    env = dict(os.environ, XDG_CONFIG_HOME=os.path.join(work, "config"), HOME=work)
    env.setdefault("ANIMORPH_VALIDATION", "1")
    env.setdefault("VK_ICD_FILENAMES", "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json")
    run = subprocess.run([editor, project, "--frame", str(frame), "--screenshot", png, "--quit", "--size", "1600x900"],
                         env=env, capture_output=True, text=True, timeout=180)
    g.check(run.returncode == 0, f"the editor exits 0 after the screenshot of frame {frame} ({run.stderr[-300:]!r})")
    g.check(os.path.exists(png), f"it wrote {png}")
    return png


early, late = capture(24), capture(180)
# Before the project is open both would show the same empty grid (the bug: 0 pixels differ).
changed = g.differing_pixels(early, late, 260, 40, 1000, 660)
g.check(changed > 5000, f"the viewport shows the dinosaur at 24 and the dragon at 180 ({changed} pixels differ)")
print("PASS", flush=True)
