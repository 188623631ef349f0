# Opens a museum.glb in Blender's own glTF importer and counts what arrived
# (docs/museum.md, "Blender"). Not part of make test: Blender is a large
# package that `make deps` does not install.
#
#   blender -b --python tests/tools/blender_import_museum.py -- DIR/museum.glb
import sys

import bpy
import numpy

# Debian 12 pairs Blender 3.4's importer with numpy 1.24, which dropped the
# np.bool alias the importer still uses.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=sys.argv[-1])
objects = bpy.data.objects
meshes = [o for o in objects if o.type == "MESH"]
levels = [o for o in meshes if ", LOD " in o.name]
print(f"museum.glb in Blender {bpy.app.version_string}: {len(objects)} objects, {len(meshes)} meshes "
      f"({len(levels)} vessel levels of detail), {sum(o.type == 'LIGHT' for o in objects)} lights, "
      f"{sum(o.type == 'CAMERA' for o in objects)} camera(s), {len(bpy.data.materials)} materials")
