#!/usr/bin/env bash
# Helpers for the top-level Makefile, kept here so the Makefile stays short.
#
#   tools/make_helpers.sh deps
#       Install what the build needs and is missing (gfortran, LAPACK, BLAS, FFTW3,
#       gnuplot, pkg-config through apt-get; fpm through pip). Silent when everything is
#       there.
#
#   tools/make_helpers.sh f90deps OBJDIR SOURCE...
#       Print make rules "OBJDIR/a.o: OBJDIR/b.o" from the `use` statements of the
#       sources (a.f90 uses a module that b.f90 defines), plus DEPS_SRCS := SOURCE...
#
#   tools/make_helpers.sh same-output DRIVER SCENE...
#       Run each scene with the fpm-built driver (`fpm run`, fpm's default debug
#       profile) and with DRIVER (the Makefile build), each with its output_dir
#       redirected into a temporary directory, and check that both wrote the same
#       files with the same header and row count and numbers that agree to a
#       relative 1e-9 (see compare_columns below).
#
#   tools/make_helpers.sh examples DRIVER EXAMPLE...
#       Run DRIVER (the Makefile build) on data/sdof_sine.nml into a temporary directory,
#       then each built example: c_contact and legacy_f77 compare their results with
#       those files (the directory is c_contact's argument, with data/sample_receptance.frf,
#       and legacy_f77's standard input); cxx_header, omp_threads, c_patch and
#       legacy_patch check themselves. When c_patch_file or legacy_patch_file is among
#       them, DRIVER also runs data/patch_road.nml (the shipped 2D patch, into a folder
#       patch/ beside the first), whose files those two compare their own time loops with
#       (the folder is c_patch_file's argument and legacy_patch_file's standard input).
#
#   tools/make_helpers.sh install DESTDIR PREFIX VERSION BUILD LIBS_PRIVATE
#       Install the driver, libgreenconv.a, libgreenconv.so.VERSION (with its soname and
#       link-name links), include/greenconv.h, the module files (PREFIX/include/greenconv)
#       and PREFIX/lib/pkgconfig/greenconv.pc from the plain build in BUILD.
#
#   tools/make_helpers.sh install-test DRIVER
#       `make install` into a temporary prefix, then build example/c_contact.c against the
#       installed shared library and example/legacy_f77.f against the installed static
#       library, both with the flags of `pkg-config greenconv`, and run them against
#       DRIVER's output for data/sdof_sine.nml; the same for example/c_patch.c and
#       example/legacy_patch.f (the multi-point patch, checked against the library's whole
#       run) and example/c_patch_file.c and example/legacy_patch_file.f (the shipped 2D
#       patch from its file, checked against DRIVER's output for data/patch_road.nml).
#       Uses $MAKE, $CC and $FC.
#
#   tools/make_helpers.sh doc-check SOURCE...
#       Check that every public entity of the sources (modules; types, procedures and
#       constants named public; components and type-bound procedures of public types)
#       has a `!>` comment on the line above.
#
#   tools/make_helpers.sh doc
#       Install FORD with pip when missing and write the API documentation to build/doc.
#
#   tools/make_helpers.sh fuzz DRIVER FUZZ CASES SEED
#       Copy data/ into a temporary directory and run the fuzz program FUZZ there on
#       DRIVER (CASES damaged files from SEED). The directory is removed when every case
#       passes, and kept (its path printed, with the damaged files in failures/) when not.
#
#   tools/make_helpers.sh valgrind DRIVER PROGRAM...
#       Run DRIVER under valgrind on every data/*.nml scene (output_dir redirected into a
#       temporary directory, n_steps cut to at most VALGRIND_STEPS, default 2000), then each
#       PROGRAM (the examples, the C tests) the way `make examples` / `make ctest` runs it.
#       Fails when valgrind reports an invalid access or memory "definitely lost"; the log of
#       a failing run is kept and its path printed.
#
#   tools/make_helpers.sh sanitize CASES [--no-unit] [VARIANT...]
#       Instrumented builds, each in its own build directory. VARIANTs (both when none is
#       named): asan, AddressSanitizer with UndefinedBehaviorSanitizer (every finding fatal)
#       and gfortran's -fcheck=all at -O1; check, -fcheck=all alone at -O0. --no-unit leaves
#       out the unit tests (fpm test), the longest part (CI's `make sanitize-ci`). Each runs
#       the unit tests (`fpm test` with those flags: fpm keeps a build directory per set of
#       flags), the C tests and CASES fuzz cases (the Makefile build in build/sanitize-*).
#       ASan runs with quarantine_size_mb=0 (the 1e8-step memory test measures the resident
#       size) and detect_leaks=0 (leaks are valgrind's: `make valgrind`).
#
#   tools/make_helpers.sh fpm-test [ARGS...]
#       `fpm test ARGS`, then the sum of the test programs' "N passed, N failed" lines (one
#       per layer's program, test/<layer>/main.f90, or the one line of a suite named after
#       "--") as the last line of the test output. A run with fewer of those lines than
#       expected (a program was stopped early) fails.
set -euo pipefail

