!> Limits on the sizes a scene may ask for. Each is far beyond any sensible scene, and is
!> there so that a mistyped value (an extra few zeros) gets a message before the run, rather
!> than a failed allocation or a run of days. doc/scenes.md lists them.
module greenconv_scene_limits
    use greenconv_core_kinds, only: dp
    implicit none
    private

    public :: max_random_modes, max_freq_lines, max_lsce_modes, max_road_terms, max_contact_points
    public :: max_kernel_values, kernel_values, max_spectrum_values

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
    !> Largest number of stored values of a sampled kernel: N_g*N_c^2 weights and 2*N_g*N_c
    !> past forces, 8 bytes each (10^8: 0.8 GB).
    integer, parameter :: max_kernel_values = 100000000
    !> Largest number of force samples the spectra of a run hold (&scene spectra): one Welch
    !> segment of the total force, and of each point with spectra_points; the sums of |X_k|^2
    !> and the scratch add about as much again (2^25: 0.27 GB of segments).
    integer, parameter :: max_spectrum_values = 2**25

contains

    !> Values a `direct` or `fft` convolver stores, N_g*N_c^2 + 2*N_g*N_c, with N_g estimated
    !> from the slowest decay rate: the envelope exp(-sigma*t) falls to tol by
    !> t = ln(1/tol)/sigma, and the kernel never exceeds the run (N_t samples). A real, so
    !> that absurd sizes do not overflow.
    pure real(dp) function kernel_values(decay_rate, dt, tol, n_steps, n_points)
        !> Slowest modal decay rate sigma = min xi_k*omega_k [1/s] (0: no decay).
        real(dp), intent(in) :: decay_rate
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Truncation fraction of max |g|, in (0, 1).
        real(dp), intent(in) :: tol
        !> Number of steps N_t.
        integer, intent(in) :: n_steps
        !> Number of contact points N_c.
        integer, intent(in) :: n_points

        real(dp) :: n_g

        n_g = real(n_steps, dp)
        if (decay_rate > 0.0_dp) n_g = min(n_g, log(1.0_dp/tol)/(decay_rate*dt) + 1.0_dp)
        kernel_values = n_g*real(n_points, dp)**2 + 2.0_dp*n_g*n_points
    end function kernel_values

end module greenconv_scene_limits
