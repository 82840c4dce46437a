#!/usr/bin/env bash
# Self-test of tools/check_links.sh: a small tree of Markdown pages whose links are all good
# passes (links to files, folders, headings of the same and of another page, a repeated
# heading, headings with punctuation and code; links in code blocks and spans and external
# links ignored), and each planted dead link (a missing file, a missing heading, a missing
# heading of another page) makes it fail naming the file, the line and the target.
set -euo pipefail

check="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/check_links.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/doc/sub"
touch "$work/data.nml"

cat > "$work/README.md" <<'PAGE'
# Top page

See [the scenes](doc/scenes.md), [their groups](doc/scenes.md#the-scene-group-scene),
[the second example](doc/scenes.md#example-1), [a folder](doc/sub/), [data](data.nml) and
![a figure](data.nml "title"). [Below](#force-spectra-13-octave-bands--and-more),
[code heading](#fortran-use-greenconv), [web](https://example.org/missing.md).

## Force spectra (1/3-octave bands) — and more

## Fortran: `use greenconv`

    [not a link](nowhere.md) in an indented code block

```
[not a link](nowhere.md) in a fenced block
```

A span: `[not a link](nowhere.md)`.
PAGE

cat > "$work/doc/scenes.md" <<'PAGE'
# Scenes

Back to [the top](../README.md#top-page).

## The `&scene` group: `&scene`

## Example

## Example
PAGE

fail=0
expect_pass() {
    if ! out=$(bash "$check" "$work/README.md" "$work/doc/scenes.md" 2>&1); then
        echo "test_check_links: FAIL: good links reported dead:"; printf '%s\n' "$out"; fail=1
    fi
}
expect_dead() { # FILE LINE TARGET: after a plant, the check fails and names it
    local out
    if out=$(bash "$check" "$work/README.md" "$work/doc/scenes.md" 2>&1); then
        echo "test_check_links: FAIL: the dead link '$3' was not caught"; fail=1
    elif ! grep -q -F "$1:$2: dead link '$3'" <<< "$out"; then
        echo "test_check_links: FAIL: expected \"$1:$2: dead link '$3'\", got:"; printf '%s\n' "$out"; fail=1
    fi
}

expect_pass
cp "$work/README.md" "$work/README.good"
line=$(($(wc -l < "$work/README.good") + 1))
echo 'A [planted](doc/missing.md) link.' >> "$work/README.md"
expect_dead "$work/README.md" "$line" doc/missing.md
cp "$work/README.good" "$work/README.md"
echo 'A [planted](#no-such-heading) anchor.' >> "$work/README.md"
expect_dead "$work/README.md" "$line" '#no-such-heading'
cp "$work/README.good" "$work/README.md"
echo 'A [planted](doc/scenes.md#example-2) anchor.' >> "$work/README.md"
expect_dead "$work/README.md" "$line" doc/scenes.md#example-2
cp "$work/README.good" "$work/README.md"
expect_pass

if [ $fail -eq 0 ]; then
    echo "greenconv: link check self-test: good links pass, 3 planted dead links caught"
fi
exit $fail
