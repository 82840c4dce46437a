# The sweep of data/tyre_sweep.nml, its spectra columns: the 1/3-octave band
# levels of the total contact force (modal method) against the band centre, one curve per
# speed, for the tread stiffness k_c = 2.0e5 N/m. The level columns L<f_c>_modal of
# out/tyre_sweep_sweep.dat are found by name in its header; awk turns them into one line
# per band: the centre, then the level of each variant with that stiffness (a failed
# variant's 'nan' is not drawn). The levels fall steeply above V/lambda_min, lambda_min = 10 mm
# the shortest wavelength of data/road_sample.dat; what rises near 5 kHz at 10 m/s is the
# file's 2 mm sampling (linear between samples), passed at V/2 mm = 5 kHz.
if (!exists("figdir")) figdir = 'out/figures'
data = 'out/tyre_sweep_sweep.dat'
stiffness = '2.0e5'
set terminal pngcairo size 800,560 noenhanced
set output figdir.'/sweep_levels.png'
set title 'Tyre sweep: 1/3-octave levels of the total contact force (modal), k_c = '.stiffness.' N/m'
set xlabel 'band centre frequency [Hz]'
set ylabel 'band level [dB re 1 N]'
set logscale x
set xrange [630:6300]
set key bottom left title 'V [m/s]'
set grid
speeds = system("grep -v '^#' ".data." | awk '$3 == \"".stiffness."\" {print $2}' | tr '\\n' ' '")
bands = "< awk '/^# variant/ { for (i = 2; i <= NF; i++) if ($i ~ /^L[0-9.]+_modal$/) { n++; col[n] = i - 1; " \
    ."fc[n] = substr($i, 2, index($i, \"_\") - 2) } } !/^#/ && $3 == \"".stiffness."\" { m++; " \
    ."for (b = 1; b <= n; b++) level[b, m] = $(col[b]) } END { for (b = 1; b <= n; b++) { printf \"%s\", fc[b]; " \
    ."for (j = 1; j <= m; j++) printf \" %s\", level[b, j]; print \"\" } }' ".data
plot for [j=1:words(speeds)] bands using 1:(column(j + 1)) with linespoints lw 2 title word(speeds, j)
