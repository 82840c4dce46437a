# Stabilisation diagram of the maximum-likelihood identification: the poles of the
# linear LSCE step at every order N (frequency against order), marked by their stability
# against order N - 1 (f and xi, f only, neither), the poles of the maximum-likelihood fit
# (order by MDL) as vertical lines: solid for the modes the data determine, dotted grey for the
# poles they do not (part of the fitted receptance, not modes), and |G| on a second axis.
#
#   gnuplot plot/ident_diagram.gp
#   gnuplot -e "datadir='out'; figdir='out/figures'; scene='identify_clean'" plot/ident_diagram.gp
#
# Reads DATADIR/SCENE_diagram.dat (order f xi flag; at order 0 the fit's poles, flag 3 a
# determined mode, 4 a pole the data do not determine) and
# DATADIR/SCENE_frf.dat (f ... abs_g ...), writes FIGDIR/SCENE_diagram.png.

if (!exists("datadir")) datadir = 'out'
if (!exists("figdir")) figdir = 'out/figures'
if (!exists("scene")) scene = 'identify_sample'

diagram = sprintf('%s/%s_diagram.dat', datadir, scene)
frf = sprintf('%s/%s_frf.dat', datadir, scene)
output = sprintf('%s/%s_diagram.png', figdir, scene)

header(file) = system(sprintf("grep '^#' '%s' | tail -n 1", file))
column_of(file, name) = sum [i = 2:words(header(file))] (word(header(file), i) eq name ? i - 1 : 0)

if (system(sprintf("test -r '%s' && test -r '%s' && echo yes", diagram, frf)) ne 'yes') {
    print sprintf('ident_diagram: cannot read %s or %s (run the scene first: make run)', diagram, frf)
    exit status 1
}
f = column_of(frf, 'f')
ag = column_of(frf, 'abs_g')
if (f * ag == 0) {
    print sprintf('ident_diagram: expected columns f and abs_g in %s', frf)
    exit status 1
}
stats diagram using 1 nooutput
top = STATS_max + 1

system(sprintf("mkdir -p '%s'", figdir))
set terminal pngcairo size 1100,650 enhanced font 'sans,11'
set output output
set title sprintf("Stabilisation diagram (linear LSCE step) and the modes chosen by maximum likelihood, %s", scene) noenhanced
set autoscale xfix
set xlabel 'f [Hz]'
set ylabel 'order N (modes)'
set yrange [0:top]
set y2label '|G| [m/N]'
set logscale y2
set format y2 '10^{%L}'
set y2tics
set ytics nomirror
set grid xtics ytics
set key outside right top box opaque

plot diagram using ($4 == 0 ? $2 : 1/0):1 with points pt 1 ps 0.6 lc rgb '#aaaaaa' title 'not stable', \
     diagram using ($4 == 1 ? $2 : 1/0):1 with points pt 6 ps 0.7 lc rgb '#ff7f0e' title 'stable in f', \
     diagram using ($4 == 2 ? $2 : 1/0):1 with points pt 7 ps 0.6 lc rgb '#2ca02c' title 'stable in f and {/Symbol x}', \
     diagram using ($4 == 3 ? $2 : 1/0):(0):(0):(top) with vectors nohead dt 2 lc rgb '#d62728' title 'mode (determined)', \
     diagram using ($4 == 4 ? $2 : 1/0):(0):(0):(top) with vectors nohead dt 3 lw 2 lc rgb '#7f7f7f' \
         title 'pole not determined by the data', \
     frf using f:ag axes x1y2 with lines lw 1 lc rgb '#1f77b4' title '|G|'

set output
set print '-'
print sprintf('ident_diagram: wrote %s', output)
