#!/usr/bin/env bash
# The implicit patch against the explicit one: per-step costs of `exact` (implicit step) and
# `modal` (explicit step) on data/tyre_patch.nml (50 x 20 = 1,000 points, 441 modes), each the
# difference between an N2-step and an N1-step run of the driver (set-up and W0's factorisation
# cancel), on 1 and 2 OpenMP threads, rounds interleaved (exact N1, exact N2, modal N1, modal N2,
# then again) so that a drift of the shared machine's speed falls on both methods; the median of
# the rounds is printed with the ratio exact/modal of each round. Then the same patch on a
# 100 x 50 grid (5,000 points) on 1 and 2 threads: its measured per-step costs (M2 - M1 steps),
# its set-up (the M1-step run less M1 steps), peak memory, and the 1,000-point costs projected
# linearly in N_c for comparison; against the target of at most 300 s per 1e5 steps on 2
# threads and 4 GB. Threads wait passively (OMP_WAIT_POLICY=passive unless set): on a shared
# machine spinning threads make two-thread runs unmeasurable.
#
# Usage: bench/patch_cost.sh DRIVER [ROUNDS] [N1] [N2] [M1] [M2]  (the driver built with OpenMP: `make lib`)
# Prints a table with `#` headers; needs /usr/bin/time (GNU time) for the memory column.
# THREADS (environment, default "1 2") lists the thread counts of the 1,000-point rows; M2 = 0
# leaves the 5,000-point rows out (`THREADS=1 bench/patch_cost.sh DRIVER 5 200 2200 0 0`: the
# implicit/explicit ratio at 1,000 points on one thread alone, in a minute or two).
set -euo pipefail
driver=${1:?usage: patch_cost.sh DRIVER [ROUNDS] [N1] [N2] [M1] [M2]}
rounds=${2:-5}
n1=${3:-200}
# 2,000 steps between the two 1,000-point runs: GNU time reads CPU seconds to 10 ms, 2 % of
# the `exact` difference and 4 % of the `modal` one at these lengths (twice that at 1,000 steps).
n2=${4:-2200}
# 2,000 steps between the two 5,000-point runs: their set-up (W0, the companions' models) varies
# by a second or more between identical runs, as much as 300 steps cost.
m1=${5:-200}
m2=${6:-2200}
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# scene METHOD STEPS NX NY: a copy of the shipped patch with these settings, output into $work.
scene() {
    local file="$work/patch_$1_$2_$3x$4.nml"
    sed -e "s/^\( *n_steps *=\).*/\1 $2/" \
        -e "s/^\( *methods *=\).*/\1 '$1'/" \
        -e "s/^\( *n_points_x *=\).*/\1 $3/" \
        -e "s/^\( *n_points_y *=\).*/\1 $4/" \
        -e "s/^\( *spectra *=\).*/\1 .false./" \
        -e "s/^\( *map_times *=\).*/\1 $(awk "BEGIN{print ($2 - 1)*2.0e-5/2}")/" \
        -e "s#^\( *output_dir *=\).*#\1 '$work/out'#" data/tyre_patch.nml > "$file"
    echo "$file"
}

# run THREADS SCENE: "cpu_s wall_s peak_kB" of one whole driver run (its exit status 4, the
# budget beyond the accuracy asked at these run lengths, does not matter here).
run() {
    OMP_NUM_THREADS=$1 /usr/bin/time -o "$work/time" -f 'TIME %U %S %e %M' "$driver" --quiet "$2" > /dev/null || true
    awk '/^TIME/ {printf "%.4f %.4f %d\n", $2 + $3, $4, $5}' "$work/time"
}

median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1)/2] : (v[NR/2] + v[NR/2 + 1])/2}'; }

