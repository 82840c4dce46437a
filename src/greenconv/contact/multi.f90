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
!> A run too long to hold is streamed like greenconv_contact_single's: `start_multi_contact`, then
!> `multi_contact_block` per block of road heights; the state carries the step index and the
!> compressions that start the next step's Newton iteration, so the blocks put together equal
!> `run_multi_contact` on the whole road bit for bit.
module greenconv_contact_multi
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use greenconv_core_kinds, only: dp
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_core_error, only: error_type, fatal_error, stat_input, stat_numerical
    use greenconv_ext_lapack, only: solve_linear
    use greenconv_contact_law, only: contact_law
    use greenconv_contact_rows, only: keep_first, keep_all
    use greenconv_conv_multipoint, only: multipoint_convolver
    implicit none
    private

    public :: newton_options, multi_contact_response, run_multi_contact, multi_contact_step
    public :: multi_contact_state, start_multi_contact, multi_contact_block

    !> Settings of the per-step nonlinear solve and of the divergence guard.
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

    !> A multi-point contact run between two blocks of a streamed run.
    type :: multi_contact_state
        !> Contact law of each point (N_c).
        type(contact_law), allocatable :: laws(:)
        !> Static preloads F0_i [N] (N_c).
        real(dp), allocatable :: preload(:)
        !> Static compressions delta0_i [m] (N_c).
        real(dp), allocatable :: delta0(:)
        !> Compressions of the last step done [m] (delta0 before step 0): the next step's guess.
        real(dp), allocatable :: delta(:)
        !> Newton and divergence settings.
        type(newton_options) :: settings
        !> Index n of the next step (the number of steps done), 64 bits.
        integer(int64) :: step = 0
    end type multi_contact_state

    !> Most halvings of a Newton step in the line search.
    integer, parameter :: max_halvings = 30

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
        type(contact_law), intent(in) :: laws(:)
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

    !> Start a streamed multi-point run: check the sizes, reset the convolver (rest, the
    !> static equilibrium under the preloads) and set `state` at step 0. Then call
    !> `multi_contact_block` once per block of road heights.
    subroutine start_multi_contact(conv, laws, preload, state, error, options)
        !> The Green's matrix of the N_c points; reset here.
        class(multipoint_convolver), intent(inout) :: conv
        !> Contact law of each point (N_c).
        type(contact_law), intent(in) :: laws(:)
        !> Static preloads F0_i [N], >= 0 (N_c).
        real(dp), intent(in) :: preload(:)
        !> The run at step 0.
        type(multi_contact_state), intent(out) :: state
        !> Set (`stat_input`) when the laws, preloads and Green's matrix disagree in size.
        type(error_type), allocatable, intent(out) :: error
        !> Newton and divergence settings; defaults when absent.
        type(newton_options), intent(in), optional :: options

        if (conv%n_points() /= size(laws) .or. size(preload) /= size(laws)) then
            call fatal_error(error, 'multi-point contact: the Green''s matrix has '//int_text(conv%n_points()) &
                             //' points, the laws '//int_text(size(laws))//' and the preloads ' &
                             //int_text(size(preload)), stat_input)
            return
        end if
        if (present(options)) state%settings = options
        state%laws = laws
        state%preload = preload
        state%delta0 = laws%compression(preload)
        state%delta = state%delta0
        state%step = 0
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
        !> Set on a road of the wrong width, a step whose forces do not converge, or divergence.
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: u(size(state%laws))
        integer :: j, n_t
        integer(int64) :: n

        n_t = size(road, 1)
        if (size(road, 2) /= size(state%laws)) then
            call fatal_error(error, 'multi-point contact: the road has '//int_text(size(road, 2)) &
                             //' columns for '//int_text(size(state%laws))//' points', stat_input)
            call allocate_response(response, 0, size(state%laws))
            return
        end if
        call allocate_response(response, n_t, size(state%laws))
        response%time(:) = [((state%step + j)*conv%dt, j=0, n_t - 1)]
        response%road(:, :) = road
        do j = 0, n_t - 1
            n = state%step + j
            call multi_contact_step(conv, state%laws, state%delta0, state%preload, road(j, :), state%delta, &
                                    response%force(j, :), u, response%iterations(j), error, state%settings)
            if (.not. allocated(error)) call divergence_guard(u, response%force(j, :), state%settings, error)
            if (allocated(error)) then
                error%message = error%message//' at step '//int_text(n)//' (t = '//sci_text(n*conv%dt)//' s)'
                call keep_all(j, response%time, response%total_force)
                call keep_first(response%iterations, j)
                call keep_all(j, response%road, response%displacement, response%force, response%compression)
                state%step = n
                return
            end if
            response%compression(j, :) = state%delta
            response%displacement(j, :) = u
            response%total_force(j) = sum(response%force(j, :))
        end do
        state%step = state%step + n_t
    end subroutine multi_contact_block

    !> One step of the loop: history, forces of all points, push of F - F0.
    !>
    !> `delta` holds on entry the compressions of the previous step (the Newton guess is the
    !> free compression corrected by the previous forces) and on return this step's.
    subroutine multi_contact_step(conv, laws, delta0, preload, road, delta, force, displacement, iterations, &
                                  error, options)
        !> The Green's matrix of the N_c points, at step n; advanced to n + 1.
        class(multipoint_convolver), intent(inout) :: conv
        !> Contact law of each point.
        type(contact_law), intent(in) :: laws(:)
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
        !> Set when the forces do not converge.
        type(error_type), allocatable, intent(out) :: error
        !> Newton settings.
        type(newton_options), intent(in) :: options

        real(dp) :: u_h(size(laws)), free(size(laws))
        logical :: explicit

        explicit = conv%is_explicit()
        call conv%history(u_h)
        free(:) = delta0 + road - u_h
        iterations = 0
        if (explicit) then
            delta(:) = free
            force(:) = laws%force(delta)
        else
            force(:) = laws%force(delta)
            delta(:) = free - matmul(conv%weight0, force - preload)
            call solve_compressions(conv%weight0, laws, preload, delta0, free, options, delta, iterations, error)
            if (allocated(error)) return
            force(:) = laws%force(delta)
        end if
        call conv%push(force - preload)
        displacement(:) = u_h
        if (.not. explicit) displacement(:) = u_h + matmul(conv%weight0, force - preload)
    end subroutine multi_contact_step

    !> Semismooth Newton on R(delta) = delta - a + W0*(F(delta) - F0), damped on |R|_2.
    subroutine solve_compressions(w0, laws, preload, delta0, free, options, delta, iterations, error)
        real(dp), intent(in) :: w0(:, :)
        type(contact_law), intent(in) :: laws(:)
        real(dp), intent(in) :: preload(:), delta0(:), free(:)
        type(newton_options), intent(in) :: options
        real(dp), intent(inout) :: delta(:)
        integer, intent(out) :: iterations
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: r(size(delta)), trial(size(delta)), r_trial(size(delta)), step(size(delta))
        real(dp) :: jacobian(size(delta), size(delta)), alpha, scale
        integer :: j, halvings

        call residual(w0, laws, preload, free, delta, r, scale)
        scale = max(scale, maxval(delta0))
        do iterations = 0, options%max_iterations
            if (maxval(abs(r)) <= options%tolerance*scale) return
            if (iterations == options%max_iterations) exit
            do j = 1, size(delta)
                jacobian(:, j) = w0(:, j)*slope(laws(j), delta(j))
                jacobian(j, j) = jacobian(j, j) + 1.0_dp
            end do
            call solve_linear(jacobian, -r, step, error)
            if (allocated(error)) return
            alpha = 1.0_dp
            do halvings = 0, max_halvings
                trial(:) = delta + alpha*step
                call residual(w0, laws, preload, free, trial, r_trial, scale)
                if (norm2(r_trial) <= (1.0_dp - 1.0e-4_dp*alpha)*norm2(r)) exit
                alpha = alpha/2
            end do
            delta(:) = trial
            r(:) = r_trial
            scale = max(scale, maxval(delta0))
        end do
        call fatal_error(error, 'multi-point contact: Newton did not converge in '//int_text(options%max_iterations) &
                         //' iterations, max |residual| = '//sci_text(maxval(abs(r)))//' m > ' &
                         //sci_text(options%tolerance*scale)//' m at point '//int_text(maxloc(abs(r), 1)), &
                         stat_numerical)
    end subroutine solve_compressions

    !> R = delta - a + W0*(F(delta) - F0) [m], and the size of its terms [m].
    subroutine residual(w0, laws, preload, free, delta, r, scale)
        real(dp), intent(in) :: w0(:, :)
        type(contact_law), intent(in) :: laws(:)
        real(dp), intent(in) :: preload(:), free(:), delta(:)
        real(dp), intent(out) :: r(:), scale

        real(dp) :: load(size(delta)), coupling(size(delta))

        load(:) = laws%force(delta) - preload
        coupling(:) = matmul(w0, load)
        r(:) = delta - free + coupling
        scale = max(maxval(abs(free)), maxval(abs(delta)), maxval(abs(coupling)), tiny(1.0_dp))
    end subroutine residual

    !> dF/ddelta = p*k_c*delta^(p - 1) [N/m] in compression, zero otherwise.
    elemental real(dp) function slope(law, delta)
        type(contact_law), intent(in) :: law
        real(dp), intent(in) :: delta

        slope = 0.0_dp
        if (delta > 0.0_dp) slope = law%tangent(delta)
    end function slope

    !> An error when a displacement exceeds the bound or a value is not finite.
    subroutine divergence_guard(u, force, options, error)
        real(dp), intent(in) :: u(:), force(:)
        type(newton_options), intent(in) :: options
        type(error_type), allocatable, intent(out) :: error

        integer :: i

        do i = 1, size(u)
            if (.not. (ieee_is_finite(u(i)) .and. ieee_is_finite(force(i)))) then
                call fatal_error(error, 'multi-point contact: diverged: displacement or force at point ' &
                                 //int_text(i)//' is not a finite number', stat_numerical)
                return
            end if
            if (abs(u(i)) > options%max_displacement) then
                call fatal_error(error, 'multi-point contact: diverged: |u| = '//sci_text(abs(u(i))) &
                                 //' m at point '//int_text(i)//' exceeds the bound ' &
                                 //sci_text(options%max_displacement)//' m', stat_numerical)
                return
            end if
        end do
    end subroutine divergence_guard

    !> Allocate the histories of n_t steps at n_c points.
    subroutine allocate_response(response, n_t, n_c)
        type(multi_contact_response), intent(inout) :: response
        integer, intent(in) :: n_t, n_c

        allocate (response%time(0:n_t - 1), response%total_force(0:n_t - 1), response%iterations(0:n_t - 1))
        allocate (response%road(0:n_t - 1, n_c), response%displacement(0:n_t - 1, n_c), &
                  response%force(0:n_t - 1, n_c), response%compression(0:n_t - 1, n_c))
    end subroutine allocate_response

end module greenconv_contact_multi
