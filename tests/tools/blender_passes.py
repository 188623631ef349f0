# Opens a celadon render's EXR in Blender's compositor and prints the
# outputs its Image node offers: the passes Blender made of the channel
# names (docs/rendering.md, "How Blender reads these names"). Not part of
# make test: Blender is a large package that `make deps` does not install;
# tests/tools/blender-passes.sh runs it when `blender` is there.
#
#   blender -b --python tests/tools/blender_passes.py -- RENDER.exr
import sys

import bpy

scene = bpy.context.scene
scene.use_nodes = True
node = scene.node_tree.nodes.new("CompositorNodeImage")
node.image = bpy.data.images.load(sys.argv[-1])
print("Blender %s, %s: %s" % (bpy.app.version_string, node.image.type,
                              ", ".join(o.name for o in node.outputs if o.enabled)))
