# The 2D contact patch from a Green's matrix file rolling over a road texture
# (data/patch_texture.nml): the contact force at each of the 4 x 3 points at four instants of
# the implicit (exact) run: the first step, the steps of the largest and the smallest total
# force, and the last step. On the texture the rows across the patch see different heights.
#
#   gnuplot plot/patch_force_map.gp
#   gnuplot -e "datadir='out'; figdir='out/figures'" plot/patch_force_map.gp
#
# Reads DATADIR/patch_texture_exact.dat (one row per step and point: t x u_road u f_contact delta
# f_total y, in s m m m N m N m) and writes FIGDIR/patch_force_map.png. The points are drawn
# as cells around their (x, y), x - x_mean along the travel, y - y_mean across.

if (!exists("datadir")) datadir = 'out'
if (!exists("figdir")) figdir = 'out/figures'
exact = sprintf('%s/patch_texture_exact.dat', datadir)
output = sprintf('%s/patch_force_map.png', figdir)
if (system(sprintf("test -r '%s' && echo yes", exact)) ne 'yes') {
    print sprintf('patch_force_map: cannot read %s (run the scene first: make run)', exact)
    exit status 1
}
# The points (rows of the first step), their mean position, the steps to draw and the force range.
n_points = int(system(sprintf("awk '!/^#/ && NF {if ($1 != 0) exit; n++} END {print n}' '%s'", exact)))
x_mean = real(system(sprintf("awk '!/^#/ && NF {if ($1 != 0) exit; s += $2; n++} END {print s/n}' '%s'", exact)))
y_mean = real(system(sprintf("awk '!/^#/ && NF {if ($1 != 0) exit; s += $8; n++} END {print s/n}' '%s'", exact)))
steps = system(sprintf("awk -v n=%d '!/^#/ && NF {k++; if (k %% n) next; s = k/n - 1; if (k == n || $7 > hi) {hi = $7; a = s}; if (k == n || $7 < lo) {lo = $7; b = s}; last = s} END {print 0, a, b, last}' '%s'", n_points, exact))
f_max = real(system(sprintf("awk '!/^#/ && NF && (n++ == 0 || $5 > m) {m = $5} END {print m}' '%s'", exact)))
f_min = real(system(sprintf("awk '!/^#/ && NF && (n++ == 0 || $5 < m) {m = $5} END {print m}' '%s'", exact)))
dx = real(system(sprintf("awk '!/^#/ && NF {if ($1 != 0) exit; if (n++ && $2 != p && (d == 0 || ($2 - p)^2 < d^2)) d = $2 - p; p = $2} END {print (d > 0 ? d : 0.01)}' '%s'", exact)))

system(sprintf("mkdir -p '%s'", figdir))
set terminal pngcairo size 1100,800 enhanced font 'sans,11'
set output output
set multiplot layout 2, 2 title sprintf("Contact force over a 2D patch of %d points on a road texture (Green's matrix of data/patch\\_green.uff, exact engine)", n_points) font ',12'
set xlabel 'x - x_{mean} along the travel [mm]'
set ylabel 'y - y_{mean} across [mm]'
set cblabel 'contact force [N]'
set palette defined (0 '#ffffff', 1 '#fdd49e', 2 '#fc8d59', 3 '#d7301f', 4 '#7f0000')
set cbrange [f_min:f_max]
set size ratio -1
set style fill solid 1.0 border lc rgb '#555555'
do for [k = 1:4] {
    step = int(word(steps, k))
    t = real(system(sprintf("awk -v r=%d '!/^#/ && NF {k++; if (k == r) {print $1; exit}}' '%s'", step*n_points + 1, exact)))
    total = real(system(sprintf("awk -v r=%d '!/^#/ && NF {k++; if (k == r) {print $7; exit}}' '%s'", step*n_points + 1, exact)))
    what = (k == 1 ? 'first step' : (k == 2 ? 'largest total force' : (k == 3 ? 'smallest total force' : 'last step')))
    set title sprintf('t = %.4f s (%s): total %.0f N', t, what, total)
    plot exact every ::(step*n_points)::(step*n_points + n_points - 1) \
         using (($2 - x_mean)*1e3):(($8 - y_mean)*1e3):(0.45*dx*1e3):(0.45*dx*1e3):5 with boxxyerror fc palette notitle, \
         '' every ::(step*n_points)::(step*n_points + n_points - 1) \
         using (($2 - x_mean)*1e3):(($8 - y_mean)*1e3):(sprintf('%.0f', $5)) with labels font ',9' notitle
}
unset multiplot
set output
set print '-'
print sprintf('patch_force_map: wrote %s', output)
