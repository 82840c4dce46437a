# Fig. 5 of Meftah et al. (2011): displacement of the multi-mode system on the random road
# of eq. (35), standard convolution with the true g against modal decomposition with the
# modes identified by LSCE. Same layout as Fig. 2, whose script draws it.
#
#   gnuplot plot/fig5_mdof_displacement.gp      (reads out/mdof_random_{direct,modal}.dat)

scene = 'mdof_random'
figname = 'fig5_mdof_displacement'
figtitle = "Displacement of an MDOF system on a random road\n(Meftah et al. 2011, Fig. 5)"
thin = 200
load 'plot/fig2_sdof_displacement.gp'
