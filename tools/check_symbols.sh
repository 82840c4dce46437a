#!/usr/bin/env bash
# Check that a greenconv library defines no global symbol outside its own prefixes, so that
# linking it into a host program can replace none of the host's own symbols (a global
# xerbla_ once replaced the host's LAPACK error handler). Allowed: Fortran module symbols of
# greenconv's modules (__greenconv*), the C API (gc_*), names starting with greenconv, and
# the OpenMP critical sections named greenconv_* (.gomp_critical_user_greenconv_*).
#
#   tools/check_symbols.sh LIBRARY...      exits 1 and lists the symbols when any is foreign
set -euo pipefail
status=0
for library in "$@"; do
    foreign=$(nm -g --defined-only "$library" 2>/dev/null | awk 'NF == 3 {print $3}' | sort -u \
              | grep -v -E '^(__greenconv|gc_|greenconv|\.gomp_critical_user_greenconv_)' || true)
    if [ -n "$foreign" ]; then
        echo "$library: expected only symbols prefixed __greenconv, gc_ or greenconv, found:"
        sed 's/^/    /' <<< "$foreign"
        status=1
    fi
done
[ $status -eq 0 ] && echo "greenconv: symbol check: no global symbol outside greenconv's prefixes in $*"
exit $status
