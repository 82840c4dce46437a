#!/bin/bash
# tools/bench_sweep.sh MPI_DRIVER [SCENE [N_STEPS]] -- sweep throughput on 1 and 2 ranks (issue 17).
# Runs the sweep (default data/tyre_sweep.nml, its variants made 3 times longer, N_STEPS
# = 6000 as in data/tyre_road.nml, so that the variants and not MPI's start-up dominate) from scratch (no records) on 1 rank, then on
# 2 ranks, and prints the wall time, the variants per second and the speed-up. Wall time
# includes MPI start-up and the check of every variant, as a user sees it.
set -eu
mpi=$(realpath "$1"); scene=${2:-data/tyre_sweep.nml}; steps=${3:-6000}; top=$PWD
MPIRUN=${MPIRUN:-mpirun}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# A rank waiting for the others yields its core instead of spinning (2 ranks may share cores).
export OMPI_MCA_mpi_yield_when_idle=1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
sed -e "s|'data/|'$top/data/|" -e "s|^\( *n_steps *= *\)[0-9]*|\1$steps|" "$scene" > "$work/sweep.nml"
declare -A rate
printf '%-6s %10s %10s %12s\n' ranks variants wall_s variants/s
for ranks in 1 2; do
    rm -rf "$work/out"
    start=$(date +%s.%N)
    (cd "$work" && "$MPIRUN" -np "$ranks" "$mpi" --quiet sweep.nml > log 2>&1)
    end=$(date +%s.%N)
    n=$(grep -vc '^#' "$work/out/"*_sweep.dat)
    rate[$ranks]=$(awk -v n="$n" -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", n/(b - a) }')
    printf '%-6s %10s %10.2f %12s\n' "$ranks" "$n" "$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }')" \
        "${rate[$ranks]}"
done
awk -v a="${rate[1]}" -v b="${rate[2]}" 'BEGIN { printf "speed-up on 2 ranks: %.2f (cores: %s)\n", b/a, "'"$(nproc)"'" }'
