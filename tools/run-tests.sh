#!/usr/bin/env bash
# `make test`'s runner: the optimised and the ASan+UBSan suites and the
# Python package's pytest suite run side by side (each Criterion runner with
# its own jobs; many tests wait on a child process, a browser or a signal,
# so several at a time keep both cores busy), each into its own log, printed
# whole once all have ended; then the slowest tests of each build, the wall
# time and one closing count. Exits non-zero when any suite fails.
#
#   tools/run-tests.sh [CRITERION_ARGS...]     (from the repository root)
#
# TEST_JOBS (default 2) sets each Criterion runner's jobs; TEST_SUITES (default
# "opt asan python") names the suites to run; PYTHON the interpreter
# (Debian's, where make deps puts numpy and pytest); PYTEST_ARGS go to pytest.
set -uo pipefail
jobs=${TEST_JOBS:-2}
suites=${TEST_SUITES:-opt asan python}
python=${PYTHON:-/usr/bin/python3}
out=build/test-logs
mkdir -p "$out"
asan_env=(ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:halt_on_error=1
          "LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
          UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1)

# The learned prior's network (OpenCV, not instrumented) runs under ASan in
# its own suite only: everywhere else the sanitized build takes the classical
# path, whose counts those tests assert there, while the optimised build
# asserts the prior's (docs/BENCHMARKS.md, "Test suite"). With ARGS (a
# filter) the one sanitized run keeps the network.
if [ $# = 0 ] && [[ " $suites " == *" asan "* ]]; then
  suites=${suites/asan/asan asan-prior}
fi

start=$(date +%s)
declare -A pid
for b in $suites; do
  if [ "$b" = python ]; then
    (cd python && CELADON_BIN="$PWD/../build/celadon" PYTHONPATH="$PWD" OMP_NUM_THREADS=2 \
       "$python" -m pytest -q -p no:cacheprovider tests ${PYTEST_ARGS:-}; rc=$?
     [ $rc = 5 ] && { echo "celadon: pytest collected no test"; rc=0; }; exit $rc) >"$out/$b.log" 2>&1 &
    pid[$b]=$!
    continue
  fi
  build=${b%-prior}
  envs=(CELADON_BUILD=$build)
  args=("$@")
  if [ "$b" = asan-prior ]; then
    args=(--filter 'object_prior/*')
  elif [[ " $suites " == *" asan-prior "* && $b = asan ]]; then
    args=(--filter '!(object_prior)/*')
    envs+=(CELADON_PRIOR_MODEL=/nonexistent/celadon-asan-runs-the-classical-path.onnx)
  fi
  if [ "$build" = asan ]; then
    envs+=("${asan_env[@]}" CELADON_BIN="$PWD/build/asan/celadon")
  else
    envs+=(CELADON_BIN="$PWD/build/celadon")
  fi
  env "${envs[@]}" ./build/$build/celadon-tests --jobs "$jobs" --xml="$out/$b.xml" "${args[@]}" >"$out/$b.log" 2>&1 &
  pid[$b]=$!
done

status=0
for b in $suites; do
  wait "${pid[$b]}" || status=1
done
end=$(date +%s)

declare -A title=([opt]="optimised build" [asan]="ASan+UBSan build" [asan-prior]="ASan+UBSan build, the learned prior's suite"
                  [python]="Python package (pytest)")
for b in $suites; do
  echo "== ${title[$b]}"
  cat "$out/$b.log"
done
for b in $suites; do
  [ "$b" = python ] && continue
  echo "== the slowest tests of the $b build (seconds; each also pays its process's start)"
  # <testsuite name="S" ...> then <testcase name="T" ... time="X">
  awk -F'"' '/<testsuite /{s=$2} /<testcase / && !/SKIPPED/{for(i=1;i<NF;i++) if($i~/ time=$/) print $(i+1), s "::" $2}' \
    "$out/$b.xml" 2>/dev/null | sort -rn | head -20
done
echo "== $suites in $((end - start)) s (Criterion with $jobs jobs each)"
# One closing line over every suite, from Criterion's syntheses and
# pytest's last line ("3 failed, 40 passed in 61.2s").
{
  for b in $suites; do
    if [ "$b" = python ]; then
      tail -1 "$out/$b.log" | awk '{for (i = 2; i <= NF; i++) {if ($i ~ /^passed/) p += $(i-1); if ($i ~ /^(failed|errors?)/) f += $(i-1)}}
                                   END {print p + 0, f + 0, 0}'
    else
      sed -n 's/.*Synthesis: Tested: [0-9]* | Passing: \([0-9]*\) | Failing: \([0-9]*\) | Crashing: \([0-9]*\).*/\1 \2 \3/p' "$out/$b.log"
    fi
  done
} | awk '{p += $1; f += $2 + $3} END {printf "tests: %d passed, %d failed\n", p, f}'
exit $status
