#!/usr/bin/env python3
"""End-to-end checks of animorph-cli bake --vdb: OpenVDB level sets of the implicit frames.

usage: vdb_checks.py MODE CLI PROJECT [ARGS...]
  bake CLI PROJECT           --vdb DIR beside the PLY sequence: a NAME_####.vdb for every B->C frame
                             and none for skinned-mesh frames; vdb_print reads each back: one grid
                             'surface' of class level set, background 3 voxels, values of both signs
                             within the band, its active voxels' world box around the PLY's box of the
                             same frame by at most the band (plus a voxel), a float-vector grid 'Cd'
                             (the surface colour) after it, none with --no-color; a --vdb path that is a
                             file and a range without an implicit frame fail naming the reason
                             (exit 77: skipped when vdb_print, Debian's libopenvdb-tools, is not installed)
  blender CLI PROJECT SCRIPT Blender imports a .vdb as a volume object headless (SCRIPT runs inside
                             it): grids 'surface' and 'Cd' (float, float vector), the volume's box around the PLY's box of the same
                             frame (exit 77: skipped when blender or vdb_print is not installed)
"""
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_checks import fail, run, blender_or_skip, run_blender  # noqa: E402 (the script beside this one)

FRAMES = (44, 54)  # the demo's collapse (no field) then B->C (B is at 48)
RES = "24"


def ply_box(path):
    """The bounding box of a binary little-endian PLY's vertices (x, y, z: its first three properties,
    floats; the others, such as uchar colours, only move the stride)."""
    sizes = {"char": 1, "uchar": 1, "short": 2, "ushort": 2, "int": 4, "uint": 4, "float": 4, "double": 8}
    with open(path, "rb") as f:
        data = f.read()
    end = data.find(b"end_header\n")
    header = data[:end].decode("ascii").split("\n")
    verts = stride = 0
    in_vertex = False
    for line in header:
        if line.startswith("element "):
            in_vertex = line.startswith("element vertex ")
            if in_vertex:
                verts = int(line.split()[2])
        elif line.startswith("property ") and in_vertex:
            stride += sizes[line.split()[1]]
    body = data[end + len("end_header\n"):]
    lo, hi = [float("inf")] * 3, [float("-inf")] * 3
    for v in range(verts):
        xyz = struct.unpack_from("<3f", body, v * stride)
        lo = [min(a, b) for a, b in zip(lo, xyz)]
        hi = [max(a, b) for a, b in zip(hi, xyz)]
    return lo, hi


def vdb_print_or_skip():
    """Exits 77 (ctest: skipped) when vdb_print, which reads the level sets back, is not installed."""
    if not shutil.which("vdb_print"):
        print("SKIP: vdb_print not installed (Debian package libopenvdb-tools; run.sh installs it)")
        sys.exit(77)


def vdb_print(path):
    r = subprocess.run(["vdb_print", "-l", "-m", path], capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"vdb_print {path}: exit {r.returncode}: {r.stderr}")
    return r.stdout


def number(text, pattern, path):
    m = re.search(pattern, text)
    if not m:
        fail(f"{path}: vdb_print shows no {pattern!r}:\n{text}")
    return m.groups() if len(m.groups()) > 1 else m.group(1)


def grid_sections(text):
    """vdb_print -l -m's account split per grid: {name: its lines}."""
    parts = re.split(r"^(?=Name: )", text, flags=re.M)
    return {re.match(r"Name: (\S+)", p).group(1): p for p in parts if p.startswith("Name: ")}


