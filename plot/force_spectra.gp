# Force spectra of the shipped contact scenes (&scene spectra = .true.): the 1/3-octave band
# levels of the total contact force, dB re 1 N, one curve per method, a panel per scene.
#
#   gnuplot plot/force_spectra.gp
#   gnuplot -e "datadir='out'; figdir='out/figures'" plot/force_spectra.gp
#
# Reads DATADIR/<scene>_<method>_spectra.dat (not the contact area's _area_spectra.dat) for
# the scenes sdof_sine, mdof_random and tyre_road (columns f_nominal f_centre f_lower f_upper
# power level spread_db [level_1 ...], in Hz Hz Hz Hz N^2 dB dB) and writes
# FIGDIR/force_spectra.png. Each band is drawn as a step from its lower to its upper edge; the
# error bars on the first method are the statistical spread of a level (one standard
# deviation, for a noise-like force); the tyre's panel also shows each contact point's levels
# (thin grey, first method) when the file holds them.

if (!exists("datadir")) datadir = 'out'
if (!exists("figdir")) figdir = 'out/figures'
if (!exists("scenes")) scenes = 'sdof_sine mdof_random tyre_road'
output = sprintf('%s/force_spectra.png', figdir)

# The spectra files of a scene, one per method, and the method of a file.
spectra_files(scene) = system(sprintf("ls %s/%s_*_spectra.dat 2>/dev/null | grep -v '_area_spectra[.]dat$' | tr '\\n' ' '", datadir, scene))
method_of(file, scene) = file[strlen(datadir) + strlen(scene) + 3:strlen(file) - strlen('_spectra.dat')]
# The Welch parameters of a file, from its header: "segments of N samples ..., K segments averaged".
header_number(file, pattern) = int(system(sprintf("sed -n 's/.*%s.*/\\1/p' '%s' | head -n 1", pattern, file)))
samples_of(file) = header_number(file, 'segments of \([0-9]*\) samples')
segments_of(file) = header_number(file, ' \([0-9]*\) segments averaged')
welch_of(file) = sprintf('%d Hann segment%s of %d samples, 50 %% overlap', segments_of(file), \
                         segments_of(file) > 1 ? 's' : '', samples_of(file))
columns_of(file) = words(system(sprintf("grep '^#' '%s' | tail -n 1", file))) - 1

found = 0
do for [scene in scenes] {
    if (words(spectra_files(scene)) > 0) { found = found + 1 }
}
if (found == 0) {
    print sprintf('force_spectra: no %s/<scene>_<method>_spectra.dat for %s (run the scenes first: make run)', \
                  datadir, scenes)
    exit status 1
}

system(sprintf("mkdir -p '%s'", figdir))
set terminal pngcairo size 1000, 330*found + 60 enhanced font 'sans,11'
set output output
set multiplot layout found, 1 title "1/3-octave band levels of the total contact force (IEC 61260-1 bands, Welch PSD, Hann window)" font ',13'
set logscale x
set grid xtics ytics mxtics
set key outside right top box opaque noenhanced
set xlabel 'frequency [Hz]'
set ylabel 'L_F [dB re 1 N]'
set lmargin 10
set rmargin 34
set style line 1 lc rgb '#d62728' lw 2.0
set style line 2 lc rgb '#1f77b4' lw 1.5 dt 2
set style line 3 lc rgb '#2ca02c' lw 1.2 dt 3
set style line 4 lc rgb '#9467bd' lw 1.2 dt 4
set style line 9 lc rgb '#c8c8c8' lw 0.6
set style line 10 lc rgb '#555555' lw 1 pt 0

do for [scene in scenes] {
    files = spectra_files(scene)
    if (words(files) > 0) {
        first = word(files, 1)
        points = columns_of(first) - 7
        set title sprintf('%s: %s', scene, welch_of(first)) noenhanced
        # the points' levels underneath; steps along the lower edges (risers and tops), the tops
        # again as bars (the last band's too); the spread on the first method
        plot for [p = 1:points] first using 3:(column(7 + p)) with steps ls 9 \
                 title (p == 1 ? sprintf('%d points, %s', points, method_of(first, scene)) : ''), \
             for [i = 1:words(files)] word(files, i) using 3:6 with steps ls i notitle, \
             for [i = 1:words(files)] word(files, i) using 3:6:($4 - $3):(0) with vectors nohead ls i \
                 title method_of(word(files, i), scene), \
             first using 2:6:7 with yerrorbars ls 10 title 'spread (1 sigma, noise)'
    }
}
unset multiplot
set output
set print '-'
print sprintf('force_spectra: wrote %s', output)
