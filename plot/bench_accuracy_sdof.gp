# Speed against accuracy on the SDOF scene of section 3.1: the relative L2 error
# of the displacement u against the ODE reference, plotted against the CPU time of the
# contact run, for every method while the time step, the N_g truncation tolerance and (on
# the multi-mode scene) the number of LSCE modes are swept.
#
#   gnuplot plot/bench_accuracy_sdof.gp
#   gnuplot -e "datadir='out/bench'; figdir='out/figures'" plot/bench_accuracy_sdof.gp
#
# Reads DATADIR/accuracy_sdof.dat, written by greenconv-bench (`make bench`; columns named
# by its last '#' line: sweep method dt n_steps n_g n_m order tol cpu_s err_u err_f fit_e
# paper), and writes FIGDIR/bench_accuracy_sdof.png. Each (sweep, method) series is a run
# of consecutive rows, picked by the sweep and method columns. The multi-mode figure sets
# `scene`, `figname` and `figtitle` and loads this script.

if (!exists("datadir")) datadir = 'out/bench'
if (!exists("figdir")) figdir = 'out/figures'
if (!exists("scene")) scene = 'sdof'
if (!exists("figname")) figname = 'bench_accuracy_sdof'
if (!exists("figtitle")) figtitle = "Speed against accuracy: SDOF on the sine road (section 3.1), 0.2 s simulated"

input = sprintf('%s/accuracy_%s.dat', datadir, scene)
output = sprintf('%s/%s.png', figdir, figname)

# Column number of NAME in FILE, from the last '#' line (the column names).
header(file) = system(sprintf("grep '^#' '%s' | tail -n 1", file))
column_of(file, name) = sum [i = 2:words(header(file))] (word(header(file), i) eq name ? i - 1 : 0)

if (system(sprintf("test -r '%s' && echo yes", input)) ne 'yes') {
    print sprintf('%s: cannot read %s (run the benchmark first: make bench)', figname, input)
    exit status 1
}
c_sweep = column_of(input, 'sweep')
c_method = column_of(input, 'method')
c_dt = column_of(input, 'dt')
c_ng = column_of(input, 'n_g')
c_nm = column_of(input, 'n_m')
c_tol = column_of(input, 'tol')
c_cpu = column_of(input, 'cpu_s')
c_err = column_of(input, 'err_u')
c_paper = column_of(input, 'paper')
c_order = column_of(input, 'order')
if (c_sweep * c_method * c_dt * c_ng * c_nm * c_tol * c_cpu * c_err * c_paper == 0) {
    print sprintf('%s: expected columns sweep, method, dt, n_g, n_m, tol, cpu_s, err_u, paper in %s', figname, input)
    exit status 1
}

system(sprintf("mkdir -p '%s'", figdir))
set terminal pngcairo size 1100,780 enhanced font 'sans,11'
set output output

# The CPU time of rows of sweep s and method m (NaN elsewhere: no point, no line).
pick(s, m) = (column(c_sweep) == s && column(c_method) == m) ? column(c_cpu) : NaN
names = 'direct fft recursive paper exact'
colors = '#d62728 #ff7f0e #1f77b4 #2ca02c #9467bd'
# sweep 1 (dt): solid, filled circles; 2 (N_g tolerance): dashed, open squares;
# 3 (number of modes): dotted, open triangles
do for [m = 1:5] {
    set style line m lc rgb word(colors, m) lw 1.8 pt 7 ps 1.1
    set style line 10 + m lc rgb word(colors, m) lw 1.5 dt 2 pt 4 ps 1.3
    set style line 20 + m lc rgb word(colors, m) lw 1.5 dt 3 pt 8 ps 1.5
}
set style line 30 lc rgb '#000000' lw 1.5 pt 6 ps 3.2     # the paper's setting

