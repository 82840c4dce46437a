# Multi-point contact at a patch's scale: CPU seconds per step of the implicit
# `exact` loop (Newton on all points, low-rank W0) and the explicit `modal` loop against the
# number of contact points N_c, at the fixed modes of the tyre line, on log-log axes.
#
#   gnuplot plot/bench_scale.gp
#   gnuplot -e "datadir='out/bench'; figdir='out/figures'" plot/bench_scale.gp
#
# Reads DATADIR/scale_cost.dat, written by greenconv-bench (`make bench`, or `--scale`;
# columns named by its last '#' line: n_c n_m exact_s_per_step modal_s_per_step start_s rank
# table_gb), and writes FIGDIR/bench_scale.png.

if (!exists("datadir")) datadir = 'out/bench'
if (!exists("figdir")) figdir = 'out/figures'

input = sprintf('%s/scale_cost.dat', datadir)
output = sprintf('%s/bench_scale.png', figdir)

# Column number of NAME in FILE, from the last '#' line (the column names).
header(file) = system(sprintf("grep '^#' '%s' | tail -n 1", file))
column_of(file, name) = sum [i = 2:words(header(file))] (word(header(file), i) eq name ? i - 1 : 0)

if (system(sprintf("test -r '%s' && echo yes", input)) ne 'yes') {
    print sprintf('bench_scale: cannot read %s (run the benchmark first: make bench)', input)
    exit status 1
}
c_n = column_of(input, 'n_c')
c_exact = column_of(input, 'exact_s_per_step')
c_modal = column_of(input, 'modal_s_per_step')
if (c_n * c_exact * c_modal == 0) {
    print sprintf('bench_scale: expected columns n_c, exact_s_per_step, modal_s_per_step in %s', input)
    exit status 1
}
about = system(sprintf("head -n 1 '%s' | sed 's/^[^:]*: *//'", input))

system(sprintf("mkdir -p '%s'", figdir))
set terminal pngcairo size 1000,720 enhanced font 'sans,11'
set output output

set style line 1 lc rgb '#d62728' lw 2 pt 7 ps 1.1     # exact (implicit)
set style line 2 lc rgb '#1f77b4' lw 2 pt 5 ps 1.0     # modal (explicit)
set style line 3 lc rgb '#777777' lw 1 dt 2            # slope 1 guide

set title sprintf("Cost per step against the number of contact points\n%s", about) font ',13'
set logscale xy
set format y '10^{%L}'
set xlabel 'contact points N_c'
set ylabel 'CPU time per step [s]'
set grid xtics ytics lc rgb '#dddddd'
set key top left box opaque

# Fitted power laws t = a*N_c^p (least squares on the logs).
fe(x) = log(ae) + pe*log(x)
fm(x) = log(am) + pm*log(x)
ae = 1e-6; pe = 1; am = 1e-6; pm = 1
set fit quiet logfile '/dev/null'
fit fe(x) input using c_n:(log(column(c_exact))) via ae, pe
fit fm(x) input using c_n:(log(column(c_modal))) via am, pm

plot input using c_n:c_exact with linespoints ls 1 title sprintf('exact (implicit, low-rank Newton): p = %.2f', pe), \
     input using c_n:c_modal with linespoints ls 2 title sprintf('modal (explicit): p = %.2f', pm)
