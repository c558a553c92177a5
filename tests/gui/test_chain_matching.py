"""The inspector's chain matching for a skeleton-correspondence morph, in the real
editor: open the demo (nothing selected: the inspector edits the morph), open
*Chain matching*, and find one row per chain of each rig -- as many as
`animorph-cli correspond --json` lists -- with the pairing drawn (a screenshot of
the inspector that is not blank there). Zero Vulkan validation errors at exit.

usage: test_chain_matching.py EDITOR_BIN DEMO_DIR"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
cli = os.path.join(os.path.dirname(editor_bin), "animorph-cli")
work = tempfile.mkdtemp(prefix="animorph-gui-chains-")
for name in ("demo.animorph", "creature.glb", "gear.glb"):
    shutil.copy(os.path.join(demo_dir, name), work)
project = os.path.join(work, "demo.animorph")
listed = json.loads(subprocess.run([cli, "correspond", project, "--json"], capture_output=True, text=True,
                                   check=True, timeout=120).stdout)
want = {"source": len(listed["source_chains"]), "target": len(listed["target_chains"])}

ed = g.Editor(editor_bin, project, workdir=work).start()
try:
    ed.click_widget("morph/chains")
    m = ed.wait_until(lambda m: "morph/chains/target/0" in m.get("widgets", {}), "the chain tables", timeout=60)
    for role, n in want.items():
        rows = [k for k in m["widgets"] if k.startswith(f"morph/chains/{role}/")]
        g.check(len(rows) == n, f"{role}: {len(rows)} rows for the {n} chains `correspond` lists")
    x0, y0, x1, _ = m["widgets"]["morph/chains/source/0"]
    _, _, _, y3 = m["widgets"][f"morph/chains/target/{want['target'] - 1}"]
    shot = ed.screenshot(os.path.join(work, "chains.png"))
    mean, sd = g.region_stats(shot, x0, y0, x1 - x0, y3 - y0)
    g.check(sd > 0.02, f"the pairing is drawn (grey-level sd {sd:.3f} over the rows)")
    g.xdo("key", "--clearmodifiers", "ctrl+q")
    rc = ed.wait_exit()
    g.check(rc == 0, f"the editor exits cleanly, no validation errors (status {rc})")
    print(f"ok: chain matching shows {want['source']} source and {want['target']} target chains")
finally:
    ed.kill()
    shutil.rmtree(work, ignore_errors=True)
