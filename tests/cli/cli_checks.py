#!/usr/bin/env python3
"""End-to-end checks of animorph-cli info / make-demo.

usage: cli_checks.py MODE CLI [ARGS...]
  info-json CLI FILE JOINTS CLIP DURATION   info --json on a glTF: counts, clip and report (exit 77: skipped
                                            when FILE, a shared asset, is not there)
  info-bad CLI FILE REASON [--absent]       info on a bad file: non-zero exit, stderr names the file and
                                            REASON; the file must exist (exit 77: skipped when it does not,
                                            so a malformed file never turns into a missing one) unless
                                            --absent, where it must not
  make-demo CLI RESOURCES_DIR               make-demo into a temp dir, then info on what it wrote;
                                            the committed resources/demo must match the generator
  new-info CLI                              new creature -> gear, then info --json: markers, timeline
  new-align CLI ASSETS_DIR                  new with a much larger source (tentacle.glb) says it aligned
                                            the target (exit 77: skipped without the shared asset)
  fit CLI                                   fit the demo creature: report printed, stand-in file loads
  bake CLI                                  bake a few frames per stage: file names (demo_####.ply), binary PLY headers,
                                            same bytes for --jobs 1 and --jobs 2
  gpu CLI RESOURCES_DIR                     bake --gpu: morph frames as the CPU's (triangle counts within
                                            0.5 %, every vertex of either within GPU_SURFACE_DISTANCE
                                            median edges of the other's surface), other stages
                                            byte-identical; with no Vulkan device bake --gpu and
                                            polygonize --gpu exit 1 naming the reason
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mesh_distance import SurfaceGrid, farthest_vertex, median_edge_length, read_ply_mesh  # noqa: E402

# bake --gpu's B->C frames against the CPU's: every vertex of either within this many median edge
# lengths (about a grid cell) of the other's surface (measured on lavapipe: under 0.0001; a GPU mesh
# shifted by a quarter cell, whose triangle counts all agree, is 0.24 off).
GPU_SURFACE_DISTANCE = 0.05


def run(cli, *args):
    return subprocess.run([cli, *args], capture_output=True, text=True, timeout=120)


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def blender_or_skip():
    """The blender program; exits 77 (ctest: skipped) when it is not installed."""
    blender = shutil.which("blender")
    if not blender:
        print("blender not installed: skipped")
        sys.exit(77)
    return blender


def run_blender(blender, script, *args, timeout=600):
    """Runs SCRIPT inside Blender headless with ARGS after '--'. Debian's Blender embeds the system
    Python and finds its standard library (and numpy) through the first python3 on PATH: a
    pyenv/venv one must not shadow it."""
    env = dict(os.environ, PATH=os.pathsep.join(["/usr/bin", "/bin", os.environ.get("PATH", "")]))
    env.pop("PYTHONHOME", None)
    env.pop("PYTHONPATH", None)
    return subprocess.run([blender, "-b", "--factory-startup", "-P", script, "--", *args],
                          capture_output=True, text=True, timeout=timeout, env=env)


def info_json(cli, path):
    r = run(cli, "info", path, "--json")
    if r.returncode != 0:
        fail(f"info --json {path} exited {r.returncode}: {r.stderr}")
    try:
        return json.loads(r.stdout)
    except json.JSONDecodeError as e:
        fail(f"info --json {path} printed invalid JSON ({e}): {r.stdout[:200]}")


def check_character_json(d, path):
    for key in ("vertices", "triangles", "joints", "meshes", "skins", "animations", "report"):
        if key not in d:
            fail(f"{path}: JSON lacks '{key}'")
    for key in ("warnings", "unsupported", "weights_normalised"):
        if key not in d["report"]:
            fail(f"{path}: JSON report lacks '{key}'")
    if d["vertices"] <= 0 or d["triangles"] <= 0:
        fail(f"{path}: no geometry: {d['vertices']} vertices, {d['triangles']} triangles")


def skip(reason):
    """Exits 77: ctest reports the test as skipped (SKIP_RETURN_CODE), not passed."""
    print(f"SKIP: {reason}")
    sys.exit(77)


def mode_info_json(cli, path, joints, clip, duration):
    if not os.path.isfile(path):
        skip(f"{path} not present (a shared asset)")
    d = info_json(cli, path)
    check_character_json(d, path)
    if d["joints"] != int(joints):
        fail(f"{path}: {d['joints']} joints, expected {joints}")
    names = [a["name"] for a in d["animations"]]
    if clip not in names:
        fail(f"{path}: clips {names}, expected {clip}")
    got = next(a["duration"] for a in d["animations"] if a["name"] == clip)
    if abs(got - float(duration)) > 1e-3:
        fail(f"{path}: {clip} lasts {got} s, expected {duration}")
    # The human summary names the same figures.
    r = run(cli, "info", path)
    if r.returncode != 0 or f"{d['triangles']} triangles" not in r.stdout or clip not in r.stdout:
        fail(f"human summary of {path} is missing figures: {r.stdout}")


def mode_info_bad(cli, path, reason, *flags):
    absent = "--absent" in flags
    if not absent and not os.path.isfile(path):
        skip(f"{path} not present (Debian package assimp-testmodels): the malformed file is not checked")
    if absent and os.path.exists(path):
        fail(f"{path} exists: it cannot stand for a missing file")
    r = run(cli, "info", path)
    if r.returncode == 0:
        fail(f"info {path} succeeded on a bad file")
    if os.path.basename(path) not in r.stderr:
        fail(f"stderr does not name the file: {r.stderr!r}")
    if reason not in r.stderr:
        fail(f"stderr does not give the reason {reason!r}: {r.stderr!r}")
    if r.stdout.strip():
        fail(f"error output went to stdout: {r.stdout!r}")
    print(r.stderr.strip())


def mode_make_demo(cli, resources):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "demo")
        r = run(cli, "make-demo", out)
        if r.returncode != 0:
            fail(f"make-demo exited {r.returncode}: {r.stderr}")
        for name in ("creature.glb", "gear.glb", "demo.animorph"):
            if not os.path.isfile(os.path.join(out, name)):
                fail(f"make-demo did not write {name}")
        creature = info_json(cli, os.path.join(out, "creature.glb"))
        check_character_json(creature, "creature.glb")
        if creature["joints"] < 10 or [a["name"] for a in creature["animations"]] != ["walk"]:
            fail(f"creature: {creature['joints']} joints, clips {creature['animations']}")
        gear = info_json(cli, os.path.join(out, "gear.glb"))
        check_character_json(gear, "gear.glb")
        if gear["joints"] < 2 or gear["report"]["warnings"]:
            fail(f"gear: {gear}")
        project = info_json(cli, os.path.join(out, "demo.animorph"))
        if project["fps"] != 24 or project["frame_start"] != 0:
            fail(f"project timeline: {project}")
        walk = creature["animations"][0]["duration"]
        span = (project["frame_end"] - project["frame_start"]) / project["fps"]
        if span < 2 * walk - 1e-6:
            fail(f"timeline covers {span} s, less than two walk cycles of {walk} s")
        actors = {a["id"]: a for a in project["actors"]}
        if set(actors) != {"creature", "gear"} or not all(a["loads"] for a in actors.values()):
            fail(f"project actors: {project['actors']}")
        r = run(cli, "info", os.path.join(out, "demo.animorph"))
        if r.returncode != 0 or "creature.glb" not in r.stdout or "24 fps" not in r.stdout:
            fail(f"human project summary: {r.stdout}")
        # The committed demo must be what the generator writes today.
        for name, fresh in (("creature.glb", creature), ("gear.glb", gear)):
            committed = info_json(cli, os.path.join(resources, name))
            for key in ("vertices", "triangles", "joints", "animations"):
                if committed[key] != fresh[key]:
                    fail(f"resources/demo/{name} is stale ({key}: {committed[key]} vs {fresh[key]}); "
                         "run animorph-cli make-demo resources/demo")
        committed = info_json(cli, os.path.join(resources, "demo.animorph"))
        if not all(a["loads"] for a in committed["actors"]):
            fail(f"resources/demo/demo.animorph has actors that do not load: {committed['actors']}")
        # A missing directory argument is a usage error.
        if run(cli, "make-demo").returncode == 0:
            fail("make-demo without DIR succeeded")


def make_demo_dir(cli, tmp):
    out = os.path.join(tmp, "demo")
    r = run(cli, "make-demo", out)
    if r.returncode != 0:
        fail(f"make-demo exited {r.returncode}: {r.stderr}")
    return out


def mode_new_info(cli):
    with tempfile.TemporaryDirectory() as tmp:
        demo = make_demo_dir(cli, tmp)
        proj = os.path.join(tmp, "sub", "m.animorph")
        os.makedirs(os.path.dirname(proj))
        r = run(cli, "new", os.path.join(demo, "creature.glb"), os.path.join(demo, "gear.glb"), "-o", proj)
        if r.returncode != 0:
            fail(f"new exited {r.returncode}: {r.stderr}")
        if "stand-in" not in r.stdout or "wrote" not in r.stdout:
            fail(f"new did not report the stand-ins: {r.stdout}")
        d = info_json(cli, proj)
        if d["fps"] != 24 or d["frame_start"] != 0 or d["frame_end"] != 144:
            fail(f"timeline: {d}")
        if d.get("markers") != {"A": 24, "B": 48, "C": 84, "D": 108}:
            fail(f"markers: {d.get('markers')}")
        if d["morph"]["source"] != "creature" or d["morph"]["target"] != "gear":
            fail(f"morph: {d['morph']}")
        if not all(a["loads"] for a in d["actors"]):
            fail(f"actors do not load from the project's directory: {d['actors']}")
        # Bad input: a missing file is named.
        r = run(cli, "new", os.path.join(tmp, "missing.glb"), os.path.join(demo, "gear.glb"), "-o", proj)
        if r.returncode == 0 or "missing.glb" not in r.stderr:
            fail(f"new with a missing file: {r.returncode} {r.stderr}")


def mode_new_align(cli, assets):
    """Very different sizes: the target is aligned to the source, and new says so."""
    tentacle = os.path.join(assets, "tentacle.glb")
    if not os.path.isfile(tentacle):
        skip(f"{tentacle} not present (a shared asset)")
    with tempfile.TemporaryDirectory() as tmp:
        demo = make_demo_dir(cli, tmp)
        r = run(cli, "new", tentacle, os.path.join(demo, "gear.glb"), "-o", os.path.join(tmp, "t.animorph"))
        if r.returncode != 0 or "aligned the target" not in r.stdout:
            fail(f"new tentacle -> gear did not align: {r.returncode} {r.stdout} {r.stderr}")


def mode_fit(cli):
    with tempfile.TemporaryDirectory() as tmp:
        demo = make_demo_dir(cli, tmp)
        out = os.path.join(tmp, "creature.standin.json")
        r = run(cli, "fit", os.path.join(demo, "creature.glb"), "-o", out)
        if r.returncode != 0 or "fit error" not in r.stdout or "segments" not in r.stdout:
            fail(f"fit: {r.returncode} {r.stdout} {r.stderr}")
        with open(out) as f:
            d = json.load(f)
        if d["format"] != "animorph-standin" or len(d["standin"]["segments"]) < 10:
            fail(f"stand-in file: {str(d)[:300]}")
        if not d["report"]["mean_error"] < 0.05:
            fail(f"fit error too large: {d['report']}")


PLY_SIZES = {"char": 1, "uchar": 1, "short": 2, "ushort": 2, "int": 4, "uint": 4, "float": 4, "double": 8}


def read_ply_header(path):
    """(vertices, faces) of a binary little-endian PLY whose body is exactly its vertices (any
    properties: floats, uchar colours) and its triangles (a uchar count, three 32-bit indices)."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.find(b"end_header\n")
    if not data.startswith(b"ply\nformat binary_little_endian 1.0\n") or end < 0:
        fail(f"{path}: not a binary little-endian PLY")
    header = data[:end].decode("ascii").split("\n")
    verts = faces = None
    stride = 0
    for line in header:
        if line.startswith("element vertex "):
            verts = int(line.split()[2])
        elif line.startswith("element face "):
            faces = int(line.split()[2])
        elif line.startswith("property ") and not line.startswith("property list") and faces is None:
            stride += PLY_SIZES[line.split()[1]]
    body = len(data) - end - len("end_header\n")
    if verts is None or faces is None or verts <= 0 or faces <= 0:
        fail(f"{path}: header counts {verts} vertices, {faces} faces")
    if body != verts * stride + faces * 13:
        fail(f"{path}: {body} bytes of data for {verts} vertices x {stride} bytes and {faces} faces")
    return verts, faces


