#!/usr/bin/env bash
# tools/test_plot_formats.sh DRIVER
#
# The plot scripts that read a contact run's column files (those that load
# plot/lib/column_file.gp, and those that load one of them) draw the same figure from a text
# run (<name>_<method>.dat) and from a binary one (<name>_<method>.bin + .bin.txt, &scene
# output_format = 'binary'). DRIVER runs the shipped scenes twice, once per format, into a
# temporary directory; each script is run on each, once drawing its PNG and once with
# `set table` (the data gnuplot would draw, as text); both runs must succeed, their tables
# must hold the same data lines and their PNGs the same bytes. Then the helper's choice
# between the two formats in one directory (the newer, or `format` forced), and a missing
# file: the script stops with status 1 and names both names.
#
# To keep it to seconds: the tyre scene is cut to 3000 steps (0.15 s: the force map shows
# 0.10-0.14 s) with truncation_tol = 0.2 for its `direct`, and Figs. 5 and 6 read a run of the
# SDOF scene named mdof_random (they need its columns, not the identification of the 10 modes).
# Prints one "ok:" or "FAIL:" line per check and a summary; exits 1 when a check failed.

set -euo pipefail

[ $# -eq 1 ] || { echo "usage: $0 DRIVER" >&2; exit 2; }
driver=$1
[ -x "$driver" ] || { echo "$0: $driver is not an executable (run make lib)" >&2; exit 2; }
GNUPLOT=${GNUPLOT:-gnuplot}
command -v "$GNUPLOT" >/dev/null || { echo "$0: gnuplot not found" >&2; exit 2; }

tmp=$(mktemp -d "${TMPDIR:-/tmp}/greenconv-plots.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
passed=0
failed=0
ok() { echo "ok: $*"; passed=$((passed + 1)); }
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }

# scene FILE DIR FORMAT [SED...]: the scene with its output into DIR in FORMAT, edited by SED.
scene() {
    local file=$1 dir=$2 format=$3
    shift 3
    sed -E -e "s|^([[:space:]]*output_dir[[:space:]]*=[[:space:]]*)'[^']*'|\1'$dir'\n    output_format = '$format'|" \
        "$@" "$file"
}

for format in text binary; do
    dir=$tmp/$format
    mkdir -p "$dir"
    scene data/sdof_sine.nml "$dir" "$format" >"$dir/sdof_sine.nml"
    scene data/sdof_sine.nml "$dir" "$format" -e "s|name = 'sdof_sine'|name = 'mdof_random'|" >"$dir/mdof_random.nml"
    # direct's kernel cut at 0.2 of max|g| for speed: the accuracy asked follows (the files, not
    # the accuracy, are under test here)
    scene data/tyre_road.nml "$dir" "$format" -e 's|n_steps = 6000|n_steps = 3000|' \
        -e "s|^([[:space:]]*methods = .*)$|\1\n    truncation_tol = 0.2|" \
        -e 's|accuracy = 1.0e-2 .*$|accuracy = 0.5|' >"$dir/tyre_road.nml"
    scene data/wheel_rail.nml "$dir" "$format" -e 's|n_steps = 50000|n_steps = 32000|' \
        -e "s|methods = 'fft', 'direct'|methods = 'fft'|" >"$dir/wheel_rail.nml"
    scene data/wheel_rail_rough.nml "$dir" "$format" -e 's|n_steps = 50000|n_steps = 32000|' >"$dir/wheel_rail_rough.nml"
    for name in sdof_sine mdof_random tyre_road wheel_rail wheel_rail_rough; do
        if "$driver" --quiet "$dir/$name.nml" >"$dir/$name.log" 2>&1; then
            ok "$format run of $name"
        else
            fail "$format run of $name: $(tail -n 1 "$dir/$name.log")"
        fi
    done
done

# The scripts that read column files through the helper, and those that load one of them.
mapfile -t readers < <(grep -l "plot/lib/column_file.gp" plot/*.gp)
for script in plot/*.gp; do
    for reader in "${readers[@]}"; do
        if [ "$script" != "$reader" ] && grep -q "load '$reader'" "$script"; then readers+=("$script"); break; fi
    done
done
[ "${#readers[@]}" -ge 5 ] && ok "${#readers[@]} scripts read column files: ${readers[*]}" \
    || fail "expected at least fig2, fig3, fig5, fig6 and tyre_force_map, found: ${readers[*]}"

for script in "${readers[@]}"; do
    base=${script##*/}
    base=${base%.gp}
    good=1
    for format in text binary; do
        if ! "$GNUPLOT" -e "datadir='$tmp/$format'; figdir='$tmp/$format/figures'" "$script" \
            >"$tmp/$format/$base.plot.log" 2>&1; then
            fail "$script on the $format run: $(grep -v "^[[:space:]]*$" "$tmp/$format/$base.plot.log" | tail -n 1)"; good=0; continue
        fi
        if ! "$GNUPLOT" -e "datadir='$tmp/$format'; figdir='$tmp/$format/tables'; set table '$tmp/$format/$base.table'" \
            "$script" >"$tmp/$format/$base.table.log" 2>&1; then
            fail "$script with set table on the $format run: $(grep -v "^[[:space:]]*$" "$tmp/$format/$base.table.log" | tail -n 1)"; good=0
        fi
    done
    [ "$good" -eq 1 ] || continue
    rows=$(grep -vc '^#' "$tmp/text/$base.table" || true)
    if [ "$rows" -gt 100 ] && cmp -s <(grep -v '^#' "$tmp/text/$base.table") <(grep -v '^#' "$tmp/binary/$base.table"); then
        ok "$script: the same figure data from text and binary ($rows table lines)"
    else
        fail "$script: figure data differ between text and binary (or fewer than 100 lines: $rows)"
    fi
    png=$(sed -n 's|.*: wrote .*/figures/||p' "$tmp/text/$base.plot.log")
    if [ -n "$png" ] && cmp -s "$tmp/text/figures/$png" "$tmp/binary/figures/$png"; then
        ok "$script: the same PNG bytes ($png)"
    else
        fail "$script: the PNGs differ ($png)"
    fi
done

# Both formats in one directory: the newer is read unless `format` says which.
both=$tmp/both
mkdir -p "$both"
cp "$tmp/text/sdof_sine_modal.dat" "$tmp/binary/sdof_sine_modal.bin" "$tmp/binary/sdof_sine_modal.bin.txt" "$both/"
pick() { "$GNUPLOT" -e "$1 load 'plot/lib/column_file.gp'; print column_file('$both/sdof_sine_modal')" 2>&1; }
touch -d '2000-01-01' "$both/sdof_sine_modal.bin"
[ "$(pick '')" = "$both/sdof_sine_modal.dat" ] && ok "both formats: the newer .dat is read" \
    || fail "both formats, .dat newer: read $(pick '')"
touch -d '2000-01-01' "$both/sdof_sine_modal.dat"
touch "$both/sdof_sine_modal.bin"
[ "$(pick '')" = "$both/sdof_sine_modal.bin" ] && ok "both formats: the newer .bin is read" \
    || fail "both formats, .bin newer: read $(pick '')"
[ "$(pick "format = 'text';")" = "$both/sdof_sine_modal.dat" ] && ok "format = 'text' takes the .dat" \
    || fail "format = 'text': read $(pick "format = 'text';")"

# No run at all: status 1 and one line naming both names.
mkdir -p "$tmp/empty"
if "$GNUPLOT" -e "datadir='$tmp/empty'; figdir='$tmp/empty'" plot/fig3_sdof_contact_force.gp >"$tmp/empty.log" 2>&1; then
    fail "fig3 without a run succeeded"
elif grep -q "cannot read $tmp/empty/sdof_sine_direct.dat or $tmp/empty/sdof_sine_direct.bin" "$tmp/empty.log"; then
    ok "fig3 without a run: $(head -n 1 "$tmp/empty.log")"
else
    fail "fig3 without a run: $(cat "$tmp/empty.log")"
fi

echo "plot formats: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
