# How the time domain departs from the linear model as the roughness grows
# (data/wheel_rail_sweep.nml, doc/rail.md): for each roughness offset, the fft run's 1/3-octave
# band levels minus the linear model's (those of data/wheel_rail.nml's linear reference, at
# offset 0 with the same phases and segments, plus the offset: the linear model scales with
# the roughness), and the share of steps with the contact lost.
#
#   gnuplot plot/wheel_rail_sweep.gp
#   gnuplot -e "datadir='out'; figdir='out/figures'" plot/wheel_rail_sweep.gp
#
# Reads DATADIR/wheel_rail_sweep_sweep.dat (columns found by their names in the '# variant'
# header line: road.roughness_offset, contact_fft, status_fft, L<f>_fft) and
# DATADIR/wheel_rail_linear_spectra.dat (f_nominal in column 1, level in column 6); writes
# FIGDIR/wheel_rail_sweep.png. Departures are taken in the bands from 200 Hz to 5 kHz (the
# bands below hold the start from rest; the roughness ends at 8.8 kHz).

if (!exists("datadir")) datadir = 'out'
if (!exists("figdir")) figdir = 'out/figures'
# (no run's column file is read: the sweep's table and the reference's bands only)
readable(file) = system(sprintf("test -r '%s' && echo 1 || echo 0", file)) eq '1'
sweep = sprintf('%s/wheel_rail_sweep_sweep.dat', datadir)
linear = sprintf('%s/wheel_rail_linear_spectra.dat', datadir)
output = sprintf('%s/wheel_rail_sweep.png', figdir)
if (!readable(sweep) || !readable(linear)) {
    print sprintf('wheel_rail_sweep: no %s or %s (run data/wheel_rail.nml and data/wheel_rail_sweep.nml ' . \
                  'first: make run)', sweep, linear)
    exit status 1
}

# One row per variant that ran (status 0 or 4): offset [dB], contact lost [% of steps], the
# largest |departure| over the bands, the rms departure over the bands, the departures at
# 250 Hz, 1 kHz and 2.5 kHz [dB].
table = system(sprintf("awk 'FNR == NR { if ($1 !~ /^#/) linear[sprintf(\"%%.0f\", $1)] = $6; next } " . \
    "/^# variant/ { for (i = 2; i <= NF; i++) { name = $i; c = i - 1; " . \
    "  if (name == \"road.roughness_offset\") co = c; if (name == \"contact_fft\") cc = c; " . \
    "  if (name == \"status_fft\") cs = c; " . \
    "  if (name ~ /^L[0-9.]+_fft$/) { f = substr(name, 2, length(name) - 5) + 0; band[c] = sprintf(\"%%.0f\", f) } } next } " . \
    "/^#/ { next } " . \
    "{ if ($cs != 0 && $cs != 4) next; worst = 0; sum = 0; n = 0; d250 = \"nan\"; d1k = \"nan\"; d2k5 = \"nan\"; " . \
    "  for (c in band) { f = band[c] + 0; if (f < 200 || f > 5000 || !(band[c] in linear)) continue; " . \
    "    d = $c - (linear[band[c]] + $co); a = d < 0 ? -d : d; if (a > worst) worst = a; sum += d * d; n++; " . \
    "    if (f == 250) d250 = d; if (f == 1000) d1k = d; if (f == 2500) d2k5 = d } " . \
    "  printf \"%%g %%g %%g %%g %%s %%s %%s\\n\", $co, 100 * (1 - $cc), worst, sqrt(sum / n), d250, d1k, d2k5 }' " . \
    "'%s' '%s'", linear, sweep))
if (strlen(table) == 0) {
    print sprintf('wheel_rail_sweep: no variant of %s ran', sweep)
    exit status 1
}
set print $departure
print table
unset print

system(sprintf("mkdir -p '%s'", figdir))
set terminal pngcairo size 900, 800 enhanced font 'sans,11'
set output output
set multiplot layout 2, 1 title "Wheel on rail: the time domain against the linear model as the roughness grows" \
    font ',13'
set grid xtics ytics
set key outside right top box opaque noenhanced
set rmargin 28
set xlabel 'roughness offset from the ISO 3095 limit [dB]'
set style line 1 lc rgb '#000000' lw 2.0 pt 7
set style line 2 lc rgb '#7f7f7f' lw 2.0 pt 5
set style line 3 lc rgb '#d62728' lw 1.5 pt 6
set style line 4 lc rgb '#1f77b4' lw 1.5 pt 4
set style line 5 lc rgb '#2ca02c' lw 1.5 pt 8
set title 'band levels of the fft run minus the linear model, 200 Hz to 5 kHz'
set ylabel 'L_{run} - L_{linear} [dB]'
plot $departure using 1:3 with linespoints ls 1 title 'largest |departure|', \
     $departure using 1:4 with linespoints ls 2 title 'rms over the bands', \
     $departure using 1:5 with linespoints ls 3 title '250 Hz', \
     $departure using 1:6 with linespoints ls 4 title '1 kHz', \
     $departure using 1:7 with linespoints ls 5 title '2.5 kHz'
set title 'contact lost (zero contact force)'
set ylabel 'share of steps [%]'
set yrange [0:*]
plot $departure using 1:2 with linespoints ls 1 title 'fft'
unset multiplot
set output
set print '-'
print sprintf('wheel_rail_sweep: wrote %s', output)
