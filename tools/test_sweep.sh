#!/bin/bash
# tools/test_sweep.sh SERIAL_DRIVER MPI_DRIVER -- the sweep checks of `make test`.
# Runs data/tyre_sweep.nml (15 variants, with the 1/3-octave level columns) in scratch
# folders and checks that:
#   the table, level columns included, is the same byte for byte on 1 rank, on 2 ranks and
#   with the serial driver; its rows are in variant order (1..15);
#   `--check` checks every variant, prints the count and runs nothing;
#   a rerun skips every finished variant; an edited sweep reruns only what changed, and an
#   edited road file reruns every variant that reads it;
#   a variant that diverges (status 3) or fails its check (status 2) is recorded in its
#   row (levels nan) while the others complete, with the same table and history files on
#   1 and 2 ranks, and `--check` exits 2 naming the bad variant.
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
for run in serial np1 np2 check; do
    mkdir -p "$work/$run"
    sed "s|'data/|'$top/data/|" "$top/data/tyre_sweep.nml" > "$work/$run/sweep.nml"
done
# np2 reads its own copy of the road file, edited below
cp "$top/data/road_sample.dat" "$work/np2/road.dat"
sed -i "s|'$top/data/road_sample.dat'|'road.dat'|" "$work/np2/sweep.nml"
(cd "$work/check" && "$MPIRUN" -np 2 --oversubscribe "$mpi" --check sweep.nml > log 2>&1); s=$?
check "--check on 2 ranks: status 0, the count once, nothing run ($s)" \
    '[ $s -eq 0 ] && [ "$(grep -c "15 variants of road.speed contact.stiffness, methods modal exact; 15 checked ok, 0 bad" \
    "$work/check/log")" -eq 1 ] && [ ! -e "$work/check/out" ]'

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
bands="800 1000 1250 1600 2000 2500 3150 4000 5000"
names=$(for m in modal exact; do for b in $bands; do printf 'L%s_%s ' "$b" "$m"; done; done)
check "the level columns L800_modal .. L5000_exact, then estimate_modal, estimate_exact end the header" \
    '[ "$(grep "^# variant" "$work/np2/$table" | awk "{for (i = 17; i <= NF; i++) printf \"%s \", \$i}")" = "$names""estimate_modal estimate_exact " ]'
check "every row has 35 columns, its 18 levels numbers (dB re 1 N), its 2 estimates numbers" \
    '[ "$(grep -v "^#" "$work/np2/$table" | awk "NF != 35 { bad++ } { for (i = 16; i <= 33; i++) if (\$i !~ /^-?[0-9]+\.[0-9][0-9][0-9][0-9]$/) bad++; for (i = 34; i <= 35; i++) if (\$i !~ /^[0-9]\.[0-9][0-9][0-9]E[-+][0-9][0-9][0-9]$/) bad++ } END { print bad + 0 }")" -eq 0 ]'

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
    'cmp -s <(grep -v "^#" "$work/np1/$table" | head -n 12) <(grep -v "^#" "$work/np2/$table" | head -n 12)'

# An edited road file (heights doubled from x = 1.0 to 1.2 m, which every variant rolls
# over) reruns all 15 variants, though the sweep file did not change.
cp "$work/np2/$table" "$work/np2/before.dat"
awk '!/^#/ && $1 >= 1.0 && $1 <= 1.2 { printf "%7.3f   %.7E\n", $1, 2*$2; next } { print }' "$top/data/road_sample.dat" \
    > "$work/np2/road.dat"
(cd "$work/np2" && "$MPIRUN" -np 2 --oversubscribe "$mpi" --quiet sweep.nml > log4 2>&1)
check "an edited road file reruns every variant (none skipped)" 'grep -q "0 already done (skipped)" "$work/np2/log4"'
check "and every row's rms force changed" \
    '[ "$(paste <(grep -v "^#" "$work/np2/before.dat") <(grep -v "^#" "$work/np2/$table") | awk "\$6 != \$41" | wc -l)" -eq 15 ]'

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
    spectra = .true., f_low = 500.0, f_high = 2000.0, histories = .true.
/
NML
mkdir -p "$work/fail1" && cp "$work/fail/fail.nml" "$work/fail1/"
(cd "$work/fail" && "$MPIRUN" -np 2 --oversubscribe "$mpi" --quiet fail.nml > log 2>&1); s=$?
(cd "$work/fail1" && "$MPIRUN" -np 1 "$mpi" --quiet fail.nml > log 2>&1)
ftable="$work/fail/out/fail_sweep.dat"
check "a sweep with failing variants completes the others, writes its table and ends with status 3, the worst of theirs ($s)" '[ $s -eq 3 ] && [ -f "$ftable" ] && grep -q "3 of 4 variants failed" "$work/fail/log"'
row() { grep -v '^#' "$ftable" | sed -n "${1}p" | awk '{print $8, $9, $14, $15}'; }
levels() { grep -v '^#' "$ftable" | sed -n "${1}p" | awk '{for (i = 16; i <= NF - 2; i++) printf "%s ", ($i == "nan" ? "nan" : "L")}'; }
check "variant 1 completes (status 0), its 14 levels numbers" \
    '[ "$(row 1)" = "0 0 0 0" ] && [ "$(levels 1)" = "$(printf "L %.0s" $(seq 14))" ]'
