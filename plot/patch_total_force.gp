# The 2D contact patch from a Green's matrix file (data/patch_road.nml): the total contact force
# of each method over the run, and each method's difference from the exact engine.
#
#   gnuplot plot/patch_total_force.gp
#   gnuplot -e "datadir='out'; figdir='out/figures'" plot/patch_total_force.gp
#
# Reads DATADIR/patch_road_exact.dat, _modal.dat, _direct.dat and _fft.dat (one row per step
# and point: t x u_road u f_contact delta f_total y, in s m m m N m N m) and writes
# FIGDIR/patch_total_force.png. exact and modal run on the identified shared modes (exact with
# the fit's upper residual in its instant matrix, implicit; modal without it, explicit), direct
# and fft on g_ij from the inverse FFT of the file's receptances.

if (!exists("datadir")) datadir = 'out'
if (!exists("figdir")) figdir = 'out/figures'
exact = sprintf('%s/patch_road_exact.dat', datadir)
modal = sprintf('%s/patch_road_modal.dat', datadir)
direct = sprintf('%s/patch_road_direct.dat', datadir)
fft = sprintf('%s/patch_road_fft.dat', datadir)
output = sprintf('%s/patch_total_force.png', figdir)
do for [file in exact.' '.modal.' '.direct.' '.fft] {
    if (system(sprintf("test -r '%s' && echo yes", file)) ne 'yes') {
        print sprintf('patch_total_force: cannot read %s (run the scene first: make run)', file)
        exit status 1
    }
}
n_points = int(system(sprintf("awk '!/^#/ && NF {if ($1 != 0) exit; n++} END {print n}' '%s'", exact)))
# Total force of a method minus exact's, one line per step (the files' rows are step-major).
difference(file) = sprintf("< awk -v n=%d '!/^#/ && NF {if (FNR == NR) {if (++k %% n == 0) e[k/n] = $7; next} if (++m %% n == 0) print $1, $7 - e[m/n]}' '%s' '%s'", n_points, exact, file)

system(sprintf("mkdir -p '%s'", figdir))
set terminal pngcairo size 1000,800 enhanced font 'sans,11'
set output output
set multiplot layout 2, 1 title sprintf("2D patch of %d points on data/road\\_sample.dat from a Green's matrix file (data/patch\\_green.uff)", n_points) font ',12'
set grid
set key top right box opaque
set offsets graph 0, 0, 0.4, 0
set xlabel 't [s]'
set ylabel 'total force [kN]'
set title 'total contact force of each method'
set style line 1 lc rgb '#d62728' lw 2
set style line 2 lc rgb '#1f77b4' lw 1.2 dt 2
set style line 3 lc rgb '#2ca02c' lw 1.2
set style line 4 lc rgb '#000000' lw 1.0 dt 3
plot exact every n_points using 1:($7/1e3) with lines ls 1 title 'exact (identified modes + U, implicit)', \
     modal every n_points using 1:($7/1e3) with lines ls 2 title 'modal (identified modes, explicit)', \
     direct every n_points using 1:($7/1e3) with lines ls 3 title 'direct (g_{ij} by inverse FFT of G)', \
     fft every n_points using 1:($7/1e3) with lines ls 4 title 'fft (the same g_{ij})'
set title 'difference from exact'
set ylabel 'total force - exact [N]'
plot difference(modal) using 1:2 with lines ls 2 title 'modal', \
     difference(direct) using 1:2 with lines ls 3 title 'direct', \
     difference(fft) using 1:2 with lines ls 4 title 'fft'
unset multiplot
set output
set print '-'
print sprintf('patch_total_force: wrote %s', output)
