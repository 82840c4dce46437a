# Speed against accuracy on the multi-mode scene of section 3.2: the same chart
# as bench_accuracy_sdof.gp, whose script draws it, with the sweep of the number of modes
# identified by LSCE added.
#
#   gnuplot plot/bench_accuracy_mdof.gp      (reads out/bench/accuracy_mdof.dat)

scene = 'mdof'
figname = 'bench_accuracy_mdof'
figtitle = "Speed against accuracy: 10 random modes identified by LSCE,\nrandom road (section 3.2), 1 s simulated"
dt_labels = 3
load 'plot/bench_accuracy_sdof.gp'