check "variant 3 diverges: status 3 and its step" '[ "$(row 3 | awk "{print \$1, \$3}")" = "3 3" ] && [ "$(row 3 | awk "{print \$2}")" -gt 0 ]'
check "variant 3's levels: nan for both methods, which diverged" '[ "$(levels 3)" = "$(printf "nan %.0s" $(seq 14))" ]'
check "variants 2 and 4 fail their check: status 2, levels nan" \
    '[ "$(row 2)" = "2 0 2 0" ] && [ "$(row 4)" = "2 0 2 0" ] && [ "$(levels 2)" = "$(levels 3)" ] && [ "$(levels 4)" = "$(levels 3)" ]'
check "1 and 2 ranks: the same table with failures, byte for byte" 'cmp -s "$ftable" "$work/fail1/out/fail_sweep.dat"'
check "histories: fail_v{1,3}_{direct,modal}.dat only (none for variants that failed their check)" \
    '[ "$(cd "$work/fail/out" && ls fail_v*)" = "$(printf "fail_v1_direct.dat\nfail_v1_modal.dat\nfail_v3_direct.dat\nfail_v3_modal.dat")" ]'
same_histories() { for f in "$work"/fail/out/fail_v*; do cmp -s "$f" "$work/fail1/out/${f##*/}" || return 1; done; }
check "histories: the same files on 1 and 2 ranks, byte for byte" same_histories
check "the diverged variant's history stops at its fault step" \
    '[ "$(grep -vc "^#" "$work/fail/out/fail_v3_direct.dat")" -le "$(row 3 | awk "{print \$2}")" ]'
check "the bad variant is named with its line" 'grep -q "fail.nml (variant 2):[0-9]*: &structure damping_ratio" "$work/fail/log"'
(cd "$work/fail" && "$serial" --check fail.nml > clog 2>&1); s=$?
check "--check counts the variants and exits 2 on a bad one ($s)" '[ $s -eq 2 ] && grep -q "4 variants of .* 2 checked ok, 2 bad" "$work/fail/clog"'
sed -i 's/model = .sdof./model = '"'"'sdoff'"'"'/' "$work/fail/fail.nml"
(cd "$work/fail" && "$MPIRUN" -np 2 --oversubscribe "$mpi" fail.nml > blog 2>&1); s=$?
check "bad input in the base scene: status 2 before anything runs ($s)" \
    '[ $s -eq 2 ] && grep -q "base scene" "$work/fail/blog"'

# Status 4 over ranks: one mode measured to 500 Hz run at dt = 1 ms, where direct's own
# estimate (7e-2 of the kernel) is above an accuracy of 1e-3: variant 2 ends 4, the sweep ends 4
# on 2 ranks as serially; with a bad variant besides, 2 (a failure ranks before 4).
mkdir -p "$work/acc"
awk 'BEGIN { pi = atan2(0, -1); w0 = 2*pi*100; printf "# one mode, 100 Hz: f [Hz], Re G, Im G [m/N]\n";
             for (l = 0; l <= 500; l++) { w = 2*pi*l; a = w0*w0 - w*w; b = 2*9.4e-3*w0*w;
                 printf "%6.1f %25.16e %25.16e\n", l, a/(a*a + b*b), -b/(a*a + b*b) } }' > "$work/acc/one_mode.frf"
cat > "$work/acc/acc.nml" <<'NML'
&scene task = 'sweep', name = 'acc', dt = 1.0e-3, n_steps = 100 /
&structure model = 'frf_file', frf_file = 'one_mode.frf' /
&road profile = 'sine', amplitude = 1.0e-4, omega = 300.0 /
&contact stiffness = 1.0e6, exponent = 1.5, preload = 10.0 /
&convolution methods = 'direct', 'exact' /
&sweep convolution.accuracy = 0.5, 1.0e-3 /
NML
(cd "$work/acc" && "$MPIRUN" -np 2 --oversubscribe "$mpi" --quiet acc.nml > log 2>&1); s=$?
check "a variant outside its accuracy: the sweep ends 4 on 2 ranks ($s)" \
    '[ $s -eq 4 ] && grep -q "outside the accuracy asked" "$work/acc/log"'
sed -i 's/accuracy = 0.5, 1.0e-3/accuracy = 0.5, 1.0e-3, -1.0/' "$work/acc/acc.nml"
(cd "$work/acc" && "$MPIRUN" -np 2 --oversubscribe "$mpi" --quiet acc.nml > log2 2>&1); s=$?
check "with a bad variant besides: status 2, not 4 ($s)" '[ $s -eq 2 ]'

echo "sweep tests: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
