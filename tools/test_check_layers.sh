#!/usr/bin/env bash
# Self-test of tools/check_layers.sh: it must pass the project's src/ and fail, naming the
# file, on a copy of src/ with one planted violation. Each case plants one file in a fresh
# copy and states what the checker must answer: exit 0 and no output, or exit 1 and a line
# that contains the planted file's path and a given phrase. Prints one line per case and
# exits 1 when a case fails.
#
#   bash tools/test_check_layers.sh
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

checker=tools/check_layers.sh
work=$(mktemp -d "${TMPDIR:-/tmp}/greenconv-layers.XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0

report() { # report OK|FAIL CASE [DETAIL]
    if [ "$1" = OK ]; then
        printf '  pass  check_layers :: %s\n' "$2"
    else
        printf '  FAIL  check_layers :: %s: %s\n' "$2" "$3"
        failures=$((failures + 1))
    fi
}

# expect_clean CASE: the checker on $work/src exits 0 and prints nothing.
expect_clean() {
    local out rc=0
    out=$(bash "$checker" "$work/src" 2>&1) || rc=$?
    if [ "$rc" -eq 0 ] && [ -z "$out" ]; then report OK "$1"
    else report FAIL "$1" "expected exit 0 and no output, got exit $rc: $out"; fi
}

# expect_violation CASE FILE PHRASE: exit 1 and a line holding FILE's path and PHRASE.
expect_violation() {
    local out rc=0
    out=$(bash "$checker" "$work/src" 2>&1) || rc=$?
    if [ "$rc" -eq 1 ] && grep -F -- "$work/src/$2" <<< "$out" | grep -q -F -- "$3"; then report OK "$1"
    else report FAIL "$1" "expected exit 1 and a line naming $2 with '$3', got exit $rc: $out"; fi
}

# fresh_copy: $work/src is a clean copy of the project's src/.
fresh_copy() { rm -rf "$work/src"; cp -R src "$work/src"; }

# plant PATH TEXT: write TEXT into $work/src/PATH.
plant() { mkdir -p "$(dirname "$work/src/$1")"; printf '%s\n' "$2" > "$work/src/$1"; }

fresh_copy
out=$(bash "$checker" 2>&1) && rc=0 || rc=$?
if [ "$rc" -eq 0 ] && [ -z "$out" ]; then report OK 'the project src/ is clean'
else report FAIL 'the project src/ is clean' "exit $rc: $out"; fi
expect_clean 'a clean copy given as the argument'

# Allowed: uses of the own layer and of lower ones, intrinsic modules, any letter case.
fresh_copy
plant greenconv/model/planted.f90 "!> Planted by tools/test_check_layers.sh.
MODULE Greenconv_Model_Planted
    use, intrinsic :: iso_fortran_env, only: real64
    USE GREENCONV_CORE_KINDS, ONLY: dp
    use :: greenconv_model_sdof, only: sdof_modes
    use, non_intrinsic :: greenconv_io_files
    implicit none
end module Greenconv_Model_Planted"
expect_clean 'model uses core, model and io (any case, use ::, non_intrinsic): allowed'

# Each spelling of a use of a higher layer is caught.
n=0
for statement in 'use greenconv_scene_read_input, only: scene_type' \
                 'USE Greenconv_Scene_Read_Input, ONLY: scene_type' \
                 'use :: greenconv_scene_read_input' \
                 'use, non_intrinsic :: greenconv_scene_read_input, only: scene_type' \
                 '  Use ,  NON_INTRINSIC::GREENCONV_SCENE_READ_INPUT'; do
    n=$((n + 1))
    fresh_copy
    plant greenconv/model/planted.f90 "module greenconv_model_planted
    use greenconv_core_kinds, only: dp
$statement
    implicit none
end module greenconv_model_planted"
    expect_violation "model uses scene: '$statement'" greenconv/model/planted.f90:3 \
        "layer 'model' uses greenconv_scene_read_input of the higher layer 'scene'"
done

# A use inside an existing module, not only in a new file.
fresh_copy
sed -i '0,/^[[:space:]]*implicit none/s//    use greenconv_contact_single, only: contact_law\n&/' \
    "$work/src/greenconv/model/sdof.f90"
expect_violation 'an existing model file (sdof.f90) uses the contact layer' greenconv/model/sdof.f90 \
    "uses greenconv_contact_single of the higher layer 'contact'"

# Above the scene layer only its facade: api reaching a scene module is caught, the facade not.
fresh_copy
plant greenconv/api/planted.f90 "module greenconv_api_planted
    use greenconv_scene_facade, only: scene_type
    use greenconv_scene_read_input, only: read_scene
    implicit none
end module greenconv_api_planted"
expect_violation 'api uses greenconv_scene_read_input, not the facade' greenconv/api/planted.f90:3 \
    "outside the scene layer use greenconv_scene_facade"

# Inside the scene layer: a lower part through its facade only, never a higher part, never
# an unknown part folder; the floor (scene/*.f90) and the own part freely.
fresh_copy
plant greenconv/scene/run/planted.f90 "module greenconv_scene_run_planted
    use greenconv_scene_settings, only: scene_type
    use greenconv_scene_read_facade, only: read_scene
    use greenconv_scene_run_stream, only: stream_run
    implicit none
end module greenconv_scene_run_planted"
expect_clean 'scene/run uses the floor, the read facade and its own part: allowed'
fresh_copy
plant greenconv/scene/run/planted.f90 "module greenconv_scene_run_planted
    use greenconv_scene_read_facade, only: scene_type
    use greenconv_scene_read_input, only: read_scene
    implicit none
end module greenconv_scene_run_planted"
expect_violation 'scene/run uses greenconv_scene_read_input, not the read facade' greenconv/scene/run/planted.f90:3 \
    "from scene/read use greenconv_scene_read_facade"
fresh_copy
plant greenconv/scene/models/planted.f90 "module greenconv_scene_models_planted
    use greenconv_scene_read_facade, only: scene_type
    implicit none
end module greenconv_scene_models_planted"
expect_violation 'scene/models uses the read facade of a higher part' greenconv/scene/models/planted.f90:2 \
    "of the higher part scene/read"
fresh_copy
plant greenconv/scene/extra/planted.f90 "module greenconv_scene_extra_planted
    implicit none
end module greenconv_scene_extra_planted"
expect_violation 'a scene file in a folder that is no part' greenconv/scene/extra/planted.f90 "found folder 'extra'"

# A file holding one module: a name that does not match its path, a name of another layer
# than its folder, a folder that is not a layer.
for planted in 'model/planted.f90 greenconv_model_other expected module greenconv_model_planted' \
               'core/planted.f90 greenconv_scene_planted expected module greenconv_core_planted' \
               "bench/planted.f90 greenconv_bench_planted found folder 'bench'"; do
    read -r path module phrase <<< "$planted"
    fresh_copy
    plant "greenconv/$path" "module $module
    implicit none
end module $module"
    expect_violation "greenconv/$path defines $module" "greenconv/$path" "$phrase"
done

if [ "$failures" -gt 0 ]; then
    echo "check_layers self-test: $failures case(s) failed"
    exit 1
fi
echo "check_layers self-test: all cases passed"
