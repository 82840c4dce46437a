#!/usr/bin/env bash
# The whole-process time of the driver on the paper's largest case (Tab. 2: the sdof scene,
# dt = 0.01 ms, 200000 steps, method `recursive`, every row written) with output_format
# 'text' and 'binary', against the C anchor bench/anchor/printf_rows.c writing the same number
# of rows of five numbers with printf("%.16e"); wall-clock seconds of each process (best of
# three, the machine may be shared) and the ratios, all measured in this one run. The force
# spectra the shipped scene asks for are turned off: this measures the rows' output.
#
#     bash bench/driver_output.sh DRIVER ANCHOR      (from the project directory)
set -euo pipefail
driver=$1 anchor=$2
dir=out/bench/driver_output
mkdir -p "$dir"
for format in text binary; do
    sed -e "s|name = 'sdof_sine'|name = 'tab2_$format'|" -e "s|output_dir = 'out'|output_dir = '$dir'|" \
        -e "s|dt = 1.0e-4|dt = 1.0e-5|" -e "s|n_steps = 2000 |n_steps = 200000 |" \
        -e "s|methods = .*|methods = 'recursive'|" -e "s|spectra = .true.|spectra = .false.|" data/sdof_sine.nml |
        awk -v f="$format" '{print} /^&scene/ {print "    output_format = '\''" f "'\''"}' > "$dir/tab2_$format.nml"
done
seconds() {  # best wall-clock seconds of three runs of the command "$@"
    local best="" start finish t
    for _ in 1 2 3; do
        start=$(date +%s.%N)
        "$@" > /dev/null
        finish=$(date +%s.%N)
        t=$(echo "$finish - $start" | bc -l)
        if [ -z "$best" ] || [ "$(echo "$t < $best" | bc -l)" = 1 ]; then best=$t; fi
    done
    printf '%.3f' "$best"
}
text=$(seconds "$driver" --quiet "$dir/tab2_text.nml")
binary=$(seconds "$driver" --quiet "$dir/tab2_binary.nml")
rows=$(grep -vc '^#' "$dir/tab2_text_recursive.dat")
printf_s=$(seconds "$anchor" "$dir/printf_rows.txt" "$rows")
echo "# driver output: Tab. 2 case (dt = 0.01 ms, 200000 steps, recursive, every row: $rows rows of 5 numbers),"
echo "# whole process, wall-clock seconds (best of 3), against the C printf(\"%.16e\") program, one run"
printf '%-34s %10s %12s %14s\n' 'process' 'seconds' 'rows/s' 'vs printf'
for line in "greenconv, output_format 'text'|$text" "greenconv, output_format 'binary'|$binary" \
            "C printf anchor (same rows)|$printf_s"; do
    name=${line%|*} s=${line#*|}
    printf '%-34s %10s %12.3e %13.2fx\n' "$name" "$s" "$(echo "$rows / $s" | bc -l)" "$(echo "$s / $printf_s" | bc -l)"
done
echo "target: the driver's whole process (text) < 1/2 of the printf program's: ratio $(printf '%.2f' \
"$(echo "$text / $printf_s" | bc -l)") $( [ "$(echo "$text < $printf_s / 2" | bc -l)" = 1 ] && echo met || echo 'NOT met')"
