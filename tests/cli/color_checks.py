#!/usr/bin/env python3
"""BlobTree colours in exported meshes (docs/blobtree.md "Colour", docs/export.md).

usage: color_checks.py MODE CLI TOOLS_DIR
  files     polygonize of a scene of a red and a blue point writes vertex colours to PLY (red green
            blue alpha, sRGB), OBJ (v x y z r g b, sRGB) and GLB (COLOR_0, linear): red near the red point, blue near
            the blue one, blends between; a scene without colours is the clay tone.
  gpu       polygonize --gpu colours every vertex on the GPU (its colour pass, not the CPU's
            colouring of the read-back vertices), within 1/255 of the colour the CPU polygoniser gives
            the same vertex (exit 77: skipped without a Vulkan device).
  validator the glTF-Validator reports 0 errors and 0 warnings on the GLB with COLOR_0 (exit 77:
            skipped when Node/npm or the registry is unavailable).
  blender   Blender imports the GLB with its COLOR_0 as a colour attribute whose values are the
            file's (exit 77: skipped without Blender)."""
import json
import os
import struct
import subprocess
import sys
import tempfile

SCENE = {
    "format": "animorph-blobtree", "version": 1, "threshold": 0.5,
    "root": {"id": 1, "type": "blend", "children": [
        {"id": 2, "type": "point", "params": {"center": [0, 0, 0], "radius": 1, "color": [1, 0, 0]}},
        {"id": 3, "type": "point", "params": {"center": [1, 0, 0], "radius": 1, "color": [0, 0, 1]}},
    ]},
}
CLAY_SRGB = (0.55, 0.68, 0.82)  # OBJ and PLY colours are sRGB (linear light ** (1 / 2.2))
HALF_SRGB = 0.5 ** (1 / 2.2)    # an even blend of red and blue, 0.5 in linear light


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def run(*args, timeout=300):
    return subprocess.run(list(args), capture_output=True, text=True, timeout=timeout)


def polygonize(cli, scene, out, *extra):
    r = run(cli, "polygonize", scene, "--time", "0", "--res", "40", "-o", out, *extra)
    if r.returncode != 0:
        fail(f"polygonize {' '.join(extra)} -> {out}: exit {r.returncode}: {r.stdout}{r.stderr}")
    return r


def obj_colored_vertices(path):
    out = []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                v = list(map(float, line.split()[1:]))
                if len(v) != 6:
                    fail(f"{path}: a vertex without colour: {line.strip()}")
                out.append(v)
    return out


def ply_colors(path):
    with open(path, "rb") as f:
        data = f.read()
    head, _, body = data.partition(b"end_header\n")
    lines = head.decode("ascii").splitlines()
    props = [ln.split()[-1] for ln in lines if ln.startswith("property") and "list" not in ln]
    for name in ("red", "green", "blue", "alpha"):
        if name not in props:
            fail(f"{path}: no '{name}' property in the header: {lines}")
    count = next(int(ln.split()[2]) for ln in lines if ln.startswith("element vertex"))
    types = {ln.split()[-1]: ln.split()[1] for ln in lines if ln.startswith("property") and "list" not in ln}
    fmt = "<" + "".join({"float": "f", "uchar": "B"}[types[p]] for p in props)
    size = struct.calcsize(fmt)
    return [dict(zip(props, struct.unpack_from(fmt, body, i * size))) for i in range(count)]


def write_scene(tmp, scene=SCENE):
    path = os.path.join(tmp, "scene.json")
    with open(path, "w") as f:
        json.dump(scene, f)
    return path


def mode_files(cli):
    with tempfile.TemporaryDirectory() as tmp:
        scene = write_scene(tmp)
        obj = os.path.join(tmp, "m.obj")
        polygonize(cli, scene, obj)
        verts = obj_colored_vertices(obj)
        red = [v for v in verts if v[0] < -0.1]
        blue = [v for v in verts if v[0] > 1.1]
        if len(red) < 20 or len(blue) < 20:
            fail(f"too few vertices beyond the points: {len(red)}, {len(blue)}")
        if any(v[3] < 0.999 or v[5] > 0.001 for v in red) or any(v[5] < 0.999 or v[3] > 0.001 for v in blue):
            fail("vertices beyond one point's reach are not that point's colour")
        mid = [v for v in verts if 0.495 < v[0] < 0.505]
        if not mid or any(abs(v[3] - HALF_SRGB) > 0.01 or abs(v[5] - HALF_SRGB) > 0.01 for v in mid):
            fail(f"vertices halfway are not an even blend (sRGB {HALF_SRGB:.4f}): {mid[:3]}")
        if any(abs(v[3] ** 2.2 + v[5] ** 2.2 - 1.0) > 2e-3 or abs(v[4]) > 1e-4 for v in verts):
            fail("a vertex colour that is not a blend of red and blue (in linear light)")

        ply = os.path.join(tmp, "m.ply")
        polygonize(cli, scene, ply)
        cols = ply_colors(ply)
        if len(cols) != len(verts):
            fail(f"PLY has {len(cols)} vertices, OBJ {len(verts)}")
        if not any(c["red"] == 255 and c["blue"] == 0 for c in cols) or not any(c["blue"] == 255 for c in cols):
            fail("PLY colours: no pure red or no pure blue vertex")

        # A scene without colours: the clay tone everywhere.
        plain = json.loads(json.dumps(SCENE))
        for n in plain["root"]["children"]:
            del n["params"]["color"]
        polygonize(cli, write_scene(tmp, plain), obj)
        for v in obj_colored_vertices(obj):
            if any(abs(a - b) > 2e-4 for a, b in zip(v[3:], CLAY_SRGB)):
                fail(f"a scene without colours: vertex colour {v[3:]}, expected the clay tone {CLAY_SRGB}")
    print("vertex colours in OBJ and PLY: red, blue and their blend; clay without colours")


