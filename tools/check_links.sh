#!/usr/bin/env bash
# Check that every relative link of the project's Markdown points at something that exists:
# a file or folder of the tree, and for an anchor (#...) on a .md file one of its headings
# (tools/check_links.awk says exactly what is checked). Links with a scheme (https:, ...)
# are not followed: this runs offline and in a second.
#
#   bash tools/check_links.sh [FILE.md...]
#
# Without arguments it checks README.md, CHANGELOG.md and doc/*.md from the project's top
# folder. Prints one line per dead link (file:line, the target, what is missing) and exits 1
# when there is any; otherwise one summary line and status 0. tools/test_check_links.sh proves
# that planted dead links are caught.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
if [ $# -eq 0 ]; then
    cd "$here/.."
    set -- README.md CHANGELOG.md doc/*.md
fi
for file in "$@"; do
    [ -f "$file" ] || { echo "check_links: no file '$file'" >&2; exit 2; }
done
if summary=$(LC_ALL=C awk -f "$here/check_links.awk" "$@"); then
    echo "greenconv: ${summary}"
else
    printf '%s\n' "$summary"
    exit 1
fi
