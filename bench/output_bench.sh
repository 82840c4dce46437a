#!/usr/bin/env bash
# The output benchmark alone, without make: compile the C anchor bench/anchor/printf_rows.c into
# build/printf_rows, then run `greenconv-bench --output build/printf_rows` (release build),
# which times the formatted WRITE, the exact text in stream blocks and binary float64 on
# 200000 rows of five doubles, runs the anchor on the same rows and prints the ratios.
# Run from the project directory: bash bench/output_bench.sh
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p build out/bench
${CC:-cc} -O2 -std=c99 -Wall -Wextra -pedantic bench/anchor/printf_rows.c -o build/printf_rows -lm
${FPM:-fpm} run --example greenconv-bench --profile release -- --output build/printf_rows
