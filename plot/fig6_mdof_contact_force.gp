# Fig. 6 of Meftah et al. (2011): contact force of the multi-mode system on the random road,
# standard convolution with the true g against modal decomposition with the LSCE modes.
# Same layout as Fig. 3, whose script draws it.
#
#   gnuplot plot/fig6_mdof_contact_force.gp     (reads out/mdof_random_{direct,modal}.dat)

scene = 'mdof_random'
figname = 'fig6_mdof_contact_force'
figtitle = "Contact force of an MDOF system on a random road\n(Meftah et al. 2011, Fig. 6)"
thin = 200
load 'plot/fig3_sdof_contact_force.gp'
