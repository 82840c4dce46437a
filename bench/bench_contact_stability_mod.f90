!> Where the explicit and the implicit contact steps stay stable and accurate: a map over
!> the contact stiffness k_c and the time step dt on the SDOF scene of the paper's Tab. 1.
!>
!> Every cell runs the scene (M = 1 kg, K = 1e6 N/m, xi = 0.02, the road A0*sin(omega_r*t)
!> with omega_r = 100 rad/s, the preload M*g) with the `exact` engine, whose instant weight
!> w0 > 0 lets the implicit step differ from the explicit one, once with each scheme. It
!> records omega_c*dt, with the contact frequency omega_c = sqrt(k_c'/M) and
!> k_c' = p*k_c*delta0^(p-1) (see greenconv_contact_single), whether the run ended without a divergence
!> fault, and the relative L2 error of u against a reference: the implicit step run at
!> dt_ref = dt_min/2^j, with j >= 2 the smallest such that sqrt((K + k_c')/M)*dt_ref <= 0.25,
!> over the same time. Time steps are dt_min*2^k, k = 0..n_dt-1, so every sample of a cell
!> is a sample of the reference.
!>
!> The linear analysis in greenconv_contact_single puts the edge of the explicit step at omega_c*dt = 2 and
!> that of the implicit one (first-order hold) at 2*sqrt(3) = 3.46. With A0 = 1 mm the body
!> leaves the road and lands again, and the stiffer contacts chatter from t = 0 (the road
!> starts at 0.1 m/s under a body at rest): that bouncing is sensitive to small changes, so
!> errors of a few per cent remain there at any dt, and impacts can break the implicit step
!> a little below 3.46. A small A0 (1 um) keeps the contact closed and shows the linear edges.
module bench_contact_stability_mod
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error, stat_input, stat_numerical
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_model_sdof, only: sdof_modes
    use greenconv_conv_recursive, only: recursive_convolver, new_exact_convolver
    use greenconv_contact_single, only: contact_law, contact_response, contact_options, run_contact
    use greenconv_model_road, only: sine_road
    use greenconv_io_files, only: write_columns, make_directory
    use verify_contact_mod, only: contact_frequency
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: stability_cell, stability_map

    !> One cell of the map: a contact stiffness and a time step, run by both schemes.
    type :: stability_cell
        !> Time step dt [s].
        real(dp) :: dt = 0.0_dp
        !> Contact stiffness k_c [N/m^p].
        real(dp) :: stiffness = 0.0_dp
        !> omega_c*dt (dimensionless), omega_c = sqrt(k_c'/M) the contact frequency.
        real(dp) :: omega_dt = 0.0_dp
        !> The explicit run ended without a divergence fault.
        logical :: explicit_bounded = .false.
        !> The implicit run ended without a divergence fault.
        logical :: implicit_bounded = .false.
        !> Relative L2 error of the explicit u against the reference; -1 when it diverged.
        real(dp) :: explicit_error = -1.0_dp
        !> Relative L2 error of the implicit u against the reference; -1 when it diverged.
        real(dp) :: implicit_error = -1.0_dp
    end type stability_cell

    !> The scene of Tab. 1: mass M [kg], stiffness K [N/m], damping ratio, road frequency
    !> omega_r [rad/s] and gravity g [m/s^2] for the preload M*g.
    real(dp), parameter :: mass = 1.0_dp, spring = 1.0e6_dp, damping_ratio = 0.02_dp
    real(dp), parameter :: road_omega = 100.0_dp, gravity = 9.81_dp
    !> Largest sqrt((K + k_c')/M)*dt_ref of the reference run.
    real(dp), parameter :: reference_omega_dt = 0.25_dp
    !> Most steps of one reference run; the simulated time is shortened to stay below it.
    integer, parameter :: max_reference_steps = 2**21
    !> Most doublings of dt_min (the grid's n_dt plus the reference's j).
    integer, parameter :: max_levels = 28

contains

    !> Run the map and write it to `path` (its directory is created when missing).
    !>
    !> The file has `#` lines describing the scene, then `# units: s N/m^p 1 1 1 1 1` and
    !> `# dt k_c omega_c_dt explicit_bounded explicit_error implicit_bounded implicit_error`,
    !> then one row per cell, k_c outer and dt inner; bounded is 1 or 0, an error is -1 where
    !> the run diverged. `plot/contact_stability_map.gp` draws it. The default map, 11 x 11
    !> cells over k_c = 1e5..1e10 N/m and dt = 1e-6..1.024e-3 s, takes about a second.
    subroutine stability_map(path, error, stiffness, dt_min, n_dt, exponent, amplitude, duration, cells)
        !> Output file, e.g. `out/bench/contact_stability_map.dat`.
        character(len=*), intent(in) :: path
        !> Set on bad arguments (`stat_input`), a failed reference run (`stat_numerical`) or
        !> a file that cannot be written.
        type(error_type), allocatable, intent(out) :: error
        !> Contact stiffnesses k_c [N/m^p], > 0; default 10^(5 + i/2), i = 0..10.
        real(dp), intent(in), optional :: stiffness(:)
        !> Smallest time step [s], > 0; default 1e-6. The others are dt_min*2^k.
        real(dp), intent(in), optional :: dt_min
        !> Number of time steps, 1..20; default 11.
        integer, intent(in), optional :: n_dt
        !> Exponent p of the contact law, > 0; default 1 (linear).
        real(dp), intent(in), optional :: exponent
        !> Road amplitude A0 [m], > 0; default 1e-3 (Tab. 1).
        real(dp), intent(in), optional :: amplitude
        !> Simulated time [s], at least the largest dt; default 0.05. Rounded down to a
        !> multiple of the largest dt, and shortened where the reference would exceed 2^21 steps.
        real(dp), intent(in), optional :: duration
        !> The cells, in the order of the file's rows.
        type(stability_cell), allocatable, intent(out), optional :: cells(:)

        type(stability_cell), allocatable :: map(:)
        real(dp), allocatable :: k_c(:)
        real(dp) :: smallest, p, height, t_end
        integer :: levels, i

        if (present(stiffness)) then
            allocate (k_c(size(stiffness)))
            k_c(:) = stiffness
        else
            allocate (k_c(11))
            k_c(:) = [(10.0_dp**(5.0_dp + 0.5_dp*i), i=0, 10)]
        end if
        smallest = 1.0e-6_dp
        if (present(dt_min)) smallest = dt_min
        levels = 11
        if (present(n_dt)) levels = n_dt
        p = 1.0_dp
        if (present(exponent)) p = exponent
        height = 1.0e-3_dp
        if (present(amplitude)) height = amplitude
        t_end = 0.05_dp
        if (present(duration)) t_end = duration
        call check_arguments(k_c, smallest, levels, p, height, t_end, error)
        if (allocated(error)) return
        allocate (map(size(k_c)*levels))
        do i = 1, size(k_c)
            call map_row(power_law(k_c(i), p), smallest, levels, height, t_end, &
                         map((i - 1)*levels + 1:i*levels), error)
            if (allocated(error)) return
        end do
        call write_map(path, map, p, height, t_end, error)
        if (present(cells)) call move_alloc(map, cells)
    end subroutine stability_map

    !> The arguments of stability_map describe a map that can be run.
    subroutine check_arguments(k_c, dt_min, n_dt, exponent, amplitude, duration, error)
        real(dp), intent(in) :: k_c(:), dt_min, exponent, amplitude, duration
        integer, intent(in) :: n_dt
        type(error_type), allocatable, intent(out) :: error

        character(len=*), parameter :: where = 'stability_map: '

        if (size(k_c) < 1 .or. .not. all(k_c > 0.0_dp)) then
            call fatal_error(error, where//'stiffness: expected one or more values > 0 N/m^p', stat_input)
        else if (.not. (dt_min > 0.0_dp)) then
            call fatal_error(error, where//'dt_min: expected a time step > 0 s, found '//sci_text(dt_min), stat_input)
        else if (n_dt < 1 .or. n_dt > 20) then
            call fatal_error(error, where//'n_dt: expected 1 to 20 time steps, found '//int_text(n_dt), stat_input)
        else if (.not. (exponent > 0.0_dp)) then
            call fatal_error(error, where//'exponent: expected p > 0, found '//sci_text(exponent), stat_input)
        else if (.not. (amplitude > 0.0_dp)) then
            call fatal_error(error, where//'amplitude: expected A0 > 0 m, found '//sci_text(amplitude), stat_input)
        else if (.not. (duration >= dt_min*2.0_dp**(n_dt - 1))) then
            call fatal_error(error, where//'duration: expected at least the largest time step ' &
                             //sci_text(dt_min*2.0_dp**(n_dt - 1))//' s, found '//sci_text(duration), stat_input)
        end if
    end subroutine check_arguments

    !> The cells of one contact law: a reference run, then each dt with both schemes.
    subroutine map_row(law, dt_min, n_dt, amplitude, duration, row, error)
        type(power_law), intent(in) :: law
        real(dp), intent(in) :: dt_min, amplitude, duration
        integer, intent(in) :: n_dt
        type(stability_cell), intent(out) :: row(:)
        type(error_type), allocatable, intent(out) :: error

        type(contact_response) :: reference
        type(contact_options) :: options
        type(error_type), allocatable :: fault
        real(dp) :: omega_c, dt_ref
        integer :: fine, intervals, n_ref, k, ratio

        omega_c = contact_frequency(law, mass*gravity, mass)
        fine = 2
        do while (sqrt(omega_c**2 + spring/mass)*dt_min/2.0_dp**fine > reference_omega_dt .and. fine < max_levels)
            fine = fine + 1
        end do
        if (n_dt - 1 + fine > max_levels) then
            call fatal_error(error, 'stability_map: k_c = '//sci_text(law%stiffness)//' N/m^p needs a reference ' &
                             //'step below dt_min/2^'//int_text(max_levels - n_dt + 1)//': lower dt_min or n_dt', &
                             stat_input)
            return
        end if
        dt_ref = dt_min/2.0_dp**fine
        intervals = min(floor(duration/(dt_min*2.0_dp**(n_dt - 1))), max_reference_steps/2**(n_dt - 1 + fine))
        if (intervals < 1) then
            call fatal_error(error, 'stability_map: the reference for k_c = '//sci_text(law%stiffness) &
                             //' N/m^p would take more than '//int_text(max_reference_steps) &
                             //' steps for one largest dt: lower n_dt or raise dt_min', stat_input)
            return
        end if
        n_ref = intervals*2**(n_dt - 1 + fine)
        options%scheme = 'implicit'
        call run_scene(law, dt_ref, n_ref, amplitude, options, reference, fault)
        if (allocated(fault)) then
            call fatal_error(error, 'stability_map: reference run (implicit, dt = '//sci_text(dt_ref) &
                             //' s) failed for k_c = '//sci_text(law%stiffness)//' N/m^p: '//fault%message, &
                             stat_numerical)
            return
        end if
        do k = 1, n_dt
            ratio = 2**(k - 1 + fine)
            row(k)%dt = dt_min*2.0_dp**(k - 1)
            row(k)%stiffness = law%stiffness
            row(k)%omega_dt = omega_c*row(k)%dt
            call run_cell(law, row(k)%dt, amplitude, 'explicit', reference%displacement(0:n_ref:ratio), &
                          row(k)%explicit_bounded, row(k)%explicit_error)
            call run_cell(law, row(k)%dt, amplitude, 'implicit', reference%displacement(0:n_ref:ratio), &
                          row(k)%implicit_bounded, row(k)%implicit_error)
        end do
    end subroutine map_row

    !> One run of a cell against the reference samples u_ref at its own times.
    subroutine run_cell(law, dt, amplitude, scheme, u_ref, bounded, relative_error)
        type(power_law), intent(in) :: law
        real(dp), intent(in) :: dt, amplitude
        character(len=*), intent(in) :: scheme
        real(dp), intent(in) :: u_ref(:)
        logical, intent(out) :: bounded
        real(dp), intent(out) :: relative_error

        type(contact_response) :: response
        type(contact_options) :: options
        type(error_type), allocatable :: fault

        options%scheme = scheme
        call run_scene(law, dt, size(u_ref) - 1, amplitude, options, response, fault)
        bounded = .not. allocated(fault)
        relative_error = -1.0_dp
        if (bounded) relative_error = norm2(response%displacement - u_ref)/norm2(u_ref)
    end subroutine run_cell

    !> The scene over n_steps steps of dt (n_steps + 1 samples, t = 0 to n_steps*dt).
    subroutine run_scene(law, dt, n_steps, amplitude, options, response, error)
        type(power_law), intent(in) :: law
        real(dp), intent(in) :: dt, amplitude
        integer, intent(in) :: n_steps
        type(contact_options), intent(in) :: options
        type(contact_response), intent(out) :: response
        type(error_type), allocatable, intent(out) :: error

        type(recursive_convolver) :: conv
        type(sine_road) :: road

        conv = new_exact_convolver(sdof_modes(mass, spring, damping_ratio), dt)
        road%amplitude = amplitude
        road%omega = road_omega
        call run_contact(conv, law, road%sample(dt, n_steps + 1), mass*gravity, response, options, error)
    end subroutine run_scene

    !> Write the cells as columns, with the scene in the header.
    subroutine write_map(path, map, exponent, amplitude, duration, error)
        character(len=*), intent(in) :: path
        type(stability_cell), intent(in) :: map(:)
        real(dp), intent(in) :: exponent, amplitude, duration
        type(error_type), allocatable, intent(out) :: error

        character(len=150) :: comments(7)
        real(dp), allocatable :: table(:, :)
        integer :: slash

        comments(1) = 'greenconv contact stability map: explicit and implicit contact steps, exact engine'
        comments(2) = 'scene: M = 1 kg, K = 1e6 N/m, xi = 0.02, road A0*sin(100 t), A0 = '//sci_text(amplitude) &
                      //' m, preload M*g, F = k_c*delta^p, p = '//sci_text(exponent)
        comments(3) = 'simulated time: '//sci_text(duration)//' s down to a multiple of the largest dt'
        comments(4) = 'omega_c_dt = sqrt(k_c''/M)*dt, k_c'' = p*k_c*delta0^(p-1); bounded = 1: no divergence fault'
        comments(5) = 'error: relative L2 error of u against the implicit step at a fine dt_ref; -1: diverged'
        comments(6) = 'units: s N/m^p 1 1 1 1 1'
        comments(7) = 'dt k_c omega_c_dt explicit_bounded explicit_error implicit_bounded implicit_error'
        allocate (table(size(map), 7))
        table(:, 1) = map%dt
        table(:, 2) = map%stiffness
        table(:, 3) = map%omega_dt
        table(:, 4) = merge(1.0_dp, 0.0_dp, map%explicit_bounded)
        table(:, 5) = map%explicit_error
        table(:, 6) = merge(1.0_dp, 0.0_dp, map%implicit_bounded)
        table(:, 7) = map%implicit_error
        slash = index(path, '/', back=.true.)
        if (slash > 1) then
            call make_directory(path(1:slash - 1), error)
            if (allocated(error)) return
        end if
        call write_columns(path, comments, table, error)
    end subroutine write_map

end module bench_contact_stability_mod