def mode_bake(cli):
    with tempfile.TemporaryDirectory() as tmp:
        demo = make_demo_dir(cli, tmp)
        proj = os.path.join(demo, "demo.animorph")
        # Two frames of each stage: source, collapse, morph, expand, target.
        outs = {}
        for jobs in ("1", "2"):
            out = os.path.join(tmp, "bake" + jobs)
            names = []
            for a, b in ((22, 23), (46, 47), (48, 49), (84, 85), (108, 109)):
                r = run(cli, "bake", proj, "--frames", f"{a}:{b}", "--res", "20", "-o", out, "--jobs", jobs)
                if r.returncode != 0:
                    fail(f"bake {a}:{b} --jobs {jobs}: {r.returncode} {r.stderr}")
                if "\r" in r.stdout:
                    fail("bake drew a progress bar although stdout is not a terminal")
                names += [f"demo_{f:04d}.ply" for f in (a, b)]  # NAME_####.ply, NAME: the project's name
            if sorted(os.listdir(out)) != sorted(names):
                fail(f"bake wrote {sorted(os.listdir(out))}, expected {sorted(names)}")
            for n in names:
                read_ply_header(os.path.join(out, n))
            outs[jobs] = out
        for n in os.listdir(outs["1"]):
            with open(os.path.join(outs["1"], n), "rb") as f1, open(os.path.join(outs["2"], n), "rb") as f2:
                if f1.read() != f2.read():
                    fail(f"{n} differs between --jobs 1 and --jobs 2")
        r = run(cli, "bake", proj, "--frames", "5:2", "--res", "20", "-o", os.path.join(tmp, "x"))
        if r.returncode != 2:
            fail(f"bake with a reversed frame range: exit {r.returncode}")


