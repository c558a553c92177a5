"""animorph-cli weights import, end to end: on a copy of the demo project,
importing from a glTF without vertex colours fails naming the file and leaves
the project untouched; a copy of the creature with a COLOR_0 written into it
(red = a known ramp over the vertices) imports as the creature's weight map,
and the saved project holds exactly those values. A copy with an embedded
8 x 1 PNG texture (alphas known) and TEXCOORD_0 at its texel centres imports
with --from-texture alpha as exactly the hand-sampled alphas.

usage: weights_checks.py CLI DEMO_DIR"""
import base64
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

cli, demo = sys.argv[1], sys.argv[2]


def fail(msg):
    print("FAIL: " + msg, flush=True)
    raise SystemExit(1)


def check(cond, msg):
    if not cond:
        fail(msg)
    print("ok: " + msg, flush=True)


def read_glb(path):
    data = open(path, "rb").read()
    magic, _, _ = struct.unpack_from("<III", data, 0)
    assert magic == 0x46546C67
    jlen, _ = struct.unpack_from("<II", data, 12)
    doc = json.loads(data[20:20 + jlen])
    blen, _ = struct.unpack_from("<II", data, 20 + jlen)
    return doc, bytearray(data[28 + jlen:28 + jlen + blen])


def write_glb(path, doc, binary):
    while len(binary) % 4:
        binary.append(0)
    doc["buffers"][0]["byteLength"] = len(binary)
    text = json.dumps(doc).encode()
    text += b" " * ((4 - len(text) % 4) % 4)
    out = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(text) + 8 + len(binary))
    out += struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(binary), 0x004E4942) + bytes(binary)
    open(path, "wb").write(out)


def append_view(doc, binary, data):
    """Appends data (bytes) to the buffer as a new bufferView, 4-byte aligned; returns its index."""
    while len(binary) % 4:
        binary.append(0)
    doc["bufferViews"].append({"buffer": 0, "byteOffset": len(binary), "byteLength": len(data)})
    binary += data
    return len(doc["bufferViews"]) - 1


def add_float_attribute(doc, binary, prim, name, values, comps):
    """Adds attribute name (float VECn, one tuple of values per vertex) to prim."""
    data = b"".join(struct.pack("<%df" % comps, *v) for v in values)
    view = append_view(doc, binary, data)
    doc["accessors"].append({"bufferView": view, "componentType": 5126, "count": len(values),
                             "type": "VEC%d" % comps})
    prim["attributes"][name] = len(doc["accessors"]) - 1


def primitives(doc):
    """Every primitive with its vertex count."""
    for mesh in doc["meshes"]:
        for prim in mesh["primitives"]:
            yield prim, doc["accessors"][prim["attributes"]["POSITION"]]["count"]


def with_colours(src, dst):
    """Adds COLOR_0 (float RGBA; red = i / (n - 1) over each primitive's vertices) to every primitive."""
    doc, binary = read_glb(src)
    reds = []
    for prim, n in primitives(doc):
        colours = [(i / max(1, n - 1), 0.5, 0.0, 1.0) for i in range(n)]
        reds += [c[0] for c in colours]
        add_float_attribute(doc, binary, prim, "COLOR_0", colours, 4)
    write_glb(dst, doc, binary)
    return reds


def png_rgba(width, height, pixels):
    """A PNG (8-bit RGBA, no filter) of pixels: rows of (r, g, b, a) tuples, top first."""
    raw = b"".join(b"\0" + bytes(c for px in row for c in px) for row in pixels)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


ALPHAS = [10 + 32 * k for k in range(8)]


def with_texture(src, dst):
    """Adds an embedded 8 x 1 PNG (alpha ALPHAS[k] at texel k) as every primitive's base colour
    texture and TEXCOORD_0 at the centre of texel i % 8 for vertex i; returns the expected alphas."""
    doc, binary = read_glb(src)
    png = png_rgba(8, 1, [[(200, 100, 50, a) for a in ALPHAS]])
    doc["images"] = [{"bufferView": append_view(doc, binary, png), "mimeType": "image/png"}]
    doc["samplers"] = [{"magFilter": 9728, "minFilter": 9728}]
    doc["textures"] = [{"source": 0, "sampler": 0}]
    doc.setdefault("materials", []).append({"name": "painted", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}})
    expected = []
    for prim, n in primitives(doc):
        add_float_attribute(doc, binary, prim, "TEXCOORD_0", [((i % 8 + 0.5) / 8, 0.5) for i in range(n)], 2)
        expected += [ALPHAS[i % 8] / 255 for i in range(n)]
        prim["material"] = len(doc["materials"]) - 1
    write_glb(dst, doc, binary)
    return expected


