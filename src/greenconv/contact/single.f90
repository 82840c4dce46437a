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
!> The step itself is greenconv_contact_step's and the loop greenconv_contact_multi's: a
!> single-point run is the multi-point run of N_c = 1 (the implicit step then solved by the
!> scalar Newton iteration above), its convolver lent to that loop as a 1 x 1 Green's matrix
!> for the length of a call (`lent_point` of greenconv_conv_point_matrix). The procedures here
!> only convert the arguments and the histories, so that a single-point run and the same structure run as one point of a
!> multi-point run agree bit for bit.
!>
!> Long runs. `run_contact` takes the whole road and returns the whole history. A run too long
!> to hold is streamed instead: `start_contact` resets the convolver into a `contact_state`,
!> and each `contact_block` continues it over the next block of road heights, returning that
!> block's histories (times t_n with the run's own step index n). The state carries what one
!> step hands the next (the step index and the implicit step's first guess), so the blocks of
!> a run put together equal `run_contact` on the whole road bit for bit.
module greenconv_contact_single
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_conv_convolver, only: convolver
    use greenconv_conv_point_matrix, only: lent_point, lend_point
    use greenconv_contact_laws, only: contact_law, replicate_law
    use greenconv_contact_step, only: contact_options, contact_state
    use greenconv_contact_multi, only: multi_contact_response, start_multi_contact, multi_contact_block
    implicit none
    private

    !> The contact law (greenconv_contact_laws: the abstract type, and `contact_law(k_c, p)` a power law).
    public :: contact_law
    !> The options and the state of a run, greenconv_contact_step's (a single-point run is a run at one point).
    public :: contact_options, contact_state
    public :: contact_response, run_contact
    public :: start_contact, contact_block, copy_histories

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
        class(convolver), intent(inout), target :: conv
        !> The contact law.
        class(contact_law), intent(in) :: law
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
            call point_histories(multi_contact_response(), response)
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
        class(convolver), intent(inout), target :: conv
        !> The contact law.
        class(contact_law), intent(in) :: law
        !> Static preload F0 [N] pressing the body onto the road, >= 0.
        real(dp), intent(in) :: preload
        !> The run at step 0.
        type(contact_state), intent(out) :: state
        !> Set (`stat_input`) when the options are unusable with this convolver.
        type(error_type), allocatable, intent(out) :: error
        !> Scheme, divergence bound and Newton settings; the defaults when absent.
        type(contact_options), intent(in), optional :: options

        type(contact_options) :: settings
        type(lent_point) :: matrix
        class(contact_law), allocatable :: laws(:)

        if (present(options)) settings = options
        call lend_point(conv, matrix)
        call replicate_law(law, 1, laws)
        call start_multi_contact(matrix, laws, [preload], state, error, settings=settings)
    end subroutine start_contact

    !> Continue a contact run over the next size(road) steps, n = state%step onwards.
    !>
    !> `response` gets this block's histories, index j for step n = state%step + j (times
    !> t_n = n*dt of the whole run), shortened to the steps done when a fault stops the run;
    !> `error` then names the step (`stat_numerical`) and the run must not be continued.
    subroutine contact_block(conv, state, road, response, error)
        !> The convolver, as the previous block (or `start_contact`) left it.
        class(convolver), intent(inout), target :: conv
        !> The run; advanced by the steps done.
        type(contact_state), intent(inout) :: state
        !> Road heights u_r(t_n) [m] of this block's steps.
        real(dp), intent(in) :: road(0:)
        !> Histories of this block's steps.
        type(contact_response), intent(out) :: response
        !> Set on a numerical fault (divergence, an implicit step that did not converge), or
        !> (`stat_input`, nothing done) for a block reaching past the steps a cut kernel covers.
        type(error_type), allocatable, intent(out) :: error

        type(lent_point) :: matrix
        type(multi_contact_response) :: block

        call lend_point(conv, matrix)
        call multi_contact_block(matrix, state, reshape(road, [size(road), 1]), block, error)
        call point_histories(block, response)
    end subroutine contact_block

    !> The histories of the one point of a multi-point run (none when unallocated), indexed from 0.
    subroutine point_histories(block, response)
        type(multi_contact_response), intent(in) :: block
        type(contact_response), intent(out) :: response

        integer :: n

        n = 0
        if (allocated(block%time)) n = size(block%time)
        allocate (response%time(0:n - 1), response%road(0:n - 1), response%displacement(0:n - 1), &
                  response%force(0:n - 1), response%compression(0:n - 1))
        if (n == 0) return
        response%time(:) = block%time
        response%road(:) = block%road(:, 1)
        response%displacement(:) = block%displacement(:, 1)
        response%force(:) = block%force(:, 1)
        response%compression(:) = block%compression(:, 1)
    end subroutine point_histories

end module greenconv_contact_single