def check_same_surface(cpu_ply, gpu_ply):
    """The two meshes are the same surface: every vertex of each lies within GPU_SURFACE_DISTANCE
    median edge lengths of the other's triangles (both ways, so a missing or an extra piece fails)."""
    cpu, gpu = read_ply_mesh(cpu_ply), read_ply_mesh(gpu_ply)
    edge = median_edge_length(*cpu)
    bound = GPU_SURFACE_DISTANCE * edge
    far_gpu, at_gpu = farthest_vertex(gpu[0], SurfaceGrid(*cpu, edge), bound)
    far_cpu, at_cpu = farthest_vertex(cpu[0], SurfaceGrid(*gpu, edge), bound)
    print(f"{os.path.basename(gpu_ply)}: GPU vertices within {far_gpu / edge:.4f} edges of the CPU surface, "
          f"CPU vertices within {far_cpu / edge:.4f} of the GPU's (median edge {edge:.4g}, bound {GPU_SURFACE_DISTANCE})")
    if far_gpu > bound or far_cpu > bound:
        fail(f"{os.path.basename(gpu_ply)}: bake --gpu is not the CPU's surface: a GPU vertex {far_gpu / edge:.3f} "
             f"median edges from it (at {at_gpu}), a CPU vertex {far_cpu / edge:.3f} from the GPU's (at {at_cpu})")


