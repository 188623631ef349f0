#!/usr/bin/env bash
# `make test`'s runner: the optimised and the ASan+UBSan suites run side by
# side (each a Criterion runner with its own jobs; many tests wait on a
# child process, a browser or a signal, so four at a time keep both cores
# busy), each into its own log, printed whole once both have ended; then the
# slowest tests of each build and the wall time. Exits non-zero when either
# suite fails.
#
#   tools/run-tests.sh [CRITERION_ARGS...]     (from the repository root)
#
# TEST_JOBS (default 2) sets each runner's jobs; TEST_SUITES=opt or asan
# runs one build only.
set -uo pipefail
jobs=${TEST_JOBS:-2}
suites=${TEST_SUITES:-opt asan}
out=build/test-logs
mkdir -p "$out"
asan_env=(ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:halt_on_error=1
          "LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
          UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1)

start=$(date +%s)
declare -A pid
for b in $suites; do
  envs=(CELADON_BUILD=$b)
  if [ "$b" = asan ]; then
    envs+=("${asan_env[@]}" CELADON_BIN="$PWD/build/asan/celadon")
  else
    envs+=(CELADON_BIN="$PWD/build/celadon")
  fi
  env "${envs[@]}" ./build/$b/celadon-tests --jobs "$jobs" --xml="$out/$b.xml" "$@" >"$out/$b.log" 2>&1 &
  pid[$b]=$!
done

status=0
for b in $suites; do
  wait "${pid[$b]}" || status=1
done
end=$(date +%s)

for b in $suites; do
  [ "$b" = opt ] && echo "== optimised build" || echo "== ASan+UBSan build"
  cat "$out/$b.log"
done
for b in $suites; do
  echo "== the slowest tests of the $b build (seconds; each also pays its process's start)"
  # <testsuite name="S" ...> then <testcase name="T" ... time="X">
  awk -F'"' '/<testsuite /{s=$2} /<testcase / && !/SKIPPED/{for(i=1;i<NF;i++) if($i~/ time=$/) print $(i+1), s "::" $2}' \
    "$out/$b.xml" 2>/dev/null | sort -rn | head -8
done
echo "== both suites in $((end - start)) s ($suites, $jobs jobs each)"
# One closing line over both builds, from Criterion's own syntheses.
sed -n 's/.*Synthesis: Tested: [0-9]* | Passing: \([0-9]*\) | Failing: \([0-9]*\) | Crashing: \([0-9]*\).*/\1 \2 \3/p' \
  $(for b in $suites; do echo "$out/$b.log"; done) |
  awk '{p += $1; f += $2 + $3} END {printf "tests: %d passed, %d failed\n", p, f}'
exit $status
