# The tyre's contact patch at scale (data/tyre_patch.nml: the belt as a plate, 50 x 20 points,
# a law per area, a 2D road texture): the contact pressure over the patch at four kept instants
# (the first after 20 ms of settling, those of the largest and the smallest total force after
# it, the last), and the total
# force and the contact area against time.
#
#   gnuplot plot/tyre_patch_map.gp
#   gnuplot -e "datadir='out'; figdir='out/figures'" plot/tyre_patch_map.gp
#
# Reads DATADIR/tyre_patch_modal.dat (one row per kept step and point: t x u_road u f_contact
# delta f_total y, in s m m m N m N m) and writes FIGDIR/tyre_patch_map.png and
# FIGDIR/tyre_patch_total.png. Pressure is each point's force over its share of the patch
# (dx*dy, the grid's spacings); the contact area counts the points with a force > 0.

if (!exists("datadir")) datadir = 'out'
if (!exists("figdir")) figdir = 'out/figures'
run = sprintf('%s/tyre_patch_modal.dat', datadir)
map_png = sprintf('%s/tyre_patch_map.png', figdir)
total_png = sprintf('%s/tyre_patch_total.png', figdir)
if (system(sprintf("test -r '%s' && echo yes", run)) ne 'yes') {
    print sprintf('tyre_patch_map: cannot read %s (run the scene first: make run)', run)
    exit status 1
}
# points per kept step (the rows of the first one), their mean place, the grid spacings
n_points = int(system(sprintf("awk '!/^#/ && NF {if ($1 != 0) exit; n++} END {print n}' '%s'", run)))
first = sprintf("awk '!/^#/ && NF {if ($1 != 0) exit; print}' '%s'", run)
x_mean = real(system(first." | awk '{s += $2; n++} END {print s/n}'"))
y_mean = real(system(first." | awk '{s += $8; n++} END {print s/n}'"))
dx = real(system(first." | awk '{print $2}' | sort -g -u | awk 'NR == 2 {print $1 - p} {p = $1}'"))
dy = real(system(first." | awk '{print $8}' | sort -g -u | awk 'NR == 2 {print $1 - p} {p = $1}'"))
# the instants drawn: after the first settling (the run starts from the static state on a flat
# road, so its first milliseconds show the patch settling on the rough one)
settle = 0.02
steps = system(sprintf("awk -v n=%d -v t0=%g '!/^#/ && NF {k++; if (k %% n) next; if ($1 < t0) next; s = k/n - 1; if (!seen || $7 > hi) {hi = $7; a = s}; if (!seen || $7 < lo) {lo = $7; b = s}; if (!seen) f = s; seen = 1; last = s} END {print f, a, b, last}' '%s'", n_points, settle, run))
p_max = real(system(sprintf("awk -v a=%.12g '!/^#/ && NF && $5/a > m {m = $5/a} END {print m/1e3}' '%s'", dx*dy, run)))

system(sprintf("mkdir -p '%s'", figdir))
set terminal pngcairo size 1200,800 enhanced font 'sans,11'
set output map_png
set multiplot layout 2, 2 title sprintf("Contact pressure over a tyre's patch: %d points, belt as a plate, law per area, 2D road texture (modal)", n_points) font ',12'
set xlabel 'x - x_{mean} along the travel [mm]'
set ylabel 'y - y_{mean} across [mm]'
set cblabel 'contact pressure [kPa]'
set palette defined (0 '#ffffff', 1 '#fdd49e', 2 '#fc8d59', 3 '#d7301f', 4 '#7f0000')
set cbrange [0:p_max]
set size ratio -1
set style fill solid 1.0 noborder
do for [k = 1:4] {
    step = int(word(steps, k))
    t = real(system(sprintf("awk -v r=%d '!/^#/ && NF {k++; if (k == r) {print $1; exit}}' '%s'", step*n_points + 1, run)))
    total = real(system(sprintf("awk -v r=%d '!/^#/ && NF {k++; if (k == r) {print $7; exit}}' '%s'", step*n_points + 1, run)))
    what = (k == 1 ? sprintf('first after %.0f ms', settle*1e3) : (k == 2 ? 'largest total force' : (k == 3 ? 'smallest total force' : 'last kept step')))
    set title sprintf('t = %.4f s (%s): total %.0f N', t, what, total)
    plot run every ::(step*n_points)::(step*n_points + n_points - 1) \
         using (($2 - x_mean)*1e3):(($8 - y_mean)*1e3):(0.5*dx*1e3):(0.5*dy*1e3):($5/(dx*dy)/1e3) \
         with boxxyerror fc palette notitle
}
unset multiplot
set output

# total force and contact area per kept step
set output total_png
set terminal pngcairo size 1000,600 enhanced font 'sans,11'
set size noratio
set multiplot layout 2, 1 title sprintf('Total contact force and contact area of the %d-point patch (modal)', n_points) font ',12'
set xlabel 't [s]'
unset cblabel
set ylabel 'total force [N]'
set title ''
series = sprintf("< awk -v n=%d -v a=%.12g '!/^#/ && NF {k++; if ($5 > 0) c++; if (k %% n == 0) {print $1, $7, c*a*1e4; c = 0}}' '%s'", n_points, dx*dy, run)
plot series using 1:2 with linespoints pt 7 ps 0.4 lc rgb '#d7301f' notitle
set ylabel 'contact area [cm^2]'
plot series using 1:3 with linespoints pt 7 ps 0.4 lc rgb '#3182bd' notitle
unset multiplot
set output
set print '-'
print sprintf('tyre_patch_map: wrote %s and %s', map_png, total_png)
