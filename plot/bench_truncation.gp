# Truncating a lightly damped g: the relative L2 error that cutting the kernel of
# `direct` at a fraction tol of max|g| costs, against the untruncated direct sum (the
# discrete convolution the truncation approximates) and against the ODE reference, on the
# SDOF scene of section 3.1 made lightly damped (xi = 0.002) and run for 6 s.
#
#   gnuplot plot/bench_truncation.gp
#   gnuplot -e "datadir='out/bench'; figdir='out/figures'" plot/bench_truncation.gp
#
# Reads DATADIR/truncation.dat, written by greenconv-bench (`make bench`; columns named by
# its last '#' line: tol n_g t_g tail err_u_full err_f_full err_u_ref err_f_ref), and writes
# FIGDIR/bench_truncation.png. The kernel length N_g of each tolerance is on the top axis.

if (!exists("datadir")) datadir = 'out/bench'
if (!exists("figdir")) figdir = 'out/figures'
if (!exists("rule")) rule = 0.01     # the paper's truncation rule, section 2.1

input = sprintf('%s/truncation.dat', datadir)
output = sprintf('%s/bench_truncation.png', figdir)

# Column number of NAME in FILE, from the last '#' line (the column names).
header(file) = system(sprintf("grep '^#' '%s' | tail -n 1", file))
column_of(file, name) = sum [i = 2:words(header(file))] (word(header(file), i) eq name ? i - 1 : 0)

if (system(sprintf("test -r '%s' && echo yes", input)) ne 'yes') {
    print sprintf('bench_truncation: cannot read %s (run the benchmark first: make bench)', input)
    exit status 1
}
c_tol = column_of(input, 'tol')
c_ng = column_of(input, 'n_g')
c_tg = column_of(input, 't_g')
c_uf = column_of(input, 'err_u_full')
c_ff = column_of(input, 'err_f_full')
c_ur = column_of(input, 'err_u_ref')
c_fr = column_of(input, 'err_f_ref')
if (c_tol * c_ng * c_tg * c_uf * c_ff * c_ur * c_fr == 0) {
    print sprintf('bench_truncation: expected columns tol, n_g, t_g, err_u_full, err_f_full, err_u_ref, ' \
                  .'err_f_ref in %s', input)
    exit status 1
}
# The first comment line describes the run after a colon (scene, damping ratio, duration, dt).
about = system(sprintf("head -n 1 '%s' | sed 's/^[^:]*: *//'", input))
rule_ng = system(sprintf("awk '!/^#/ && $%d == %g {printf \"%%d %%.2f\", $%d, $%d}' '%s'", c_tol, rule, c_ng, c_tg, input))

system(sprintf("mkdir -p '%s'", figdir))
set terminal pngcairo size 1000,720 enhanced font 'sans,11'
set output output

set style line 1 lc rgb '#d62728' lw 2 pt 7 ps 1.1            # u against the untruncated sum
set style line 2 lc rgb '#d62728' lw 1.5 dt 2 pt 6 ps 1.1      # F against the untruncated sum
set style line 3 lc rgb '#1f77b4' lw 2 pt 5 ps 1.0            # u against the ODE
set style line 4 lc rgb '#1f77b4' lw 1.5 dt 2 pt 4 ps 1.0      # F against the ODE
set style line 5 lc rgb '#000000' lw 1.5 dt 4                  # the 1 % rule

set title sprintf("Truncating a lightly damped g: the error of direct\n%s", about) font ',13'
set tmargin 6
stats input using c_tol nooutput
set logscale xyx2
# the same reversed range on both x axes: coarse kernels on the left
set xrange [STATS_max*1.6:STATS_min/1.6]
set x2range [STATS_max*1.6:STATS_min/1.6]
set format x '10^{%L}'
set format y '10^{%L}'
set xlabel 'truncation tolerance: neglected samples of g below tol*max|g|'
set x2label 'kernel length N_g [samples]'
set ylabel 'relative L2 error'
set xtics nomirror
set x2tics font ',9'
set grid xtics ytics lc rgb '#dddddd'
set key top right box opaque
set offsets 0, 0, graph 0.05, graph 0.05
if (words(rule_ng) == 2) {
    set arrow 1 from first rule, graph 0 to first rule, graph 1 nohead ls 5
    set label 1 sprintf("the paper's rule, tol = %g %%:\nN_g = %s (%s s of g)", 100*rule, word(rule_ng, 1), \
        word(rule_ng, 2)) at first rule, graph 0.08 offset char 1, 0 font ',10'
}

plot input using c_tol:c_uf:x2tic(sprintf('%d', column(c_ng))) with linespoints ls 1 \
         title 'u against the untruncated direct sum', \
     input using c_tol:c_ff with linespoints ls 2 title 'F against the untruncated direct sum', \
     input using c_tol:c_ur with linespoints ls 3 title 'u against the ODE reference', \
     input using c_tol:c_fr with linespoints ls 4 title 'F against the ODE reference'

set output
set print '-'
print sprintf('bench_truncation: wrote %s', output)
