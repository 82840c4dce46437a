# The maximum-likelihood fit of a noisy receptance: |G|, the model, and the
# residual |G - model| against the noise standard deviation of each line, and the poles of the
# fit at their natural frequencies: red triangles for the modes the data determine, grey crosses
# for the poles they do not (part of the fitted receptance, not modes).
#
#   gnuplot plot/ident_fit.gp
#   gnuplot -e "datadir='out'; figdir='out/figures'; scene='identify_clean'" plot/ident_fit.gp
#
# Reads DATADIR/SCENE_frf.dat (f ... abs_g ... abs_fit ... abs_residual sigma) and
# DATADIR/SCENE_modes.dat (f ... determined), writes FIGDIR/SCENE_fit.png.

if (!exists("datadir")) datadir = 'out'
if (!exists("figdir")) figdir = 'out/figures'
if (!exists("scene")) scene = 'identify_sample'

input = sprintf('%s/%s_frf.dat', datadir, scene)
modes = sprintf('%s/%s_modes.dat', datadir, scene)
output = sprintf('%s/%s_fit.png', figdir, scene)

header(file) = system(sprintf("grep '^#' '%s' | tail -n 1", file))
column_of(file, name) = sum [i = 2:words(header(file))] (word(header(file), i) eq name ? i - 1 : 0)

if (system(sprintf("test -r '%s' && echo yes", input)) ne 'yes') {
    print sprintf('ident_fit: cannot read %s (run the scene first: make run)', input)
    exit status 1
}
f = column_of(input, 'f')
ag = column_of(input, 'abs_g')
af = column_of(input, 'abs_fit')
ar = column_of(input, 'abs_residual')
sg = column_of(input, 'sigma')
if (f * ag * af * ar * sg == 0) {
    print sprintf('ident_fit: expected columns f, abs_g, abs_fit, abs_residual, sigma in %s (a maximum-likelihood fit)', input)
    exit status 1
}
if (system(sprintf("test -r '%s' && echo yes", modes)) ne 'yes') {
    print sprintf('ident_fit: cannot read %s (run the scene first: make run)', modes)
    exit status 1
}
mf = column_of(modes, 'f')
md = column_of(modes, 'determined')
if (mf * md == 0) {
    print sprintf('ident_fit: expected columns f and determined in %s (a maximum-likelihood fit)', modes)
    exit status 1
}
stats input using ag nooutput
top = STATS_max
title_line = system(sprintf("grep '^#' '%s' | head -n 1 | cut -c 14-", input))

system(sprintf("mkdir -p '%s'", figdir))
set terminal pngcairo size 1100,700 enhanced font 'sans,11'
set output output
set title title_line
set autoscale xfix
set xlabel 'f [Hz]'
set ylabel '[m/N]'
set logscale y
set format y '10^{%L}'
set grid
set key bottom right box opaque

plot input using f:ar with points pt 7 ps 0.15 lc rgb '#bbbbbb' title '|G - model| (residual)', \
     input using f:sg with lines lw 1.5 lc rgb '#2ca02c' title 'noise {/Symbol s} per line', \
     input using f:ag with lines lw 1 lc rgb '#1f77b4' title '|G| (data)', \
     input using f:af with lines lw 1.5 dt 2 lc rgb '#d62728' title '|G| model', \
     modes using (column(md) == 1 ? column(mf) : 1/0):(2 * top) with points pt 9 ps 1.2 lc rgb '#d62728' \
         title 'mode (determined)', \
     modes using (column(md) == 0 ? column(mf) : 1/0):(2 * top) with points pt 2 ps 1.2 lw 2 lc rgb '#7f7f7f' \
         title 'pole not determined by the data'

set output
set print '-'
print sprintf('ident_fit: wrote %s', output)