def saved_weights(project):
    doc = json.load(open(project))
    actor = next(a for a in doc["morph"]["actors"] if a["id"] == "creature")
    raw = base64.b64decode(actor["weight_map"])
    return struct.unpack("<%df" % (len(raw) // 4), raw)


work = tempfile.mkdtemp(prefix="animorph-cli-weights-")
for name in ("demo.animorph", "creature.glb", "gear.glb"):
    shutil.copy(os.path.join(demo, name), work)
project = os.path.join(work, "demo.animorph")
before = open(project).read()

r = subprocess.run([cli, "weights", "import", project, "--actor", "creature", "--from", "red"],
                   capture_output=True, text=True)
check(r.returncode == 1, f"importing from a glTF without COLOR_0 fails (exit {r.returncode})")
check("creature.glb: no vertex colours (COLOR_0)" in r.stderr, f"the error names the file: {r.stderr.strip()}")
check(open(project).read() == before, "the project is left untouched")

r = subprocess.run([cli, "weights", "import", project, "--actor", "nobody"], capture_output=True, text=True)
check(r.returncode == 1 and "'nobody'" in r.stderr, f"an unknown actor is named: {r.stderr.strip()}")
r = subprocess.run([cli, "weights", "import", project, "--actor", "creature", "--from", "green"],
                   capture_output=True, text=True)
check(r.returncode == 2, "an unknown channel is a usage error")

painted = os.path.join(work, "creature_painted.glb")
reds = with_colours(os.path.join(work, "creature.glb"), painted)
r = subprocess.run([cli, "weights", "import", project, "--actor", "creature", "--from", "color", "--gltf", painted],
                   capture_output=True, text=True)
check(r.returncode == 0, f"importing the red channel of a coloured copy works: {r.stdout.strip()} {r.stderr.strip()}")
doc = json.load(open(project))
actor = next(a for a in doc["morph"]["actors"] if a["id"] == "creature")
raw = base64.b64decode(actor["weight_map"])
weights = struct.unpack("<%df" % (len(raw) // 4), raw)
check(len(weights) == len(reds), f"one weight per creature vertex ({len(weights)})")
check(max(abs(a - b) for a, b in zip(weights, reds)) < 1e-6, "the weights are the red channel exactly")
r = subprocess.run([cli, "info", "--json", project], capture_output=True, text=True)
check(r.returncode == 0, "the project still loads (info --json)")

r = subprocess.run([cli, "weights", "import", project, "--actor", "creature", "--gltf",
                    os.path.join(work, "gear.glb")], capture_output=True, text=True)
check(r.returncode == 1 and "gear.glb" in r.stderr and "vertices" in r.stderr,
      f"a glTF with other vertices is refused, naming it: {r.stderr.strip()}")

textured = os.path.join(work, "creature_textured.glb")
alphas = with_texture(os.path.join(work, "creature.glb"), textured)
r = subprocess.run([cli, "weights", "import", project, "--actor", "creature", "--from-texture", "alpha", "--gltf",
                    textured], capture_output=True, text=True)
check(r.returncode == 0 and "texture channel alpha" in r.stdout,
      f"importing a texture's alpha works: {r.stdout.strip()} {r.stderr.strip()}")
weights = saved_weights(project)
check(len(weights) == len(alphas), f"one weight per creature vertex ({len(weights)})")
check(max(abs(a - b) for a, b in zip(weights, alphas)) < 1e-6,
      "the weights are the texture's alpha sampled at each vertex, as sampled by hand")
r = subprocess.run([cli, "weights", "import", project, "--actor", "creature", "--from-texture", "alpha", "--gltf",
                    os.path.join(work, "gear.glb")], capture_output=True, text=True)
check(r.returncode == 1, "a glTF without a texture (and other vertices) is refused")
r = subprocess.run([cli, "weights", "import", project, "--actor", "creature", "--from-texture", "luminance"],
                   capture_output=True, text=True)
check(r.returncode == 2 and "--from-texture" in r.stderr, "an unknown texture channel is a usage error")
print("weights import: all checks passed")
