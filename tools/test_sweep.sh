#!/bin/bash
# tools/test_sweep.sh SERIAL_DRIVER MPI_DRIVER -- the sweep checks of `make test` (issue 17).
# Runs data/tyre_sweep.nml (15 variants) in scratch folders and checks that:
#   the table is the same byte for byte on 1 rank, on 2 ranks and with the serial driver;
#   its rows are in variant order (1..15);
#   a rerun skips every finished variant, and an edited sweep reruns only what changed;
#   a variant that diverges (status 3) or fails its check (status 2) is recorded in its
#   row while the others complete, and `--check` exits 2 naming the bad variant.
# Prints "ok: ..." or "FAIL: ..." per check and ends with "sweep tests: N passed, N failed".
set -u
serial=$(realpath "$1"); mpi=$(realpath "$2"); top=$PWD
MPIRUN=${MPIRUN:-mpirun}
# OpenMPI refuses to run as root unless told; CI runs as root. --oversubscribe: 2 ranks on 1 core.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
passed=0; failed=0
check() { if eval "$2"; then echo "ok: $1"; passed=$((passed + 1)); else echo "FAIL: $1"; failed=$((failed + 1)); fi; }

# One folder per run, each with the same scene file name, so the tables may be compared whole.
for run in serial np1 np2; do
    mkdir -p "$work/$run"
    sed "s|'data/|'$top/data/|" "$top/data/tyre_sweep.nml" > "$work/$run/sweep.nml"
done
(cd "$work/serial" && "$serial" --quiet sweep.nml > log 2>&1); s1=$?
(cd "$work/np1" && "$MPIRUN" -np 1 "$mpi" --quiet sweep.nml > log 2>&1); s2=$?
(cd "$work/np2" && "$MPIRUN" -np 2 --oversubscribe "$mpi" --quiet sweep.nml > log 2>&1); s3=$?
check "the three runs end with status 0 ($s1 $s2 $s3)" '[ $s1 -eq 0 ] && [ $s2 -eq 0 ] && [ $s3 -eq 0 ]'
table=out/tyre_sweep_sweep.dat
check "1 and 2 ranks give the same table, byte for byte" 'cmp -s "$work/np1/$table" "$work/np2/$table"'
check "the serial driver gives the same table as MPI" 'cmp -s "$work/serial/$table" "$work/np2/$table"'
check "rows are in variant order 1..15" \
    '[ "$(grep -v "^#" "$work/np2/$table" | awk "{print \$1}" | tr "\n" " ")" = "$(seq 1 15 | tr "\n" " ")" ]'
check "every variant ended with status 0" \
    '[ "$(grep -v "^#" "$work/np2/$table" | awk "\$9 != 0 || \$15 != 0" | wc -l)" -eq 0 ]'

# Resume: a rerun skips all 15; editing one speed (30 -> 35 m/s) reruns its 3 variants only.
(cd "$work/np2" && "$MPIRUN" -np 2 --oversubscribe "$mpi" --quiet sweep.nml > log2 2>&1)
check "a rerun skips the 15 finished variants" 'grep -q "15 already done (skipped)" "$work/np2/log2"'
check "the rerun's table is unchanged" 'cmp -s "$work/np1/$table" "$work/np2/$table"'
records=$(ls "$work/np2/out/tyre_sweep_sweep.d" | wc -l)
sed -i 's/25.0, 30.0 /25.0, 35.0 /' "$work/np2/sweep.nml"
(cd "$work/np2" && "$MPIRUN" -np 2 --oversubscribe "$mpi" --quiet sweep.nml > log3 2>&1)
check "an edited sweep skips the 12 unchanged variants" 'grep -q "12 already done (skipped)" "$work/np2/log3"'
check "and runs the 3 edited ones (3 new records)" \
    '[ "$(ls "$work/np2/out/tyre_sweep_sweep.d" | wc -l)" -eq $((records + 3)) ]'
check "the edited rows show 35.0" '[ "$(grep -c "^1[345] *35.0 " "$work/np2/$table")" -eq 3 ]'
check "the unchanged rows are as before" \
    'cmp -s <(head -n 15 "$work/np1/$table" | tail -n 12) <(head -n 15 "$work/np2/$table" | tail -n 12)'

# Failures: a stiffness that makes the explicit step diverge (status 3 at its step) and a
# damping ratio out of range (status 2, found by the check); the other variants complete.
mkdir -p "$work/fail"
cat > "$work/fail/fail.nml" <<'NML'
&scene
    task = 'sweep'
    name = 'fail'
    dt = 1.0e-4
    n_steps = 2000
/
&structure
    model = 'sdof'
    mass = 1.0
    stiffness = 1.0e6
    damping_ratio = 0.02
/
&road
    profile = 'sine'
/
&contact
    stiffness = 1.0e6
    exponent = 1.5
/
&convolution
    methods = 'direct', 'modal'
/
&sweep
    contact.stiffness = 1.0e6, 1.0e14
    structure.damping_ratio = 0.02, 1.5
/
NML
(cd "$work/fail" && "$MPIRUN" -np 2 --oversubscribe "$mpi" --quiet fail.nml > log 2>&1); s=$?
ftable="$work/fail/out/fail_sweep.dat"
check "a sweep with failing variants ends with status 0 and writes its table ($s)" '[ $s -eq 0 ] && [ -f "$ftable" ]'
row() { grep -v '^#' "$ftable" | sed -n "${1}p" | awk '{print $8, $9, $14, $15}'; }
check "variant 1 completes (status 0)" '[ "$(row 1)" = "0 0 0 0" ]'
check "variant 3 diverges: status 3 and its step" '[ "$(row 3 | awk "{print \$1, \$3}")" = "3 3" ] && [ "$(row 3 | awk "{print \$2}")" -gt 0 ]'
check "variants 2 and 4 fail their check: status 2" '[ "$(row 2)" = "2 0 2 0" ] && [ "$(row 4)" = "2 0 2 0" ]'
check "the bad variant is named with its line" 'grep -q "fail.nml (variant 2):[0-9]*: &structure damping_ratio" "$work/fail/log"'
(cd "$work/fail" && "$serial" --check fail.nml > clog 2>&1); s=$?
check "--check counts the variants and exits 2 on a bad one ($s)" '[ $s -eq 2 ] && grep -q "4 variants of .* 2 checked ok, 2 bad" "$work/fail/clog"'
sed -i 's/model = .sdof./model = '"'"'sdoff'"'"'/' "$work/fail/fail.nml"
(cd "$work/fail" && "$MPIRUN" -np 2 --oversubscribe "$mpi" fail.nml > blog 2>&1); s=$?
check "bad input in the base scene: status 2 before anything runs ($s)" \
    '[ $s -eq 2 ] && grep -q "base scene" "$work/fail/blog"'

echo "sweep tests: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
