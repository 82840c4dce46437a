# Fig. 2 of Meftah et al. (2011): displacement of the SDOF body rolling on the sinusoidal
# road, standard (direct) convolution "-+-" against modal decomposition "-□-".
#
#   gnuplot plot/fig2_sdof_displacement.gp
#   gnuplot -e "datadir='out'; figdir='out/figures'" plot/fig2_sdof_displacement.gp
#
# Reads DATADIR/sdof_sine_direct and _modal, .dat or .bin (plot/lib/column_file.gp; columns
# named by the last '#' line: t u_road u f_contact delta, in s m m N m) and writes
# FIGDIR/fig2_sdof_displacement.png.
#
# The body moves by tens of micrometres while the road goes +-1 mm, so the figure has two
# panels sharing the time axis: the top one is the paper's view (road and body on one
# scale), the bottom one zooms on the body displacement u. Both in mm.

if (!exists("datadir")) datadir = 'out'
if (!exists("figdir")) figdir = 'out/figures'
if (!exists("scene")) scene = 'sdof_sine'
# Another scene's figure (Figs. 5 and 6) sets these three and loads this script.
if (!exists("figname")) figname = 'fig2_sdof_displacement'
if (!exists("figtitle")) figtitle = "Displacement of an SDOF system on a sinusoidal road\n(Meftah et al. 2011, Fig. 2)"
if (!exists("thin")) thin = 40

output = sprintf('%s/%s.png', figdir, figname)

# The runs' column files, text (.dat) or binary (.bin), and how gnuplot reads each.
load 'plot/lib/column_file.gp'
direct = column_file(sprintf('%s/%s_direct', datadir, scene))
modal = column_file(sprintf('%s/%s_modal', datadir, scene))
do for [method in 'direct modal'] {
    if (column_file(sprintf('%s/%s_%s', datadir, scene, method)) eq '') {
        print sprintf('fig2: %s', missing_file(sprintf('%s/%s_%s', datadir, scene, method)))
        exit status 1
    }
}
direct_opts = data_options(direct)
modal_opts = data_options(modal)
t = column_of(direct, 't')
u_road = column_of(direct, 'u_road')
u = column_of(direct, 'u')
if (t == 0 || u_road == 0 || u == 0 || column_of(modal, 'u') != u) {
    print sprintf('fig2: expected columns t, u_road, u in %s and %s', direct, modal)
    exit status 1
}

system(sprintf("mkdir -p '%s'", figdir))
set terminal pngcairo size 1000,800 enhanced font 'sans,11'
set output output

mm = 1.0e3          # m -> mm
# one marker every `thin` samples; the modal markers sit half way between
set style line 1 lc rgb '#000000' lw 2                        # road profile
set style line 2 lc rgb '#d62728' lw 1.5 pt 1 ps 1.6          # direct: -+-
set style line 3 lc rgb '#1f77b4' lw 1.0 dt 2 pt 4 ps 1.2     # modal: -□- (dashed, on top)

set multiplot layout 2, 1 title figtitle font ',13'
set grid
set key top right box opaque
set offsets graph 0, graph 0, graph 0.3, graph 0.05   # head room for the key
set xlabel 't [s]'
set format x '%.2f'
set lmargin 12

# Top: the paper's view.
set ylabel 'displacement [mm]'
plot direct @direct_opts using t:(column(u_road)*mm) with lines ls 1 title 'road profile u_{road}', \
     direct @direct_opts using t:(column(u)*mm) with lines ls 2 notitle, \
     direct @direct_opts using t:(column(u)*mm) every thin::0 with points ls 2 notitle, \
     keyentry with linespoints ls 2 title 'body u, standard convolution', \
     modal @modal_opts using t:(column(u)*mm) with lines ls 3 notitle, \
     modal @modal_opts using t:(column(u)*mm) every thin::(thin/2) with points ls 3 notitle, \
     keyentry with linespoints ls 3 title 'body u, modal decomposition'

# Bottom: the body alone.
set ylabel 'body displacement u [mm]'
set format y '%.3f'
plot direct @direct_opts using t:(column(u)*mm) with lines ls 2 notitle, \
     direct @direct_opts using t:(column(u)*mm) every thin::0 with points ls 2 notitle, \
     keyentry with linespoints ls 2 title 'standard convolution', \
     modal @modal_opts using t:(column(u)*mm) with lines ls 3 notitle, \
     modal @modal_opts using t:(column(u)*mm) every thin::(thin/2) with points ls 3 notitle, \
     keyentry with linespoints ls 3 title 'modal decomposition'

unset multiplot
set output
set print '-'
print sprintf('%s: wrote %s', figname, output)
