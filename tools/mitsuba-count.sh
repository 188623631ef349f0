#!/bin/sh
# The yardstick of issue 12: how many of Mitsuba's own scene files open here
# unmodified. Renders every scene file of a copy of mitsuba-data (github
# mitsuba-renderer/mitsuba-data) under docs/, scenes/ and tests/ with
#
#     celadon render SCENE -o OUT.exr --res 32x24 --spp 1 --threads 1 -a MITSUBA_DATA_DIR/common
#
# under a time limit, and prints one markdown row per scene and a summary:
#
#   rendered   exit status 0 and an image written;
#   missing    refused only because a file it names is absent from the copy
#              (a mesh too large for it): the refusal says "file '...' not
#              found" and no file of that name exists anywhere in the copy;
#   refused    exit status 2 with one line on stderr (the reason, shown);
#   crashed    any other exit status (a signal, an internal failure), or a
#              refusal that is not exactly one line;
#   hung       still running after the time limit.
#
# `-a MITSUBA_DATA_DIR/common` adds the copy's common/ folder to where files
# are looked for, as Mitsuba's documentation build adds it to its file
# resolver: the documentation scenes name shared meshes and textures by
# paths relative to it (include/sensor_scene.xml names
# meshes/matpreview.serialized, which is common/meshes/matpreview.serialized),
# so without it they open in Mitsuba itself only from that build.
#
# Include fragments are not scenes: a file that another file of the set
# names in an <include filename="..."/> is left out, and so is every file
# of a folder from which a file of another folder includes (19 of the 166
# files of mitsuba-data: docs/scenes/include/, scenes/cbox/fragments/, ...).
#
#   tools/mitsuba-count.sh MITSUBA_DATA_DIR [--celadon PATH] [--timeout SECONDS]
#
# Run by hand (docs/scene-format.md publishes its table), not by `make
# test`. Exit status 0 when nothing crashed or hung, 1 otherwise, 2 on a
# usage error.
set -eu

usage() {
    echo "usage: tools/mitsuba-count.sh MITSUBA_DATA_DIR [--celadon PATH] [--timeout SECONDS]" >&2
    exit 2
}
[ $# -ge 1 ] || usage
data=$1
shift
celadon=build/celadon
limit=60
while [ $# -gt 0 ]; do
    [ $# -ge 2 ] || usage
    case $1 in
    --celadon) celadon=$2 ;;
    --timeout) limit=$2 ;;
    *) usage ;;
    esac
    shift 2
done
[ -d "$data/docs" ] && [ -d "$data/scenes" ] && [ -d "$data/tests" ] && [ -d "$data/common" ] || {
    echo "mitsuba-count: $data is not a copy of mitsuba-data (no docs/, scenes/, tests/, common/)" >&2
    exit 2
}
[ -x "$celadon" ] || {
    echo "mitsuba-count: $celadon is not an executable (make build/celadon, or --celadon PATH)" >&2
    exit 2
}

work=$(mktemp -d "${TMPDIR:-/tmp}/mitsuba-count.XXXXXX")
trap 'rm -rf "$work"' EXIT INT TERM
data=$(cd "$data" && pwd)

# Every scene file, as a path relative to the copy.
(cd "$data" && find docs scenes tests -name '*.xml' -type f | sort) >"$work/all"

# The included files, each as "FILE INCLUDER_FOLDER": each <include
# filename="X"/> of file F names the first existing of dir(F)/X,
# dir(dir(F))/X, ... (the reader looks in the including file's folder, then
# in the scene's, which is one of these).
while read -r f; do
    grep -o '<include[^>]*filename="[^"]*"' "$data/$f" 2>/dev/null |
        sed 's/.*filename="\([^"]*\)"/\1/' |
        while read -r inc; do
            d=$(dirname "$f")
            while [ ! -f "$data/$d/$inc" ] && [ "$d" != . ]; do d=$(dirname "$d"); done
            [ -f "$data/$d/$inc" ] && echo "$(cd "$data" && realpath --relative-to=. "$d/$inc") $(dirname "$f")"
        done
done <"$work/all" | sort -u >"$work/included"
# Fragments: the included files, and every file of a folder from which
# another folder includes (scenes/cbox/fragments/bsdfs-white.xml is included
# by no one, but is a fragment like its neighbours).
awk '{ n = split($1, p, "/"); d = substr($1, 1, length($1) - length(p[n]) - 1); print $1
       if (d != $2) print "DIR " d }' "$work/included" | sort -u >"$work/inc-or-dirs"
{
    grep -v '^DIR ' "$work/inc-or-dirs" || true
    sed -n 's/^DIR //p' "$work/inc-or-dirs" | while read -r d; do grep "^$d/[^/]*$" "$work/all" || true; done
} | sort -u >"$work/fragments"
grep -vxF -f "$work/fragments" "$work/all" >"$work/scenes" || true

echo "| scene | result | reason |"
echo "|---|---|---|"
while read -r f; do
    rc=0
    timeout -k 5 "$limit" "$celadon" render "$data/$f" -o "$work/out.exr" --res 32x24 --spp 1 --threads 1 \
        -a "$data/common" </dev/null >/dev/null 2>"$work/stderr" || rc=$?
    rm -f "$work/out.exr"
    # The reason without the copy's folder (so the table reads the same on any machine).
    reason=$(sed -e "s|^celadon: ||" -e "s|$data/||g" -e 's/|/\\|/g' "$work/stderr" | grep -v '^render: ' | head -n 1)
    lines=$(grep -vc '^render: ' "$work/stderr" || true)
    result=crashed
    case $rc in
    0) result=rendered reason= ;;
    124 | 137) result=hung reason="no answer after ${limit} s" ;;
    2)
        if [ "$lines" -eq 1 ]; then
            result=refused
            missing=$(echo "$reason" | sed -n "s/.*file '\([^']*\)' not found.*/\1/p")
            if [ -n "$missing" ] && [ -z "$(find "$data" -name "$(basename "$missing")" -print -quit)" ]; then
                result=missing
            fi
        else
            reason="exit 2 with $lines lines on stderr: $reason"
        fi
        ;;
    *) reason="exit status $rc: $reason" ;;
    esac
    echo "$result" >>"$work/results"
    echo "| $f | $result | ${reason:+\`$reason\`} |"
    [ "$result" = refused ] && echo "$reason" | sed 's/^[^ ]*:[0-9]*: //;t;s/^[^ ]*: //' >>"$work/reasons"
done <"$work/scenes"

total=$(wc -l <"$work/scenes")
count() { grep -cx "$1" "$work/results" || true; }
echo
echo "$(count rendered) of $total scene files rendered ($(wc -l <"$work/fragments") include fragments left out):"
for r in rendered missing refused crashed hung; do
    n=$(count $r)
    echo "- $r: $n ($(awk -v n="$n" -v t="$total" 'BEGIN { printf "%.1f", t ? 100 * n / t : 0 }')%)"
done
if [ -s "$work/reasons" ]; then
    echo
    echo "Refusals by reason (file:line left out):"
    sort "$work/reasons" | uniq -c | sort -rn | sed 's/^ *\([0-9]*\) \(.*\)/- \1 × `\2`/'
fi
[ "$(count crashed)" -eq 0 ] && [ "$(count hung)" -eq 0 ]
