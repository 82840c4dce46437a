# Stability map of the contact step: where the explicit and the implicit step stay bounded,
# and how far each is from a fine-dt reference, over the contact stiffness k_c and the time
# step dt (SDOF scene of Tab. 1, `exact` engine; greenconv_bench_stability's stability_map).
#
#   gnuplot plot/contact_stability_map.gp
#   gnuplot -e "benchdir='out/bench'; figdir='out/figures'" plot/contact_stability_map.gp
#
# Reads BENCHDIR/contact_stability_map.dat (columns named by the last '#' line: dt k_c
# omega_c_dt explicit_bounded explicit_error implicit_bounded implicit_error) and writes
# FIGDIR/contact_stability_map.png. Without the data file (it is written by the benchmark,
# not by `make run`) the script says so and draws nothing, so that `make figures` goes on.
#
# One panel per scheme; each cell is a tile coloured by log10 of the relative L2 error of u,
# a black cross where the run was stopped as divergent. The lines mark omega_c*dt = 2 (edge
# of the explicit step) and omega_c*dt = 2*sqrt(3) (edge of the implicit step with the
# first-order hold), both from the linear analysis in greenconv_contact_single.

if (!exists("benchdir")) benchdir = 'out/bench'
if (!exists("figdir")) figdir = 'out/figures'

input = sprintf('%s/contact_stability_map.dat', benchdir)
output = sprintf('%s/contact_stability_map.png', figdir)

header(file) = system(sprintf("grep '^#' '%s' | tail -n 1", file))
column_of(file, name) = sum [i = 2:words(header(file))] (word(header(file), i) eq name ? i - 1 : 0)

if (system(sprintf("test -r '%s' && echo yes", input)) ne 'yes') {
    print sprintf('contact_stability_map: no %s (written by the benchmark): nothing drawn', input)
    exit
}
c_dt = column_of(input, 'dt')
c_k = column_of(input, 'k_c')
c_w = column_of(input, 'omega_c_dt')
c_eb = column_of(input, 'explicit_bounded')
c_ee = column_of(input, 'explicit_error')
c_ib = column_of(input, 'implicit_bounded')
c_ie = column_of(input, 'implicit_error')
if (c_dt * c_k * c_w * c_eb * c_ee * c_ib * c_ie == 0) {
    print sprintf('contact_stability_map: expected columns dt k_c omega_c_dt explicit_bounded explicit_error implicit_bounded implicit_error in %s', input)
    exit status 1
}
scene = system(sprintf("grep '^# scene:' '%s' | cut -c 10-", input))

# Tile sizes: dt doubles along a row; k_c is log-spaced, its ratio from the number of rows.
stats input using c_dt nooutput
dt_min = STATS_min
dt_max = STATS_max
n_rows = STATS_records
stats input using c_k nooutput
k_min = STATS_min
k_max = STATS_max
n_dt = int(log(dt_max/dt_min)/log(2) + 1.5)
n_k = n_rows/n_dt
kx = sqrt(2.0)
ky = (n_k > 1) ? (k_max/k_min)**(0.5/(n_k - 1)) : sqrt(10.0)

system(sprintf("mkdir -p '%s'", figdir))
set terminal pngcairo size 1300,650 enhanced font 'sans,11'
set output output

set logscale xy
set xrange [dt_min/kx:dt_max*kx]
set yrange [k_min/ky:k_max*ky]
set format x '10^{%L}'
set format y '10^{%L}'
set xlabel 'time step dt [s]'
set ylabel 'contact stiffness k_c [N/m^p]'
set cbrange [-8:1]
set cblabel 'log_{10} relative L2 error of u'
set palette defined (-8 '#313695', -5 '#4575b4', -3 '#abd9e9', -2 '#ffffbf', -1 '#fdae61', 0 '#d73027', 1 '#67001f')
set key below horizontal
set bmargin 5
set clip two

set style line 1 lc rgb '#000000' lw 2             # omega_c*dt = 2
set style line 2 lc rgb '#000000' lw 2 dt 2        # omega_c*dt = 2*sqrt(3)
set style line 3 lc rgb '#000000' pt 2 ps 1.6 lw 2 # diverged

# tile, coloured by log10(error), only where the run stayed bounded
tile(bounded, err) = (column(bounded) > 0.5 && column(err) > 0) ? log10(column(err)) : NaN
cross(bounded) = (column(bounded) > 0.5) ? NaN : column(c_k)
edge(ratio) = ratio*column(c_dt)/column(c_w)

set multiplot layout 1, 2 title sprintf("Contact step stability: %s", scene) font ',12'
do for [panel = 1:2] {
    bounded = (panel == 1) ? c_eb : c_ib
    err = (panel == 1) ? c_ee : c_ie
    set title (panel == 1) ? 'explicit step (the paper''s)' : 'implicit step'
    plot input using c_dt:c_k:(column(c_dt)/kx):(column(c_dt)*kx):(column(c_k)/ky):(column(c_k)*ky):(tile(bounded, err)) \
             with boxxyerror fs solid 1.0 noborder lc palette notitle, \
         input using c_dt:(cross(bounded)) with points ls 3 title 'diverged', \
         input using (edge(2.0)):c_k with lines ls 1 title '{/Symbol w}_c dt = 2', \
         input using (edge(2.0*sqrt(3.0))):c_k with lines ls 2 title '{/Symbol w}_c dt = 2{/Symbol \326}3'
}
unset multiplot
set output
set print '-'
print sprintf('contact_stability_map: wrote %s', output)
