!> Unilateral contact of a linear structure with a road at N_c points, all forces of a step
!> solved together.
!>
!> Conventions of greenconv_contact_single, per point i (SI units): displacement u_i and road height
!> u_r,i point up, u_i from the static equilibrium under the preloads F0_i; compression
!> delta_i = delta0_i + u_r,i - u_i with delta0_i = law_i%compression(F0_i); force
!> F_i = law_i%force(delta_i), k_c,i*delta_i^p_i in compression and exactly zero otherwise;
!> the structure is loaded by F - F0.
!>
!> Each step n, the multi-point convolver (greenconv_conv_multipoint) gives the history
!> displacements u_h(n); with the free compression a_i = delta0_i + u_r,i(t_n) - u_h,i(n)
!> the step's compressions solve
!>
!>     R_i(delta) = delta_i - a_i + sum_j W0_ij*(F_j(delta_j) - F0_j) = 0,   i = 1..N_c,
!>
!> then F - F0 is pushed and u_i(t_n) = u_h,i(n) + sum_j W0_ij*(F_j - F0_j). With W0 = 0 (the
!> paper's explicit scheme, eqs. 20-23 at every point) the solution is delta = a, evaluated
!> directly. Otherwise a semismooth Newton method on the compressions: the Jacobian
!> I + W0*D, D = diag(dF_j/ddelta_j), has D_jj = 0 off the active set {delta_j > 0}, which is
!> updated at every iterate; the step is solved by LAPACK (dgesv) and damped by halving
!> until the Euclidean norm of R decreases (Armijo). Writing the unknowns as compressions
!> makes the unilateral condition exact: F_j = 0 wherever delta_j <= 0. For a compliance
!> matrix W0 that is symmetric positive semi-definite and monotone laws, I + W0*D has
!> eigenvalues >= 1, so every Newton system is solvable.
!>
!> The step is greenconv_contact_step's, the one single-point contact takes too (one point is
!> solved there by its scalar Newton iteration instead); here are the loop that feeds it the
!> histories of a multi-point convolver, and the settings multi-point callers know.
!>
!> A run too long to hold is streamed like greenconv_contact_single's: `start_multi_contact`, then
!> `multi_contact_block` per block of road heights; the state carries the step index and the
!> compressions that start the next step's Newton iteration, so the blocks put together equal
!> `run_multi_contact` on the whole road bit for bit.
module greenconv_contact_multi
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_text, only: int_text
    use greenconv_core_error, only: error_type, fatal_error, stat_input
    use greenconv_contact_law, only: contact_law
    use greenconv_contact_step, only: contact_options, multi_contact_state => contact_state, start_state, &
                                      step_contact
    use greenconv_contact_rows, only: keep_first, keep_all
    use greenconv_conv_multipoint, only: multipoint_convolver
    implicit none
    private

    public :: newton_options, multi_contact_response, run_multi_contact, multi_contact_step
    !> The state of a run between two blocks: greenconv_contact_step's `contact_state`, by the
    !> name multi-point callers know.
    public :: multi_contact_state
    public :: start_multi_contact, multi_contact_block, as_contact_options

    !> Settings of the per-step nonlinear solve and of the divergence guard, with the defaults
    !> of multi-point contact (the C and Fortran 77 multi-point doors document them). A run
    !> takes them as the `implicit` scheme of `contact_options` (`as_contact_options`), which
    !> with W0 = 0 is the paper's explicit step.
    type :: newton_options
        !> Convergence: max_i |R_i| <= tolerance*scale, scale = the largest of |a_i|, |delta_i|,
        !> delta0_i and |sum_j W0_ij*(F_j - F0_j)| (dimensionless).
        real(dp) :: tolerance = 1.0e-12_dp
        !> Largest number of Newton iterations per step.
        integer :: max_iterations = 50
        !> Divergence guard: |u_i| above this [m] (or a NaN) stops the run with an error.
        real(dp) :: max_displacement = 1.0_dp
    end type newton_options

    !> Histories of a multi-point run at t_n = n*dt, n = 0..N-1 (N = N_t, or the steps done
    !> before an error); per-point arrays are (0:N-1, N_c).
    type :: multi_contact_response
        !> Times t_n [s].
        real(dp), allocatable :: time(:)
        !> Road heights u_r,i(t_n) [m].
        real(dp), allocatable :: road(:, :)
        !> Displacements u_i(t_n) [m] from static equilibrium.
        real(dp), allocatable :: displacement(:, :)
        !> Contact forces F_i(t_n) [N], >= 0.
        real(dp), allocatable :: force(:, :)
        !> Compressions delta_i(t_n) [m] (negative: no contact at that point).
        real(dp), allocatable :: compression(:, :)
        !> Total contact force sum_i F_i(t_n) [N].
        real(dp), allocatable :: total_force(:)
        !> Newton iterations of each step (0 for the explicit scheme).
        integer, allocatable :: iterations(:)
    end type multi_contact_response