# Data rows of the input that meet an awk condition, and the distinct values (times a
# scale) of column c of rows piped in, comma-separated, in order of appearance.
rows(condition) = sprintf("awk '!/^#/ && %s' '%s'", condition, input)
distinct(c, scale) = sprintf(" | awk '!seen[$%d]++ {s = s (s ? \", \" : \"\") ($%d*%g)} END {print s}'", c, c, scale)

# Labels: the time step along one dt series (method dt_labels, on the left of its points);
# the two ends of direct's N_g sweep (cost grows with N_g from left to right); the poor
# LSCE fits of the mode sweep (E of eq. 7 above 1e-3) in one label at the first of them.
# The full model's point is the 0.1 ms point of the dt sweep.
if (!exists("dt_labels")) dt_labels = 5
c_fit = column_of(input, 'fit_e')
n_orders = system(rows(sprintf('$%d == 3', c_sweep)).' | wc -l') + 0
dts = system(rows(sprintf('$%d == 1', c_sweep)).distinct(c_dt, 1e3))
max_tol = system(rows(sprintf('$%d == 2', c_sweep)).sprintf(" | awk '$%d > t {t = $%d} END {print t + 0}'", \
    c_tol, c_tol)) + 0
poor_rows = rows(sprintf('$%d == 3 && $%d == 3 && $%d > 1e-3', c_sweep, c_method, c_fit))
poor_modes = system(poor_rows.distinct(c_nm, 1))
poor_e = system(poor_rows.sprintf(" | awk 'NR == 1 || $%d < e {e = $%d} END {printf \"%%.2f\", e}'", c_fit, c_fit))
poor_first = system(poor_rows.sprintf(" | awk 'NR == 1 {f = $%d} END {print f + 0}'", c_order)) + 0
is_poor_first(order) = column(c_sweep) == 3 && column(c_method) == 3 && order == poor_first

set title figtitle font ',13'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set xlabel 'CPU time of one contact run [s]'
set ylabel 'relative L2 error of u against the ODE reference'
set grid xtics ytics mxtics mytics lc rgb '#dddddd'
set key below horizontal maxrows 4 box opaque spacing 1.2 width 2 samplen 3
set bmargin (n_orders > 0 ? 11 : 9)
set label 1 sprintf('solid lines: dt = %s ms, from left to right', dts) at graph 0.02, graph 0.04 font ',10'
set offsets graph 0.08, graph 0.04, graph 0.05, graph 0.05

plot for [m = 1:5] input using (pick(1, m)):c_err with linespoints ls m \
         title sprintf('%s (dt sweep)', word(names, m)), \
     for [m = 1:2] input using (pick(2, m)):c_err with linespoints ls 10 + m \
         title sprintf('%s (N_g tolerance sweep)', word(names, m)), \
     for [m = 3:5:2] input using (pick(3, m)):c_err with linespoints ls 20 + m \
         title (n_orders > 0 ? sprintf('%s (number of LSCE modes)', word(names, m)) : ''), \
     input using (column(c_paper) == 1 ? column(c_cpu) : NaN):c_err with points ls 30 \
         title "the paper's setting", \
     input using (pick(1, dt_labels)):c_err:(sprintf('%g ms', column(c_dt)*1e3)) with labels \
         right offset char -1, char 0 font ',9' tc rgb word(colors, dt_labels) notitle, \
     input using (pick(2, 1)):c_err:(column(c_tol) == max_tol ? sprintf('N_g: %g %% of max|g|', \
         100*max_tol) : column(c_tol) == 0 ? 'N_g: whole run' : '') with labels left offset char 1, char 0.3 \
         font ',9' tc rgb word(colors, 1) notitle, \
     input using (is_poor_first(column(c_order)) ? column(c_cpu) : NaN):c_err:(sprintf('N_m = %s: E = %s or more', \
         poor_modes, poor_e)) with labels right offset char -1.5, char 0 font ',9' tc rgb word(colors, 3) notitle

set output
set print '-'
print sprintf('%s: wrote %s', figname, output)
