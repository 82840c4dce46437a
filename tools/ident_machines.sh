#!/usr/bin/env bash
# The identification suites under other BLAS kernels, BLAS libraries, thread counts and builds:
# what another machine would run.
#
#   bash tools/ident_machines.sh [SETUP...]
#
# SETUPs (all when none is named):
#   default      the system's OpenBLAS as it picks its kernels, OMP_NUM_THREADS unset
#   haswell      OPENBLAS_CORETYPE=Haswell
#   skylakex     OPENBLAS_CORETYPE=SkylakeX
#   sandybridge  OPENBLAS_CORETYPE=Sandybridge
#   reference    Debian's reference BLAS and LAPACK (LD_LIBRARY_PATH to their folders)
#   threads1     OMP_NUM_THREADS=1
#   threads2     OMP_NUM_THREADS=2
#   release      the fpm release profile (-O3) instead of the debug one (-O0)
#   make         the Makefile's build (make lib, -O2 with OpenMP): test/threads/ident_threads
#                (pyuff's beam FRF 1 and sdypy's H_51) under the default, Haswell and reference set-ups
# SUITES (default: identreal outofband identsearch mlfit polyref) chooses the suites.
# Each run prints "setup suite: N passed, N failed" and the determined modes of the measured beam
# (outofband) and of sdypy's FRFs (identreal);
# the last line is the total "N passed, N failed"; the exit status is 1 when any run failed.
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

FPM=${FPM:-fpm}
SUITES=${SUITES:-identreal outofband identsearch mlfit polyref}
REFERENCE_PATH=/usr/lib/x86_64-linux-gnu/blas:/usr/lib/x86_64-linux-gnu/lapack
ALL="default haswell skylakex sandybridge reference threads1 threads2 release make"
setups=${*:-$ALL}

# The environment of a set-up, as `env` arguments.
environment() {
    case "$1" in
        haswell) echo "OPENBLAS_CORETYPE=Haswell" ;;
        skylakex) echo "OPENBLAS_CORETYPE=SkylakeX" ;;
        sandybridge) echo "OPENBLAS_CORETYPE=Sandybridge" ;;
        reference) echo "LD_LIBRARY_PATH=$REFERENCE_PATH" ;;
        threads1) echo "OMP_NUM_THREADS=1" ;;
        threads2) echo "OMP_NUM_THREADS=2" ;;
        default | release | make) echo "GREENCONV_SETUP=$1" ;;
        *) echo "ident_machines.sh: unknown set-up '$1' (one of: $ALL)" >&2; exit 2 ;;
    esac
}

passed=0
failed=0
log=$(mktemp)
trap 'rm -f "$log"' EXIT
for setup in $setups; do
    vars=$(environment "$setup") || exit 2
    if [ "$setup" = make ]; then
        make -s lib >/dev/null || { echo "make: make lib failed"; failed=$((failed + 1)); continue; }
        for env_vars in "GREENCONV_SETUP=default" "OPENBLAS_CORETYPE=Haswell" "LD_LIBRARY_PATH=$REFERENCE_PATH"; do
            if env "$env_vars" make -s thread-ident >"$log" 2>&1; then
                passed=$((passed + 1)); verdict="1 passed, 0 failed"
            else
                failed=$((failed + 1)); verdict="0 passed, 1 failed"
            fi
            echo "make ($env_vars) thread-ident: $verdict"
            grep -E 'poles|determined' "$log" | sed 's/^/    /' | head -n 6
        done
        continue
    fi
    profile=()
    [ "$setup" = release ] && profile=(--profile release)
    for suite in $SUITES; do
        env "$vars" "$FPM" test "${profile[@]}" -- "$suite" >"$log" 2>&1
        summary=$(grep -E '^[0-9]+ passed, [0-9]+ failed' "$log" | tail -n 1)
        [ -n "$summary" ] || summary="0 passed, 1 failed"
        echo "$setup $suite: $summary"
        p=${summary%% passed*}
        f=${summary#*passed, }
        f=${f%% failed*}
        passed=$((passed + p))
        failed=$((failed + f))
        # The determined modes per FRF (pyuff's measured beam, sdypy's FRFs), as the suites note them.
        if [ "$suite" = outofband ] || [ "$suite" = identreal ]; then
            grep -oE '(measured beam, FRF [0-9]|(receptance|accelerance) H_[0-9]+): (modes determined|f \[Hz\]) = [0-9.E+-]+' "$log" |
                awk -F': ' '{split($2, v, " = "); key = $1; if (v[1] ~ /^modes/) {printf "%s%s:", (n++ ? "\n" : ""), "    " key; } else printf " %.4f", v[2] + 0}
                     END {if (n) print ""}'
        fi
    done
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
