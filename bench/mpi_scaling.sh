#!/bin/sh
# What ranks cost and what they save (docs/distributed.md, "Cost of a rank";
# docs/BENCHMARKS.md, "MPI scaling"): scenes/studio at 320x180 and 64 spp,
# one thread per rank, rendered by one process and by `mpirun -np R` for R
# in 1 2 4, each run REPEAT times; wall and CPU seconds (every process of
# the run, mpirun's included) and the load average before each run. Then
# the same at 4 spp ("fixed-"), whose wall time F(R) is the fixed cost of
# the job (launch, MPI_Init, scene build, sum, write, MPI_Finalize) plus
# 1/16 of the samples; the cost model T(R) = F(R) + (T1 - F1) / min(R,
# cores), T1 and F1 those of one process, is then exact for a job whose
# fixed cost is F(R)'s (the samples F(R) holds and T1 - F1 add up to the
# whole render's), and is checked against the measured T(R).
# Last, whether each R's image is bit-equal to the one process's (idiff).
#
#   bench/mpi_scaling.sh [REPEAT]        (from the repository root; default 3)
#   CELADON_BIN=build/celadon  RANKS="1 2 4"  RES=320x180  SPP=64
#
# Prints one line per run and a summary; images go to out/bench/mpi/.
set -eu

repeat=${1:-3}
bin=${CELADON_BIN:-build/celadon}
ranks=${RANKS:-1 2 4}
res=${RES:-320x180}
spp=${SPP:-64}
scene=scenes/studio/scene.xml
out=out/bench/mpi
cores=$(nproc)

[ -x "$bin" ] || { echo "mpi_scaling: $bin is not built (make build/celadon)" >&2; exit 2; }
command -v mpirun >/dev/null || { echo "mpi_scaling: mpirun is missing (make deps)" >&2; exit 2; }
mkdir -p "$out"
mpirun="mpirun -q --oversubscribe"
[ "$(id -u)" -ne 0 ] || mpirun="$mpirun --allow-run-as-root"

# run LABEL RES SPP LAUNCHER...: one run; appends "label wall cpu load" to
# $out/runs.txt and prints it.
run() {
    label=$1 r=$2 s=$3
    shift 3
    load=$(cut -d' ' -f1 /proc/loadavg)
    /usr/bin/time -f '%e %U %S' -o "$out/time.txt" "$@" "$bin" render "$scene" -o "$out/$label.exr" \
        --res "$r" --spp "$s" --threads 1 2>"$out/$label.log" || {
        cat "$out/$label.log" >&2
        exit 1
    }
    read -r wall user sys <"$out/time.txt"
    cpu=$(awk -v u="$user" -v s="$sys" 'BEGIN { printf "%.2f", u + s }')
    printf '%-10s wall %6.2f s  cpu %6.2f s  load %s\n' "$label" "$wall" "$cpu" "$load"
    echo "$label $wall $cpu $load" >>"$out/runs.txt"
}

: >"$out/runs.txt"
echo "studio $res, $spp spp, 1 thread per rank; $cores cores; $repeat runs each"
for i in $(seq "$repeat"); do
    run single "$res" "$spp"
    for n in $ranks; do run "np$n" "$res" "$spp" $mpirun -np "$n"; done
    run fixed-single "$res" 4
    for n in $ranks; do run "fixed-np$n" "$res" 4 $mpirun -np "$n"; done
done

# The fastest run of each label (the one the other sessions disturbed least).
best() { awk -v l="$1" -v f="$2" '$1 == l && (b == "" || $f < b) { b = $f } END { print b }' "$out/runs.txt"; }

t1=$(best single 2)
f1=$(best fixed-single 2)
c1=$(best single 3)
echo
echo "fastest of $repeat (wall s, cpu s); model: T(R) = F(R) + (T1 - F1) / min(R, $cores)"
echo "  F(R): the 4-spp render's wall time under mpirun -np R (F1: one process's)"
printf '%-8s %7s %7s %7s %8s %9s %s\n' run wall cpu speedup "F(R)" model "image"
printf '%-8s %7.2f %7.2f %7s %8.2f %9s %s\n' single "$t1" "$c1" 1.00 "$f1" - reference
for n in $ranks; do
    t=$(best "np$n" 2)
    c=$(best "np$n" 3)
    f=$(best "fixed-np$n" 2)
    model=$(awk -v f="$f" -v t1="$t1" -v f1="$f1" -v n="$n" -v c="$cores" \
        'BEGIN { printf "%.2f", f + (t1 - f1) / (n < c ? n : c) }')
    speedup=$(awk -v a="$t1" -v b="$t" 'BEGIN { printf "%.2f", a / b }')
    if idiff -fail 0 -warn 0 "$out/single.exr" "$out/np$n.exr" >/dev/null 2>&1; then same=bit-equal; else same=DIFFERS; fi
    printf '%-8s %7.2f %7.2f %7s %8.2f %9s %s\n' "np$n" "$t" "$c" "${speedup}x" "$f" "$model" "$same"
done