def check_level_set(path, ply, colors=True):
    """vdb_print's account of one file against the PLY of the same frame; returns the voxel size.
    colors: a float-vector grid 'Cd' (the surface colour next to the surface) follows the level set."""
    grids = grid_sections(vdb_print(path))
    expected = ["surface", "Cd"] if colors else ["surface"]
    if list(grids) != expected:
        fail(f"{path}: grids {list(grids)}, expected {expected}:\n{grids}")
    if colors:
        cd = grids["Cd"]
        if "vec3s" not in cd or "Bounding box of active voxels" not in cd:
            fail(f"{path}: grid 'Cd' is not a float-vector grid with active voxels:\n{cd}")
    text = grids["surface"]
    if "class: level set" not in text:
        fail(f"{path}: the grid is not of class level set:\n{text}")
    voxel = float(number(text, r"voxel size: ([-0-9.e+]+)", path))
    background = float(number(text, r"Background value: ([-0-9.e+]+)", path))
    lo_v = float(number(text, r"Min value: ([-0-9.e+]+)", path))
    hi_v = float(number(text, r"Max value: ([-0-9.e+]+)", path))
    if abs(background - 3 * voxel) > 2e-3 * background:  # vdb_print rounds to a few digits
        fail(f"{path}: background {background}, expected 3 voxels of {voxel}")
    if not (-background - 1e-6 <= lo_v < 0 < hi_v <= background + 1e-6):
        fail(f"{path}: values {lo_v}..{hi_v} are not both signs within the band {background}")
    imin = [int(x) for x in number(text, r"Bounding box of active voxels: \[(-?\d+), (-?\d+), (-?\d+)\]", path)]
    imax = [int(x) for x in number(text, r"Bounding box of active voxels: \[[^]]*\] -> \[(-?\d+), (-?\d+), (-?\d+)\]", path)]
    rows = re.findall(r"^\s*\[([-0-9.e+]+), ([-0-9.e+]+), ([-0-9.e+]+), ([-0-9.e+]+)\]", text, re.M)
    if len(rows) != 4:
        fail(f"{path}: no 4x4 index-to-world matrix:\n{text}")
    translation = [float(x) for x in rows[3][:3]]
    world_lo = [translation[a] + voxel * imin[a] for a in range(3)]
    world_hi = [translation[a] + voxel * imax[a] for a in range(3)]
    mesh_lo, mesh_hi = ply_box(ply)
    slack = 4.0 * voxel  # the band (3 voxels) and the voxel the crossing lies in
    eps = 0.1 * voxel  # vdb_print's rounding of the voxel size and the translation
    for a in range(3):
        if not (mesh_lo[a] - slack <= world_lo[a] <= mesh_lo[a] + eps and
                mesh_hi[a] - eps <= world_hi[a] <= mesh_hi[a] + slack):
            fail(f"{path}: active voxels span {world_lo}..{world_hi} (voxel {voxel}), the mesh {mesh_lo}..{mesh_hi}: "
                 f"axis {a} is not the mesh's box grown by at most {slack}")
    return voxel


def mode_bake(cli, project):
    vdb_print_or_skip()
    with tempfile.TemporaryDirectory() as tmp:
        ply_dir, vdb_dir = os.path.join(tmp, "ply"), os.path.join(tmp, "vdb")
        r = run(cli, "bake", project, "--frames", f"{FRAMES[0]}:{FRAMES[1]}", "--res", RES, "-o", ply_dir,
                "--vdb", vdb_dir, "--jobs", "2")
        if r.returncode != 0:
            fail(f"bake --vdb: exit {r.returncode}: {r.stderr}")
        morph = int(number(r.stdout, r"(\d+) morph", "bake's log"))
        vdbs = sorted(os.listdir(vdb_dir))
        if len(vdbs) != morph or morph < 3 or morph >= FRAMES[1] - FRAMES[0] + 1:
            fail(f"{len(vdbs)} .vdb files for {morph} B->C frames of {FRAMES}: {vdbs}\n{r.stdout}")
        skipped = FRAMES[1] - FRAMES[0] + 1 - morph
        if f"wrote {morph} OpenVDB level sets into {vdb_dir}" not in r.stdout or f"{skipped} frames are skinned" not in r.stdout:
            fail(f"bake --vdb did not say what it wrote and skipped:\n{r.stdout}")
        last = FRAMES[1]
        expected = [f"demo_{f:04d}.vdb" for f in range(last - morph + 1, last + 1)]
        if vdbs != expected:
            fail(f"--vdb wrote {vdbs}, expected {expected}")
        voxels = [check_level_set(os.path.join(vdb_dir, v), os.path.join(ply_dir, v[:-4] + ".ply")) for v in vdbs]
        print(f"{len(vdbs)} level sets with colour grids (voxel {voxels[0]:.4g}..{voxels[-1]:.4g}), "
              f"{skipped} skinned frames without one")

        # --no-color: the level sets alone.
        plain_ply, plain_vdb = os.path.join(tmp, "plain_ply"), os.path.join(tmp, "plain_vdb")
        r = run(cli, "bake", project, "--frames", "54:54", "--res", RES, "-o", plain_ply, "--vdb", plain_vdb,
                "--no-color")
        if r.returncode != 0:
            fail(f"bake --vdb --no-color: exit {r.returncode}: {r.stderr}")
        check_level_set(os.path.join(plain_vdb, "demo_0054.vdb"), os.path.join(plain_ply, "demo_0054.ply"), colors=False)

        # A --vdb path that is a file, and a range of skinned frames only: exit 1, naming the reason.
        blocker = os.path.join(tmp, "a_file")
        with open(blocker, "w") as fh:
            fh.write("x")
        r = run(cli, "bake", project, "--frames", "50:50", "--res", RES, "--format", "none", "--vdb", blocker)
        if r.returncode != 1 or blocker not in r.stderr:
            fail(f"--vdb onto a file: exit {r.returncode}, stderr {r.stderr!r}")
        r = run(cli, "bake", project, "--frames", "0:1", "--res", RES, "--format", "none", "--vdb", os.path.join(tmp, "none"))
        if r.returncode != 1 or "no frame of the range has an implicit field" not in r.stderr:
            fail(f"--vdb over skinned frames: exit {r.returncode}, stderr {r.stderr!r}")


