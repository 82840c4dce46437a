#!/usr/bin/env bash
# No static local in greenconv's library: two host threads may call it at once, so
# every local must live on the stack. Lists, per object file of the library, each writable
# static symbol (nm types b, d: .bss and .data) that is not one of
#   - a module variable (__greenconv_<module>_MOD_<name>; each documents how threads share it),
#   - an OpenMP critical section's lock (.gomp_critical_user_greenconv_*),
#   - a table gfortran fills once at compile time and only reads (A.<n>: an array constructor
#     of constants; jumptable.<n>: a select's branch table),
#   - the part-file table of io/part_files.c (its signal handler's slots; written under the
#     critical section greenconv_part_names, see that file).
# `slen.<n>` is the length of a deferred-length character function result (character(len=:),
# allocatable), which gfortran 12 keeps in static storage at each call site whatever
# -frecursive or -fopenmp say: two threads through the same call site cut or splice each
# other's texts. Such a function becomes a subroutine with an intent(out) text, or a function
# whose result length is a specification expression (core/text.f90).
#
#   tools/check_statics.sh OBJECT_DIR     exits 1 and lists "file: symbol" when any is found
set -euo pipefail
dir=${1:-build/make/src}
found=$(find "$dir" -name '*.o' | sort | while read -r object; do
    nm "$object" 2>/dev/null | awk '$2 ~ /^[bBdD]$/ {print $3}' \
        | grep -v -E '^(__greenconv[a-z0-9_]*_MOD_|\.gomp_critical_user_greenconv_|A\.[0-9.]+$|jumptable\.[0-9.]+$)' \
        | { if [[ $object == */part_files.c.o ]]; then grep -v -E '^part_(claimed|paths|ready)$'; else cat; fi; } \
        | sed "s|^|${object#"$dir"/}: |" || true
done)
if [ -n "$found" ]; then
    count=$(wc -l <<< "$found")
    echo "greenconv: static check: $count writable static locals in $dir (threads share them; see tools/check_statics.sh):"
    awk -F': ' '{n[$1]++} END {for (f in n) printf "    %4d %s\n", n[f], f}' <<< "$found" | sort -rn
    sed 's/^/    /' <<< "$found"
    exit 1
fi
echo "greenconv: static check: no writable static local in $dir"