def mode_gpu(cli):
    with tempfile.TemporaryDirectory() as tmp:
        scene = write_scene(tmp)
        cpu, gpu = os.path.join(tmp, "cpu.obj"), os.path.join(tmp, "gpu.obj")
        polygonize(cli, scene, cpu)
        r = run(cli, "polygonize", scene, "--time", "0", "--res", "40", "-o", gpu, "--gpu")
        if r.returncode != 0:
            if "no usable Vulkan device" in r.stderr:
                print("no Vulkan device: skipped")
                sys.exit(77)
            fail(f"polygonize --gpu: {r.returncode} {r.stderr}")
        if "colours: GPU" not in r.stdout:
            fail(f"polygonize --gpu did not colour on the GPU: {r.stdout}")
        a, b = obj_colored_vertices(cpu), obj_colored_vertices(gpu)
        # The same grid: match each GPU vertex to the CPU vertex at the same place.
        grid = {}
        for v in a:
            grid.setdefault(tuple(round(x * 200) for x in v[:3]), []).append(v)
        worst, matched = 0.0, 0
        for v in b:
            key = tuple(round(x * 200) for x in v[:3])
            near = [w for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1)
                    for w in grid.get((key[0] + dx, key[1] + dy, key[2] + dz), [])]
            if not near:
                continue
            w = min(near, key=lambda w: sum((p - q) ** 2 for p, q in zip(v[:3], w[:3])))
            if sum((p - q) ** 2 for p, q in zip(v[:3], w[:3])) > 1e-8:
                continue
            matched += 1
            # compared in linear light, as the meshes hold them (the OBJ has sRGB)
            worst = max(worst, max(abs(p ** 2.2 - q ** 2.2) for p, q in zip(v[3:], w[3:])))
        if matched < 0.9 * len(b):
            fail(f"only {matched} of {len(b)} GPU vertices lie on CPU vertices")
        print(f"GPU vs CPU: {matched} vertices matched, largest colour difference {worst:.5f} (<= 1/255 = 0.00392)")
        if worst > 1.0 / 255.0:
            fail(f"GPU and CPU colours differ by {worst}")


def mode_validator(cli, tools):
    r = run(os.path.join(tools, "install_validator.sh"), tools)
    if r.returncode != 0:
        print(r.stdout.strip())
        sys.exit(r.returncode)
    with tempfile.TemporaryDirectory() as tmp:
        glb = os.path.join(tmp, "m.glb")
        polygonize(cli, write_scene(tmp), glb)
        with open(glb, "rb") as f:
            data = f.read()
        length = struct.unpack_from("<I", data, 12)[0]
        doc = json.loads(data[20:20 + length])
        attrs = doc["meshes"][0]["primitives"][0]["attributes"]
        if "COLOR_0" not in attrs:
            fail(f"no COLOR_0 in {attrs}")
        r = run("node", os.path.join(tools, "validate_gltf.js"), glb)
        print(r.stdout.strip())
        if r.returncode != 0 or " 0 errors, 0 warnings" not in r.stdout:
            fail(f"the glTF-Validator did not accept the GLB with COLOR_0: {r.stdout}{r.stderr}")


BLENDER_SCRIPT = r"""
import bpy, json, sys
try:
    import numpy
    numpy.bool = bool  # Debian's numpy dropped the alias Blender 3.4's glTF add-on still uses
except ImportError:
    pass
path, out = sys.argv[sys.argv.index("--") + 1:]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=path)
mesh = [o for o in bpy.context.scene.objects if o.type == "MESH"][0].data
attrs = getattr(mesh, "color_attributes", None) or mesh.vertex_colors
res = {"attributes": [a.name for a in attrs]}
if len(attrs):
    a = attrs[0]
    vals = [tuple(d.color[:3]) for d in a.data]
    res["min_red"] = min(v[0] for v in vals); res["max_red"] = max(v[0] for v in vals)
    res["max_blue"] = max(v[2] for v in vals)
json.dump(res, open(out, "w"))
"""


def mode_blender(cli):
    blender = subprocess.run(["which", "blender"], capture_output=True, text=True).stdout.strip()
    if not blender:
        print("blender not installed: skipped")
        sys.exit(77)
    with tempfile.TemporaryDirectory() as tmp:
        glb = os.path.join(tmp, "m.glb")
        polygonize(cli, write_scene(tmp), glb)
        script, out = os.path.join(tmp, "read.py"), os.path.join(tmp, "out.json")
        with open(script, "w") as f:
            f.write(BLENDER_SCRIPT)
        r = run(blender, "--background", "--factory-startup", "--python", script, "--", glb, out, timeout=600)
        if r.returncode != 0 or not os.path.exists(out):
            fail(f"blender exited {r.returncode}: {r.stdout[-2000:]}{r.stderr[-2000:]}")
        with open(out) as f:
            got = json.load(f)
        print(f"Blender: {got}")
        if not got["attributes"]:
            fail("Blender imported no colour attribute")
        if got["max_red"] < 0.99 or got["min_red"] > 0.01 or got["max_blue"] < 0.99:
            fail(f"Blender's colours are not the file's red-to-blue range: {got}")


def main():
    mode, cli = sys.argv[1], sys.argv[2]
    if mode == "files":
        mode_files(cli)
    elif mode == "gpu":
        mode_gpu(cli)
    elif mode == "validator":
        mode_validator(cli, sys.argv[3])
    elif mode == "blender":
        mode_blender(cli)
    else:
        fail(f"unknown mode {mode}")


if __name__ == "__main__":
    main()
