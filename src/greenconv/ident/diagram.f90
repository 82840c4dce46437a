!> The stabilisation diagram of the maximum-likelihood identification (steps 2 and 3 of
!> greenconv_ident_mlfit's description): the linear LSCE step at N = 1..max_order modes (further
!> when no pole has settled by then), each pole flagged by its stability against order N - 1,
!> the start poles (the chains stable over stable_orders orders) and the other poles of the
!> highest order as candidates of the order search; on a grid other than the uniform grid from
!> 0 Hz, G resampled onto one for the diagram alone.
module greenconv_ident_diagram
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_model_frf, only: frf_type, min_frf_lines
    use greenconv_ident_lsce, only: impulse_from_frf, lsce_poles, natural_frequency, damping_ratio
    use greenconv_ident_ml_types, only: ml_options, ml_result
    use greenconv_ident_noise_model, only: line_spacing
    implicit none
    private

    public :: build_diagram

    real(dp), parameter :: two_pi = 2.0_dp*3.141592653589793238462643383279_dp

contains

    !> G resampled onto a uniform grid from 0 Hz for the stabilisation diagram alone (its LSCE
    !> step needs g, the inverse FFT of that grid), when the lines given are not such a grid
    !> (a uniform grid from df, a band from f_min > 0, uneven lines). The step is the smallest
    !> line spacing, coarsened when needed so that the grid has at most diagram_intervals + 1
    !> lines, and adjusted to end exactly at f_max; between two lines G is interpolated
    !> linearly (Re and Im); below the first line f_1 > 0 a receptance tends to its static
    !> compliance, real at 0 Hz, with an imaginary part vanishing like omega (viscous damping):
    !> G(f) = Re G(f_1) + i*Im G(f_1)*f/f_1. The interpolation only blunts peaks between coarse
    !> lines, which moves the start poles a little: the maximum-likelihood fit and the order
    !> search then run on the lines given alone.
    pure function diagram_grid(frf) result(uniform)
        type(frf_type), intent(in) :: frf
        type(frf_type) :: uniform

        !> Most intervals of the resampled grid (the diagram uses at most max_samples of its 2*m
        !> impulse samples; 2^16 keeps the FFT and the memory small).
        integer, parameter :: diagram_intervals = 65536
        real(dp) :: f_max, step, t
        integer :: m, j, l, n

        n = frf%n_freq()
        f_max = frf%f_max()
        step = line_spacing(frf)
        m = ceiling(f_max/step*(1.0_dp - 1.0e-9_dp))
        m = max(min(m, diagram_intervals), min_frf_lines - 1)
        allocate (uniform%frequency(m + 1), uniform%receptance(m + 1))
        uniform%frequency(:) = [(j*(f_max/m), j=0, m)]
        uniform%frequency(m + 1) = f_max
        uniform%source = ''
        l = 1
        do j = 1, m + 1
            associate (f => uniform%frequency(j), g => frf%receptance, fl => frf%frequency)
                if (f <= fl(1)) then
                    uniform%receptance(j) = cmplx(real(g(1), dp), aimag(g(1))*f/fl(1), dp)
                    if (fl(1) == 0.0_dp) uniform%receptance(j) = g(1)
                    cycle
                end if
                do while (l < n - 1 .and. fl(l + 1) < f)
                    l = l + 1
                end do
                t = min(max((f - fl(l))/(fl(l + 1) - fl(l)), 0.0_dp), 1.0_dp)
                uniform%receptance(j) = g(l) + t*(g(l + 1) - g(l))
            end associate
        end do
    end function diagram_grid

    !> The stabilisation diagram (LSCE step only at N = 1..max_order, further when no pole is
    !> stable by then), the start poles (run of stable_orders or more at the highest order)
    !> and the other poles of the highest order as candidates.
    subroutine build_diagram(frf, options, result, start, candidates, error)
        !> The receptance (any increasing grid; resampled for the diagram when needed).
        type(frf_type), intent(in) :: frf
        !> Settings: max_order, stable_orders, stable_frequency, stable_damping, max_samples.
        type(ml_options), intent(in) :: options
        !> The result: its diagram, max_modes, n_wandering, unstable_by_order, real_by_order are set.
        type(ml_result), intent(inout) :: result
        !> Start poles of the fit [rad/s].
        complex(dp), allocatable, intent(out) :: start(:)
        !> The other physical poles of the highest order below f_max [rad/s]: candidates of the search.
        complex(dp), allocatable, intent(out) :: candidates(:)
        !> Set when the impulse response or the LSCE step fails.
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: g(:), f(:), xi(:), f_prev(:), xi_prev(:)
        integer, allocatable :: run(:), run_prev(:), flag(:)
        complex(dp), allocatable :: poles(:)
        real(dp) :: dt
        integer :: n, n_data, n_max, k, j
        integer, allocatable :: unstable(:), real_roots(:), settled(:)

        if (frf%uniform_from_zero()) then
            call impulse_from_frf(frf, g, dt, error)
        else
            call impulse_from_frf(diagram_grid(frf), g, dt, error)
        end if
        if (allocated(error)) return
        n_data = min(size(g) - 1, options%max_samples)/6
        result%max_modes = min(options%max_order, n_data)
        ! Beyond max_order only when no pole has been stable over stable_orders orders by then: the
        ! poles of a band-limited G settle a few orders above the number of modes, and a max_order
        ! close to it would leave the fit without start poles. The diagram then goes on until the
        ! number of such poles has not grown for stable_orders orders.
        n_max = min(2*options%max_order + options%stable_orders, n_data)
        if (allocated(result%diagram_order)) deallocate (result%diagram_order, result%diagram_frequency, &
                                                         result%diagram_damping, result%diagram_flag, &
                                                         result%unstable_by_order, result%real_by_order)
        allocate (result%diagram_order(0), result%diagram_frequency(0), result%diagram_damping(0), &
                  result%diagram_flag(0), unstable(n_max), real_roots(n_max))
        allocate (f_prev(0), xi_prev(0), run_prev(0), poles(0), settled(0:n_max))
        settled = 0
        do n = 1, n_max
            if (n > result%max_modes) then
                if (settled(result%max_modes) > 0) exit
                if (settled(n - 1) > 0 .and. settled(n - 1) == settled(max(n - 1 - options%stable_orders, 0))) exit
            end if
            call lsce_poles(g, dt, 2*n, options%max_samples, poles, unstable(n), real_roots(n), error)
            if (allocated(error)) return
            f = natural_frequency(poles)/two_pi
            xi = damping_ratio(poles)
            allocate (flag(size(poles)), run(size(poles)))
            do k = 1, size(poles)
                flag(k) = 0
                run(k) = 0
                if (size(f_prev) == 0) cycle
                j = minloc(abs(f_prev - f(k)), 1)
                if (abs(f_prev(j) - f(k)) > options%stable_frequency*f_prev(j)) cycle
                flag(k) = 1
                if (abs(xi_prev(j) - xi(k)) > options%stable_damping*xi_prev(j)) cycle
                flag(k) = 2
                run(k) = run_prev(j) + 1
            end do
            result%diagram_order = [result%diagram_order, spread(n, 1, size(poles))]
            result%diagram_frequency = [result%diagram_frequency, f]
            result%diagram_damping = [result%diagram_damping, xi]
            result%diagram_flag = [result%diagram_flag, flag]
            call move_alloc(f, f_prev)
            call move_alloc(xi, xi_prev)
            settled(n) = count(run >= options%stable_orders)
            call move_alloc(run, run_prev)
            deallocate (flag)
        end do
        n = maxval([0, result%diagram_order])
        result%unstable_by_order = unstable(:n)
        result%real_by_order = real_roots(:n)
        candidates = pack(poles, .not. (run_prev >= options%stable_orders) .and. f_prev < frf%f_max())
        result%n_wandering = size(candidates)
        call start_poles(result, options, frf%f_max(), start)
    end subroutine build_diagram

    !> Start poles from the diagram: going down from the highest order, every pole stable in
    !> f and xi for stable_orders orders in a row (flag 2 that many times along its chain)
    !> whose frequency is not within stable_frequency of one already taken; when there is
    !> none, the poles of the highest order flagged 1 or 2.
    pure subroutine start_poles(result, options, f_max, start)
        type(ml_result), intent(in) :: result
        type(ml_options), intent(in) :: options
        real(dp), intent(in) :: f_max
        complex(dp), allocatable, intent(out) :: start(:)

        integer :: run(size(result%diagram_order))
        real(dp), allocatable :: taken(:)
        integer, allocatable :: length(:)
        integer :: i, j, n, needed

        ! run(i): orders in a row ending at pole i stable in f and xi, along nearest-frequency links.
        run = 0
        do i = 1, size(run)
            if (result%diagram_flag(i) < 2) cycle
            n = result%diagram_order(i)
            j = nearest_pole(result%diagram_frequency, result%diagram_order, n - 1, result%diagram_frequency(i))
            if (j > 0) run(i) = run(j) + 1
        end do
        ! When no chain is that long (max_order hardly above the number of modes: the poles of
        ! a band-limited G settle only a few orders above it), the poles of the highest order
        ! stable in f against the order below start the fit instead.
        needed = options%stable_orders
        if (.not. any(run >= needed)) then
            needed = 1
            run = 0
            where (result%diagram_order == maxval([0, result%diagram_order]) .and. result%diagram_flag >= 1) run = 1
        end if
        allocate (start(0), taken(0), length(0))
        do i = size(run), 1, -1
            if (run(i) < needed .or. result%diagram_frequency(i) >= f_max) cycle
            if (size(taken) > 0) then
                if (minval(abs(taken - result%diagram_frequency(i))) <= options%stable_frequency &
                    *result%diagram_frequency(i)) cycle
            end if
            taken = [taken, result%diagram_frequency(i)]
            length = [length, run(i)]
            start = [start, two_pi*result%diagram_frequency(i)*cmplx(-result%diagram_damping(i), &
                                                                     sqrt(1.0_dp - result%diagram_damping(i)**2), dp)]
        end do
        ! No more than the model may hold (a diagram gone beyond max_order): the longest chains.
        do while (size(start) > result%max_modes)
            i = minloc(length, 1, back=.true.)
            start = [start(:i - 1), start(i + 1:)]
            length = [length(:i - 1), length(i + 1:)]
        end do
    end subroutine start_poles

    !> Index of the pole of order n nearest in frequency to f (0 when order n has none).
    pure integer function nearest_pole(frequency, order, n, f)
        real(dp), intent(in) :: frequency(:)
        integer, intent(in) :: order(:), n
        real(dp), intent(in) :: f

        integer :: i

        nearest_pole = 0
        do i = 1, size(order)
            if (order(i) /= n) cycle
            if (nearest_pole == 0) then
                nearest_pole = i
            else if (abs(frequency(i) - f) < abs(frequency(nearest_pole) - f)) then
                nearest_pole = i
            end if
        end do
    end function nearest_pole

end module greenconv_ident_diagram
