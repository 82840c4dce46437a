#!/usr/bin/env bash
# Check the layering of src/ (doc/layout.md): a module in src/greenconv/<layer>/ may use
# modules of its own layer and of the layers below it, never one above. The layers, bottom
# to top, are listed in LAYERS; src/greenconv.f90 (the facade) sits at the top with api.
# Above the scene layer its modules are reached through greenconv_scene_facade only.
# Inside it, the scene layer has floors of its own, bottom to top (SCENE_PARTS): the files
# directly in scene/ (settings, scan, limits: the floor every part shares), models/, read/,
# run/, sweep/ (with scene/sweep.f90), and scene/facade.f90 on top. A file may use the
# modules of its own part and of the floor, and of a lower part only that part's facade
# (scene/<part>/facade.f90, greenconv_scene_<part>_facade; greenconv_scene_sweep for sweep/).
# Every module under src/greenconv/<layer>/<name>.f90 must be named greenconv_<layer>_<name>
# (the path says the layer and the name), and every layer folder must be in LAYERS.
#
#   bash tools/check_layers.sh [SRC]
#
# SRC is the source root to check (default: the project's src/). Prints one line per
# violation, naming the file (and the line of a `use`), and exits 1 when there is any;
# silent and 0 otherwise. `use` statements are read in every form Fortran allows:
# `use m`, `use :: m`, `use, non_intrinsic :: m`, any letter case; `use, intrinsic :: m`
# and modules defined outside SRC (FFTW's, the compiler's) are not ours and are skipped.
# tools/test_check_layers.sh proves that each kind of violation is caught.
set -euo pipefail

