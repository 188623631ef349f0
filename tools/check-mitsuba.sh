#!/bin/sh
# Issue 27's yardstick: celadon judged by Mitsuba 3's own render test
# (docs/validation.md). Every scene tests/scenes/FOLDER/NAME_INTEGRATOR.xml of
# mitsuba-data that has a reference refs/NAME_ref_rgb.exr and its per-sample
# variance refs/NAME_ref_rgb_var.exr is rendered as Mitsuba's test renders it,
#
#     celadon render SCENE --spp S -D spp=S -D integrator=INTEGRATOR --seed 0
#
# with S = 2000000 // (the reference's pixel count), and a `volpath` scene a
# second time with volpathmis; build/tools/mitsuba_ztest then applies the
# test's statistic (linear sRGB -> XYZ, z, p, Sidak level, 0.9975 of the
# pixels). One markdown row per render, a total, and for each failing render
# OUT/NAME_INTEGRATOR.png: celadon | Mitsuba | z map (failing pixels red).
#
#   tools/check-mitsuba.sh [MITSUBA_DATA_DIR] [--only SUBSTRING] [--threads N] [--out DIR] [--celadon PATH]
#
# --only renders the scenes whose file name contains SUBSTRING; --threads
# (default 2) goes to `celadon render`; --celadon judges another build.
#
# The copy of mitsuba-data: the argument, else $MITSUBA_DATA, else
# ${XDG_CACHE_HOME:-~/.cache}/celadon/mitsuba-data, which a first run clones
# (git clone --depth 1 https://github.com/mitsuba-renderer/mitsuba-data; ~350 MB).
# Exit status 0 when every render passes, 1 otherwise, 2 on a usage error.
set -eu

usage() {
    echo "usage: tools/check-mitsuba.sh [MITSUBA_DATA_DIR] [--only SUBSTRING] [--threads N] [--out DIR] [--celadon PATH]" >&2
    exit 2
}
data=${MITSUBA_DATA:-}
only=
threads=2
out=out/mitsuba
celadon=build/celadon
ztest=build/tools/mitsuba_ztest
while [ $# -gt 0 ]; do
    case $1 in
    --only | --threads | --out | --celadon)
        [ $# -ge 2 ] || usage
        case $1 in --only) only=$2 ;; --threads) threads=$2 ;; --out) out=$2 ;; --celadon) celadon=$2 ;; esac
        shift 2
        ;;
    -*) usage ;;
    *) data=$1 && shift ;;
    esac
done
if [ -z "$data" ]; then
    data=${XDG_CACHE_HOME:-$HOME/.cache}/celadon/mitsuba-data
    if [ ! -d "$data/tests/scenes" ]; then
        echo "check-mitsuba: cloning mitsuba-data into $data" >&2
        mkdir -p "$(dirname "$data")"
        git clone --quiet --depth 1 https://github.com/mitsuba-renderer/mitsuba-data "$data" || {
            echo "check-mitsuba: no copy of mitsuba-data (give its folder, or set MITSUBA_DATA)" >&2
            exit 2
        }
    fi
fi
[ -d "$data/tests/scenes" ] || {
    echo "check-mitsuba: $data is not a copy of mitsuba-data (no tests/scenes/)" >&2
    exit 2
}
for x in "$celadon" "$ztest"; do
    [ -x "$x" ] || {
        echo "check-mitsuba: $x is missing (make check-mitsuba builds it)" >&2
        exit 2
    }
done
mkdir -p "$out"
work=$(mktemp -d "${TMPDIR:-/tmp}/check-mitsuba.XXXXXX")
trap 'rm -rf "$work"' EXIT INT TERM

echo "| scene | integrator | spp | failed px | of | min p | Y ratio | result | s |"
echo "|---|---|---|---|---|---|---|---|---|"
runs=0
passed=0
for scene in "$data"/tests/scenes/*/*.xml; do
    base=$(basename "$scene" .xml)
    name=${base%_*}
    integrator=${base##*_}
    ref=$(dirname "$scene")/refs/${name}_ref_rgb.exr
    var=$(dirname "$scene")/refs/${name}_ref_rgb_var.exr
    [ -f "$ref" ] && [ -f "$var" ] || continue
    case $base in *"$only"*) ;; *) continue ;; esac
    set -- "$integrator"
    # Mitsuba skips volpathmis on emissive media (it samples no emitting medium).
    [ "$integrator" = volpath ] && case $name in *emissive*) ;; *) set -- volpath volpathmis ;; esac
    pixels=$("$ztest" --size "$ref" | awk '{ print $1 * $2 }')
    spp=$((2000000 / pixels))
    for integ in "$@"; do
        t0=$(date +%s.%N)
        rc=0
        "$celadon" render "$scene" -o "$work/img.exr" --spp "$spp" -D "spp=$spp" -D "integrator=$integ" \
            --seed 0 --threads "$threads" </dev/null >/dev/null 2>"$work/stderr" || rc=$?
        secs=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
        runs=$((runs + 1))
        label=$(basename "$(dirname "$scene")")/$base
        if [ $rc -ne 0 ]; then
            echo "| $label | $integ | $spp | | $pixels | | | refused: $(head -n 1 "$work/stderr" | sed 's/|/\\|/g') | $secs |"
            continue
        fi
        rm -f "$out/${name}_$integ.png"
        set -- $("$ztest" "$work/img.exr" "$ref" "$var" "$spp" "$out/${name}_$integ.png")
        [ "$1" = pass ] && passed=$((passed + 1))
        echo "| $label | $integ | $spp | $2 | $3 | $4 | $6 | $1 | $secs |"
    done
done
echo
echo "$passed of $runs renders pass Mitsuba's test (failing ones: $out/*.png)"
[ "$passed" -eq "$runs" ]
