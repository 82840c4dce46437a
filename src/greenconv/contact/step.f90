!> One step of a contact run at N_c points, single-point contact being the case N_c = 1: the
!> one place where the forces of a step are decided, for greenconv_contact_single and
!> greenconv_contact_multi alike (they only fetch the history from their convolver, call
!> `step_contact`, push the load and record).
!>
!> Conventions (SI units), per point i: the body's displacement u_i and the road height u_r,i
!> point up, u_i from the static equilibrium under the preloads F0_i; the compression is
!> delta_i = delta0_i + u_r,i - u_i, delta0_i = law_i%compression(F0_i); the force
!> F_i = law_i%force(delta_i) (greenconv_contact_law); the structure is loaded by F - F0.
!> The convolver gives the history displacements u_h(n) and the instant compliance W0 [m/N]
!> of the step's own forces, so that at t_n
!>
!>     u = u_h + W0*(F - F0),   delta = a - (u - u_h),   a = delta0 + u_r - u_h,
!>
!> a being the free compression, the one the springs would have if the step's loads were zero.
!> Two schemes close these relations (`contact_options%scheme`):
!>
!> - `explicit` (the paper's, eqs. 20-23): delta = a; W0*(F - F0) enters u afterwards only.
!> - `implicit`: delta solves R(delta) = delta - a + W0*(F(delta) - F0) = 0. With W0 = 0 this is
!>   delta = a, the explicit step itself. For one point the equation is scalar,
!>   delta + w0*F(delta) = a + w0*F0, and is solved exactly by a safeguarded Newton iteration
!>   (greenconv_contact_single tells why it converges: the residual increases strictly for
!>   w0 >= 0, and the root is bracketed in (0, b]). For N_c > 1 a semismooth Newton method on
!>   the compressions (greenconv_contact_multi tells how: active set, Armijo damping), its
!>   linear systems solved in O(N_c*N_m^2) when W0 has the low rank N_m of a modal structure
!>   (greenconv_contact_lowrank_solve), by dgesv otherwise.
!>
!> The load a single-point loop pushes is F - F0, halved at step 0 (`step_load` tells why:
!> second order in dt when a road that is not at its static height at t = 0 switches the loads
!> on at t = 0+); a multi-point convolver halves its first load itself
!> (greenconv_conv_multipoint's `recorded_load`), so the multi-point loop pushes F - F0.
!>
!> Then every point passes the divergence guard - |u_i| at most the bound, F_i and delta_i
!> finite - before the caller pushes the load: a fault leaves the convolver where it was and
!> names the step, its time, the point (when N_c > 1) and what to change.
!>
!> The laws are `class(contact_law)` (greenconv_contact_law), the points' laws one polymorphic
!> array of one dynamic type, and the step calls only their `force`, `compression` and
!> `tangent`. A new law is its module and its row in the registry greenconv_contact_laws;
!> nothing here, in the single- and multi-point loops, the runner, the doors or the tests' ODE
!> reference changes.
module greenconv_contact_step
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error, stat_input, stat_numerical
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_contact_law, only: contact_law
    use greenconv_contact_lowrank_solve, only: lowrank_compliance, factor_compliance, factor_modal_compliance, &
                                               apply_compliance, newton_solve, woodbury_step
    use greenconv_model_point_modes, only: separable_shapes
    use greenconv_conv_multipoint, only: multipoint_convolver
    implicit none
    private

    public :: contact_options, contact_state, start_state, step_contact, step_load

    !> How a contact run steps and when it gives up. The defaults are those of single-point
    !> contact (`run_contact`, `gc_contact_options_init`); multi-point contact has its own
    !> (greenconv_contact_multi's `newton_options`, which converts into this type).
    type :: contact_options
        !> `'explicit'`: the compressions from the history displacements alone (the paper's scheme).
        !> `'implicit'`: forces, compressions and displacements of each step solved together
        !> (needs w0 >= 0 at a single point; gains stability and accuracy only with W0 /= 0, as
        !> for `exact`).
        character(len=16) :: scheme = 'explicit'
        !> Largest |u_i| [m] accepted; a larger, infinite or NaN u stops the run as divergent.
        !> The default, 0.1 m, is a hundred times the millimetres a tyre, wheel or rail moves at
        !> its contact point, and far below overflow. A run whose unresolved impacts pump energy
        !> in without growing exponentially (the implicit step at omega_c*dt near 3 on the SDOF
        !> scene) reaches some 0.6 m; a bound of 1 m would let it through.
        real(dp) :: divergence_bound = 0.1_dp
        !> Implicit step: stop when the residual is at most tolerance times the compression
        !> scale (dimensionless, > 0; 1e-12 is a few thousand round-offs). The scale is
        !> max(b, delta0) at one point, and the largest of |a_i|, |delta_i|, delta0_i and
        !> |(W0*(F - F0))_i| at several.
        real(dp) :: tolerance = 1.0e-12_dp
        !> Implicit step: most Newton (or bisection) iterations per step (>= 1). At one point
        !> bisection alone needs about 40 to reach the default tolerance; Newton typically 2 to 6.
        integer :: max_iterations = 100
    end type contact_options

    !> A contact run at N_c points between two steps: what one step hands the next.
    type :: contact_state
        !> Contact law of each point (N_c).
        class(contact_law), allocatable :: laws(:)
        !> Static preloads F0_i [N] (N_c).
        real(dp), allocatable :: preload(:)
        !> Static compressions delta0_i = law_i%compression(F0_i) [m] (N_c).
        real(dp), allocatable :: delta0(:)
        !> Compressions of the last step done [m] (delta0 before step 0): the first guess of
        !> the next implicit step.
        real(dp), allocatable :: delta(:)
        !> W0*(F(delta) - F0) [m] of the compressions in `delta` when the last step solved them
        !> by the implicit multi-point iteration (`coupling_kept`): the next step's first guess
        !> without a product by W0. Allocated at the first such step and kept.
        real(dp), allocatable :: coupling(:)
        !> Whether `coupling` holds the last step's.
        logical :: coupling_kept = .false.
        !> max_i delta0_i [m], a floor of the implicit iteration's scale.
        real(dp) :: delta0_max = 0.0_dp
        !> Scheme, divergence bound and Newton settings.
        type(contact_options) :: settings
        !> Whether W0 /= 0 (some step's own force reaches the body within the step).
        logical :: coupled = .false.
        !> Time step dt [s] of the convolver, for the times in the messages.
        real(dp) :: dt = 0.0_dp
        !> Index n of the next step (the number of steps done), 64 bits for runs past 2^31 steps.
        integer(int64) :: step = 0
        !> W0 as the implicit multi-point step uses it: factored U*V^T at the first such step
        !> when its rank is below N_c/2 (a modal structure; in the span of the convolver's
        !> separable modes when it offers them), dense otherwise (greenconv_contact_lowrank_solve).
        type(lowrank_compliance) :: compliance
    end type contact_state

    !> Most halvings of a Newton step in the line search of the semismooth method.
    integer, parameter :: max_halvings = 30

contains

    !> A run at step 0: the options checked against W0, the static compressions computed.
    subroutine start_state(laws, preload, weight0, dt, options, state, error)
        !> Contact law of each point (N_c).
        class(contact_law), intent(in) :: laws(:)
        !> Static preloads F0_i [N], >= 0 (N_c).
        real(dp), intent(in) :: preload(:)
        !> The convolver's instant compliance W0 [m/N] (N_c x N_c).
        real(dp), intent(in) :: weight0(:, :)
        !> The convolver's time step dt [s].
        real(dp), intent(in) :: dt
        !> Scheme, divergence bound and Newton settings.
        type(contact_options), intent(in) :: options
        !> The run at step 0.
        type(contact_state), intent(out) :: state
        !> Set (`stat_input`) when the options are unusable with this W0.
        type(error_type), allocatable, intent(out) :: error

        call check_options(options, weight0, error)
        if (allocated(error)) return
        allocate(state%laws, source=laws)
        state%preload = preload
        state%delta0 = laws%compression(preload)
        state%delta = state%delta0
        state%delta0_max = maxval(state%delta0)
        state%settings = options
        state%coupled = .not. (maxval(abs(weight0)) <= 0.0_dp)
        state%dt = dt
        state%step = 0
    end subroutine start_state

    !> Step n = state%step: from the history displacements and road heights, the forces,
    !> compressions (into state%delta) and displacements of the step, state%step advanced.
    !> The caller then pushes force - state%preload. On a fault nothing in `state` that a
    !> later step reads is trusted: the run must end, its steps before n kept.
    subroutine step_contact(state, weight0, u_h, road, force, displacement, iterations, fault, conv)
        !> The run; advanced by one step unless a fault.
        type(contact_state), intent(inout) :: state
        !> The convolver's instant compliance W0 [m/N] (N_c x N_c).
        real(dp), intent(in) :: weight0(:, :)
        !> History displacements u_h,i(n) [m].
        real(dp), intent(in) :: u_h(:)
        !> Road heights u_r,i(t_n) [m].
        real(dp), intent(in) :: road(:)
        !> Contact forces F_i(t_n) [N].
        real(dp), intent(out) :: force(:)
        !> Displacements u_i(t_n) [m].
        real(dp), intent(out) :: displacement(:)
        !> Newton iterations of the step (0 when explicit).
        integer, intent(out) :: iterations
        !> Set (`stat_numerical`) when the step does not converge or the run diverges.
        type(error_type), allocatable, intent(out) :: fault
        !> The convolver whose W0 this is: its own product W0*x serves the implicit step when it
        !> is cheaper than W0's low-rank factors (`fast_instant`), and keeps what the push of the
        !> step's loads can reuse (`apply_instant_kept`).
        class(multipoint_convolver), intent(inout), optional :: conv

        real(dp) :: free(size(u_h)), residual
        integer :: point
        character(len=:), allocatable :: message

        free(:) = state%delta0 + road - u_h
        iterations = 0
        point = 1
        residual = 0.0_dp
        if (state%settings%scheme /= 'implicit') then
            state%delta(:) = free
        else if (size(free) == 1) then
            call implicit_compression(state%laws(1), free(1) + weight0(1, 1)*state%preload(1), weight0(1, 1), &
                                      state%delta0(1), state%settings, state%delta(1), residual, iterations)
        else if (.not. state%coupled) then
            state%delta(:) = free
        else
            call solve_compressions(weight0, state, free, force, displacement, iterations, residual, point, fault, &
                                    conv)
            if (allocated(fault)) then
                if (all(ieee_is_finite(road))) then
                    fault%message = fault%message//' '//where(state, 0)
                else
                    call step_fault(state, road, findloc(ieee_is_finite(road), .false., 1), '', fault)
                end if
                return
            end if
        end if
        if (iterations > state%settings%max_iterations) then
            call convergence_message(state, point, residual, message)
            call step_fault(state, road, point, message, fault)
            return
        end if
        ! the implicit multi-point iteration leaves the forces of its compressions in `force`
        if (.not. (size(u_h) > 1 .and. state%coupled .and. state%settings%scheme == 'implicit')) &
            call law_forces(state%laws, state%delta, force)
        if (size(u_h) == 1) then
            displacement(1) = u_h(1) + weight0(1, 1)*(force(1) - state%preload(1))
        else if (state%coupled .and. state%settings%scheme == 'implicit') then
            ! W0*(F - F0) of these forces is the last residual's coupling, left in displacement
            displacement(:) = u_h + displacement
        else if (state%coupled) then
            displacement(:) = u_h + instant_product(state%compliance, weight0, force - state%preload, conv)
        else
            displacement(:) = u_h
        end if
        call divergence_guard(state, road, displacement, force, fault)
        if (.not. allocated(fault)) state%step = state%step + 1
    end subroutine step_contact

    !> The load [N] a single-point loop pushes after a step done by `step_contact`: F - F0,
    !> halved after step 0 (a multi-point convolver does this itself, `recorded_load`).
    !>
    !> The body is at rest before t = 0 and the loads q = F - F0 are zero before; a road that
    !> is not at its static height at t = 0 switches them on at t = 0+. The
    !> convolvers' kernels w_j ~ dt*g(t_j) are the trapezoidal rule of the convolution integral,
    !> whose end sample at tau = 0 carries half a weight: pushing q(t_0)/2 makes every scheme
    !> of second order (rectangle rule: the trapezoidal rule exactly; first-order hold: the
    !> weight of q(t_0) in u(t_n) is then dt*g(t_n)/2 + O(dt^3) against the exact
    !> int_0^dt g(t_n - tau)*(1 - tau/dt) dtau = dt*g(t_n)/2 + O(dt^2)). Pushing the whole
    !> q(t_0) puts an impulse q(t_0)*dt/2 too much at the start: an error of first order in dt.
    !> A load that starts from zero (a road at its static height at t = 0) is not changed.
    pure function step_load(state, force) result(load)
        !> The run, after `step_contact` (state%step is the number of steps done).
        type(contact_state), intent(in) :: state
        !> Contact forces F_i of the step [N].
        real(dp), intent(in) :: force(:)
        real(dp) :: load(size(force))

        load(:) = force - state%preload
        if (state%step == 1) load(:) = 0.5_dp*load
    end function step_load

    !> The options are usable with the instant compliance W0 [m/N].
    subroutine check_options(settings, weight0, error)
        type(contact_options), intent(in) :: settings
        real(dp), intent(in) :: weight0(:, :)
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
        else if (settings%scheme == 'implicit' .and. size(weight0) == 1) then
            if (.not. (weight0(1, 1) >= 0.0_dp)) call fatal_error(error, 'implicit contact step: the ' &
                    //'convolver''s instant weight w0 = '//sci_text(weight0(1, 1))//' m/N must be >= 0 for the ' &
                    //'step to have a unique solution', stat_input)
        end if
    end subroutine check_options

    !> The compression delta [m] solving delta + w0*law(delta) = b, by safeguarded Newton.
    !>
    !> On entry `delta` is a first guess (the previous step's), used when it lies in (0, b).
    !> `scale` is delta0 [m]; the iteration stops at |r| <= tolerance*max(b, delta0).
    !> `iterations` is the number of updates made, max_iterations + 1 when not converged.
    pure subroutine implicit_compression(law, b, w0, scale, settings, delta, residual, iterations)
        class(contact_law), intent(in) :: law
        real(dp), intent(in) :: b, w0, scale
        type(contact_options), intent(in) :: settings
        real(dp), intent(inout) :: delta
        real(dp), intent(out) :: residual
        integer, intent(out) :: iterations

        real(dp) :: lower, upper, step, step_before, newton, target

        residual = 0.0_dp
        iterations = 0
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
        do iterations = 0, settings%max_iterations - 1
            residual = delta + w0*law%force(delta) - b
            if (abs(residual) <= target) return
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
        if (.not. (abs(residual) <= target)) iterations = settings%max_iterations + 1
    end subroutine implicit_compression

    !> Semismooth Newton on R(delta) = delta - a + W0*(F(delta) - F0), damped on |R|_2, from
    !> the free compression corrected by the previous step's forces (`load` is work space;
    !> the correction is state%coupling when the previous step left it). With Woodbury's M^-1
    !> the first, full step is made without R at the guess (greenconv_contact_lowrank_solve's
    !> `woodbury_step`) and kept when it meets the tolerance; otherwise the damped iteration
    !> runs from the guess as if that step had not been tried.
    !> `coupling` is W0*(F(delta) - F0) [m] of the compressions left in state%delta, the
    !> residual's own product (the step's displacements less the history: no product more), and
    !> `load` their forces F(delta) [N] (no law evaluated again).
    !> Not converged: `iterations` = max_iterations + 1, `largest` [m] the largest |R_i| left,
    !> at `point`. `error` is set only when a Newton system cannot be solved.
    subroutine solve_compressions(weight0, state, free, load, coupling, iterations, largest, point, error, conv)
        real(dp), intent(in) :: weight0(:, :)
        type(contact_state), intent(inout) :: state
        real(dp), intent(in) :: free(:)
        real(dp), intent(out) :: load(:), coupling(:)
        integer, intent(out) :: iterations, point
        real(dp), intent(out) :: largest
        type(error_type), allocatable, intent(out) :: error
        class(multipoint_convolver), intent(inout), optional :: conv

        real(dp) :: r(size(free)), trial(size(free)), r_trial(size(free)), step(size(free))
        real(dp) :: coupling_trial(size(free)), force_trial(size(free)), alpha, scale, largest_trial
        integer :: halvings
        logical :: taken

        largest = 0.0_dp
        point = 1
        if (.not. state%compliance%checked) call factor_instant(weight0, state%compliance, conv)
        associate (delta => state%delta, laws => state%laws, options => state%settings, &
                   compliance => state%compliance)
            if (state%coupling_kept) then
                delta(:) = free - state%coupling
                state%coupling_kept = .false.
            else
                call law_forces(laws, delta, load)
                load(:) = load - state%preload
                delta(:) = free - instant_product(compliance, weight0, load, conv)
            end if
            call laws(1)%forces(laws, delta, load, step)
            load(:) = load - state%preload - step*(delta - free)
            call woodbury_step(compliance, weight0, step, load, free, trial, taken, error)
            if (allocated(error)) return
            if (taken) then
                call residual(compliance, weight0, laws, state%preload, free, trial, r_trial, coupling, force_trial, &
                              scale, largest, conv)
                if (largest <= options%tolerance*max(scale, state%delta0_max)) then
                    delta(:) = trial
                    load(:) = force_trial
                    call keep_coupling(state, coupling)
                    iterations = 1
                    largest = 0.0_dp
                    return
                end if
            end if
            call residual(compliance, weight0, laws, state%preload, free, delta, r, coupling, load, scale, largest, conv)
            scale = max(scale, state%delta0_max)
            do iterations = 0, options%max_iterations
                if (largest <= options%tolerance*scale) then
                    call keep_coupling(state, coupling)
                    largest = 0.0_dp
                    return
                end if
                if (iterations == options%max_iterations) exit
                call newton_solve(compliance, weight0, slope(laws, delta), -r, step, error)
                if (allocated(error)) return
                alpha = 1.0_dp
                do halvings = 0, max_halvings
                    trial(:) = delta + alpha*step
                    call residual(compliance, weight0, laws, state%preload, free, trial, r_trial, coupling_trial, &
                                  force_trial, scale, largest_trial, conv)
                    if (norm2(r_trial) <= (1.0_dp - 1.0e-4_dp*alpha)*norm2(r)) exit
                    alpha = alpha/2
                end do
                delta(:) = trial
                r(:) = r_trial
                coupling(:) = coupling_trial
                load(:) = force_trial
                largest = largest_trial
                scale = max(scale, state%delta0_max)
            end do
        end associate
        iterations = state%settings%max_iterations + 1
        point = maxloc(abs(r), 1)
        largest = r(point)
    end subroutine solve_compressions

    !> Keep W0*(F(delta) - F0) [m] of the step's compressions for the next step's first guess.
    subroutine keep_coupling(state, coupling)
        type(contact_state), intent(inout) :: state
        real(dp), intent(in) :: coupling(:)

        if (.not. allocated(state%coupling)) allocate (state%coupling(size(coupling)))
        state%coupling(:) = coupling
        state%coupling_kept = .true.
    end subroutine keep_coupling

    !> W0's low-rank factors, once per run: in the span of the convolver's separable modes when
    !> it offers them (no N_c x N_c elimination), else by eliminating the dense W0; dense when
    !> its rank is not below N_c/2.
    subroutine factor_instant(weight0, compliance, conv)
        real(dp), intent(in) :: weight0(:, :)
        type(lowrank_compliance), intent(out) :: compliance
        class(multipoint_convolver), intent(inout), optional :: conv

        type(separable_shapes), allocatable :: shapes
        real(dp), allocatable :: weight(:)
        logical :: offered, done

        offered = .false.
        if (present(conv)) call conv%instant_modes(shapes, weight, offered)
        if (offered) then
            call factor_modal_compliance(shapes, weight, compliance, done)
            if (done) return
        end if
        call factor_compliance(weight0, compliance)
    end subroutine factor_instant

    !> R = delta - a + W0*(F(delta) - F0) [m], its coupling W0*(F(delta) - F0) [m], the forces
    !> F(delta) [N], the size of its terms [m] (the largest |a_i|, |delta_i|, |coupling_i|, at
    !> least tiny) and max_i |R_i| [m]; the maxima over the numbers that are not NaN, as MAXVAL.
    subroutine residual(compliance, weight0, laws, preload, free, delta, r, coupling, force, scale, largest, conv)
        type(lowrank_compliance), intent(in) :: compliance
        real(dp), intent(in) :: weight0(:, :)
        class(contact_law), intent(in) :: laws(:)
        real(dp), intent(in) :: preload(:), free(:), delta(:)
        real(dp), intent(out) :: r(:), coupling(:), force(:), scale, largest
        class(multipoint_convolver), intent(inout), optional :: conv

        integer :: i
        logical :: number

        call law_forces(laws, delta, force)
        coupling(:) = instant_product(compliance, weight0, force - preload, conv)
        scale = tiny(1.0_dp)
        largest = -huge(1.0_dp)
        number = .false.
        do i = 1, size(r)
            r(i) = delta(i) - free(i) + coupling(i)
            if (abs(free(i)) > scale) scale = abs(free(i))
            if (abs(delta(i)) > scale) scale = abs(delta(i))
            if (abs(coupling(i)) > scale) scale = abs(coupling(i))
            if (abs(r(i)) >= largest) then
                largest = abs(r(i))
                number = .true.
            end if
        end do
        ! every R_i NaN: no convergence (MAXVAL's NaN)
        if (.not. number) largest = ieee_value(largest, ieee_quiet_nan)
    end subroutine residual

    !> W0*x [m] for loads x [N]: the convolver's own product when it is the cheaper
    !> (`fast_instant`, as on a plate's separable mode shapes), else by W0's low-rank factors or
    !> densely (greenconv_contact_lowrank_solve's `apply_compliance`). Both are W0*x to round-off.
    !> The convolver keeps its modal loads of x (`apply_instant_kept`): the last product of a
    !> step is that of the loads F - F0 it pushes, whose projection the push then reuses.
    function instant_product(compliance, weight0, x, conv) result(y)
        type(lowrank_compliance), intent(in) :: compliance
        real(dp), intent(in) :: weight0(:, :), x(:)
        class(multipoint_convolver), intent(inout), optional :: conv
        real(dp) :: y(size(x))

        if (present(conv)) then
            if (conv%fast_instant()) then
                call conv%apply_instant_kept(x, y)
                return
            end if
        end if
        y(:) = apply_compliance(compliance, weight0, x)
    end function instant_product

    !> The forces F_i(delta_i) [N] of the points' laws: one point's `force`, or the laws' `forces`
    !> at several (one call through the type's table for all points).
    subroutine law_forces(laws, delta, force)
        class(contact_law), intent(in) :: laws(:)
        real(dp), intent(in) :: delta(:)
        real(dp), intent(out) :: force(:)

        if (size(laws) == 1) then
            force(1) = laws(1)%force(delta(1))
        else if (size(laws) > 1) then
            call laws(1)%forces(laws, delta, force)
        end if
    end subroutine law_forces

    !> dF/ddelta [N/m] (the law's tangent) in compression, zero otherwise.
    elemental real(dp) function slope(law, delta)
        class(contact_law), intent(in) :: law
        real(dp), intent(in) :: delta

        slope = 0.0_dp
        if (delta > 0.0_dp) slope = law%tangent(delta)
    end function slope

    !> A fault unless every |u_i| is within the bound and F_i, delta_i are finite: the first
    !> point that fails is named.
    subroutine divergence_guard(state, road, displacement, force, fault)
        type(contact_state), intent(in) :: state
        real(dp), intent(in) :: road(:), displacement(:), force(:)
        type(error_type), allocatable, intent(out) :: fault

        integer :: i
        character(len=:), allocatable :: message

        do i = 1, size(displacement)
            if (abs(displacement(i)) <= state%settings%divergence_bound .and. ieee_is_finite(force(i)) &
                .and. ieee_is_finite(state%delta(i))) cycle
            call divergence_message(state, i, displacement(i), message)
            call step_fault(state, road, i, message, fault)
            return
        end do
    end subroutine divergence_guard

    !> The fault of step state%step at a point: `what` went wrong, unless the road height
    !> there is not a finite number, which is then said instead.
    subroutine step_fault(state, road, point, what, fault)
        type(contact_state), intent(in) :: state
        real(dp), intent(in) :: road(:)
        integer, intent(in) :: point
        character(len=*), intent(in) :: what
        type(error_type), allocatable, intent(inout) :: fault

        character(len=:), allocatable :: message

        if (ieee_is_finite(road(point))) then
            message = what
        else
            message = 'contact run stopped '//where(state, point)//': the road height u_r is not a finite ' &
                      //'number (NaN or infinite); steps before it are kept. Check the road data of that step'
        end if
        if (allocated(fault)) deallocate (fault)
        call fatal_error(fault, message, stat_numerical)
    end subroutine step_fault

    !> `where` blank-padded to a fixed length, which gives that function a result of spec length.
    pure function where_buffer(state, point) result(text)
        type(contact_state), intent(in) :: state
        integer, intent(in) :: point
        character(len=96) :: text

        text = 'at step '//int_text(state%step)//' (t = '//sci_text(state%step*state%dt)//' s)'
        if (size(state%laws) > 1 .and. point > 0) text = trim(text)//' at point '//int_text(point)
    end function where_buffer

    !> "at step n (t = t_n s)", and " at point i" when the run has more than one point and
    !> i > 0.
    pure function where(state, point) result(text)
        type(contact_state), intent(in) :: state
        integer, intent(in) :: point
        character(len=len_trim(where_buffer(state, point))) :: text

        text = where_buffer(state, point)
    end function where

    !> One line on an implicit step that did not converge: where, and the residual left [m].
    pure subroutine convergence_message(state, point, residual, message)
        type(contact_state), intent(in) :: state
        integer, intent(in) :: point
        real(dp), intent(in) :: residual
        character(len=:), allocatable, intent(out) :: message

        message = 'implicit contact step did not converge '//where(state, point)//': residual |r| = ' &
                  //sci_text(abs(residual))//' m after '//int_text(state%settings%max_iterations) &
                  //' iterations (tolerance '//sci_text(state%settings%tolerance)//' of the compression scale)'
    end subroutine convergence_message

    !> One line on a divergent run at a point: where, how large, and what to change.
    pure subroutine divergence_message(state, point, u, message)
        type(contact_state), intent(in) :: state
        integer, intent(in) :: point
        real(dp), intent(in) :: u
        character(len=:), allocatable, intent(out) :: message

        message = 'contact run diverged '//where(state, point)//': '
        if (ieee_is_finite(u)) then
            message = message//'|u| = '//sci_text(abs(u))//' m exceeds the divergence bound ' &
                      //sci_text(state%settings%divergence_bound)//' m'
        else
            message = message//'u, F or delta is not finite'
        end if
        if (state%step > 0) then
            message = message//'; steps 0 to '//int_text(state%step - 1)//' are kept. '
        else
            message = message//'; no step is kept. '
        end if
        message = message//'The contact frequency is omega_c = sqrt(k_c''/M), k_c'' = p*k_c*delta0^(p-1) = ' &
                  //sci_text(state%laws(point)%tangent(state%delta0(point)))//' N/m: '
        if (state%settings%scheme == 'implicit' .and. state%coupled) then
            message = message//'the implicit step with w0 > 0 is stable up to omega_c*dt of about ' &
                      //'2*sqrt(3) = 3.46 (first-order hold, exact): reduce dt below ~3.46/omega_c'
        else
            message = message//'the explicit step is stable only for omega_c*dt < 2: reduce dt below ' &
                      //'~2/omega_c or use scheme = ''implicit'' with an engine whose w0 > 0 (exact)'
        end if
    end subroutine divergence_message

end module greenconv_contact_step