# The fpm command (the Makefile exports its FPM variable).
FPM=${FPM:-fpm}
# The fpm release the build and tests are checked with (pip installs exactly this one).
FPM_VERSION=0.12.0

say() { printf 'greenconv: %s\n' "$*"; }
die() { printf 'greenconv: error: %s\n' "$*" >&2; exit 1; }

# ---------------------------------------------------------------------------------
# deps
# ---------------------------------------------------------------------------------

# Is the shared library lib$1.so (the unversioned link-time name) findable?
have_lib() {
    local name="lib$1.so" ldconfig_bin
    ldconfig_bin=$(command -v ldconfig || echo /sbin/ldconfig)
    if [ -x "$ldconfig_bin" ] && "$ldconfig_bin" -p 2>/dev/null | grep -q "[[:space:]]$name[[:space:]]"; then
        return 0
    fi
    compgen -G "/usr/lib/*/$name" >/dev/null || compgen -G "/usr/lib/$name" >/dev/null \
        || compgen -G "/usr/lib64/$name" >/dev/null || compgen -G "/usr/local/lib/$name" >/dev/null
}

# Does fpm run? (Under pyenv a shim can exist for a version that lacks fpm.)
have_fpm() { $FPM --version >/dev/null 2>&1; }

have_pip() { python3 -m pip --version >/dev/null 2>&1; }

# Run a command as root: directly, through sudo, or fail with a hint.
as_root() {
    if [ "$(id -u)" -eq 0 ]; then
        "$@"
    elif command -v sudo >/dev/null 2>&1; then
        sudo "$@"
    else
        die "need root (or sudo) to run: $*"
    fi
}

cmd_deps() {
    local missing=() packages=(gfortran liblapack-dev libblas-dev libfftw3-dev gnuplot-nox pkg-config openmpi-bin
                               libopenmpi-dev valgrind)
    command -v gfortran >/dev/null 2>&1 || missing+=(gfortran)
    have_lib lapack || missing+=(LAPACK)
    have_lib blas || missing+=(BLAS)
    have_lib fftw3 || missing+=(FFTW3)
    command -v gnuplot >/dev/null 2>&1 || missing+=(gnuplot)
    command -v pkg-config >/dev/null 2>&1 || missing+=(pkg-config)
    # OpenMPI for the MPI driver of sweeps (make mpi, make sweep-test).
    command -v mpif90 >/dev/null 2>&1 && command -v mpirun >/dev/null 2>&1 || missing+=(OpenMPI)
    # valgrind's helgrind for the two-thread check of make test (make thread-helgrind).
    command -v valgrind >/dev/null 2>&1 || missing+=(valgrind)
    # fpm comes from pip; without python3/pip, apt brings them along.
    if ! have_fpm && ! have_pip; then
        missing+=(pip)
        packages+=(python3-pip)
    fi

    if [ "${#missing[@]}" -gt 0 ]; then
        say "installing ${packages[*]} (missing: ${missing[*]})"
        export DEBIAN_FRONTEND=noninteractive
        as_root apt-get update -qq
        as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${packages[@]}" >/dev/null
    fi

    # An optimised BLAS/LAPACK (the field's default; the identification's Gram matrices
    # and the LU of the implicit step run through it). Debian's OpenMP build of OpenBLAS becomes
    # the system's libblas.so.3/liblapack.so.3 by update-alternatives, so the link line stays
    # -llapack -lblas, and it runs serially inside greenconv's (or a host's) parallel regions.
    # Optional: without it (no apt, no root) the reference BLAS gives the same results, slower.
    if ! have_lib openblas; then
        if command -v apt-get >/dev/null 2>&1 && { [ "$(id -u)" -eq 0 ] || command -v sudo >/dev/null 2>&1; }; then
            say "installing libopenblas-openmp-dev (an optimised BLAS/LAPACK; optional)"
            as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libopenblas-openmp-dev >/dev/null 2>&1 \
                || { as_root apt-get update -qq >/dev/null 2>&1 \
                     && as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libopenblas-openmp-dev >/dev/null; } \
                || say "could not install OpenBLAS; the reference BLAS/LAPACK is used (slower; results equal to round-off)"
        else
            say "no OpenBLAS and no apt/root: the reference BLAS/LAPACK is used (slower; results equal to round-off)"
        fi
    fi

    if ! have_fpm; then
        say "installing fpm with pip (fpm not found on PATH; the build and the tests use it)"
        pip_install "fpm==$FPM_VERSION"
        # The Makefile appends ~/.local/bin (pip's user scheme) to PATH; anything else
        # has to be put on PATH by the user.
        have_fpm || die "fpm was installed but is not on PATH ($PATH); add pip's script directory to PATH"
    fi
}

