#!/usr/bin/env bash
# Two drivers on bench/tyre_patch_5000.nml (5,000 points, `exact`) and data/tyre_patch.nml
# (1,000 points, `exact` and `modal`), rounds interleaved (the first driver, then the second,
# for each run length), on 1 and 2 OpenMP threads: per-step wall and CPU time as the
# difference between an N2-step and an N1-step run (set-up cancels), the set-up (the N1-step
# run less its steps), the peak memory, and the second driver's ratios to the first.
#
# Usage: bench/woodbury_driver.sh BEFORE_DRIVER AFTER_DRIVER [ROUNDS] [N1] [N2]
# Run from the repository's root; needs /usr/bin/time (GNU time).
set -euo pipefail
before=${1:?usage: woodbury_driver.sh BEFORE AFTER [ROUNDS] [N1] [N2]}
after=${2:?usage: woodbury_driver.sh BEFORE AFTER [ROUNDS] [N1] [N2]}
rounds=${3:-2}
n1=${4:-100}
n2=${5:-400}
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# scene FILE METHOD STEPS: a copy with these settings, no spectra, output into $work.
scene() {
    local file="$work/$(basename "$1" .nml)_$2_$3.nml"
    sed -e "s/^\( *n_steps *=\).*/\1 $3/" \
        -e "s/^\( *methods *=\).*/\1 '$2'/" \
        -e "s/^\( *spectra *=\).*/\1 .false./" \
        -e "s/^\( *map_times *=\).*/\1 $(awk "BEGIN{print ($3 - 1)*2.0e-5/2}")/" \
        -e "s#^\( *output_dir *=\).*#\1 '$work/out'#" "$1" > "$file"
    echo "$file"
}

# run DRIVER THREADS SCENE: "cpu_s wall_s peak_kB".
run() {
    OMP_NUM_THREADS=$2 /usr/bin/time -o "$work/time" -f 'TIME %U %S %e %M' "$1" --quiet "$3" > /dev/null || true
    awk '/^TIME/ {printf "%.3f %.3f %d\n", $2 + $3, $4, $5}' "$work/time"
}

echo "# per step = (run of $n2 steps - run of $n1)/$((n2 - n1)); $(uptime)"
echo "# points method threads round | before: wall_ms cpu_ms setup_wall_s peak_MB | after: the same | wall before/after"
for round in $(seq "$rounds"); do
    for case in "bench/tyre_patch_5000.nml exact 5000" "data/tyre_patch.nml exact 1000" "data/tyre_patch.nml modal 1000"; do
        set -- $case
        for threads in 1 2; do
            row="$3 $2 $threads $round |"
            walls=()
            for driver in "$before" "$after"; do
                a=$(run "$driver" "$threads" "$(scene "$1" "$2" "$n1")")
                b=$(run "$driver" "$threads" "$(scene "$1" "$2" "$n2")")
                cells=$(awk -v a="$a" -v b="$b" -v n="$((n2 - n1))" -v s="$n1" 'BEGIN {
                    split(a, A, " "); split(b, B, " ")
                    w = (B[2] - A[2])/n; c = (B[1] - A[1])/n
                    printf "%.3f %.3f %.1f %.0f", 1e3*w, 1e3*c, A[2] - w*s, B[3]/1024 }')
                walls+=("$(cut -d' ' -f1 <<< "$cells")")
                row="$row $cells |"
            done
            echo "$row $(awk -v x="${walls[0]}" -v y="${walls[1]}" 'BEGIN{printf "%.2f", (y > 0 ? x/y : 0)}')  load $(cut -d' ' -f1 /proc/loadavg)"
        done
    done
done
