# Runs inside Blender (blender -b --factory-startup -P blender_import_vdb.py -- FILE.vdb OUT.json):
# imports the OpenVDB file as a volume object and writes what Blender read: the object, its grids
# their types and the volume's bounding box, as JSON for vdb_checks.py.
import json
import sys

import bpy

vdb, out = sys.argv[sys.argv.index("--") + 1:][:2]
before = set(bpy.data.objects.keys())
bpy.ops.object.volume_import(filepath=vdb, files=[{"name": vdb.rsplit("/", 1)[-1]}],
                             directory=vdb.rsplit("/", 1)[0] + "/")
added = [o for o in bpy.data.objects if o.name not in before]
if len(added) != 1 or added[0].type != "VOLUME":
    raise SystemExit(f"volume_import added {[(o.name, o.type) for o in added]}, expected one VOLUME object")
volume = added[0].data
volume.grids.load()  # reads the file; grids stay empty when Blender cannot
if not volume.grids.is_loaded:
    raise SystemExit(f"Blender could not load {vdb}: {volume.grids.error_message}")
bpy.context.view_layer.update()
corners = [list(c) for c in added[0].bound_box]  # the grids' active box in world units (object at the origin)
with open(out, "w") as fh:
    json.dump({"version": bpy.app.version_string, "object": added[0].name,
               "grids": [g.name for g in volume.grids],
               "grid_type": volume.grids[0].data_type if len(volume.grids) else "",
               "grid_types": [g.data_type for g in volume.grids],
               "box": [[min(c[a] for c in corners) for a in range(3)], [max(c[a] for c in corners) for a in range(3)]]}, fh)