def mode_gpu(cli, resources):
    with tempfile.TemporaryDirectory() as tmp:
        demo = make_demo_dir(cli, tmp)
        proj = os.path.join(demo, "demo.animorph")
        frames = {}
        for label, extra in (("cpu", []), ("gpu", ["--gpu"])):
            out = os.path.join(tmp, label)
            for a, b in ((22, 23), (48, 49), (60, 61)):  # source, then two pairs of morph (B->C) frames
                r = run(cli, "bake", proj, "--frames", f"{a}:{b}", "--res", "24", "-o", out, *extra)
                if r.returncode != 0:
                    fail(f"bake {a}:{b} {extra}: exit {r.returncode}: {r.stderr}")
                if extra and "on the GPU" not in r.stdout:
                    fail(f"bake --gpu does not say the morph ran on the GPU: {r.stdout}")
            frames[label] = out
        for f in (22, 23, 48, 49, 60, 61):
            n = f"demo_{f:04d}.ply"
            cv, cf = read_ply_header(os.path.join(frames["cpu"], n))
            gv, gf = read_ply_header(os.path.join(frames["gpu"], n))
            if f < 48:
                with open(os.path.join(frames["cpu"], n), "rb") as f1, open(os.path.join(frames["gpu"], n), "rb") as f2:
                    if f1.read() != f2.read():
                        fail(f"{n} (before the morph) differs between bake and bake --gpu")
            else:
                if abs(gf - cf) > 0.005 * cf:
                    fail(f"{n}: bake --gpu made {gf} triangles, the CPU {cf}")
                check_same_surface(os.path.join(frames["cpu"], n), os.path.join(frames["gpu"], n))
        # No Vulkan device: explicit --gpu fails with the reason, no silent CPU fallback.
        env = dict(os.environ, VK_ICD_FILENAMES=os.path.join(tmp, "no-such-icd.json"))
        for args in (["bake", proj, "--frames", "48:48", "--res", "16", "-o", os.path.join(tmp, "none"), "--gpu"],
                     ["polygonize", os.path.join(resources, "blob_creature.json"), "--res", "16", "--gpu",
                      "-o", os.path.join(tmp, "none.ply")]):
            r = subprocess.run([cli, *args], capture_output=True, text=True, timeout=120, env=env)
            if r.returncode != 1 or "Vulkan" not in r.stderr or "--gpu" not in r.stderr:
                fail(f"{args[0]} --gpu without a device: exit {r.returncode}, stderr {r.stderr!r}")
            if os.path.exists(args[-1]) and args[0] == "polygonize":
                fail("polygonize --gpu without a device wrote a mesh")


