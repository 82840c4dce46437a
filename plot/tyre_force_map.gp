# The tyre/road scene (data/tyre_road.nml): contact force over the contact patch and time,
# and the total force of each method.
#
#   gnuplot plot/tyre_force_map.gp
#   gnuplot -e "datadir='out'; figdir='out/figures'" plot/tyre_force_map.gp
#
# Reads DATADIR/tyre_road_exact, _modal and _direct, .dat or .bin (plot/lib/column_file.gp;
# one row per step and point: t x u_road u f_contact delta f_total, in s m m m N m N) and writes
# FIGDIR/tyre_force_map.png.

if (!exists("datadir")) datadir = 'out'
if (!exists("figdir")) figdir = 'out/figures'
output = sprintf('%s/tyre_force_map.png', figdir)
# The runs' column files, text (.dat) or binary (.bin), and how gnuplot reads each.
load 'plot/lib/column_file.gp'
do for [method in 'exact modal direct'] {
    if (column_file(sprintf('%s/tyre_road_%s', datadir, method)) eq '') {
        print sprintf('tyre_force_map: %s', missing_file(sprintf('%s/tyre_road_%s', datadir, method)))
        exit status 1
    }
}
exact = column_file(sprintf('%s/tyre_road_exact', datadir))
modal = column_file(sprintf('%s/tyre_road_modal', datadir))
direct = column_file(sprintf('%s/tyre_road_direct', datadir))
exact_opts = data_options(exact)
modal_opts = data_options(modal)
direct_opts = data_options(direct)
# The points of the patch: the rows of the first step (t = 0), and their mean position.
stats exact @exact_opts using ($1 == 0 ? 1 : 0) nooutput
n_points = int(STATS_sum)
stats exact @exact_opts every ::0::(n_points - 1) using 2 nooutput
x_centre = STATS_mean

system(sprintf("mkdir -p '%s'", figdir))
set terminal pngcairo size 1000,900 enhanced font 'sans,11'
set output output
set multiplot layout 2, 1 title "Tyre on a rough road: 20 contact points, all forces solved together each step" font ',13'

# Top: the force map of the implicit (exact) run.
set xlabel 't [s]'
set ylabel 'position in the patch [mm]'
set cblabel 'contact force per point [N]'
set palette defined (0 '#ffffff', 1 '#fdd49e', 2 '#fc8d59', 3 '#d7301f', 4 '#7f0000')
set cbrange [0:*]
set autoscale xfix
set autoscale yfix
set lmargin 12
set rmargin 14
set title 'contact force over the patch, 40 ms of the run (exact engine, implicit step): road features cross the patch'
set xrange [0.10:0.14]
plot exact @exact_opts using 1:(($2 - x_centre)*1e3):5 with image notitle

# Bottom: total force of the three methods.
unset cblabel
set autoscale x
set title 'total contact force, whole run'
set ylabel 'total force [kN]'
set grid
set key top right box opaque
set style line 1 lc rgb '#d62728' lw 2
set style line 2 lc rgb '#1f77b4' lw 1.2 dt 2
set style line 3 lc rgb '#2ca02c' lw 1.0 dt 3
plot exact @exact_opts every n_points using 1:($7/1e3) with lines ls 1 title 'exact (modes, implicit step)', \
     modal @modal_opts every n_points using 1:($7/1e3) with lines ls 2 title 'modal (modes, explicit step)', \
     direct @direct_opts every n_points using 1:($7/1e3) with lines ls 3 title 'direct (sampled g_{ij}, explicit step)'
unset multiplot
set output
set print '-'
print sprintf('tyre_force_map: wrote %s', output)