# pip_install REQUIREMENT: quietly, retrying with --break-system-packages where the system
# Python refuses (externally managed).
pip_install() {
    local log
    log=$(mktemp)
    export PIP_DISABLE_PIP_VERSION_CHECK=1 PIP_ROOT_USER_ACTION=ignore
    if ! python3 -m pip install -q "$1" >"$log" 2>&1; then
        if grep -q externally-managed-environment "$log"; then
            say "pip refused (externally managed Python); retrying with --break-system-packages"
            python3 -m pip install -q --break-system-packages "$1" >"$log" 2>&1 \
                || { cat "$log" >&2; rm -f "$log"; die "pip install $1 failed"; }
        else
            cat "$log" >&2; rm -f "$log"; die "pip install $1 failed"
        fi
    fi
    rm -f "$log"
    if command -v pyenv >/dev/null 2>&1; then pyenv rehash >/dev/null 2>&1 || true; fi
    hash -r
}

# ---------------------------------------------------------------------------------
# f90deps
# ---------------------------------------------------------------------------------

cmd_f90deps() {
    [ $# -ge 1 ] || die "usage: $0 f90deps OBJDIR SOURCE..."
    local objdir=$1
    shift
    printf '# Generated by tools/make_helpers.sh f90deps from the use statements; do not edit.\n'
    printf 'DEPS_SRCS := %s\n' "$*"
    [ $# -gt 0 ] || return 0
    awk -v objdir="$objdir" '
        function object(src) { sub(/\.[fF]90$/, ".o", src); return objdir "/" src }
        {
            line = tolower($0)
            sub(/!.*/, "", line)                      # strip comments
        }
        # module NAME (not "module procedure", "module function", ...)
        match(line, /^[ \t]*module[ \t]+[a-z][a-z0-9_]*[ \t]*$/) {
            name = line; sub(/^[ \t]*module[ \t]+/, "", name); sub(/[ \t]*$/, "", name)
            if (name != "procedure" && name != "function" && name != "subroutine")
                defines[name] = FILENAME
            next
        }
        # submodule (ancestor[:parent]) NAME: depends on the ancestor module
        match(line, /^[ \t]*submodule[ \t]*\([ \t]*[a-z][a-z0-9_]*/) {
            name = substr(line, RSTART, RLENGTH); sub(/.*\([ \t]*/, "", name)
            uses[FILENAME, name] = 1; files[FILENAME] = 1
            next
        }
        # use NAME | use :: NAME | use, non_intrinsic :: NAME  (intrinsic modules skipped)
        match(line, /^[ \t]*use[ \t,:]/) {
            if (line ~ /^[ \t]*use[ \t]*,[ \t]*intrinsic/) next
            name = line
            if (name ~ /::/) sub(/^.*::[ \t]*/, "", name)
            else sub(/^[ \t]*use[ \t]+/, "", name)
            if (match(name, /^[a-z][a-z0-9_]*/)) {
                uses[FILENAME, substr(name, 1, RLENGTH)] = 1; files[FILENAME] = 1
            }
        }
        END {
            for (key in uses) {
                split(key, part, SUBSEP)
                src = part[1]; mod = part[2]
                if ((mod in defines) && defines[mod] != src)
                    print object(src) ": " object(defines[mod])
            }
        }
    ' "$@" | sort
}

# ---------------------------------------------------------------------------------
# same-output
# ---------------------------------------------------------------------------------

# compare_columns A B: same '#' line count, same last '#' line (the column names), same
# number of data rows and columns, and every number within
#     |a - b| <= rtol*max(|a|, |b|) + rtol*scale(column)
# with rtol = 1e-9 and scale = the largest |value| of that column in A. The column scale
# keeps values that are round-off around zero (u ~ 1e-23 m at t = 0) from failing a purely
# relative test. Prints the largest |a - b|/scale(column) seen.
compare_columns() {
    awk -v rtol=1e-9 -v A="$1" -v B="$2" '
        function abs(x) { return x < 0 ? -x : x }
        function max(x, y) { return x > y ? x : y }
        { file = (FILENAME == A) ? 1 : 2 }
        /^#/ { ncom[file]++; head[file] = $0; next }
        file == 1 { n1++; nc1[n1] = NF; for (i = 1; i <= NF; i++) { a[n1, i] = $i + 0; scale[i] = max(scale[i], abs($i + 0)) } }
        file == 2 { n2++; nc2[n2] = NF; for (i = 1; i <= NF; i++) b[n2, i] = $i + 0 }
        END {
            if (ncom[1] != ncom[2] || head[1] != head[2]) { printf "headers differ: %s | %s\n", head[1], head[2]; exit 1 }
            if (n1 != n2 || n1 == 0) { printf "row counts differ (or are zero): %d vs %d\n", n1, n2; exit 1 }
            worst = 0
            for (r = 1; r <= n1; r++) {
                if (nc1[r] != nc2[r]) { printf "row %d: %d vs %d columns\n", r, nc1[r], nc2[r]; exit 1 }
                for (i = 1; i <= nc1[r]; i++) {
                    d = abs(a[r, i] - b[r, i])
                    if (d > rtol * max(abs(a[r, i]), abs(b[r, i])) + rtol * scale[i]) {
                        printf "row %d column %d: %.17g vs %.17g\n", r, i, a[r, i], b[r, i]; exit 1
                    }
                    if (scale[i] > 0) worst = max(worst, d / scale[i])
                }
            }
            printf "%d rows, max deviation %.1e of column scale\n", n1, worst
        }
    ' "$1" "$2"
}

# redirected_scene SCENE DIR: the scene file with its output_dir set to DIR.
redirected_scene() {
    sed -E "s|^([[:space:]]*output_dir[[:space:]]*=[[:space:]]*)['\"][^'\"]*['\"]|\1'$2'|I" "$1"
}

cmd_same_output() {
    [ $# -ge 2 ] || die "usage: $0 same-output DRIVER SCENE..."
    local driver=$1 scene tmp failed=0 summary
    shift
    [ -x "$driver" ] || die "$driver not built (run make lib)"
    tmp=$(mktemp -d "${TMPDIR:-/tmp}/greenconv-check.XXXXXX")
    CHECK_TMP=$tmp
    trap 'rm -rf "$CHECK_TMP"' EXIT

    say "building the fpm driver for the comparison"
    $FPM build >"$tmp/fpm-build.log" 2>&1 || { cat "$tmp/fpm-build.log" >&2; die "fpm build failed"; }

    for scene in "$@"; do
        local base=${scene##*/}
        base=${base%.nml}
        grep -Eiq "^[[:space:]]*output_dir[[:space:]]*=" "$scene" \
            || die "$scene sets no output_dir; cannot redirect its output for the check"
        for kind in fpm make; do
            mkdir -p "$tmp/$kind/$base/out"
            redirected_scene "$scene" "$tmp/$kind/$base/out" >"$tmp/$kind/$base/scene.nml"
        done
        if ! $FPM run -- "$tmp/fpm/$base/scene.nml" >"$tmp/fpm/$base/log" 2>&1; then
            cat "$tmp/fpm/$base/log" >&2; say "FAIL: fpm-built driver on $scene"; failed=1; continue
        fi
        if ! "$driver" "$tmp/make/$base/scene.nml" >"$tmp/make/$base/log" 2>&1; then
            cat "$tmp/make/$base/log" >&2; say "FAIL: $driver on $scene"; failed=1; continue
        fi
        local files_fpm files_make
        files_fpm=$(cd "$tmp/fpm/$base/out" && find . -type f | sort)
        files_make=$(cd "$tmp/make/$base/out" && find . -type f | sort)
        if [ -z "$files_fpm" ] || [ "$files_fpm" != "$files_make" ]; then
            say "FAIL: $scene: output files differ: fpm [${files_fpm//$'\n'/ }] make [${files_make//$'\n'/ }]"
            failed=1; continue
        fi
        local f
        for f in $files_fpm; do
            if summary=$(compare_columns "$tmp/fpm/$base/out/$f" "$tmp/make/$base/out/$f"); then
                say "ok: $driver matches the fpm build on $scene: ${f#./} ($summary)"
            else
                say "FAIL: $scene: ${f#./}: $summary"; failed=1
            fi
        done
    done
    return "$failed"
}

# ---------------------------------------------------------------------------------
# examples, install, install-test
# ---------------------------------------------------------------------------------

# The scene the examples reproduce.
EXAMPLE_SCENE=data/sdof_sine.nml

# driver_reference DRIVER DIR: DRIVER's output files for EXAMPLE_SCENE, written into DIR.
driver_reference() {
    mkdir -p "$2"
    redirected_scene "$EXAMPLE_SCENE" "$2" >"$2/scene.nml"
    "$1" "$2/scene.nml" >"$2/driver.log" 2>&1 || { cat "$2/driver.log" >&2; die "$1 failed on $EXAMPLE_SCENE"; }
}

# The shipped 2D patch from a Green's matrix file: c_patch_file and legacy_patch_file run it
# with their own time loops and compare with the driver's files for it.
PATCH_SCENE=data/patch_road.nml

# patch_reference DRIVER DIR: DRIVER's output files for PATCH_SCENE, written into DIR/patch
# (the scene identifies its file once, about 5 s).
patch_reference() {
    mkdir -p "$2/patch"
    redirected_scene "$PATCH_SCENE" "$2/patch" >"$2/patch/scene.nml"
    # PATCH_RUNNER: a command to run the driver under (the valgrind run sets it, so that the
    # reference and the examples see the same arithmetic: under valgrind libm and LAPACK take
    # other code paths, and the implicit step's Newton iterates then differ in the last bits).
    ${PATCH_RUNNER:-} "$1" "$2/patch/scene.nml" >"$2/patch/driver.log" 2>&1 \
        || { cat "$2/patch/driver.log" >&2; die "$1 failed on $PATCH_SCENE"; }
}

# needs_patch PROGRAM...: whether one of the programs compares with patch_reference's files.
needs_patch() {
    local program
    for program in "$@"; do
        case ${program##*/} in c_patch_file | legacy_patch_file) return 0 ;; esac
    done
    return 1
}

# run_example PROGRAM REFERENCE_DIR: run one example the way it takes its input.
run_example() {
    case ${1##*/} in
        c_contact) "$1" "$2" data/sample_receptance.frf ;;
        legacy_f77) printf '%s\n' "$2" | "$1" ;;
        c_patch_file) "$1" "$2/patch" ;;
        legacy_patch_file) printf '%s\n' "$2/patch" | "$1" ;;
        *) "$1" ;;
    esac
}

cmd_examples() {
    [ $# -ge 1 ] || die "usage: $0 examples DRIVER EXAMPLE..."
    local driver=$1 tmp example failed=0
    shift
    tmp=$(mktemp -d "${TMPDIR:-/tmp}/greenconv-examples.XXXXXX")
    CHECK_TMP=$tmp
    trap 'rm -rf "$CHECK_TMP"' EXIT
    driver_reference "$driver" "$tmp/reference"
    if needs_patch "$@"; then patch_reference "$driver" "$tmp/reference"; fi
    say "examples, against $driver's output for $EXAMPLE_SCENE (and $PATCH_SCENE)"
    for example in "$@"; do
        if ! run_example "$example" "$tmp/reference"; then
            say "FAIL: $example"
            failed=1
        fi
    done
    return "$failed"
}

# vg_run LOG COMMAND...: COMMAND under valgrind; 0 when clean, else the log is kept.
vg_run() {
    local log=$1
    shift
    if valgrind --quiet --leak-check=full --show-leak-kinds=definite --errors-for-leak-kinds=definite \
        --error-exitcode=99 \
        --log-file="$log" "$@" >"$log.out" 2>&1 && [ ! -s "$log" ]; then
        return 0
    fi
    say "FAIL: valgrind: $* (log: $log, output: $log.out)"
    return 1
}

cmd_valgrind() {
    [ $# -ge 1 ] || die "usage: $0 valgrind DRIVER PROGRAM..."
    # Steps per scene: at most VALGRIND_STEPS, and at most VALGRIND_POINT_STEPS point-steps
    # (N_c * N_t), at least 50: memcheck is 30-100 times slower, and what it checks (every
    # allocation, every code path of a step) is the same at 200 steps of a 1,000-point patch as
    # at 2,000.
    local driver=$1 tmp scene name program failed=0 steps cap points
    local point_steps=${VALGRIND_POINT_STEPS:-200000}
    steps=${VALGRIND_STEPS:-2000}
    shift
    command -v valgrind >/dev/null || die "valgrind not found (apt-get install valgrind)"
    [ -x "$driver" ] || die "$driver not built (run make lib)"
    tmp=$(mktemp -d "${TMPDIR:-/tmp}/greenconv-valgrind.XXXXXX")
    driver_reference "$driver" "$tmp/reference"
    if needs_patch "$@"; then
        PATCH_RUNNER="valgrind --quiet --error-exitcode=99" patch_reference "$driver" "$tmp/reference"
    fi
    for scene in data/*.nml; do
        name=${scene##*/}
        name=${name%.nml}
        points=$(awk 'tolower($0) ~ /^[[:space:]]*n_points(_x|_y)?[[:space:]]*=/ {
                split($0, part, "="); n = part[2] + 0; if (n > 0) product *= n }
                BEGIN { product = 1 } END { print product }' "$scene")
        cap=$((point_steps / points))
        [ "$cap" -gt "$steps" ] && cap=$steps
        [ "$cap" -lt 50 ] && cap=50
        redirected_scene "$scene" "$tmp/$name" |
            awk -v cap="$cap" 'tolower($0) ~ /^[[:space:]]*n_steps[[:space:]]*=/ {
                split($0, part, "="); value = part[2] + 0
                if (value > cap) { sub(/=[[:space:]]*[0-9]+/, "= " cap); cut = 1 } }
                cut && tolower($0) ~ /^[[:space:]]*map_times[[:space:]]*=/ { next } { print }' >"$tmp/$name.nml"
        say "valgrind: $scene"
        vg_run "$tmp/$name.log" "$driver" --quiet "$tmp/$name.nml" || failed=1
    done
    for program in "$@"; do
        say "valgrind: $program"
        case ${program##*/} in
            c_contact) vg_run "$tmp/c_contact.log" "$program" "$tmp/reference" data/sample_receptance.frf || failed=1 ;;
            legacy_f77) vg_run "$tmp/legacy_f77.log" "$program" <<<"$tmp/reference" || failed=1 ;;
            c_patch_file) vg_run "$tmp/c_patch_file.log" "$program" "$tmp/reference/patch" || failed=1 ;;
            legacy_patch_file) vg_run "$tmp/legacy_patch_file.log" "$program" <<<"$tmp/reference/patch" || failed=1 ;;
            *) vg_run "$tmp/${program##*/}.log" "$program" || failed=1 ;;
        esac
    done
    if [ "$failed" -eq 0 ]; then
        rm -rf "$tmp"
        say "valgrind: clean (no invalid access, nothing definitely lost)"
    fi
    return "$failed"
}