def mode_real_rig(cli):
    """make-demo's rigged figure (60 units tall, armature scale 0.01, helper bones): info's bounds
    in scene units, new taking its 42x as inches (import_checks.py units: a size no unit explains),
    fit's report."""
    with tempfile.TemporaryDirectory() as tmp:
        demo = make_demo_dir(cli, tmp)
        fig = os.path.join(demo, "rigged_figure.glb")
        b = info_json(cli, fig)["bounds"]
        height = b["max"][1] - b["min"][1]
        if not 55.0 < height < 62.0:
            fail(f"info bounds ignore the node transforms: height {height} ({b})")
        proj = os.path.join(tmp, "f.animorph")
        # 42x the 1 m creature: taken as inches (60 in = 1.5 m) without a flag, and said so.
        r = run(cli, "new", os.path.join(demo, "creature.glb"), fig, "-o", proj)
        if (r.returncode != 0 or "(probably authored in inches): scaled by 0.0254" not in r.stdout
                or "scale factor 0.0254x applied" not in r.stdout or "WARNING" in r.stderr):
            fail(f"new did not take the 42x figure as inches: {r.returncode} {r.stdout} {r.stderr}")
        r = run(cli, "fit", fig, "--previous", "-o", os.path.join(tmp, "prev.json"))
        if r.returncode != 0 or "POOR FIT" not in r.stdout or "pieces" not in r.stdout:
            fail(f"fit --previous on the helper-bone rig is not reported poor: {r.stdout}")
        r = run(cli, "fit", fig, "-o", os.path.join(tmp, "new.json"))
        if r.returncode != 0 or "POOR FIT" in r.stdout or "1 piece(s), mesh in 1" not in r.stdout:
            fail(f"fit on the helper-bone rig: {r.stdout}")


def main():
    if len(sys.argv) < 3:
        fail(__doc__)
    mode, cli, args = sys.argv[1], sys.argv[2], sys.argv[3:]
    {"info-json": mode_info_json, "info-bad": mode_info_bad, "make-demo": mode_make_demo, "new-info": mode_new_info,
     "new-align": mode_new_align,
     "fit": mode_fit, "bake": mode_bake, "gpu": mode_gpu, "real-rig": mode_real_rig}[mode](cli, *args)
    print("ok")


if __name__ == "__main__":
    main()
