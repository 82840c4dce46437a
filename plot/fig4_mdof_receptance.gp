# Fig. 4 of Meftah et al. (2011): the receptance G of the random multi-mode system against
# its LSCE approximation, magnitude (log scale) and phase.
#
#   gnuplot plot/fig4_mdof_receptance.gp
#   gnuplot -e "datadir='out'; figdir='out/figures'" plot/fig4_mdof_receptance.gp
#
# Reads DATADIR/mdof_random_frf.dat (columns named by the last '#' line:
# f re_g im_g abs_g phase_g re_fit im_fit abs_fit phase_fit) and writes
# FIGDIR/fig4_mdof_receptance.png.

if (!exists("datadir")) datadir = 'out'
if (!exists("figdir")) figdir = 'out/figures'
if (!exists("scene")) scene = 'mdof_random'
if (!exists("f_plot")) f_plot = 1200.0     # upper end of the frequency axis [Hz]

input = sprintf('%s/%s_frf.dat', datadir, scene)
output = sprintf('%s/fig4_mdof_receptance.png', figdir)

header(file) = system(sprintf("grep '^#' '%s' | tail -n 1", file))
column_of(file, name) = sum [i = 2:words(header(file))] (word(header(file), i) eq name ? i - 1 : 0)

if (system(sprintf("test -r '%s' && echo yes", input)) ne 'yes') {
    print sprintf('fig4: cannot read %s (run the scene first: make run)', input)
    exit status 1
}
f = column_of(input, 'f')
ag = column_of(input, 'abs_g')
pg = column_of(input, 'phase_g')
af = column_of(input, 'abs_fit')
pf = column_of(input, 'phase_fit')
if (f * ag * pg * af * pf == 0) {
    print sprintf('fig4: expected columns f, abs_g, phase_g, abs_fit, phase_fit in %s', input)
    exit status 1
}
fit_error = system(sprintf("grep -o 'E = *[0-9.E+-]*' '%s' | head -n 1", input))

system(sprintf("mkdir -p '%s'", figdir))
set terminal pngcairo size 1000,800 enhanced font 'sans,11'
set output output

set style line 1 lc rgb '#d62728' lw 1.5 pt 4 ps 1.0           # analytic: -□-
set style line 2 lc rgb '#1f77b4' lw 1.0 dt 2 pt 1 ps 1.4      # LSCE: -+-
thin = 40

set multiplot layout 2, 1 title sprintf("Receptance of the MDOF system and its LSCE approximation, %s\n(Meftah et al. 2011, Fig. 4)", fit_error) font ',13'
set grid
set xrange [0:f_plot]
set key top right box opaque

set ylabel '|G| [m/N]'
set logscale y
set format y '10^{%L}'
plot input using f:ag with lines ls 1 notitle, \
     input using f:ag every thin::0 with points ls 1 notitle, \
     keyentry with linespoints ls 1 title 'analytic', \
     input using f:af with lines ls 2 notitle, \
     input using f:af every thin::(thin/2) with points ls 2 notitle, \
     keyentry with linespoints ls 2 title 'LSCE approximation'

unset logscale y
set format y '%g'
set ylabel 'phase of G [deg]'
set xlabel 'f [Hz]'
set yrange [-200:20]
set ytics 45
plot input using f:pg with lines ls 1 notitle, \
     input using f:pg every thin::0 with points ls 1 notitle, \
     keyentry with linespoints ls 1 title 'analytic', \
     input using f:pf with lines ls 2 notitle, \
     input using f:pf every thin::(thin/2) with points ls 2 notitle, \
     keyentry with linespoints ls 2 title 'LSCE approximation'
unset multiplot

set output
set print '-'
print sprintf('fig4: wrote %s', output)
