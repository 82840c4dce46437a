# Fig. 3 of Meftah et al. (2011): contact force between the SDOF body and the sinusoidal
# road, standard (direct) convolution "-+-" against modal decomposition "-□-".
#
#   gnuplot plot/fig3_sdof_contact_force.gp
#   gnuplot -e "datadir='out'; figdir='out/figures'" plot/fig3_sdof_contact_force.gp
#
# Reads DATADIR/sdof_sine_direct and _modal, .dat or .bin (plot/lib/column_file.gp; columns
# named by the last '#' line: t u_road u f_contact delta, in s m m N m) and writes
# FIGDIR/fig3_sdof_contact_force.png.

if (!exists("datadir")) datadir = 'out'
if (!exists("figdir")) figdir = 'out/figures'
if (!exists("scene")) scene = 'sdof_sine'
# Another scene's figure (Figs. 5 and 6) sets these three and loads this script.
if (!exists("figname")) figname = 'fig3_sdof_contact_force'
if (!exists("figtitle")) figtitle = "Contact force of an SDOF system on a sinusoidal road\n(Meftah et al. 2011, Fig. 3)"
if (!exists("thin")) thin = 40

output = sprintf('%s/%s.png', figdir, figname)

# The runs' column files, text (.dat) or binary (.bin), and how gnuplot reads each.
load 'plot/lib/column_file.gp'
direct = column_file(sprintf('%s/%s_direct', datadir, scene))
modal = column_file(sprintf('%s/%s_modal', datadir, scene))
do for [method in 'direct modal'] {
    if (column_file(sprintf('%s/%s_%s', datadir, scene, method)) eq '') {
        print sprintf('fig3: %s', missing_file(sprintf('%s/%s_%s', datadir, scene, method)))
        exit status 1
    }
}
direct_opts = data_options(direct)
modal_opts = data_options(modal)
t = column_of(direct, 't')
f = column_of(direct, 'f_contact')
if (t == 0 || f == 0 || column_of(modal, 'f_contact') != f) {
    print sprintf('fig3: expected columns t, f_contact in %s and %s', direct, modal)
    exit status 1
}

system(sprintf("mkdir -p '%s'", figdir))
set terminal pngcairo size 1000,600 enhanced font 'sans,11'
set output output

# one marker every `thin` samples; the modal markers sit half way between
set style line 2 lc rgb '#d62728' lw 1.5 pt 1 ps 1.6          # direct: -+-
set style line 3 lc rgb '#1f77b4' lw 1.0 dt 2 pt 4 ps 1.2     # modal: -□- (dashed, on top)

set title figtitle font ',13'
set grid
set key top right box opaque
set offsets graph 0, graph 0, graph 0.3, graph 0   # head room for the key; F >= 0
set xlabel 't [s]'
set ylabel 'contact force f_{contact} [N]'
set format x '%.2f'

plot direct @direct_opts using t:f with lines ls 2 notitle, \
     direct @direct_opts using t:f every thin::0 with points ls 2 notitle, \
     keyentry with linespoints ls 2 title 'standard convolution', \
     modal @modal_opts using t:f with lines ls 3 notitle, \
     modal @modal_opts using t:f every thin::(thin/2) with points ls 3 notitle, \
     keyentry with linespoints ls 3 title 'modal decomposition'

set output
set print '-'
print sprintf('%s: wrote %s', figname, output)
