# The tyre's contact patch at scale (data/tyre_patch.nml: the belt as a plate, 50 x 20 points,
# a law per area, a 2D road texture): the contact pressure over the patch at the scene's
# map_times (one panel each), and the total force and the contact area against time.
#
#   gnuplot plot/tyre_patch_map.gp
#   gnuplot -e "datadir='out'; figdir='out/figures'; method='exact'" plot/tyre_patch_map.gp
#
# Reads DATADIR/tyre_patch_<method>_maps.dat (N_c rows per map, the per-point columns t x u_road
# u f_contact delta f_total y, in s m m m N m N m; &scene map_times) and
# DATADIR/tyre_patch_<method>_totals.dat (t f_total area n_contact, in s N m^2 1), method
# 'modal' by default, and writes FIGDIR/tyre_patch_map.png and FIGDIR/tyre_patch_total.png.
# Pressure is each point's force over its share of the patch (dx*dy, the grid's spacings);
# the contact area is the driver's (the shares of the points with a force > 0).

if (!exists("datadir")) datadir = 'out'
if (!exists("figdir")) figdir = 'out/figures'
if (!exists("method")) method = 'modal'
maps = sprintf('%s/tyre_patch_%s_maps.dat', datadir, method)
totals = sprintf('%s/tyre_patch_%s_totals.dat', datadir, method)
map_png = sprintf('%s/tyre_patch_map.png', figdir)
total_png = sprintf('%s/tyre_patch_total.png', figdir)
do for [file in maps.' '.totals] {
    if (system(sprintf("test -r '%s' && echo yes", file)) ne 'yes') {
        print sprintf('tyre_patch_map: cannot read %s (run the scene first: make run)', file)
        exit status 1
    }
}
# points per map (the rows of the first map), the number of maps, the mean place, the spacings
first = sprintf("awk '!/^#/ && NF {if (n && $1 != t) exit; t = $1; n++; print}' '%s'", maps)
n_points = int(system(first." | wc -l"))
n_maps = int(system(sprintf("awk '!/^#/ && NF {n++} END {print n}' '%s'", maps)))/n_points
x_mean = real(system(first." | awk '{s += $2; n++} END {print s/n}'"))
y_mean = real(system(first." | awk '{s += $8; n++} END {print s/n}'"))
dx = real(system(first." | awk '{print $2}' | sort -g -u | awk 'NR == 2 {print $1 - p} {p = $1}'"))
dy = real(system(first." | awk '{print $8}' | sort -g -u | awk 'NR == 2 {print $1 - p} {p = $1}'"))
p_max = real(system(sprintf("awk -v a=%.12g '!/^#/ && NF && $5/a > m {m = $5/a} END {print m/1e3}' '%s'", dx*dy, maps)))
map_times = system(sprintf("awk '!/^#/ && NF && $1 != t {t = $1; printf \"%%s \", t}' '%s'", maps))
columns = (n_maps <= 3 ? n_maps : ceil(sqrt(n_maps)))
rows = ceil(real(n_maps)/columns)

system(sprintf("mkdir -p '%s'", figdir))
set terminal pngcairo size 480*columns + 120, 420*rows + 60 enhanced font 'sans,11'
set output map_png
set multiplot layout rows, columns title sprintf("Contact pressure over a tyre's patch: %d points, belt as a plate, law per area, 2D road texture (%s)", n_points, method) font ',12'
set xlabel 'x - x_{mean} along the travel [mm]'
set ylabel 'y - y_{mean} across [mm]'
set cblabel 'contact pressure [kPa]'
set palette defined (0 '#ffffff', 1 '#fdd49e', 2 '#fc8d59', 3 '#d7301f', 4 '#7f0000')
set cbrange [0:p_max]
set size ratio -1
set style fill solid 1.0 noborder
do for [k = 1:n_maps] {
    t = real(word(map_times, k))
    total = real(system(sprintf("awk -v r=%d '!/^#/ && NF {k++; if (k == r) {print $7; exit}}' '%s'", (k - 1)*n_points + 1, maps)))
    set title sprintf('t = %.4f s: total %.0f N', t, total)
    plot maps every ::((k - 1)*n_points)::(k*n_points - 1) \
         using (($2 - x_mean)*1e3):(($8 - y_mean)*1e3):(0.5*dx*1e3):(0.5*dy*1e3):($5/(dx*dy)/1e3) \
         with boxxyerror fc palette notitle
}
unset multiplot
set output

# total force and contact area of every kept step, the map times marked
set output total_png
set terminal pngcairo size 1000,600 enhanced font 'sans,11'
set size noratio
set multiplot layout 2, 1 title sprintf('Total contact force and contact area of the %d-point patch (%s)', n_points, method) font ',12'
set xlabel 't [s]'
unset cblabel
set title ''
do for [k = 1:n_maps] {
    set arrow k from first real(word(map_times, k)), graph 0 to first real(word(map_times, k)), graph 1 nohead dt 2 lc rgb '#777777'
}
set ylabel 'total force [N]'
plot totals using 1:2 with lines lw 1.2 lc rgb '#d7301f' notitle
set ylabel 'contact area [cm^2]'
plot totals using 1:($3*1e4) with lines lw 1.2 lc rgb '#3182bd' notitle
unset multiplot
set output
set print '-'
print sprintf('tyre_patch_map: wrote %s and %s', map_png, total_png)
