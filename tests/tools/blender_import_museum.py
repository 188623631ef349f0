# Opens a museum.glb in Blender's own glTF importer and checks that
# everything the file holds arrived (docs/museum.md, "Blender"): one mesh
# object per glTF node with a mesh, one light per node with a
# KHR_lights_punctual light, the camera, every material and every image,
# counted from the file's own JSON chunk. Prints one line, raises (exit 1
# with --python-exit-code 1) on a mismatch. Not part of make test: Blender
# is a large package that `make deps` does not install;
# tests/tools/blender-museum.sh runs it when `blender` is there.
#
#   blender -b --factory-startup --python-exit-code 1 \
#       --python tests/tools/blender_import_museum.py -- DIR/museum.glb
import json
import struct
import sys

import bpy
import numpy

# Debian 12 pairs Blender 3.4's importer with numpy 1.24, which dropped the
# np.bool alias the importer still uses.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

path = sys.argv[-1]
with open(path, "rb") as f:
    magic, _, _, json_len, chunk = struct.unpack("<4sIIII", f.read(20))
    assert magic == b"glTF" and chunk == 0x4E4F534A, f"{path}: not a binary glTF"
    gltf = json.loads(f.read(json_len))
nodes = gltf.get("nodes", [])
want = {
    "mesh objects": sum("mesh" in n for n in nodes),
    "lights": sum("KHR_lights_punctual" in n.get("extensions", {}) for n in nodes),
    "cameras": sum("camera" in n for n in nodes),
    "vessel levels": sum("lod_distance" in n.get("extras", {}) for n in nodes),
    "materials": len(gltf.get("materials", [])),
    "images": len(gltf.get("images", [])),
}

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=path)
objects = bpy.data.objects
# The importer adds one computed "Specular Tint" image per material with
# KHR_materials_specular and a texture; the file's own images keep their
# names. Every one of them must have decoded (a size).
images = [i for i in bpy.data.images if not i.name.startswith("Specular Tint")]
undecoded = [i.name for i in images if not (i.size[0] > 0 and i.size[1] > 0)]
got = {
    "mesh objects": sum(o.type == "MESH" for o in objects),
    "lights": sum(o.type == "LIGHT" for o in objects),
    "cameras": sum(o.type == "CAMERA" for o in objects),
    "vessel levels": sum(o.type == "MESH" and "lod_distance" in o.keys() for o in objects),  # glTF extras
    "materials": len(bpy.data.materials),
    "images": len(images) - len(undecoded),
}
triangles = sum(sum(len(p.vertices) - 2 for p in o.data.polygons) for o in objects if o.type == "MESH")
print(f"museum.glb in Blender {bpy.app.version_string}: {len(objects)} objects, "
      + ", ".join(f"{v} {k}" for k, v in got.items())
      + f" ({triangles} triangles)")
missing = [f"{k}: {got[k]} of {want[k]}" for k in want if got[k] != want[k]]
if missing:
    raise SystemExit(f"blender_import_museum: {path}: " + "; ".join(missing))