if [ $# -gt 1 ]; then
    echo "usage: bash tools/check_layers.sh [SRC]" >&2
    exit 2
fi
if [ $# -eq 1 ]; then
    [ -d "$1" ] || { echo "check_layers: no directory '$1': give the source root (e.g. src)" >&2; exit 2; }
    root=${1%/}
else
    cd "$(dirname "${BASH_SOURCE[0]}")/.."
    root=src
fi

LAYERS=(core ext io model ident conv contact scene api)
SCENE_PARTS=(floor models read run sweep door)

scene_rank() { # rank of a scene part, or -1
    local i
    for i in "${!SCENE_PARTS[@]}"; do [ "${SCENE_PARTS[$i]}" = "$1" ] && { echo "$i"; return; }; done
    echo -1
}

# The part of the scene layer a file is in: its sub-folder, `floor` for a file directly in
# scene/, `sweep` for scene/sweep.f90 and `door` for scene/facade.f90.
scene_part_of_file() {
    local rel=${1#"$root"/greenconv/scene/}
    case $rel in
        facade.f90) echo door ;;
        sweep.f90) echo sweep ;;
        */*) echo "${rel%%/*}" ;;
        *) echo floor ;;
    esac
}

# The module a lower part shows the parts above it.
scene_facade_of() {
    if [ "$1" = sweep ]; then echo greenconv_scene_sweep; else echo "greenconv_scene_$1_facade"; fi
}

rank_of() { # rank of a layer name, or -1
    local i
    for i in "${!LAYERS[@]}"; do [ "${LAYERS[$i]}" = "$1" ] && { echo "$i"; return; }; done
    echo -1
}

# The layer of a file: the folder under greenconv/, or api for the facade greenconv.f90.
layer_of_file() {
    local rel=${1#"$root"/}
    if [ "$rel" = greenconv.f90 ]; then echo api; return; fi
    rel=${rel#greenconv/}
    echo "${rel%%/*}"
}

# The modules a file defines, lower case, one a line (`module procedure` and
# `module subroutine`/`function` of submodules are not definitions).
modules_defined() {
    sed -n -E 's/^[[:space:]]*[Mm][Oo][Dd][Uu][Ll][Ee][[:space:]]+([A-Za-z][A-Za-z0-9_]*)[[:space:]]*(!.*)?$/\1/p' "$1" \
        | tr 'A-Z' 'a-z' | grep -v -x -E 'procedure|subroutine|function' || true
}

# "LINE:MODULE" for every non-intrinsic `use` of a file, MODULE in lower case.
modules_used() {
    grep -n -i -E '^[[:space:]]*use([[:space:]]*,[[:space:]]*non_intrinsic[[:space:]]*::|[[:space:]]*::|[[:space:]]+)[[:space:]]*[A-Za-z]' "$1" \
        | sed -E 's/^([0-9]+):[[:space:]]*[Uu][Ss][Ee][[:space:]]*(,[[:space:]]*[A-Za-z_]+[[:space:]]*)?(::)?[[:space:]]*([A-Za-z][A-Za-z0-9_]*).*/\1:\4/' \
        | tr 'A-Z' 'a-z' || true
}

mapfile -t files < <(find "$root" -name '*.f90' -o -name '*.F90' | sort)

# module name -> layer, from the file that defines it
declare -A layer_of part_of
status=0
for file in "${files[@]}"; do
    layer=$(layer_of_file "$file")
    rel=${file#"$root"/}
    if [ "$rel" != greenconv.f90 ]; then
        if [ "$(rank_of "$layer")" -lt 0 ]; then
            echo "$file: expected a file in a layer folder $root/greenconv/{$(IFS=,; echo "${LAYERS[*]}")}/, found folder '$layer'"
            status=1; continue
        fi
        if [ "$layer" = scene ] && [ "$(scene_rank "$(scene_part_of_file "$file")")" -lt 0 ]; then
            parts=$(IFS=,; echo "${SCENE_PARTS[*]:1:4}")
            echo "$file: expected a file in scene/ or a scene part folder scene/{$parts}/," \
                 "found folder '$(scene_part_of_file "$file")'"
            status=1; continue
        fi
        stem=${rel#greenconv/"$layer"/}; stem=${stem%.*}; stem=${stem//\//_}
        expected="greenconv_${layer}_${stem}"
        found=$(modules_defined "$file" | head -n 1)
        # the C API and the F77 layer keep the names host programs already `use`
        if [ "$found" != "$expected" ] && ! { [ "$layer" = api ] && [[ $found == greenconv_* ]]; }; then
            echo "$file: expected module $expected (the path names the layer and the module), found '$found'"
            status=1
        fi
    fi
    while IFS= read -r module; do
        layer_of[$module]=$layer
        [ "$layer" = scene ] && part_of[$module]=$(scene_part_of_file "$file")
    done < <(modules_defined "$file")
done

for file in "${files[@]}"; do
    layer=$(layer_of_file "$file")
    own=$(rank_of "$layer")
    [ "$own" -lt 0 ] && continue
    while IFS=: read -r line used; do
        [ -z "$used" ] && continue
        other=${layer_of[$used]:-}
        [ -z "$other" ] && continue   # a module not defined under SRC (FFTW's, the compiler's)
        if [ "$(rank_of "$other")" -gt "$own" ]; then
            echo "$file:$line: layer '$layer' uses $used of the higher layer '$other'"
            status=1
        elif [ "$other" = scene ] && [ "$layer" != scene ] && [ "$used" != greenconv_scene_facade ]; then
            echo "$file:$line: layer '$layer' uses $used: outside the scene layer use greenconv_scene_facade"
            status=1
        elif [ "$other" = scene ] && [ "$layer" = scene ]; then
            mine=$(scene_part_of_file "$file")
            theirs=${part_of[$used]}
            if [ "$(scene_rank "$theirs")" -gt "$(scene_rank "$mine")" ]; then
                echo "$file:$line: scene/$mine uses $used of the higher part scene/$theirs"
                status=1
            elif [ "$theirs" != "$mine" ] && [ "$theirs" != floor ] && [ "$used" != "$(scene_facade_of "$theirs")" ]; then
                echo "$file:$line: scene/$mine uses $used: from scene/$theirs use $(scene_facade_of "$theirs")"
                status=1
            fi
        fi
    done < <(modules_used "$file")
done
exit $status
