#!/usr/bin/env bash
# Mutation testing (docs/faults.md): each mutant plants one deliberate bug in
# core code, in a copy of the repository at HEAD; the optimised test suite is
# built and run against it, and the mutant is killed when a test fails (the
# run stops at the first failure, which it names).
# Prints one line per mutant and the kill rate.
#
#   tools/mutate.sh            every mutant, the whole suite (about 5 min each)
#   tools/mutate.sh 2 5        mutants 2 and 5 only
#   MUTATE_QUICK=1 tools/mutate.sh
#                              each mutant against the suites named for it
#                              below: a kill there is a kill by the whole
#                              suite; a survivor there may still be killed
#                              by another suite
#   MUTATE_FILTER='render_lights/*' tools/mutate.sh 2
#                              a part of the suite of your choosing
#   MUTATE_WORK=/tmp/m tools/mutate.sh 1
#                              builds in that folder and keeps it, so that the
#                              next run at the same commit rebuilds only what
#                              a mutant touches (at another commit the folder
#                              is made again from HEAD)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)

# file | text | replacement (exact, once) | the suites meant to kill it. What each one breaks, in order:
#  1 Russian roulette without its 1/q compensation
#  2 an area-sampled light's pdf left per unit area (no distance^2 / cosine)
#  3 the crosscheck stall's slope taken over the wrong rows
#  4 sub-pixel edges rounded to whole pixels
#  5 the diffuse BSDF's 1/pi taken as 1/(2 pi)
#  6 the film ignoring the samples' filter weights
#  7 the Bezier split's blending off by a little
#  8 devices and FIFOs read as files
#  9 temporaries not tracked (signals leave them)
# 10 the mesh's normals from a profile derivative of the wrong sign
# 11 the power heuristic replaced by equal weights
# 12 the SOR's quadratic root from rho^2 clamped the wrong way
# 13 Russian roulette's 1/q weight floored at one half
# 14 the crosscheck's stall threshold on the image slope at -0.5, not -1
# 15 the sub-pixel edge's first pass rounded to whole pixels
# 16 the light tree's pmf off its pick's by a little
# 17 the low-discrepancy sampler's 2D points without their digital shift in y
# 18 <rotate> angles by 181 degrees a half turn
# 19 bitmap texels looked up without their half-texel centre in v
# 20 --part K/N: every part but the last one sample short
# 21 the perspective camera's pitch left out of a cross-section's radius
mutants=(
  'src/integrators/path.c|beta = rgb_scale(beta, 1.0 / survive);|(void)survive;|render_furnace/*'
  'src/shapes/shape.c|*pdf = dist2 > 0.0 && cos_l > 0.0 ? pdf_area * dist2 * sqrt(dist2) / cos_l : 0.0;|*pdf = dist2 > 0.0 && cos_l > 0.0 ? pdf_area : 0.0;|@(render_lights|light_sampling)/*'
  'src/crosscheck/crosscheck.c|chord_slope(rows, from, last, CROSSCHECK_MEAN_ABS_DIFF)|chord_slope(rows, from + 1, last, CROSSCHECK_MEAN_ABS_DIFF)|crosscheck/*'
  'src/recon/subpixel_edge.c|out.x = side > 0 ? a0 + len : a1 + 1 - len;|out.x = round(side > 0 ? a0 + len : a1 + 1 - len);|recon_subpixel/*'
  'src/bsdfs/diffuse.c|wo.z / M_PI|wo.z / (2.0 * M_PI)|render_furnace/*'
  'src/render/film.c|f->weight[p] += weight;|f->weight[p] += 1.0;|@(film|render_filters)/*'
  'src/curve/bspline.c|alphas[j - mult - 1] = numer / (U[a + j] - U[a]);|alphas[j - mult - 1] = 1.001 * numer / (U[a + j] - U[a]);|bspline/*'
  'src/core/input_file.c|if (!S_ISREG(st.st_mode)) {|if (0) {|hostile_input/*'
  'src/core/atomic_file.c|    temp_files_track(tmp);||faults/*'
  'src/mesh/revolve.c|    double len = v2_len(d1);|    d1 = v2_scale(d1, -1.0);\n    double len = v2_len(d1);|mesh_revolve/*'
  'src/integrators/path.c|double w = es.delta ? 1.0 : mis_power_heuristic(pdf_l, bsdf_pdf(b, q, wo));|double w = es.delta ? 1.0 : 0.5 + 0.0 * bsdf_pdf(b, q, wo);|@(render_lights|render_integrators)/*'
  'src/sor/sor_solve.c|double rho = sqrt(sor_max(rho2, 0.0));|double rho = sqrt(fabs(rho2) + 1e-9);|@(sor_reference|sor_consistency|accel_sor)/*'
  'src/integrators/path.c|beta = rgb_scale(beta, 1.0 / survive);|beta = rgb_scale(beta, 1.0 / fmax(survive, 0.5));|render_furnace/*'
  'src/crosscheck/crosscheck.c|st.found = st.image_slope > -1.0|st.found = st.image_slope > -0.5|crosscheck/*'
  'src/recon/subpixel_edge.c|double e = side > 0 ? a0 + len : a1 + 1 - len;|double e = round(side > 0 ? a0 + len : a1 + 1 - len);|recon_subpixel/*'
  'src/emitters/light_tree.c|p *= mine / (i0 + i1);|p *= (mine + 0.01 * (i0 + i1 - mine)) / (i0 + i1);|@(light_tree|light_sampling)/*'
  'src/samplers/ldsampler.c|y = seq_sobol1(i) ^ sampler_dim_hash(st, 2);|y = seq_sobol1(i);|samplers/*'
  'src/math/transform.c|double rad = angle_deg * (M_PI / 180.0);|double rad = angle_deg * (M_PI / 181.0);|@(transform|scene_xml)/*'
  'src/textures/bitmap.c|    y -= 0.5;|    (void)0;|texture/*'
  'src/render/parts.c|*s1 = (int)((long long)p.k * spp / p.n);|*s1 = (int)((long long)p.k * spp / p.n) - (p.k < p.n);|parts/*'
  'src/perspective/camera_from_sor.c|rho = r * cos(cam->pitch);|rho = r;|recon_camera*/*'
)

