#!/bin/sh
# Renders the same scenes with two revisions of celadon and compares the
# images byte for byte: a refactoring that claims "behaviour unchanged" must
# leave every bit of every image as it was.
#
#   tools/compare-renders.sh REV_A REV_B [--res WxH] [--spp N] [--mesh N]
#
# Each revision is exported with `git archive` (the repository is not
# touched) and built once into $CELADON_COMPARE_DIR/<commit> (default
# ${TMPDIR:-/tmp}/celadon-compare), so later runs reuse the build. Both
# builds render the scene files of REV_A, each with its SORs analytic and
# with --geometry mesh:N, at a small size with a fixed seed and every AOV
# (depth, normal, albedo) in a float EXR: scenes/*/scene.xml, the test
# scenes tests/data/scenes/*.xml, tools/compare-scenes/*.xml (every plugin
# at least once), and the furnace with -D bsdf=dielectric. The cross-check
# of the studio scene is compared too (its EXRs, and report.json without
# the render times). Exit status 0 when everything is identical, 1 when
# anything differs (idiff then says by how much), 2 on a usage or build error.
set -eu

usage() {
    echo "usage: tools/compare-renders.sh REV_A REV_B [--res WxH] [--spp N] [--mesh N]" >&2
    exit 2
}
[ $# -ge 2 ] || usage
rev_a=$1
rev_b=$2
shift 2
res=48x32
spp=4
mesh=48
while [ $# -gt 0 ]; do
    [ $# -ge 2 ] || usage
    case $1 in
    --res) res=$2 ;;
    --spp) spp=$2 ;;
    --mesh) mesh=$2 ;;
    *) usage ;;
    esac
    shift 2
done

top=$(git rev-parse --show-toplevel)
cache=${CELADON_COMPARE_DIR:-${TMPDIR:-/tmp}/celadon-compare}
mkdir -p "$cache"

# build REV: exports and builds REV once; prints its folder.
build() {
    sha=$(git -C "$top" rev-parse --verify "$1^{commit}") || {
        echo "compare-renders: unknown revision '$1'" >&2
        exit 2
    }
    dir=$cache/$sha
    if [ ! -x "$dir/build/celadon" ]; then
        rm -rf "$dir"
        mkdir -p "$dir"
        git -C "$top" archive "$sha" | tar -x -C "$dir"
        echo "compare-renders: building $1 ($sha) in $dir" >&2
        nice make -C "$dir" -j2 build/celadon >"$dir/build.log" 2>&1 || {
            echo "compare-renders: the build of $1 failed; see $dir/build.log" >&2
            exit 2
        }
    fi
    echo "$dir"
}

dir_a=$(build "$rev_a")
dir_b=$(build "$rev_b")
out=$(mktemp -d "${TMPDIR:-/tmp}/celadon-compare-out.XXXXXX")
trap 'rm -rf "$out"' EXIT

same=0
differ=0
# check NAME FILE_A FILE_B
check() {
    if cmp -s "$2" "$3"; then
        same=$((same + 1))
    else
        differ=$((differ + 1))
        echo "DIFFERS: $1" >&2
        case $2 in *.exr) idiff -a "$2" "$3" 2>&1 | sed 's/^/    /' >&2 || true ;; esac
    fi
}

# render NAME SCENE [ARGS...]: both builds, analytic and meshed.
render() {
    name=$1
    scene=$2
    shift 2
    for geometry in analytic "mesh:$mesh"; do
        tag=$name-$(echo "$geometry" | tr : -)
        for side in a b; do
            eval "bin=\$dir_$side/build/celadon"
            nice "$bin" render "$scene" -o "$out/$tag-$side.exr" --res "$res" --spp "$spp" --seed 7 \
                --threads 2 --aov depth,normal,albedo --geometry "$geometry" "$@" 2>"$out/$tag-$side.log" || {
                echo "compare-renders: $tag failed with build $side:" >&2
                cat "$out/$tag-$side.log" >&2
                exit 2
            }
        done
        check "$tag" "$out/$tag-a.exr" "$out/$tag-b.exr"
    done
}

for scene in "$dir_b"/scenes/*/scene.xml "$dir_b"/tests/data/scenes/*.xml "$dir_b"/tools/compare-scenes/*.xml; do
    [ -f "$scene" ] || continue
    name=$(basename "$(dirname "$scene")")-$(basename "$scene" .xml)
    render "$name" "$scene"
done
render furnace-dielectric "$dir_b/scenes/furnace/scene.xml" -D bsdf=dielectric

for side in a b; do
    eval "bin=\$dir_$side/build/celadon"
    mkdir -p "$out/crosscheck-$side"
    nice "$bin" crosscheck "$dir_b/scenes/studio/scene.xml" --segments 16,64 -o "$out/crosscheck-$side" \
        --res "$res" --spp "$spp" --seed 7 --threads 2 --grid 2 >/dev/null 2>&1 || {
        echo "compare-renders: the crosscheck failed with build $side" >&2
        exit 2
    }
    grep -v '"seconds"' "$out/crosscheck-$side/report.json" >"$out/crosscheck-$side/report-no-times.json"
done
for f in analytic.exr mesh-16.exr mesh-64.exr report-no-times.json; do
    check "crosscheck/$f" "$out/crosscheck-a/$f" "$out/crosscheck-b/$f"
done

echo "compare-renders: $rev_a vs $rev_b at $res, $spp spp, mesh:$mesh: $same identical, $differ different"
[ "$differ" -eq 0 ]