# per_step THREADS NX NY STEPS1 STEPS2 ROUNDS: rows "exact_s modal_s ratio exact_peak_kB exact_setup_s
# exact_cpu_s" per round, per-step seconds (CPU on 1 thread, wall on more; CPU always in the last).
per_step() {
    local field=1 r e1 e2 m1 m2
    [ "$1" -gt 1 ] && field=2
    for ((r = 1; r <= $6; r++)); do
        e1=$(run "$1" "$(scene exact "$4" "$2" "$3")")
        e2=$(run "$1" "$(scene exact "$5" "$2" "$3")")
        m1=$(run "$1" "$(scene modal "$4" "$2" "$3")")
        m2=$(run "$1" "$(scene modal "$5" "$2" "$3")")
        awk -v a="$e1" -v b="$e2" -v c="$m1" -v d="$m2" -v f="$field" -v n="$(($5 - $4))" -v s1="$4" 'BEGIN {
            split(a, A, " "); split(b, B, " "); split(c, C, " "); split(d, D, " ")
            e = (B[f] - A[f])/n; m = (D[f] - C[f])/n; c = (B[1] - A[1])/n
            printf "%.6e %.6e %.3f %d %.2f %.6e\n", e, m, (m > 0 ? e/m : 0), B[3], A[f] - e*s1, c }'
    done
}

declare -a e1000
echo "# implicit (exact) against explicit (modal) on data/tyre_patch.nml:" \
     "per-step cost = (run of $n2 steps - run of $n1)/$((n2 - n1)),"
echo "# $rounds interleaved rounds, median; 1 thread: CPU seconds, 2 threads: wall seconds" \
     "(OMP_WAIT_POLICY=$OMP_WAIT_POLICY); $(uptime)"
echo "# n_c  threads  exact_s_per_step  modal_s_per_step  exact/modal" \
     " (min..max of the rounds' ratios)  exact_s_per_1e5_steps"
for threads in ${THREADS:-1 2}; do
    rows=$(per_step "$threads" 50 20 "$n1" "$n2" "$rounds")
    e=$(cut -d' ' -f1 <<< "$rows" | median)
    m=$(cut -d' ' -f2 <<< "$rows" | median)
    lo=$(cut -d' ' -f3 <<< "$rows" | sort -g | head -1)
    hi=$(cut -d' ' -f3 <<< "$rows" | sort -g | tail -1)
    printf '%5d  %7d  %16.3e  %16.3e  %11.2f  (%s..%s)  %10.1f\n' 1000 "$threads" "$e" "$m" \
        "$(awk -v e="$e" -v m="$m" 'BEGIN{print e/m}')" "$lo" "$hi" "$(awk -v e="$e" 'BEGIN{print e*1e5}')"
    e1000[$threads]=$e
done
if [ "$m2" -eq 0 ]; then
    echo "# end: $(uptime)"
    exit 0
fi
echo "# 5,000 points (100 x 50 on the same patch), $m1 and $m2 steps, one round;" \
     "target: exact <= 300 s per 1e5 steps on 2 threads (wall), <= 4 GB; $(uptime)"
echo "# n_c  threads  exact_s_per_step  modal_s_per_step  exact/modal  exact_s_per_1e5_steps" \
     " projected_from_1000_s_per_1e5  peak_GB  exact_setup_s  exact_cpu_s_per_step  target"
for threads in 1 2; do
    row=$(per_step "$threads" 100 50 "$m1" "$m2" 1)
    read -r e m ratio peak setup cpu <<< "$row"
    verdict=-
    if [ "$threads" -eq 2 ]; then
        verdict=$(awk -v e="$e" -v p="$peak" 'BEGIN{printf "time %s, memory %s", (e*1e5 <= 300 ? "met" : "NOT met"),
                  (p/1048576 <= 4 ? "met" : "NOT met")}')
    fi
    printf '%5d  %7d  %16.3e  %16.3e  %11.2f  %21.1f  %29.1f  %7.2f  %13.1f  %20.3e  %s\n' 5000 "$threads" "$e" "$m" \
        "$ratio" "$(awk -v e="$e" 'BEGIN{print e*1e5}')" "$(awk -v e="${e1000[$threads]:-0}" 'BEGIN{print 5*e*1e5}')" \
        "$(awk -v p="$peak" 'BEGIN{print p/1048576}')" "$setup" "$cpu" "$verdict"
done
echo "# end: $(uptime)"
