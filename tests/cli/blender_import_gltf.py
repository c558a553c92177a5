# Runs inside Blender (blender -b --factory-startup -P blender_import_gltf.py -- FILE.glb RESULT.json):
# imports an animated glTF written by `animorph-cli bake --gltf` and writes what
# Blender made of it: the frame objects, their vertex counts and which of them
# is visible (non-zero world scale) at each frame of the sequence's range.
import json
import re
import struct
import sys

import numpy

numpy.bool = bool  # Debian's numpy dropped the alias Blender 3.4's glTF add-on still uses
import bpy  # noqa: E402

glb, result = sys.argv[sys.argv.index("--") + 1:][:2]

# The sequence's fps and frame range, from the file's scene extras.
with open(glb, "rb") as f:
    data = f.read()
(json_len,) = struct.unpack_from("<I", data, 12)
extras = json.loads(data[20:20 + json_len])["scenes"][0]["extras"]

scene = bpy.context.scene
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
fps = float(extras["fps"])
scene.render.fps = round(fps)
scene.render.fps_base = round(fps) / fps
scene.frame_start, scene.frame_end = extras["frameStart"], extras["frameEnd"]
bpy.ops.import_scene.gltf(filepath=glb)

frame_objects = {o.name: o for o in scene.objects if re.fullmatch(r".+_\d{4}", o.name)}
visible = {}
for frame in range(scene.frame_start, scene.frame_end + 1):
    scene.frame_set(frame)
    visible[frame] = sorted(n for n, o in frame_objects.items() if o.matrix_world.to_scale().length > 0.5)
out = {
    "version": bpy.app.version_string,
    "fps": scene.render.fps / scene.render.fps_base,
    "scene_range": [scene.frame_start, scene.frame_end],
    "frame_objects": sorted(frame_objects),
    "vertices": {n: len(o.data.vertices) for n, o in frame_objects.items() if o.type == "MESH"},
    "visible": visible,
}
with open(result, "w") as f:
    json.dump(out, f)
