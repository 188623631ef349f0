#!/bin/sh
# Imports a museum.glb with Blender's own glTF importer
# (tests/tools/blender_import_museum.py): every mesh node, light, camera,
# material and image of the file must arrive. Exits 0 without Blender,
# saying so; 1 when something is missing.
#
#   tests/tools/blender-museum.sh DIR/museum.glb   (e.g. out/museum-real-dev/museum.glb)
set -eu
glb=${1:?usage: $0 MUSEUM.glb}
if ! command -v blender >/dev/null 2>&1; then
    echo "blender-museum: no blender on PATH: skipped (museum_web checks the glb with the Khronos validator)"
    exit 0
fi
log=$(mktemp)
trap 'rm -f "$log"' EXIT
status=0
blender -b --factory-startup --python-exit-code 1 --python tests/tools/blender_import_museum.py -- "$glb" \
    >"$log" 2>&1 || status=$?
grep -E '^(museum.glb in Blender|blender_import_museum:|Traceback|Error)' "$log" || tail -5 "$log"
exit "$status"
