# The sweep of data/tyre_sweep.nml: rms of the total contact force (modal method)
# against the speed, one curve per tread stiffness. Columns of out/tyre_sweep_sweep.dat:
# 1 variant, 2 road.speed, 3 contact.stiffness, then per method max, mean, rms, contact
# fraction, status, fault step (modal: 4-9, exact: 10-15). Rows of a failed variant are skipped.
if (!exists("figdir")) figdir = 'out/figures'
data = 'out/tyre_sweep_sweep.dat'
set terminal pngcairo size 800,560 noenhanced
set output figdir.'/sweep_rms_force.png'
set title 'Tyre sweep: rms of the total contact force (modal), one curve per tread stiffness k_c'
set xlabel 'speed V [m/s]'
set ylabel 'rms total contact force [N]'
set key top left title 'k_c [N/m]'
set grid
stiffnesses = system("grep -v '^#' ".data." | awk '{print $3}' | sort -g -u | tr '\\n' ' '")
# The stiffness varies fastest: the rows of stiffness i are i, i + n, i + 2n, ...
n = words(stiffnesses)
plot for [i=1:n] data every n::(i - 1) using 2:($8 == 0 ? $6 : NaN) with linespoints lw 2 title word(stiffnesses, i)
