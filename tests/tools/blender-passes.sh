#!/bin/sh
# Renders a small scene with every AOV and opens it in Blender's
# compositor (tests/tools/blender_passes.py), which prints the passes it
# found: Combined, Alpha, Depth, N, albedo, IndexOB, IndexMA, variance, spp,
# Denoising Albedo, Denoising Depth, Denoising Normal, Denoising Mirror, half,
# specular, specular half (Blender 3.4.1: all sixteen; it dropped variance and spp
# while they were dotless names, docs/rendering.md).
# Exits 0 without Blender, saying so.
#
#   tests/tools/blender-passes.sh [CELADON]   (default build/celadon; from the repository root)
set -eu
bin=${1:-build/celadon}
if ! command -v blender >/dev/null 2>&1; then
    echo "blender-passes: no blender on PATH: skipped (the channel names are checked by make test:" \
         "render_outputs/aov_names_open_as_blender_passes)"
    exit 0
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$bin" render scenes/studio/scene.xml -o "$tmp/passes.exr" --res 64x36 --spp 4 \
    --aov depth,normal,albedo,index,variance,spp,denoising,half,specular 2>/dev/null
blender -b --factory-startup --python tests/tools/blender_passes.py -- "$tmp/passes.exr" 2>&1 | grep '^Blender .*:'