cmd_sanitize() {
    [ $# -ge 1 ] || die "usage: $0 sanitize CASES [--no-unit] [asan|check...]"
    local cases=$1 variant fflags cflags lflags failed=0 started variants unit=yes
    shift
    if [ "${1:-}" = --no-unit ]; then unit=no; shift; fi
    variants=${*:-asan check}
    local asan='-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer'
    export ASAN_OPTIONS=quarantine_size_mb=0:detect_leaks=0:abort_on_error=1
    export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
    for variant in $variants; do
        started=$SECONDS
        if [ "$variant" = asan ]; then
            fflags="-g -O1 -fcheck=all $asan"
            cflags="-g -O1 -std=c99 $asan"
            lflags=$asan
        elif [ "$variant" = check ]; then
            fflags='-g -O0 -fcheck=all -fbacktrace'
            cflags='-g -O0 -std=c99'
            lflags=''
        else
            die "sanitize: unknown variant '$variant' (asan or check)"
        fi
        if [ "$unit" = yes ]; then
            say "sanitize ($variant): fpm test with $fflags"
            if ! "$FPM" test --flag "$fflags" --c-flag "$cflags" ${lflags:+--link-flag "$lflags"}; then
                say "FAIL: sanitize ($variant): fpm test"
                failed=1
            fi
        fi
        say "sanitize ($variant): C tests and $cases fuzz cases (build/sanitize-$variant)"
        if ! "${MAKE:-make}" BUILD="build/sanitize-$variant" FFLAGS="$fflags -std=f2018 -fimplicit-none" \
            CFLAGS="$cflags" FUZZ_CASES="$cases" ctest fuzz; then
            say "FAIL: sanitize ($variant): C tests or fuzz"
            failed=1
        fi
        say "sanitize ($variant): $((SECONDS - started)) s"
    done
    [ "$failed" -eq 0 ] && say "sanitize: clean (ASan+UBSan and -fcheck=all)"
    return "$failed"
}

cmd_install() {
    [ $# -eq 5 ] || die "usage: $0 install DESTDIR PREFIX VERSION BUILD LIBS_PRIVATE"
    local destdir=$1 prefix=$2 version=$3 build=$4 private=$5
    local root=$destdir$prefix major=${version%%.*}
    install -d "$root/bin" "$root/lib/pkgconfig" "$root/include/greenconv"
    install -m 755 "$build/greenconv" "$root/bin/"
    install -m 644 "$build/libgreenconv.a" "$root/lib/"
    install -m 755 "$build/libgreenconv.so.$version" "$root/lib/"
    ln -sf "libgreenconv.so.$version" "$root/lib/libgreenconv.so.$major"
    ln -sf "libgreenconv.so.$major" "$root/lib/libgreenconv.so"
    install -m 644 include/greenconv.h "$root/include/"
    install -m 644 "$build"/include/*.mod "$root/include/greenconv/"
    {
        printf 'prefix=%s\n' "$prefix"
        printf '%s\n' 'exec_prefix=${prefix}' 'libdir=${exec_prefix}/lib' 'includedir=${prefix}/include' \
            'moduledir=${includedir}/greenconv' ''
        printf '%s\n' 'Name: greenconv' \
            "Description: Fast convolution with Green's functions and dynamic contact (C, Fortran, Fortran 77 APIs)"
        printf 'Version: %s\n' "$version"
        printf '%s\n' 'Cflags: -I${includedir} -I${moduledir}' 'Libs: -L${libdir} -lgreenconv'
        printf 'Libs.private: %s\n' "$private"
    } >"$root/lib/pkgconfig/greenconv.pc"
    say "installed greenconv $version into $root (bin, lib, include, lib/pkgconfig/greenconv.pc)"
}

cmd_install_test() {
    [ $# -eq 1 ] || die "usage: $0 install-test DRIVER"
    local driver=$1 tmp prefix cflags libs private
    tmp=$(mktemp -d "${TMPDIR:-/tmp}/greenconv-install.XXXXXX")
    CHECK_TMP=$tmp
    trap 'rm -rf "$CHECK_TMP"' EXIT
    prefix=$tmp/prefix
    ${MAKE:-make} --no-print-directory install PREFIX="$prefix" >"$tmp/install.log" 2>&1 \
        || { cat "$tmp/install.log" >&2; die "make install PREFIX=$prefix failed"; }
    driver_reference "$driver" "$tmp/reference"
    export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
    cflags=$(pkg-config --cflags greenconv)
    libs=$(pkg-config --libs greenconv)
    private=$(pkg-config --static --libs-only-l greenconv | sed 's/-lgreenconv//')
    say "install test: make install PREFIX=$prefix; pkg-config --cflags --libs greenconv: $cflags $libs"
    # shellcheck disable=SC2086 # the flags are words
    "${CC:-cc}" -O2 -o "$tmp/c_contact" example/c_contact.c $cflags $libs -lm \
        || die "building example/c_contact.c against the installed library failed"
    # Linked against the shared library (the link name picks it), found at run time here.
    readelf -d "$tmp/c_contact" | grep -q 'NEEDED.*libgreenconv\.so' \
        || die "c_contact is not linked against libgreenconv.so"
    LD_LIBRARY_PATH=$prefix/lib run_example "$tmp/c_contact" "$tmp/reference" || die "the installed C example failed"
    # shellcheck disable=SC2086
    "${FC:-gfortran}" -O2 -ffixed-form -J"$tmp" -o "$tmp/legacy_f77" example/legacy_f77.f $cflags \
        "$prefix/lib/libgreenconv.a" $private \
        || die "building example/legacy_f77.f against the installed library failed"
    run_example "$tmp/legacy_f77" "$tmp/reference" || die "the installed Fortran 77 example failed"
    # The multi-point patch: C against the shared library, fixed form against the static one.
    # shellcheck disable=SC2086
    "${CC:-cc}" -O2 -o "$tmp/c_patch" example/c_patch.c $cflags $libs -lm \
        || die "building example/c_patch.c against the installed library failed"
    LD_LIBRARY_PATH=$prefix/lib run_example "$tmp/c_patch" || die "the installed C patch example failed"
    # shellcheck disable=SC2086
    "${FC:-gfortran}" -O2 -ffixed-form -J"$tmp" -o "$tmp/legacy_patch" example/legacy_patch.f $cflags \
        "$prefix/lib/libgreenconv.a" $private \
        || die "building example/legacy_patch.f against the installed library failed"
    run_example "$tmp/legacy_patch" || die "the installed Fortran 77 patch example failed"
    # The shipped 2D patch from its file, against the driver's run of the scene.
    patch_reference "$driver" "$tmp/reference"
    # shellcheck disable=SC2086
    "${CC:-cc}" -O2 -o "$tmp/c_patch_file" example/c_patch_file.c $cflags $libs -lm \
        || die "building example/c_patch_file.c against the installed library failed"
    LD_LIBRARY_PATH=$prefix/lib run_example "$tmp/c_patch_file" "$tmp/reference" \
        || die "the installed C patch-file example failed"
    # shellcheck disable=SC2086
    "${FC:-gfortran}" -O2 -ffixed-form -J"$tmp" -o "$tmp/legacy_patch_file" example/legacy_patch_file.f $cflags \
        "$prefix/lib/libgreenconv.a" $private \
        || die "building example/legacy_patch_file.f against the installed library failed"
    run_example "$tmp/legacy_patch_file" "$tmp/reference" || die "the installed Fortran 77 patch-file example failed"
    say "ok: C examples (shared library) and Fortran 77 examples (static library), built with" \
        "pkg-config from the installed prefix, match the driver (c_contact, legacy_f77, and the" \
        "shipped patch from its file: c_patch_file, legacy_patch_file) and the library's whole" \
        "multi-point run (c_patch, legacy_patch)"
}

# ---------------------------------------------------------------------------------
# doc-check, doc
# ---------------------------------------------------------------------------------

cmd_doc_check() {
    local missing
    missing=$(awk -f tools/doc_check.awk "$@")
    if [ -n "$missing" ]; then
        printf '%s\n' "$missing" >&2
        die "public entities without a !> doc comment (listed above)"
    fi
    say "doc-check: every public entity of the $# sources has a !> comment"
}

cmd_doc() {
    if ! command -v ford >/dev/null 2>&1; then
        say "installing FORD with pip (ford not found on PATH; make doc uses it)"
        pip_install ford
        command -v ford >/dev/null 2>&1 || die "ford was installed but is not on PATH ($PATH)"
    fi
    # src/greenconv/core/version.F90 needs fpm.toml's version as GREENCONV_VERSION, as in a build
    ford --quiet --macro "GREENCONV_VERSION=$(sed -n 's/^version *= *"\(.*\)"/\1/p' fpm.toml)" doc/greenconv.md
    say "API documentation: build/doc/index.html"
}

# ---------------------------------------------------------------------------------
# fuzz
# ---------------------------------------------------------------------------------

cmd_fuzz() {
    local driver=$1 fuzz=$2 cases=$3 seed=$4 work rc=0 start workers w counts=()
    driver="$(cd "$(dirname "$driver")" && pwd)/$(basename "$driver")"
    workers=$(nproc 2>/dev/null || echo 1)
    [ "$workers" -gt 4 ] && workers=4
    work=$(mktemp -d "${TMPDIR:-/tmp}/greenconv-fuzz.XXXXXX")
    say "fuzz: $cases damaged copies of data/*.nml, data/sample_receptance.frf and data/road_sample.dat" \
        "through $driver ($workers workers, in $work)"
    start=$SECONDS
    for ((w = 1; w <= workers; w++)); do
        mkdir -p "$work/w$w"
        cp -r data "$work/w$w/data"
        counts+=("$work/w$w/counts.txt")
        "$fuzz" "$driver" "$work/w$w" "$cases" "$seed" "$w" "$workers" > "$work/w$w/log.txt" 2>&1 &
    done
    wait || true
    cat "$work"/w*/log.txt
    "$fuzz" --report "${counts[@]}" || rc=$?
    if [ "$rc" -eq 0 ]; then
        rm -rf "$work"
        say "fuzz: ok ($((SECONDS - start)) s)"
    else
        say "fuzz: FAILED; the failing cases are kept in $work/w*/failures"
    fi
    return "$rc"
}

# ---------------------------------------------------------------------------------
# fpm-test
# ---------------------------------------------------------------------------------

cmd_fpm_test() {
    local log rc=0 lines expected passed=0 failed=0 line count
    log=$(mktemp)
    $FPM test "$@" 2>&1 | tee "$log" || rc=$?
    # Each layer's test program (test/<layer>/main.f90) ends with "<layer>: N passed, N failed";
    # the one program that runs a suite named on the command line, with "N passed, N failed".
    lines=$(grep -E '^([A-Za-z]+: )?[0-9]+ passed, [0-9]+ failed' "$log" || true)
    rm -f "$log"
    # Every layer's line, or the one line of the suite that the arguments after "--" name.
    expected=$(grep -c '^name = "greenconv-tests-' fpm.toml)
    case " $* " in *" -- "?*) expected=1 ;; esac
    count=0
    while IFS= read -r line; do
        [ -n "$line" ] || continue
        line=${line#*: }
        passed=$((passed + ${line%% passed*}))
        line=${line#*passed, }
        failed=$((failed + ${line%% failed*}))
        count=$((count + 1))
    done <<< "$lines"
    # A program stopped inside a library (the reference LAPACK's XERBLA stops with status 0)
    # exits "successfully" without the harness's closing line: that is a failure too.
    if [ "$rc" -eq 0 ] && [ "$count" -ne "$expected" ]; then
        say "fpm test printed $count of the $expected \"N passed, N failed\" lines its test programs end" \
            "with: a test program was stopped early (see the lines above, e.g. a LAPACK \"On entry to ...\" message)"
        rc=1
    fi
    if [ "$rc" -ne 0 ]; then
        say "fpm test failed (exit status $rc)"
    fi
    if [ "$count" -gt 0 ]; then printf '%d passed, %d failed\n' "$passed" "$failed"; fi
    return "$rc"
}

case "${1:-}" in
    deps) shift; cmd_deps "$@" ;;
    f90deps) shift; cmd_f90deps "$@" ;;
    same-output) shift; cmd_same_output "$@" ;;
    examples) shift; cmd_examples "$@" ;;
    install) shift; cmd_install "$@" ;;
    install-test) shift; cmd_install_test "$@" ;;
    doc-check) shift; cmd_doc_check "$@" ;;
    doc) shift; cmd_doc "$@" ;;
    fuzz) shift; cmd_fuzz "$@" ;;
    fpm-test) shift; cmd_fpm_test "$@" ;;
    valgrind) shift; cmd_valgrind "$@" ;;
    sanitize) shift; cmd_sanitize "$@" ;;
    *) die "usage: $0 deps | f90deps OBJDIR SOURCE... | same-output DRIVER SCENE... | examples DRIVER EXAMPLE..." \
           "| install DESTDIR PREFIX VERSION BUILD LIBS | install-test DRIVER | doc-check SOURCE... | doc" \
           "| fuzz DRIVER FUZZ CASES SEED | fpm-test [ARGS...] | valgrind DRIVER PROGRAM... | sanitize CASES" ;;
esac
