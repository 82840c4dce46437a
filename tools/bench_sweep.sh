#!/bin/bash
# tools/bench_sweep.sh MPI_DRIVER [SCENE [N_STEPS [N_POINTS]]] -- sweep throughput on 1 and 2 ranks
# and the cost of rerunning a complete sweep.
# Runs the sweep (default data/tyre_sweep.nml with N_STEPS = 6000 steps and N_POINTS = 50
# contact points, so that each of its 15 variants takes about half a second and the variants,
# not MPI's start-up, dominate) from scratch (no records) on 1 rank, then on 2 ranks, then
# once more on 1 rank over the finished records (every variant skipped). Prints the wall
# times, the variants per second, "speed-up 2 ranks / 1 rank = X" and "rerun of a complete
# sweep = Y of a run" (the rerun's wall time over the 1-rank run's). Wall times include MPI
# start-up, as a user sees them; the load average before the runs is printed beside them
# (other work on the machine lowers the speed-up), and MPI's start-up alone, which a rerun
# is mostly made of.
set -eu
mpi=$(realpath "$1"); scene=${2:-data/tyre_sweep.nml}; steps=${3:-6000}; points=${4:-50}; top=$PWD
MPIRUN=${MPIRUN:-mpirun}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# A rank waiting for the others yields its core instead of spinning (2 ranks may share cores).
export OMPI_MCA_mpi_yield_when_idle=1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
sed -e "s|'data/|'$top/data/|" -e "s|^\( *n_steps *= *\)[0-9]*|\1$steps|" \
    -e "s|^\( *n_points *= *\)[0-9]*|\1$points|" "$scene" > "$work/sweep.nml"
load=$(cut -d ' ' -f 1 /proc/loadavg 2>/dev/null || echo '?')
declare -A wall rate outside
run() { # run LABEL RANKS: one run of the sweep in $work, its wall time in wall[LABEL]
    local start end status=0
    start=$(date +%s.%N)
    (cd "$work" && "$MPIRUN" -np "$2" "$mpi" --quiet sweep.nml > "log_$1" 2>&1) || status=$?
    end=$(date +%s.%N)
    # status 4: some variants ran outside the accuracy asked, their rows whole and marked; the
    # sweep itself went through, which is what is timed here. Any other status is a failure.
    if [ "$status" -ne 0 ] && [ "$status" -ne 4 ]; then
        echo "bench_sweep: the sweep on $2 rank(s) failed with status $status:" >&2
        grep '^greenconv' "$work/log_$1" >&2 || true
        exit "$status"
    fi
    if [ "$status" -eq 4 ]; then
        outside[$1]=$(grep -c 'ran outside the accuracy asked (status 4' "$work/log_$1" || true)
    fi
    wall[$1]=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", b - a }')
}
printf '%-8s %6s %10s %10s %12s\n' run ranks variants wall_s variants/s
for ranks in 1 2; do
    rm -rf "$work/out"
    run "np$ranks" "$ranks"
    n=$(grep -vc '^#' "$work/out/"*_sweep.dat)
    rate[$ranks]=$(awk -v n="$n" -v t="${wall[np$ranks]}" 'BEGIN { printf "%.2f", n/t }')
    printf '%-8s %6s %10s %10s %12s\n' scratch "$ranks" "$n" "${wall[np$ranks]}" "${rate[$ranks]}"
done
run rerun 1
# Control: two 1-rank runs at once, each in its own folder. On an idle 2-core machine they
# take the time of one (capacity 2.0); other work on the machine lowers the capacity, and the
# speed-up of 2 ranks can be no better than it.
for copy in a b; do mkdir -p "$work/$copy"; cp "$work/sweep.nml" "$work/$copy/"; done
start=$(date +%s.%N)
# Each run is its own mpirun, which would bind its one rank to core 0 like the other: unbound.
for copy in a b; do (cd "$work/$copy" && "$MPIRUN" -np 1 --bind-to none "$mpi" --quiet sweep.nml > log 2>&1) & done
wait
both=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.3f", b - a }')
# MPI's start-up, which every run above includes: one rank checking a one-line-summary scene
start=$(date +%s.%N)
"$MPIRUN" -np 1 "$mpi" --check "$top/data/sdof_sine.nml" > /dev/null 2>&1
startup=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.3f", b - a }')
grep -q "$n already done (skipped)" "$work/log_rerun" || { echo "bench_sweep: the rerun did not skip all $n variants" >&2; exit 1; }
printf '%-8s %6s %10s %10s %12s\n' rerun 1 "$n" "${wall[rerun]}" -
if [ -n "${outside[np1]:-}" ]; then
    echo "(status 4 on 1 rank: ${outside[np1]} of the $n variants ran outside the accuracy asked; their rows are whole and timed like the others)"
fi
awk -v a="${rate[1]}" -v b="${rate[2]}" -v c="$(nproc)" -v l="$load" \
    'BEGIN { printf "speed-up 2 ranks / 1 rank = %.2f (%s variants of %s steps at %s points; cores: %s, load average before: %s)\n", b/a, "'"$n"'", "'"$steps"'", "'"$points"'", c, l }'
awk -v t="${wall[np1]}" -v b="$both" -v a="${rate[1]}" -v c="${rate[2]}" \
    'BEGIN { printf "control: two 1-rank runs at once took %.2f s, capacity 2 x %.2f / %.2f = %.2f; speed-up / capacity = %.2f\n", b, t, b, 2*t/b, (c/a)/(2*t/b) }'
awk -v r="${wall[rerun]}" -v s="${wall[np1]}" \
    -v u="$startup" 'BEGIN { printf "rerun of a complete sweep = %.3f of a run (%.2f s against %.2f s on 1 rank, every variant skipped; of which MPI start-up about %.2f s)\n", r/s, r, s, u }'
