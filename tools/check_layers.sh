#!/usr/bin/env bash
# Check the layering of src/ (README, "Layout"): a module in src/greenconv/<layer>/ may use
# modules of its own layer and of the layers below it, never one above. The layers, bottom
# to top, are listed in LAYERS; src/greenconv.f90 (the facade) sits at the top with api.
# Every module under src/greenconv/<layer>/<name>.f90 must be named greenconv_<layer>_<name>
# (the path says the layer and the name), and every layer folder must be in LAYERS.
# Prints one line per violation and exits 1 when there is any; silent and 0 otherwise.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

LAYERS=(core ext io model ident conv contact verify scene api)

rank_of() { # rank of a layer name, or -1
    local i
    for i in "${!LAYERS[@]}"; do [ "${LAYERS[$i]}" = "$1" ] && { echo "$i"; return; }; done
    echo -1
}

# module name -> layer, from the file that defines it
declare -A layer_of
status=0
while IFS= read -r file; do
    rel=${file#src/}
    if [ "$rel" = greenconv.f90 ]; then
        layer=api
    else
        layer=${rel#greenconv/}; layer=${layer%%/*}
        if [ "$(rank_of "$layer")" -lt 0 ]; then
            echo "$file: expected a file in a layer folder src/greenconv/{$(IFS=,; echo "${LAYERS[*]}")}/, found folder '$layer'"
            status=1; continue
        fi
        stem=${rel#greenconv/"$layer"/}; stem=${stem%.f90}; stem=${stem//\//_}
        expected="greenconv_${layer}_${stem}"
        found=$(sed -n 's/^[[:space:]]*module[[:space:]]\+\([A-Za-z0-9_]\+\)[[:space:]]*$/\1/Ip' "$file" | head -n 1 | tr 'A-Z' 'a-z')
        # the C API and the F77 layer keep the names host programs already `use`
        if [ "$found" != "$expected" ] && ! { [ "$layer" = api ] && [[ $found == greenconv_* ]]; }; then
            echo "$file: expected module $expected (the path names the layer and the module), found '$found'"
            status=1
        fi
    fi
    while IFS= read -r module; do
        layer_of[$module]=$layer
    done < <(sed -n 's/^[[:space:]]*module[[:space:]]\+\([A-Za-z0-9_]\+\)[[:space:]]*$/\1/Ip' "$file" | tr 'A-Z' 'a-z')
done < <(find src -name '*.f90' | sort)

while IFS= read -r file; do
    rel=${file#src/}
    if [ "$rel" = greenconv.f90 ]; then layer=api; else layer=${rel#greenconv/}; layer=${layer%%/*}; fi
    own=$(rank_of "$layer")
    [ "$own" -lt 0 ] && continue
    while IFS=: read -r line used; do
        used=$(tr 'A-Z' 'a-z' <<< "$used")
        other=${layer_of[$used]:-}
        [ -z "$other" ] && continue   # intrinsic or external module
        if [ "$(rank_of "$other")" -gt "$own" ]; then
            echo "$file:$line: layer '$layer' uses $used of the higher layer '$other'"
            status=1
        fi
    done < <(grep -n -i -E '^[[:space:]]*use[[:space:]]*(,[[:space:]]*non_intrinsic[[:space:]]*::)?[[:space:]]*[A-Za-z0-9_]+' "$file" \
             | sed -E 's/^([0-9]+):[[:space:]]*[Uu][Ss][Ee][[:space:]]*(,[[:space:]]*[A-Za-z_]+[[:space:]]*::)?[[:space:]]*([A-Za-z0-9_]+).*/\1:\3/')
done < <(find src -name '*.f90' | sort)
exit $status
