# Where the paper's recursion (eqs. 15-17) overflows: measured failure time of `paper` over
# the natural frequency f and damping ratio xi of one mode (2 s of simulated time at
# dt = 20 us), with the predicted boundary xi*omega*t = ln(huge) = 709.78 at t = 2 s.
# `recursive` and `exact` stay finite in every cell (greenconv-bench prints their errors).
#
#   gnuplot plot/bench_overflow_map.gp
#   gnuplot -e "datadir='out/bench'; figdir='out/figures'" plot/bench_overflow_map.gp
#
# Reads DATADIR/overflow_map.dat (columns f xi t_fail t_predicted dev_recursive dev_exact,
# written by greenconv-bench) and writes FIGDIR/bench_overflow_map.png.

if (!exists("datadir")) datadir = 'out/bench'
if (!exists("figdir")) figdir = 'out/figures'
data = sprintf('%s/overflow_map.dat', datadir)
output = sprintf('%s/bench_overflow_map.png', figdir)
if (system(sprintf("test -r '%s' && echo yes", data)) ne 'yes') {
    print sprintf('bench_overflow_map: cannot read %s (run the benchmark first: make bench)', data)
    exit status 1
}

system(sprintf("mkdir -p '%s'", figdir))
set terminal pngcairo size 900,750 enhanced font 'sans,11'
set output output
set title "Where the paper's recursion overflows\n(one mode under a step load, 2 s at dt = 20 {/Symbol m}s)" font ',13'
set logscale xy
set xrange [70:7000]
set yrange [0.0035:0.28]
set xlabel 'natural frequency f [Hz]'
set ylabel 'damping ratio {/Symbol x}'
set grid
set key below box
set bmargin 7
set cblabel 'paper fails at t [s]'
set logscale cb
set cbrange [0.1:2]
set palette defined (0 '#67001f', 1 '#d6604d', 2 '#fddbc7')
run = 2.0
boundary(f) = log(1.7976931348623157e308)/(2*pi*f*run)
plot data using 1:($3 > 0 ? $2 : 1/0):3 with points pt 7 ps 3.2 lc palette title 'paper: overflow (Inf/NaN)', \
     data using 1:($3 < 0 ? $2 : 1/0) with points pt 6 ps 3.2 lw 2 lc rgb '#2166ac' title 'paper: finite for 2 s', \
     boundary(x) with lines lw 2 dt 2 lc rgb '#000000' title '{/Symbol x}{/Symbol w}t = 709.78 at t = 2 s', \
     data using 1:2 with points pt 1 ps 1.2 lc rgb '#1a9850' title 'recursive, exact: finite, exact to 1e-7'
set output
set print '-'
print sprintf('bench_overflow_map: wrote %s', output)
