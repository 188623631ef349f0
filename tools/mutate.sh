#!/usr/bin/env bash
# Mutation testing (docs/faults.md): each mutant plants one deliberate bug in
# core code, in a copy of the repository at HEAD; the optimised test suite is
# built and run against it, and the mutant is killed when a test fails (the
# run stops at the first failure, which it names).
# Prints one line per mutant and the kill rate.
#
#   tools/mutate.sh            every mutant, the whole suite (about 5 min each)
#   tools/mutate.sh 2 5        mutants 2 and 5 only
#   MUTATE_FILTER='render_lights/*' tools/mutate.sh 2
#                              a part of the suite (to try a mutant quickly;
#                              the kill rate in docs/faults.md is the whole suite's)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)

# file | text | replacement (exact, once). What each one breaks, in order:
#  1 Russian roulette without its 1/q compensation
#  2 the area light's pdf left per unit area (no distance^2 / cosine)
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
mutants=(
  'src/integrators/path.c|beta = rgb_scale(beta, 1.0 / survive);|(void)survive;'
  'src/emitters/area.c|out->pdf = pdf_area * dist2 / cos_l;|out->pdf = pdf_area;'
  'src/crosscheck/crosscheck.c|chord_slope(rows, from, last, CROSSCHECK_MEAN_ABS_DIFF)|chord_slope(rows, from + 1, last, CROSSCHECK_MEAN_ABS_DIFF)'
  'src/recon/subpixel_edge.c|out.x = side > 0 ? a0 + len : a1 + 1 - len;|out.x = round(side > 0 ? a0 + len : a1 + 1 - len);'
  'src/bsdfs/diffuse.c|wo.z / M_PI|wo.z / (2.0 * M_PI)'
  'src/render/film.c|f->weight[p] += weight;|f->weight[p] += 1.0;'
  'src/curve/bspline.c|alphas[j - mult - 1] = numer / (U[a + j] - U[a]);|alphas[j - mult - 1] = 1.001 * numer / (U[a + j] - U[a]);'
  'src/core/input_file.c|if (!S_ISREG(st.st_mode)) {|if (0) {'
  'src/core/atomic_file.c|    temp_files_track(tmp);|'
  'src/mesh/revolve.c|    double len = v2_len(d1);|    d1 = v2_scale(d1, -1.0);\n    double len = v2_len(d1);'
  'src/integrators/path.c|double w = es.delta ? 1.0 : mis_power_heuristic(pdf_l, bsdf_pdf(b, q, wo));|double w = es.delta ? 1.0 : 0.5 + 0.0 * bsdf_pdf(b, q, wo);'
  'src/sor/sor_solve.c|double rho = sqrt(sor_max(rho2, 0.0));|double rho = sqrt(fabs(rho2) + 1e-9);'
)

work=$(mktemp -d /tmp/celadon-mutate-XXXXXX)
trap 'rm -rf "$work"' EXIT
git -C "$root" archive HEAD | tar -x -C "$work"
export CELADON_SHARED="${CELADON_SHARED:-$root/../shared}"
selected=("$@")
[ ${#selected[@]} -gt 0 ] || selected=($(seq 1 ${#mutants[@]}))

killed=0 tried=0
for k in "${selected[@]}"; do
  IFS='|' read -r file from to <<<"${mutants[$((k - 1))]}"
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
          ./build/opt/celadon-tests --jobs 2 --fail-fast ${MUTATE_FILTER:+--filter "$MUTATE_FILTER"} >>"$log" 2>&1); then
    verdict="SURVIVED"
  else
    first=$(grep -m1 -o '^\[FAIL\] [^:]*' "$log" | cut -c8-)
    verdict="killed by ${first:-a crash of the suite}"
    killed=$((killed + 1))
  fi
  echo "mutant $k ($file): $verdict"
  mv "$work/$file.orig" "$work/$file"
  touch "$work/$file"
done
echo "killed $killed of $tried"