def mode_blender(cli, project, script):
    blender = blender_or_skip()
    vdb_print_or_skip()
    with tempfile.TemporaryDirectory() as tmp:
        ply_dir, vdb_dir = os.path.join(tmp, "ply"), os.path.join(tmp, "vdb")
        r = run(cli, "bake", project, "--frames", "60:60", "--res", RES, "-o", ply_dir, "--vdb", vdb_dir)
        if r.returncode != 0:
            fail(f"bake --vdb: exit {r.returncode}: {r.stderr}")
        vdb, ply = os.path.join(vdb_dir, "demo_0060.vdb"), os.path.join(ply_dir, "demo_0060.ply")
        voxel = check_level_set(vdb, ply)
        result = os.path.join(tmp, "blender.json")
        r = run_blender(blender, script, vdb, result, timeout=300)
        if r.returncode != 0 or not os.path.exists(result):
            fail(f"blender exited {r.returncode}: {r.stdout[-2000:]}{r.stderr[-2000:]}")
        with open(result) as fh:
            got = json.load(fh)
        if got["grids"] != ["surface", "Cd"] or got["grid_types"] != ["FLOAT", "VECTOR_FLOAT"]:
            fail(f"Blender's volume has grids {got['grids']} of types {got['grid_types']}, "
                 f"expected ['surface', 'Cd'] (FLOAT, VECTOR_FLOAT)")
        # Blender's box is the grid's leaf nodes (8^3 voxels) in world units: around the mesh's box by at
        # most the band, the crossing's voxel and a leaf.
        mesh_lo, mesh_hi = ply_box(ply)
        lo, hi = got["box"]
        slack = (3 + 1 + 8) * voxel
        for a in range(3):
            if not (mesh_lo[a] - slack <= lo[a] <= mesh_lo[a] and mesh_hi[a] <= hi[a] <= mesh_hi[a] + slack):
                fail(f"Blender's volume spans {lo}..{hi}, the mesh {mesh_lo}..{mesh_hi}: axis {a} off by more than {slack}")
        print(f"Blender {got['version']}: volume object {got['object']} with grids 'surface' and 'Cd' ({got['grid_types']}), "
              f"box {lo}..{hi} around the mesh's {mesh_lo}..{mesh_hi}")


def main():
    if len(sys.argv) < 4:
        fail(__doc__)
    mode, args = sys.argv[1], sys.argv[2:]
    {"bake": mode_bake, "blender": mode_blender}[mode](*args)
    print("ok")


if __name__ == "__main__":
    main()
