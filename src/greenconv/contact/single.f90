!> Unilateral contact between a linear structure and a road, stepped as in eqs. (20)-(24).
!>
!> Sign convention (SI units): the body's displacement u [m] and the road height u_r [m]
!> point up; u is measured from the static equilibrium under the preload F0 [N]. The
!> contact spring's compression is delta = delta0 + u_r - u, with delta0 = (F0/k_c)^(1/p)
!> its static compression, so delta plays the part of Delta x in eq. (21) with l0 = delta0.
!> The contact force (up, on the body) is F = k_c*delta^p for delta > 0 and F = 0 otherwise
!> (eq. 23: Hertz, p = 3/2; p = 1 is a linear spring). The structure is loaded by F - F0.
!>
!> Each step n the convolver gives the history displacement u_h(n) from the forces of steps
!> 0..n-1 (eq. 20 or 24); the step's own force reaches the body through the instant weight
!> w0 = conv%instant_weight() [m/N], so that three relations hold at t_n:
!>
!>     u = u_h + w0*(F - F0),   delta = delta0 + u_r - u,   F = law(delta).
!>
!> Two schemes close them (`contact_options%scheme`):
!>
!> - `explicit`, the paper's and the default: the compression is the one the history alone
!>   gives, delta = delta0 + u_r - u_h, and w0*(F - F0) is added to u afterwards only.
!> - `implicit`: the three relations are solved together. With b = delta0 + u_r - u_h + w0*F0,
!>   the compression the spring would have if this step's force were zero, delta is the root
!>   of r(delta) = delta + w0*k_c*max(delta, 0)^p - b. For w0 >= 0, r increases strictly, so
!>   the root is unique: delta = b and F = 0 exactly when b <= 0; otherwise delta lies in
!>   (0, b], where r(0) = -b < 0 <= r(b), and a safeguarded Newton iteration finds it: each
!>   residual narrows the bracket, and a Newton step that leaves the bracket or shrinks by
!>   less than half is replaced by bisection. This copes with p < 1, whose slope
!>   1 + w0*k_c*p*delta^(p-1) is infinite at delta = 0. The iteration stops when
!>   |r| <= tolerance*max(b, delta0). When w0 = 0 (`direct` on a structure with g(0) = 0,
!>   `recursive`, `paper`) the root is delta = b and the step is the explicit one, bit for bit.
!>
!> Stability. Near the static compression the spring has the tangent stiffness
!> k_c' = p*k_c*delta0^(p-1) = p*F0/delta0 [N/m], and a body of mass M on it the contact
!> frequency omega_c = sqrt(k_c'/M) [rad/s]. Over a few steps a structure is a free mass
!> (g(t) = t/M for t << 1/omega_0), and on a linear spring the explicit step becomes the
!> central difference scheme y_{n+1} - 2*y_n + y_{n-1} = -(omega_c*dt)^2*y_n for the history
!> displacement y = u_h (the rectangle rule, and the first-order hold of `exact` alike). Its
!> amplification factors solve rho^2 - (2 - (omega_c*dt)^2)*rho + 1 = 0: both have modulus 1
!> while omega_c*dt <= 2, and past it one is below -1 (-7.9 at omega_c*dt = sqrt(10)), so any
!> perturbation is multiplied by it at every step in contact and the run blows up within tens
!> of steps. The first-order hold of `exact` has w0 = dt^2/(6M) for a free mass, and the
!> implicit step then is Newmark's linear acceleration method: (omega_c*dt)^2 turns into
!> a/(1 + a/6), a = (omega_c*dt)^2, stable up to omega_c*dt = 2*sqrt(3) = 3.46 only, with a
!> factor tending to -(2 + sqrt(3)) = -3.73 beyond. So the implicit step widens the stable
!> range by sqrt(3) and makes the discrete static balance exact; it is not unconditionally
!> stable. Impacts, the contact closing and opening within a few steps, pump energy in near
!> either edge (the implicit step fails at omega_c*dt = 3.16 on a body bouncing on the road);
!> bench/bench_contact_stability_mod.f90 maps both schemes.
!>
!> A run that diverges is stopped (`contact_options%divergence_bound`): the response keeps
!> the steps computed before, and never holds a NaN or an infinity.
!>
!> Long runs. `run_contact` takes the whole road and returns the whole history. A run too long
!> to hold is streamed instead: `start_contact` resets the convolver into a `contact_state`,
!> and each `contact_block` continues it over the next block of road heights, returning that
!> block's histories (times t_n with the run's own step index n). The state carries what one
!> step hands the next (the step index and the implicit step's first guess), so the blocks of
!> a run put together equal `run_contact` on the whole road bit for bit.
module greenconv_contact_single
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error, stat_input, stat_numerical
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_conv_convolver, only: convolver
    use greenconv_contact_law, only: contact_law
    use greenconv_contact_rows, only: keep_first, keep_all
    implicit none
    private

    !> The contact law, greenconv_contact_law's, named here too for the callers that take it from this module.
    public :: contact_law
    public :: contact_response, contact_options, run_contact
    public :: contact_state, start_contact, contact_block, copy_histories

    !> Time histories of a contact run, sampled at t_n = n*dt, n = 0..N-1, where N is the
    !> number of road samples, or fewer when the run was stopped by a fault.
    type :: contact_response
        !> Times t_n [s].
        real(dp), allocatable :: time(:)
        !> Road height u_r(t_n) [m].
        real(dp), allocatable :: road(:)
        !> Body displacement u(t_n) [m] from static equilibrium.
        real(dp), allocatable :: displacement(:)
        !> Contact force F(t_n) [N], >= 0.
        real(dp), allocatable :: force(:)
        !> Compression delta(t_n) [m] of the contact spring (negative: no contact).
        real(dp), allocatable :: compression(:)
    end type contact_response

    !> How `run_contact` steps and when it gives up; the defaults give the paper's scheme.
    type :: contact_options
        !> `'explicit'`: the force from the history displacement alone (the paper's scheme).
        !> `'implicit'`: the force, compression and displacement of each step solved together
        !> (needs w0 >= 0; gains stability and accuracy only with w0 > 0, as for `exact`).
        character(len=16) :: scheme = 'explicit'
        !> Largest |u| [m] accepted; a larger, infinite or NaN u stops the run as divergent.
        !> The default, 0.1 m, is a hundred times the millimetres a tyre, wheel or rail moves at
        !> its contact point, and far below overflow. A run whose unresolved impacts pump energy
        !> in without growing exponentially (the implicit step at omega_c*dt near 3 on the SDOF
        !> scene) reaches some 0.6 m; a bound of 1 m would let it through.
        real(dp) :: divergence_bound = 0.1_dp
        !> Implicit step: stop when |r(delta)| <= tolerance*max(b, delta0), relative to the
        !> compression scale (dimensionless, > 0; 1e-12 is a few thousand round-offs).
        real(dp) :: tolerance = 1.0e-12_dp
        !> Implicit step: most Newton or bisection iterations per step (>= 1). Bisection alone
        !> needs about 40 to reach the default tolerance; Newton typically 2 to 6.
        integer :: max_iterations = 100
    end type contact_options

    !> A contact run between two blocks of a streamed run (`start_contact`, `contact_block`).
    type :: contact_state
        !> The contact law.
        type(contact_law) :: law
        !> Scheme, divergence bound and Newton settings.
        type(contact_options) :: settings
        !> Static preload F0 [N].
        real(dp) :: preload = 0.0_dp
        !> Static compression delta0 = law%compression(F0) [m].
        real(dp) :: delta0 = 0.0_dp
        !> The convolver's instant weight w0 [m/N].
        real(dp) :: w0 = 0.0_dp
        !> Compression of the last step done [m] (delta0 before step 0): the first guess of
        !> the next implicit step.
        real(dp) :: delta = 0.0_dp
        !> Index n of the next step (the number of steps done), 64 bits for runs past 2^31 steps.
        integer(int64) :: step = 0
    end type contact_state

contains

    !> Run the contact loop over size(road) steps with any convolver.
    !>
    !> The convolver is reset first; it starts from rest (no force history), which is the
    !> static equilibrium under the preload. Without `options` the step is the paper's
    !> explicit one. A fault (bad options, an implicit step that does not converge, a
    !> divergent run) ends the run: the response then holds the steps done before it (none
    !> for bad options) and `error` says what happened. When `error` is absent a fault stops
    !> the program with the message (`error stop`, as stdlib does): pass `error` to handle it.
    subroutine run_contact(conv, law, road, preload, response, options, error)
        !> The convolution method: history before each step, load pushed after it.
        class(convolver), intent(inout) :: conv
        !> The contact law.
        type(contact_law), intent(in) :: law
        !> Road heights u_r(t_n) [m], n = 0..N_t-1.
        real(dp), intent(in) :: road(0:)
        !> Static preload F0 [N] pressing the body onto the road, >= 0.
        real(dp), intent(in) :: preload
        !> Histories of the run, shortened to the steps done when a fault stopped it.
        type(contact_response), intent(out) :: response
        !> Scheme, divergence bound and Newton settings; the defaults when absent.
        type(contact_options), intent(in), optional :: options
        !> Set on a fault: `stat_input` for bad options, `stat_numerical` for divergence or
        !> an implicit step that did not converge, with the step, time and values in the message.
        !> Absent: a fault stops the program with that message.
        type(error_type), allocatable, intent(out), optional :: error

        type(contact_state) :: state
        type(error_type), allocatable :: fault

        call start_contact(conv, law, preload, state, fault, options)
        if (allocated(fault)) then
            call keep_rows(response, 0)
        else
            call contact_block(conv, state, road, response, fault)
        end if
        if (.not. allocated(fault)) return
        if (.not. present(error)) error stop fault%message
        call move_alloc(fault, error)
    end subroutine run_contact

    !> Copy a run's histories into arrays as long as the run was asked to be: the steps done
    !> first, then zero (0 m, 0 N, 0 m) for every step a fault left undone, so that a caller's
    !> fixed-size arrays never keep stale values and nothing past the response is read.
    subroutine copy_histories(response, displacement, force, compression)
        !> The run, possibly shortened by a fault (histories indexed from 0).
        type(contact_response), intent(in) :: response
        !> Body displacements u(t_n) [m]; zero after the steps done.
        real(dp), intent(out) :: displacement(:)
        !> Contact forces F(t_n) [N]; zero after the steps done.
        real(dp), intent(out) :: force(:)
        !> Compressions delta(t_n) [m]; zero after the steps done.
        real(dp), intent(out) :: compression(:)

        integer :: n_done

        displacement(:) = 0.0_dp
        force(:) = 0.0_dp
        compression(:) = 0.0_dp
        if (.not. allocated(response%displacement)) return
        n_done = min(size(response%displacement), size(displacement), size(force), size(compression))
        displacement(1:n_done) = response%displacement(0:n_done - 1)
        force(1:n_done) = response%force(0:n_done - 1)
        compression(1:n_done) = response%compression(0:n_done - 1)
    end subroutine copy_histories

    !> Start a streamed contact run: check the options, reset the convolver (rest, the static
    !> equilibrium under the preload) and set `state` at step 0. Then call `contact_block`
    !> once per block of road heights.
    subroutine start_contact(conv, law, preload, state, error, options)
        !> The convolution method; reset here.
        class(convolver), intent(inout) :: conv
        !> The contact law.
        type(contact_law), intent(in) :: law
        !> Static preload F0 [N] pressing the body onto the road, >= 0.
        real(dp), intent(in) :: preload
        !> The run at step 0.
        type(contact_state), intent(out) :: state
        !> Set (`stat_input`) when the options are unusable with this convolver.
        type(error_type), allocatable, intent(out) :: error
        !> Scheme, divergence bound and Newton settings; the defaults when absent.
        type(contact_options), intent(in), optional :: options

        if (present(options)) state%settings = options
        call check_options(state%settings, conv%instant_weight(), error)
        if (allocated(error)) return
        call conv%reset()
        state%law = law
        state%preload = preload
        state%delta0 = law%compression(preload)
        state%w0 = conv%instant_weight()
        state%delta = state%delta0
        state%step = 0
    end subroutine start_contact

    !> Continue a contact run over the next size(road) steps, n = state%step onwards.
    !>
    !> `response` gets this block's histories, index j for step n = state%step + j (times
    !> t_n = n*dt of the whole run), shortened to the steps done when a fault stops the run;
    !> `error` then names the step (`stat_numerical`) and the run must not be continued.
    subroutine contact_block(conv, state, road, response, error)
        !> The convolver, as the previous block (or `start_contact`) left it.
        class(convolver), intent(inout) :: conv
        !> The run; advanced by the steps done.
        type(contact_state), intent(inout) :: state
        !> Road heights u_r(t_n) [m] of this block's steps.
        real(dp), intent(in) :: road(0:)
        !> Histories of this block's steps.
        type(contact_response), intent(out) :: response
        !> Set on a numerical fault (divergence, an implicit step that did not converge).
        type(error_type), allocatable, intent(out) :: error

        integer :: n_done

        call contact_loop(conv, state, road, response, n_done, error)
        state%step = state%step + n_done
        call keep_rows(response, n_done)
    end subroutine contact_block

    !> The options are usable with an instant weight w0 [m/N].
    subroutine check_options(settings, w0, error)
        type(contact_options), intent(in) :: settings
        real(dp), intent(in) :: w0
        type(error_type), allocatable, intent(out) :: error

        if (settings%scheme /= 'explicit' .and. settings%scheme /= 'implicit') then
            call fatal_error(error, "contact_options%scheme: expected 'explicit' or 'implicit', found '" &
                             //trim(settings%scheme)//"'", stat_input)
        else if (.not. (settings%divergence_bound > 0.0_dp)) then
            call fatal_error(error, 'contact_options%divergence_bound: expected a bound > 0 m, found ' &
                             //sci_text(settings%divergence_bound), stat_input)
        else if (.not. (settings%tolerance > 0.0_dp)) then
            call fatal_error(error, 'contact_options%tolerance: expected a tolerance > 0, found ' &
                             //sci_text(settings%tolerance), stat_input)
        else if (settings%max_iterations < 1) then
            call fatal_error(error, 'contact_options%max_iterations: expected at least 1, found ' &
                             //int_text(settings%max_iterations), stat_input)
        else if (settings%scheme == 'implicit' .and. .not. (w0 >= 0.0_dp)) then
            call fatal_error(error, 'implicit contact step: the convolver''s instant weight w0 = '//sci_text(w0) &
                             //' m/N must be >= 0 for the step to have a unique solution', stat_input)
        end if
    end subroutine check_options

    !> Step the run over size(road) steps from state%step; n_done is the number of steps of
    !> this block completed (all of them unless a fault).
    subroutine contact_loop(conv, state, road, response, n_done, fault)
        class(convolver), intent(inout) :: conv
        type(contact_state), intent(inout) :: state
        real(dp), intent(in) :: road(0:)
        type(contact_response), intent(inout) :: response
        integer, intent(out) :: n_done
        type(error_type), allocatable, intent(out) :: fault

        real(dp) :: u_h, delta, force, u, residual
        logical :: implicit, converged
        integer :: j, n_t
        integer(int64) :: n

        n_t = size(road)
        allocate (response%time(0:n_t - 1), response%road(0:n_t - 1), response%displacement(0:n_t - 1), &
                  response%force(0:n_t - 1), response%compression(0:n_t - 1))
        implicit = state%settings%scheme == 'implicit'
        associate (law => state%law, settings => state%settings, delta0 => state%delta0, w0 => state%w0, &
                   preload => state%preload)
            delta = state%delta
            do j = 0, n_t - 1
                n_done = j
                n = state%step + j
                u_h = conv%history()
                if (implicit) then
                    call implicit_compression(law, delta0 + road(j) - u_h + w0*preload, w0, delta0, settings, &
                                              delta, residual, converged)
                    if (.not. converged) then
                        if (ieee_is_finite(road(j))) then
                            call fatal_error(fault, convergence_message(n, conv%dt, residual, settings), stat_numerical)
                        else
                            call fatal_error(fault, road_message(n, conv%dt), stat_numerical)
                        end if
                        return
                    end if
                else
                    delta = delta0 + road(j) - u_h
                end if
                force = law%force(delta)
                u = u_h + w0*(force - preload)
                if (.not. (abs(u) <= settings%divergence_bound .and. ieee_is_finite(force) &
                           .and. ieee_is_finite(delta))) then
                    if (ieee_is_finite(road(j))) then
                        call fatal_error(fault, divergence_message(n, conv%dt, u, settings, law%tangent(delta0), w0), &
                                         stat_numerical)
                    else
                        call fatal_error(fault, road_message(n, conv%dt), stat_numerical)
                    end if
                    return
                end if
                call conv%push(force - preload)
                state%delta = delta
                response%time(j) = n*conv%dt
                response%road(j) = road(j)
                response%displacement(j) = u
                response%force(j) = force
                response%compression(j) = delta
            end do
        end associate
        n_done = n_t
    end subroutine contact_loop

    !> One line on a road height that is not a finite number at step n.
    pure function road_message(n, dt) result(message)
        integer(int64), intent(in) :: n
        real(dp), intent(in) :: dt
        character(len=:), allocatable :: message

        message = 'contact run stopped at step '//int_text(n)//' (t = '//sci_text(n*dt)//' s): the road height ' &
                  //'u_r is not a finite number (NaN or infinite); steps before it are kept. Check the road data ' &
                  //'of that step'
    end function road_message

    !> One line on an implicit step n that did not converge: where, and the residual.
    pure function convergence_message(n, dt, residual, settings) result(message)
        integer(int64), intent(in) :: n
        real(dp), intent(in) :: dt, residual
        type(contact_options), intent(in) :: settings
        character(len=:), allocatable :: message

        message = 'implicit contact step did not converge at step '//int_text(n)//' (t = '//sci_text(n*dt) &
                  //' s): residual |r| = '//sci_text(abs(residual))//' m after ' &
                  //int_text(settings%max_iterations)//' iterations (tolerance '//sci_text(settings%tolerance) &
                  //' of the compression scale)'
    end function convergence_message

    !> The compression delta [m] solving delta + w0*law(delta) = b, by safeguarded Newton.
    !>
    !> On entry `delta` is a first guess (the previous step's), used when it lies in (0, b).
    !> `scale` is delta0 [m]; the iteration stops at |r| <= tolerance*max(b, delta0).
    pure subroutine implicit_compression(law, b, w0, scale, settings, delta, residual, converged)
        type(contact_law), intent(in) :: law
        real(dp), intent(in) :: b, w0, scale
        type(contact_options), intent(in) :: settings
        real(dp), intent(inout) :: delta
        real(dp), intent(out) :: residual
        logical, intent(out) :: converged

        real(dp) :: lower, upper, step, step_before, newton, target
        integer :: iteration

        residual = 0.0_dp
        converged = .true.
        if (b <= 0.0_dp .or. .not. (w0 > 0.0_dp)) then
            delta = b
            return
        end if
        target = settings%tolerance*max(b, scale)
        lower = 0.0_dp
        upper = b
        if (.not. (delta > lower .and. delta < upper)) delta = upper
        step = upper - lower
        step_before = step
        do iteration = 1, settings%max_iterations
            residual = delta + w0*law%force(delta) - b
            converged = abs(residual) <= target
            if (converged) return
            if (residual < 0.0_dp) then
                lower = delta
            else
                upper = delta
            end if
            newton = residual/(1.0_dp + w0*law%tangent(delta))
            if (delta - newton > lower .and. delta - newton < upper .and. abs(newton) <= 0.5_dp*abs(step_before)) then
                step_before = step
                step = newton
            else
                step_before = step
                step = delta - 0.5_dp*(lower + upper)
            end if
            delta = delta - step
        end do
        residual = delta + w0*law%force(delta) - b
        converged = abs(residual) <= target
    end subroutine implicit_compression

    !> One line on a divergent run at step n: where, how large, and what to change.
    pure function divergence_message(n, dt, u, settings, stiffness, w0) result(message)
        integer(int64), intent(in) :: n
        real(dp), intent(in) :: dt, u, stiffness, w0
        type(contact_options), intent(in) :: settings
        character(len=:), allocatable :: message

        character(len=:), allocatable :: advice

        message = 'contact run diverged at step '//int_text(n)//' (t = '//sci_text(n*dt)//' s): '
        if (ieee_is_finite(u)) then
            message = message//'|u| = '//sci_text(abs(u))//' m exceeds the divergence bound ' &
                      //sci_text(settings%divergence_bound)//' m'
        else
            message = message//'u, F or delta is not finite'
        end if
        if (n > 0) then
            message = message//'; steps 0 to '//int_text(n - 1)//' are kept. '
        else
            message = message//'; no step is kept. '
        end if
        message = message//'The contact frequency is omega_c = sqrt(k_c''/M), k_c'' = p*k_c*delta0^(p-1) = ' &
                  //sci_text(stiffness)//' N/m: '
        if (settings%scheme == 'implicit' .and. w0 > 0.0_dp) then
            advice = 'the implicit step with w0 > 0 is stable up to omega_c*dt of about 2*sqrt(3) = 3.46 ' &
                     //'(first-order hold, exact): reduce dt below ~3.46/omega_c'
        else
            advice = 'the explicit step is stable only for omega_c*dt < 2: reduce dt below ~2/omega_c ' &
                     //'or use scheme = ''implicit'' with an engine whose w0 > 0 (exact)'
        end if
        message = message//advice
    end function divergence_message

    !> Shorten the histories to their first n_done steps, keeping the lower bound 0
    !> (histories never allocated get n_done = 0 rows).
    subroutine keep_rows(response, n_done)
        type(contact_response), intent(inout) :: response
        integer, intent(in) :: n_done

        call keep_all(n_done, response%time, response%road, response%displacement, response%force)
        call keep_first(response%compression, n_done)
    end subroutine keep_rows

end module greenconv_contact_single
