"""File > Export > Meshes and Volumes... in the real editor: the demo morph exported as a PLY sequence at a high
resolution is cancelled from the progress panel: no output file is left and the editor stays
responsive; a short glTF export then runs to the end and writes its file; the settings are kept
in the saved project; OpenVDB level sets of two frames are written.

usage: test_export_dialog.py EDITOR_BIN DEMO_DIR"""
import json
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

g.ensure_display(sys.argv)
editor_bin, demo_dir = sys.argv[1], sys.argv[2]
work, project, _ = g.demo_copy(demo_dir, "animorph-gui-export-")
frames_dir = os.path.join(work, "frames")
glb = os.path.join(work, "out", "morph.glb")


def open_export(ed):
    ed.click_widget("menu/File")
    ed.click_widget("menu/Export")
    ed.click_widget("menu/Meshes and Volumes...")
    ed.widget("export/export")


def set_field(ed, key, text):
    ed.click_widget(key)
    ed.key("ctrl+a")
    ed.type_text(text)
    ed.key("Tab")


ed = g.Editor(editor_bin, project, workdir=work).start()
try:
    ed.wait_until(lambda m: m["project"] == project, "the demo opens")
    open_export(ed)
    ed.click_widget("export/format")
    ed.click_widget("export/format/ply")
    set_field(ed, "export/resolution", "320")  # seconds of work even on an idle machine: time to cancel
    set_field(ed, "export/output", frames_dir)
    ed.screenshot(os.path.join(work, "dialog.png"))
    ed.click_widget("export/export")
    m = ed.wait_until(lambda m: m.get("job") == "Export" and m["job_fraction"] > 0.0, "the export makes progress",
                      timeout=60)
    g.check("job/cancel" in m["widgets"], f"the progress panel shows ({m['job_fraction']:.0%} done)")
    ed.screenshot(os.path.join(work, "exporting.png"))
    ed.click_widget("job/cancel")
    m = ed.wait_until(lambda m: m.get("job", "x") == "", "the export ends after Cancel", timeout=60)
    g.check("cancelled" in m["status"], f"the status bar says so: {m['status']!r}")
    left = os.listdir(frames_dir) if os.path.isdir(frames_dir) else []
    g.check(left == [], f"no file left in {frames_dir}: {left}")
    before = m["current_frame"]
    ed.key("Right")
    m = ed.fresh_map()
    g.check(m["current_frame"] == before + 1, "the editor is responsive (Right steps a frame)")

    # A short glTF export runs to the end.
    open_export(ed)
    ed.click_widget("export/format")
    ed.click_widget("export/format/gltf")
    ed.click_widget("export/use_timeline")
    set_field(ed, "export/first", "40")
    set_field(ed, "export/last", "44")
    set_field(ed, "export/resolution", "24")
    set_field(ed, "export/output", glb)
    ed.click_widget("export/export")
    m = ed.wait_until(lambda m: m.get("job", "x") == "" and "Exported" in m["status"], "the export finishes",
                      timeout=120)
    g.check(os.path.getsize(glb) > 1000, f"{glb} written ({os.path.getsize(glb)} bytes): {m['status']!r}")
    ed.key("ctrl+s")
    with open(project) as f:
        saved = json.load(f)["export"]
    g.check(saved["format"] == "gltf" and saved["first"] == 40 and saved["last"] == 44 and saved["output"] == glb,
            f"the last settings are saved in the project: {saved}")

    # OpenVDB level sets of two B->C frames (the format comes from the shared format table).
    vdb_dir = os.path.join(work, "vdb")
    open_export(ed)
    ed.click_widget("export/format")
    ed.click_widget("export/format/vdb")
    set_field(ed, "export/first", "60")
    set_field(ed, "export/last", "61")
    set_field(ed, "export/output", vdb_dir)
    ed.screenshot(os.path.join(os.environ.get("ANIMORPH_GUI_SHOTS", work), "dialog_vdb.png"))
    ed.click_widget("export/export")
    want = ["demo_0060.vdb", "demo_0061.vdb"]
    m = ed.wait_until(lambda m: m.get("job", "x") == "" and os.path.isdir(vdb_dir) and sorted(os.listdir(vdb_dir)) == want,
                      "the VDB export writes a level set per frame", timeout=120)
    g.check(all(os.path.getsize(os.path.join(vdb_dir, f)) > 1000 for f in want), f"{want} written: {m['status']!r}")
    ed.key("ctrl+s")  # the export's settings are a change of the project
    g.xdo("key", "--clearmodifiers", "ctrl+q")
    rc = ed.wait_exit()
    g.check(rc == 0, f"the editor quits cleanly with no validation errors (exit {rc})")
finally:
    ed.kill()
print("export dialog: all checks passed")
