#!/usr/bin/env bash
# Check that a greenconv library defines no global symbol outside its own prefixes, so that
# linking it into a host program can replace none of the host's own symbols (a global
# xerbla_ once replaced the host's LAPACK error handler). Allowed: Fortran module symbols of
# greenconv's modules (__greenconv*), the C API (gc_*), names starting with greenconv, and
# the OpenMP critical sections named greenconv_* (.gomp_critical_user_greenconv_*).
#
#   tools/check_symbols.sh LIBRARY...      exits 1 and lists the symbols when any is foreign
#
#   tools/check_symbols.sh --static-locals LIBRARY...
#       exits 1 when a library holds static string lengths `slen.*`: gfortran
#       (12 and later, whatever -frecursive or -fopenmp say) keeps the length of every
#       deferred-length character function result in static storage at each call site, so
#       two threads running the same code share it and cut or splice each other's messages.
#       `make thread-check` runs this; it passes once no call site needs such a temporary.
set -euo pipefail
status=0
if [ "${1:-}" = --static-locals ]; then
    shift
    for library in "$@"; do
        count=$(nm "$library" 2>/dev/null | grep -c ' [bBdD] slen\.' || true)
        if [ "$count" -gt 0 ]; then
            echo "$library: $count static string lengths (slen.*) of deferred-length character function results;" \
                 "two threads calling the same code share each one (see tools/check_symbols.sh)"
            status=1
        fi
    done
    [ $status -eq 0 ] && echo "greenconv: symbol check: no static string length in $*"
    exit $status
fi
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
