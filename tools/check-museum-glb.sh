#!/bin/sh
# Checks a built museum's museum.glb as docs/museum.md ("Light to load",
# "Blender") promises it: at most MAX_BYTES, no error or warning from the
# Khronos glTF validator (as museum_web runs it), and every mesh node, light,
# camera, material and image of the file arriving in Blender's importer
# (tests/tools/blender-museum.sh; skipped, saying so, without Blender).
#   tools/check-museum-glb.sh out/museum-real-dev 8000000   (from the repository root)
set -eu
dir=${1:?usage: $0 MUSEUM_DIR MAX_BYTES}
max=${2:?usage: $0 MUSEUM_DIR MAX_BYTES}
glb=$dir/museum.glb
bytes=$(stat -c %s "$glb")
echo "check-museum-glb: $glb is $bytes bytes (at most $max)"
[ "$bytes" -le "$max" ] || { echo "check-museum-glb: $glb: $bytes bytes, over $max" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
node tests/web/museum_page.mjs "$PWD/build/celadon" "$(cd "$dir" && pwd)" "$tmp" 640 360 server >"$tmp/report.json"
grep -o '"validator":{[^}]*}' "$tmp/report.json"
grep -q '"validator":{"errors":0,"warnings":0' "$tmp/report.json" ||
    { echo "check-museum-glb: $glb: the validator reports errors or warnings" >&2; exit 1; }
tests/tools/blender-museum.sh "$glb"
