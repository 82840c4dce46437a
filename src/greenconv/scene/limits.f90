!> Limits on the sizes a scene may ask for. Each is far beyond any sensible scene, and is
!> there so that a mistyped value (an extra few zeros) gets a message before the run, rather
!> than a failed allocation or a run of days. doc/scenes.md lists them.
module greenconv_scene_limits
    use greenconv_conv_builder, only: max_kernel_values
    implicit none
    private

    public :: max_random_modes, max_freq_lines, max_lsce_modes, max_road_terms, max_contact_points
    public :: max_spectrum_values
    !> The cap on a sampled kernel and its estimate live with the builder, which applies them
    !> at every door (C, Fortran, F77); scenes check them when read.
    public :: max_kernel_values

    !> Largest number of random modes (&structure n_modes).
    integer, parameter :: max_random_modes = 1000
    !> Largest number of frequency lines of a sampled G (&identification n_freq): 10^7 lines
    !> hold 160 MB of G and its FFT of 2*10^7 samples.
    integer, parameter :: max_freq_lines = 10000001
    !> Largest number of modes LSCE tries (&identification max_order, order): the companion
    !> matrix is 2N x 2N, the least-squares problem has 2N unknowns.
    integer, parameter :: max_lsce_modes = 200
    !> Largest number of terms of the random road, eq. (35) (&road n_terms).
    integer, parameter :: max_road_terms = 100000
    !> Largest number of contact points (&contact n_points, n_points_x*n_points_y): a tyre's
    !> patch at a few millimetres; `exact` holds its N_c x N_c instantaneous matrix (0.2 GB).
    integer, parameter :: max_contact_points = 5000
    !> Largest number of force samples the spectra of a run hold (&scene spectra): one Welch
    !> segment of the total force, and of each point with spectra_points; the sums of |X_k|^2
    !> and the scratch add about as much again (2^25: 0.27 GB of segments).
    integer, parameter :: max_spectrum_values = 2**25

end module greenconv_scene_limits
