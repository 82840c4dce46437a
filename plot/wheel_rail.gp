# A wheel on a rail (data/wheel_rail.nml, data/wheel_rail_rough.nml): the 1/3-octave band
# levels of the contact force of the time-domain runs against the linear frequency-domain
# reference F = -r/(alpha_w + alpha_r + 1/k_H) (doc/rail.md), at the ISO 3095 limit roughness
# and 12 dB above it, the narrowband force PSD of the fft run at the limit against the linear
# model's, and a stretch of the rough run's contact force, where the contact opens.
#
#   gnuplot plot/wheel_rail.gp
#   gnuplot -e "datadir='out'; figdir='out/figures'" plot/wheel_rail.gp
#
# Reads DATADIR/<scene>_<method>_spectra.dat and DATADIR/<scene>_linear_spectra.dat (columns
# f_nominal f_centre f_lower f_upper power level ..., Hz Hz Hz Hz N^2 dB re 1 N), the narrowband
# files DATADIR/wheel_rail_fft_narrowband.dat (f psd_force) and wheel_rail_linear_narrowband.dat
# (f psd_roughness alpha_abs h_abs psd_force), and the rough
# run's column file (text or binary, plot/lib/column_file.gp); writes FIGDIR/wheel_rail.png.

if (!exists("datadir")) datadir = 'out'
if (!exists("figdir")) figdir = 'out/figures'
load 'plot/lib/column_file.gp'
output = sprintf('%s/wheel_rail.png', figdir)
scenes = 'wheel_rail wheel_rail_rough'
titles = "'ISO 3095 limit roughness' 'roughness 12 dB above the limit'"

# The time-domain spectra files of a scene, one per method (not the linear reference).
run_files(scene) = system(sprintf("for m in fft direct exact modal auto; do f='%s/%s_'$m'_spectra.dat'; " . \
                                  "[ -r \"$f\" ] && printf '%%s ' \"$f\"; done", datadir, scene))
method_of(file, scene) = file[strlen(datadir) + strlen(scene) + 3:strlen(file) - strlen('_spectra.dat')]
linear_of(scene) = sprintf('%s/%s_linear_spectra.dat', datadir, scene)

do for [scene in scenes] {
    if (!readable(linear_of(scene)) || words(run_files(scene)) == 0) {
        print sprintf('wheel_rail: no %s or run spectra of %s (run the scenes first: make run)', \
                      linear_of(scene), scene)
        exit status 1
    }
}
narrow_run = sprintf('%s/wheel_rail_fft_narrowband.dat', datadir)
narrow_linear = sprintf('%s/wheel_rail_linear_narrowband.dat', datadir)
if (!readable(narrow_run) || !readable(narrow_linear)) {
    print sprintf('wheel_rail: no %s or %s (run the scenes first: make run)', narrow_run, narrow_linear)
    exit status 1
}
rough = column_file(sprintf('%s/wheel_rail_rough_fft', datadir))
if (rough eq '') {
    print missing_file(sprintf('%s/wheel_rail_rough_fft', datadir))
    exit status 1
}
opts = data_options(rough)
column_t = column_of(rough, 't')
column_f = column_of(rough, 'f_contact')

system(sprintf("mkdir -p '%s'", figdir))
set terminal pngcairo size 1000, 1300 enhanced font 'sans,11'
set output output
set multiplot layout 4, 1 title "Wheel on rail: contact force, time domain against the linear model" font ',13'
set grid xtics ytics mxtics
set key outside right top box opaque noenhanced
set lmargin 10
set rmargin 30
set style line 1 lc rgb '#d62728' lw 2.0
set style line 2 lc rgb '#1f77b4' lw 1.5 dt 2
set style line 3 lc rgb '#000000' lw 1.5
set logscale x
set xrange [100:11000]
set yrange [20:100]
set xlabel 'frequency [Hz]'
set ylabel 'L_F [dB re 1 N]'
do for [k = 1:2] {
    scene = word(scenes, k)
    files = run_files(scene)
    set title word(titles, k) noenhanced
    plot linear_of(scene) using 3:6 with steps ls 3 title 'linear reference', \
         for [i = 1:words(files)] word(files, i) using 3:6 with steps ls i title method_of(word(files, i), scene)
}
set title 'ISO 3095 limit roughness: narrowband PSD on the Welch lines' noenhanced
set logscale y
set format y '10^{%L}'
set yrange [*:*]
set ylabel 'S_F [N^2/Hz]'
plot narrow_run using 1:2 with lines ls 1 title 'fft', \
     narrow_linear using 1:5 with lines ls 3 title 'linear reference'
unset logscale y
set format y '%g'
unset logscale x
set autoscale y
set xrange [0.5:0.6]
set xlabel 't [s]'
set ylabel 'F [kN]'
set title 'roughness 12 dB above the limit: the contact force, 0.1 s (F = 0: contact lost)'
plot rough @opts using column_t:(column(column_f)/1000.0) with lines ls 1 \
     title 'fft'
unset multiplot
set output
set print '-'
print sprintf('wheel_rail: wrote %s', output)
