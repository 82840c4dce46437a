#!/usr/bin/env bash
# Check that greenconv's version is written in one place and reported the same everywhere:
# fpm.toml's `version = "x.y.z"` is the source; the C header's GREENCONV_VERSION, the FORD
# project file's `version:` and CHANGELOG.md's latest release heading `## [x.y.z]` must repeat
# it (nothing can generate those), and each DRIVER given must print "greenconv x.y.z" for
# `--version` with status 0. (The library's own text, which the build takes from fpm.toml, is
# checked by the test suite `version` and by test/c/version.c.)
#
#   bash tools/check_version.sh [DRIVER...]
#
# One line per disagreement and status 1; otherwise one summary line.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

version=$(sed -n 's/^version *= *"\(.*\)"/\1/p' fpm.toml | head -n 1)
if [ -z "$version" ]; then
    echo "check_version: fpm.toml: expected a line version = \"x.y.z\", found none"
    exit 1
fi
status=0
expect() { # WHERE FOUND
    if [ "$2" != "$version" ]; then
        echo "check_version: $1: expected $version (fpm.toml's version), found '$2'"
        status=1
    fi
}
expect 'include/greenconv.h GREENCONV_VERSION' \
    "$(sed -n 's/^#define GREENCONV_VERSION "\(.*\)"/\1/p' include/greenconv.h)"
expect 'doc/greenconv.md version:' "$(sed -n 's/^version: *//p' doc/greenconv.md)"
expect 'CHANGELOG.md latest release ## [x.y.z]' \
    "$(sed -n 's/^## \[\([0-9][^]]*\)\].*/\1/p' CHANGELOG.md | head -n 1)"
for driver in "$@"; do
    rc=0
    printed=$("$driver" --version 2>&1) || rc=$?
    if [ $rc -ne 0 ] || [ "$printed" != "greenconv $version" ]; then
        echo "check_version: $driver --version: expected 'greenconv $version' and status 0, found '$(head -n 1 <<< "$printed")' and status $rc"
        status=1
    fi
done
if [ $status -eq 0 ]; then
    echo "greenconv: version $version (fpm.toml) in the header, the FORD page, CHANGELOG.md and $# --version line(s)"
fi
exit $status
