!> Limits on the sizes a scene may ask for. Each is far beyond any sensible scene, and is
!> there so that a mistyped value (an extra few zeros) gets a message before the run, rather
!> than a failed allocation or a run of days. doc/scenes.md lists them.
module greenconv_scene_limits
    use greenconv_core_kinds, only: dp
    use greenconv_conv_builder, only: max_kernel_values
    use greenconv_conv_methods, only: cost_model, method_cost
    implicit none
    private

    public :: max_random_modes, max_freq_lines, max_lsce_modes, max_road_terms, max_contact_points
    public :: max_spectrum_values
    !> The cap on a sampled kernel and its estimate live with the builder, which applies them
    !> at every door (C, Fortran, F77); scenes check them when read.
    public :: max_kernel_values
    public :: work_rate, projected_run, smaller_step

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

    !> Multiply-adds per second [1/s] that `--check` assumes to turn a run's projected work
    !> into seconds: direct's inner sum measured at 3.1e9 to 5.7e9 per second on this 2-core
    !> machine (one core, gfortran -O2); the other methods' factors (their registry rows'
    !> `cost_model`) are fitted to the shipped scenes' CPU times, doc/scenes.md gives the ratios
    !> of projected to measured time.
    real(dp), parameter :: work_rate = 3.0e9_dp
    !> Work of a step whatever its sizes (the contact law, the road, the block's bookkeeping).
    real(dp), parameter :: step_work = 200.0_dp

contains

    !> What a contact run of one method is projected to take, from its sizes and the cost
    !> coefficients of its registry row (greenconv_conv_methods's `cost_model`): the work
    !> [multiply-adds] of its steps and the memory [bytes] it holds (kernel, modal states and
    !> shapes, the instantaneous matrix of an implicit multi-point step). A method that picks
    !> another (`auto`) is projected as the dearer of those it chooses between.
    pure recursive subroutine projected_run(method, n_c, n_m, n_terms, n_g, n_steps, work, bytes)
        !> Method name (lower case).
        character(len=*), intent(in) :: method
        !> Number of contact points N_c.
        integer, intent(in) :: n_c
        !> Number of modes N_m (a bound for a model identified at the run).
        integer, intent(in) :: n_m
        !> Modal terms the recursion steps at each point: N_m, or N_m*N_c for a Green's
        !> matrix, whose every pair of points has its own residues.
        integer, intent(in) :: n_terms
        !> Samples of the kernel N_g (at most N_t).
        real(dp), intent(in) :: n_g
        !> Number of steps N_t.
        integer, intent(in) :: n_steps
        !> Multiply-adds of the run.
        real(dp), intent(out) :: work
        !> Memory [bytes] the run holds.
        real(dp), intent(out) :: bytes

        type(cost_model) :: cost
        real(dp) :: c, m, terms, g, t, other_work, other_bytes
        integer :: i

        cost = method_cost(method)
        if (any(len_trim(cost%dearer_of) > 0)) then
            work = 0.0_dp
            bytes = 0.0_dp
            do i = 1, size(cost%dearer_of)
                if (len_trim(cost%dearer_of(i)) == 0) cycle
                call projected_run(trim(cost%dearer_of(i)), n_c, n_m, n_terms, n_g, n_steps, other_work, other_bytes)
                work = max(work, other_work)
                bytes = max(bytes, other_bytes)
            end do
            return
        end if
        c = real(max(n_c, 1), dp)
        m = real(max(n_m, 1), dp)
        terms = real(max(n_terms, 1), dp)
        g = max(n_g, 1.0_dp)
        t = real(max(n_steps, 0), dp)
        work = t*(c*c*g*cost%work_pair_kernel + c*c*cost%work_pair_fft*log(2.0_dp*g)/log(2.0_dp) &
                  + c*terms*cost%work_point_term + c*m*cost%work_point_mode + step_work)
        bytes = c*c*g*cost%bytes_pair_kernel + c*c*cost%bytes_pair + c*g*cost%bytes_point_kernel &
                + terms*cost%bytes_term + c*terms*cost%bytes_point_term
        if (n_c > 1) bytes = bytes + c*c*cost%bytes_pair_implicit
    end subroutine projected_run

    !> The time step [s] at which a method of order p in dt brings a time-step error
    !> `step_part` measured at `dt` to half the accuracy asked: dt*(accuracy/(2*step_part))^(1/p).
    pure real(dp) function smaller_step(dt, step_part, accuracy, order)
        !> The time step of the run [s].
        real(dp), intent(in) :: dt
        !> Its time-step error [-], > 0.
        real(dp), intent(in) :: step_part
        !> The accuracy asked [-], > 0.
        real(dp), intent(in) :: accuracy
        !> Order of the method in dt (1 or 2).
        integer, intent(in) :: order

        smaller_step = dt*min(1.0_dp, 0.5_dp*accuracy/max(step_part, tiny(1.0_dp)))**(1.0_dp/order)
    end function smaller_step

end module greenconv_scene_limits