if [ -n "${MUTATE_WORK:-}" ]; then
  # A folder holding another commit is made again from HEAD: kept as it
  # was, it tested the mutants against that commit's code and tests.
  work=$MUTATE_WORK
  head=$(git -C "$root" rev-parse HEAD)
  if [ "$(cat "$work/.mutate-head" 2>/dev/null)" != "$head" ]; then
    [ ! -e "$work" ] || [ -f "$work/.mutate-head" ] ||
      { echo "tools/mutate.sh: $work exists and was not made by an earlier run; choose another MUTATE_WORK" >&2; exit 2; }
    rm -rf "$work" && mkdir -p "$work" && git -C "$root" archive HEAD | tar -x -C "$work"
    echo "$head" >"$work/.mutate-head"
  fi
else
  work=$(mktemp -d /tmp/celadon-mutate-XXXXXX)
  trap 'rm -rf "$work"' EXIT
  git -C "$root" archive HEAD | tar -x -C "$work"
fi
export CELADON_SHARED="${CELADON_SHARED:-$root/../shared}"
selected=("$@")
[ ${#selected[@]} -gt 0 ] || selected=($(seq 1 ${#mutants[@]}))

killed=0 tried=0
for k in "${selected[@]}"; do
  IFS='|' read -r file from to suites <<<"${mutants[$((k - 1))]}"
  filter=${MUTATE_FILTER:-}
  [ -z "${MUTATE_QUICK:-}" ] || filter=$suites
  cp "$work/$file" "$work/$file.orig"
  python3 - "$work/$file" "$from" "$to" <<'PY' || { echo "mutant $k: text not found in $file (update tools/mutate.sh)"; exit 2; }
import sys
path, old, new = sys.argv[1], sys.argv[2], sys.argv[3].replace('\\n', '\n')
s = open(path).read()
if s.count(old) != 1:
    sys.exit(1)
open(path, 'w').write(s.replace(old, new))
PY
  tried=$((tried + 1))
  log="$work/mutant-$k.log"
  if ! make -C "$work" --no-print-directory -j2 build/opt/celadon-tests build/celadon >"$log" 2>&1; then
    verdict="killed (does not build)"
    killed=$((killed + 1))
  elif (cd "$work" && CELADON_BIN="$work/build/celadon" CELADON_BUILD=opt \
          ./build/opt/celadon-tests --jobs 2 --fail-fast ${filter:+--filter "$filter"} >>"$log" 2>&1); then
    verdict="SURVIVED"
  else
    first=$(sed -n 's/^\[FAIL\] \([^:]*::[^:]*\):.*/\1/p' "$log" | head -1)
    verdict="killed by ${first:-a crash of the suite}"
    killed=$((killed + 1))
  fi
  echo "mutant $k ($file${filter:+, $filter}): $verdict"
  mv "$work/$file.orig" "$work/$file"
  touch "$work/$file"
done
echo "killed $killed of $tried"