contains

    !> Run the multi-point contact loop over size(road, 1) steps.
    !>
    !> The convolver is reset first and starts from rest (static equilibrium under the
    !> preloads). On a Newton failure or divergence, `error` names the step, and `response`
    !> keeps the steps completed before it.
    subroutine run_multi_contact(conv, laws, road, preload, response, error, options)
        !> The Green's matrix of the N_c points.
        class(multipoint_convolver), intent(inout) :: conv
        !> Contact law of each point (N_c).
        class(contact_law), intent(in) :: laws(:)
        !> Road heights road(n, i) = u_r,i(t_n) [m], n = 0..N_t-1, i = 1..N_c.
        real(dp), intent(in) :: road(0:, :)
        !> Static preloads F0_i [N], >= 0 (N_c).
        real(dp), intent(in) :: preload(:)
        !> Histories of the run.
        type(multi_contact_response), intent(out) :: response
        !> Set on inconsistent sizes, a step whose forces do not converge, or divergence.
        type(error_type), allocatable, intent(out) :: error
        !> Newton and divergence settings; defaults when absent.
        type(newton_options), intent(in), optional :: options

        type(multi_contact_state) :: state

        call start_multi_contact(conv, laws, preload, state, error, options)
        if (.not. allocated(error)) call multi_contact_block(conv, state, road, response, error)
    end subroutine run_multi_contact

    !> Start a streamed multi-point run: check the sizes and the settings, reset the convolver
    !> (rest, the static equilibrium under the preloads) and set `state` at step 0. Then call
    !> `multi_contact_block` once per block of road heights.
    !>
    !> The settings are the multi-point ones (`options`, the implicit scheme), or any
    !> `contact_options` (`settings`): a single-point run's scheme too, its structure's convolver
    !> wrapped as the 1 x 1 case (greenconv_conv_point_matrix), so that one loop runs both.
    subroutine start_multi_contact(conv, laws, preload, state, error, options, settings)
        !> The Green's matrix of the N_c points; reset here.
        class(multipoint_convolver), intent(inout) :: conv
        !> Contact law of each point (N_c).
        class(contact_law), intent(in) :: laws(:)
        !> Static preloads F0_i [N], >= 0 (N_c).
        real(dp), intent(in) :: preload(:)
        !> The run at step 0.
        type(multi_contact_state), intent(out) :: state
        !> Set (`stat_input`) when the laws, preloads and Green's matrix disagree in size, or
        !> the settings are unusable with this W0.
        type(error_type), allocatable, intent(out) :: error
        !> Newton and divergence settings; the defaults when both are absent.
        type(newton_options), intent(in), optional :: options
        !> Scheme, divergence bound and Newton settings, in place of `options`.
        type(contact_options), intent(in), optional :: settings

        type(contact_options) :: chosen

        if (conv%n_points() /= size(laws) .or. size(preload) /= size(laws)) then
            call fatal_error(error, 'multi-point contact: the Green''s matrix has '//int_text(conv%n_points()) &
                             //' points, the laws '//int_text(size(laws))//' and the preloads ' &
                             //int_text(size(preload)), stat_input)
            return
        end if
        chosen = as_contact_options(newton_options())
        if (present(options)) chosen = as_contact_options(options)
        if (present(settings)) chosen = settings
        call start_state(laws, preload, conv%weight0, conv%dt, chosen, state, error)
        if (allocated(error)) return
        call conv%reset()
    end subroutine start_multi_contact

    !> Continue a multi-point run over the next size(road, 1) steps, n = state%step onwards.
    !>
    !> `response` gets this block's histories, index j for step n = state%step + j (times
    !> t_n = n*dt of the whole run), shortened to the steps done when a fault stops the run;
    !> `error` then names the step and the run must not be continued.
    subroutine multi_contact_block(conv, state, road, response, error)
        !> The Green's matrix, as the previous block (or `start_multi_contact`) left it.
        class(multipoint_convolver), intent(inout) :: conv
        !> The run; advanced by the steps done.
        type(multi_contact_state), intent(inout) :: state
        !> Road heights road(j, i) = u_r,i(t_n) [m] of this block's steps, n = state%step + j.
        real(dp), intent(in) :: road(0:, :)
        !> Histories of this block's steps.
        type(multi_contact_response), intent(out) :: response
        !> Set on a road of the wrong width or a block reaching past the steps a cut kernel covers
        !> (`stat_input`, nothing done), a step whose forces do not converge, or divergence.
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: u_h(size(state%laws))
        integer :: j, n_t

        n_t = size(road, 1)
        if (size(road, 2) /= size(state%laws)) then
            call fatal_error(error, 'multi-point contact: the road has '//int_text(size(road, 2)) &
                             //' columns for '//int_text(size(state%laws))//' points', stat_input)
            call allocate_response(response, 0, size(state%laws))
            return
        end if
        call conv%check_validity(int(n_t, int64), error)
        if (allocated(error)) then
            call allocate_response(response, 0, size(state%laws))
            return
        end if
        call allocate_response(response, n_t, size(state%laws))
        response%time(:) = [((state%step + j)*conv%dt, j=0, n_t - 1)]
        response%road(:, :) = road
        do j = 0, n_t - 1
            call conv%history(u_h)
            call step_contact(state, conv%weight0, u_h, road(j, :), response%force(j, :), &
                              response%displacement(j, :), response%iterations(j), error, conv)
            if (allocated(error)) then
                call keep_all(j, response%time, response%total_force)
                call keep_first(response%iterations, j)
                call keep_all(j, response%road, response%displacement, response%force, response%compression)
                return
            end if
            call conv%push(response%force(j, :) - state%preload)
            response%compression(j, :) = state%delta
            response%total_force(j) = sum(response%force(j, :))
        end do
    end subroutine multi_contact_block

    !> One step of the loop on its own, outside a run's state: history, forces of all points,
    !> push of F - F0 (when the step succeeds). `delta` holds on entry the compressions of the
    !> previous step (the first guess of the Newton iteration) and on return this step's.
    subroutine multi_contact_step(conv, laws, delta0, preload, road, delta, force, displacement, iterations, &
                                  error, options)
        !> The Green's matrix of the N_c points, at step n; advanced to n + 1.
        class(multipoint_convolver), intent(inout) :: conv
        !> Contact law of each point.
        class(contact_law), intent(in) :: laws(:)
        !> Static compressions delta0_i [m].
        real(dp), intent(in) :: delta0(:)
        !> Static preloads F0_i [N].
        real(dp), intent(in) :: preload(:)
        !> Road heights u_r,i(t_n) [m].
        real(dp), intent(in) :: road(:)
        !> Compressions delta_i [m]: previous step's on entry, this step's on return.
        real(dp), intent(inout) :: delta(:)
        !> Contact forces F_i(t_n) [N].
        real(dp), intent(out) :: force(:)
        !> Displacements u_i(t_n) [m].
        real(dp), intent(out) :: displacement(:)
        !> Newton iterations used (0 when W0 = 0).
        integer, intent(out) :: iterations
        !> Set when the options are unusable, the forces do not converge or the step diverges.
        type(error_type), allocatable, intent(out) :: error
        !> Newton settings.
        type(newton_options), intent(in) :: options

        type(multi_contact_state) :: state
        real(dp) :: u_h(size(laws))

        call start_state(laws, preload, conv%weight0, conv%dt, as_contact_options(options), state, error)
        if (allocated(error)) return
        state%delta0(:) = delta0
        state%delta(:) = delta
        state%step = conv%step
        call conv%history(u_h)
        call step_contact(state, conv%weight0, u_h, road, force, displacement, iterations, error, conv)
        delta(:) = state%delta
        if (.not. allocated(error)) call conv%push(force - preload)
    end subroutine multi_contact_step

    !> The contact options of a multi-point run: the implicit scheme with these Newton and
    !> divergence settings.
    pure function as_contact_options(newton) result(options)
        !> The multi-point settings.
        type(newton_options), intent(in) :: newton
        type(contact_options) :: options

        options = contact_options(scheme='implicit', divergence_bound=newton%max_displacement, &
                                  tolerance=newton%tolerance, max_iterations=newton%max_iterations)
    end function as_contact_options

    !> Allocate the histories of n_t steps at n_c points.
    subroutine allocate_response(response, n_t, n_c)
        type(multi_contact_response), intent(inout) :: response
        integer, intent(in) :: n_t, n_c

        allocate (response%time(0:n_t - 1), response%total_force(0:n_t - 1), response%iterations(0:n_t - 1))
        allocate (response%road(0:n_t - 1, n_c), response%displacement(0:n_t - 1, n_c), &
                  response%force(0:n_t - 1, n_c), response%compression(0:n_t - 1, n_c))
    end subroutine allocate_response

end module greenconv_contact_multi
