!> Speed against accuracy: the error of every convolution method against the
!> independent reference (`contact_reference`: the modal state-space ODE, adaptive
!> Dormand-Prince at rtol 1e-10) next to the CPU time of its contact run, while the time
!> step, the N_g truncation tolerance and (for the identified structure) the number of
!> modes are swept; and the error that truncating a lightly damped g costs `direct`.
!>
!> Every run of a scene covers the scene's own duration N_t*dt. The time steps are the
!> scene's dt times 4, 2, 1, 1/2, 1/4 and 1/8, so that all grids nest in the finest one; the
!> reference is computed once on it and read every 2^k samples for the coarser grids. A
!> run's CPU time is `contact_seconds` repeated to at least 0.05 s of CPU (the tables use
!> 0.25 s; the chart has about 130 runs).
!>
!> The mode sweep (identified structures) re-identifies the structure by LSCE with 1 .. 10
!> modes asked, each scan capped at the order the scene's own identification stopped at.
!> It takes most of the chart's time: a scan that never finds exactly the modes asked runs
!> to the cap and keeps its best fit (on the section 3.2 scene: 10 modes when 3, 4, 6-9 are
!> asked).
!>
!> Files, written atomically with `#` header lines (description, units, column names):
!>
!> - `accuracy_<tag>.dat` (tag `sdof`, `mdof`): one row per run, columns
!>   `sweep method dt n_steps n_g n_m order tol cpu_s err_u err_f fit_e paper`. `sweep` is
!>   1 (time step), 2 (N_g tolerance) or 3 (number of modes); `method` is 1 direct, 2 fft,
!>   3 recursive, 4 paper, 5 exact. The rows of one (sweep, method) series are consecutive,
!>   so gnuplot draws a series by testing these two columns. `paper` is 1 on the paper's
!>   own setting (its two methods, direct and paper, at the scene's dt with the 1 % rule).
!> - `truncation.dat`: `direct` on a lightly damped oscillator against the untruncated sum
!>   and against the ODE reference, one row per truncation tolerance.
module bench_accuracy_mod
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error, stat_numerical
    use greenconv_conv_convolver, only: convolver, free_convolver
    use greenconv_conv_direct, only: new_direct_convolver
    use greenconv_conv_kernel, only: sample_kernel
    use greenconv_contact_single, only: contact_response, run_contact
    use verify_contact_mod, only: contact_reference
    use greenconv_scene_read_input, only: scene_type
    use greenconv_ident_structure, only: structure_model
    use greenconv_scene_models_structure, only: build_structure
    use greenconv_scene_run_runner, only: make_convolver
    use greenconv_io_files, only: write_columns, make_directory
    use bench_tables_mod, only: load_scene
    use bench_timing_mod, only: contact_seconds
    implicit none
    private

    public :: accuracy_charts

    !> Methods, numbered by their position (the `method` column).
    character(len=9), parameter :: methods(5) = [character(len=9) :: 'direct', 'fft', 'recursive', 'paper', 'exact']
    !> Methods of the N_g sweep (a truncated kernel) and of the mode sweep, by number.
    integer, parameter :: kernel_methods(2) = [1, 2], mode_methods(2) = [3, 5]
    !> Codes of the `sweep` column.
    integer, parameter :: sweep_dt = 1, sweep_tolerance = 2, sweep_order = 3
    !> Names of the sweeps, for the summary.
    character(len=5), parameter :: sweep_names(3) = [character(len=5) :: 'dt', 'N_g', 'modes']
    !> Time steps of the dt sweep as multiples of the finest one, which is the scene's dt/8.
    integer, parameter :: strides(6) = [32, 16, 8, 4, 2, 1], fine_division = 8
    !> Truncation tolerances of the N_g sweep (fractions of max|g|; 0 keeps the whole run).
    real(dp), parameter :: tolerances(8) = [0.3_dp, 0.1_dp, 0.03_dp, 0.01_dp, 0.003_dp, 1.0e-3_dp, 1.0e-4_dp, 0.0_dp]
    !> Numbers of modes of the order sweep: 1 .. max_modes.
    integer, parameter :: max_modes = 10
    !> Error levels the summary looks for the cheapest run to reach.
    real(dp), parameter :: targets(2) = [1.0e-3_dp, 1.0e-5_dp]
    !> Shortest CPU time [s] each timed run is repeated to.
    real(dp), parameter :: repeat_seconds = 0.05_dp
    !> Relative tolerance of the ODE reference.
    real(dp), parameter :: reference_rtol = 1.0e-10_dp
    !> The truncation study: damping ratio, duration [s] and tolerances.
    real(dp), parameter :: light_damping = 0.002_dp, truncation_duration = 6.0_dp
    real(dp), parameter :: truncation_tols(15) = [0.5_dp, 0.2_dp, 0.1_dp, 0.05_dp, 0.02_dp, 0.01_dp, 5.0e-3_dp, &
                                                  2.0e-3_dp, 1.0e-3_dp, 5.0e-4_dp, 2.0e-4_dp, 1.0e-4_dp, 5.0e-5_dp, &
                                                  2.0e-5_dp, 1.0e-5_dp]

    !> The reference run on the finest grid.
    type :: reference_run
        !> Its time step [s].
        real(dp) :: dt = 0.0_dp
        !> u(t_n) [m] and F(t_n) [N], n = 0..N-1.
        real(dp), allocatable :: u(:), f(:)
    end type reference_run

    !> One contact run of the chart: its setting, CPU time and errors.
    type :: accuracy_point
        !> Sweep and method codes, steps N_t, kernel length N_g (direct, fft), modes N_m
        !> (modal methods) and modes asked of LSCE (mode sweep), 0 where they do not apply.
        integer :: sweep = 0, method = 0, n_steps = 0, n_g = 0, n_m = 0, order = 0
        !> Time step [s], truncation tolerance, CPU seconds [s] of one run, relative L2 errors
        !> of u and F, E of eq. (7) of the modes used (0: not identified).
        real(dp) :: dt = 0.0_dp, tol = 0.0_dp, seconds = 0.0_dp, err_u = 0.0_dp, err_f = 0.0_dp, fit_e = 0.0_dp
        !> Whether this is the paper's setting.
        logical :: paper = .false.
    end type accuracy_point

contains

    !> Run the sweeps on both scenes and the truncation study, write their column files to
    !> `dir` (created if missing) and print the cheapest run per method and error level on
    !> `unit`.
    subroutine accuracy_charts(unit, dir, sdof_file, mdof_file, error)
        !> Unit the summary is printed on.
        integer, intent(in) :: unit
        !> Directory of the column files (out/bench).
        character(len=*), intent(in) :: dir
        !> Scene files of sections 3.1 and 3.2.
        character(len=*), intent(in) :: sdof_file, mdof_file
        !> Set when a scene cannot be read or built, or a file cannot be written.
        type(error_type), allocatable, intent(out) :: error

        call make_directory(dir, error)
        if (allocated(error)) return
        call scene_chart(unit, sdof_file, 'section 3.1, SDOF on the sine road', dir//'/accuracy_sdof.dat', error)
        if (allocated(error)) return
        call scene_chart(unit, mdof_file, 'section 3.2, 10 random modes identified by LSCE, random road', &
                         dir//'/accuracy_mdof.dat', error)
        if (allocated(error)) return
        call truncation_chart(unit, sdof_file, dir//'/truncation.dat', error)
    end subroutine accuracy_charts

    !> All sweeps of one scene, its file and its summary.
    subroutine scene_chart(unit, path, title, file, error)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: path, title, file
        type(error_type), allocatable, intent(out) :: error

        type(scene_type) :: scene
        type(structure_model) :: structure
        type(reference_run) :: reference
        type(accuracy_point), allocatable :: points(:)

        call load_scene(path, scene, structure, error)
        if (allocated(error)) return
        reference%dt = scene%dt/fine_division
        call contact_reference(structure%exact, scene%law, scene%road, scene%preload, reference%dt, &
                               scene%n_steps*fine_division, reference%u, reference%f, reference_rtol)
        call run_sweeps(scene, structure, reference, points, error)
        if (allocated(error)) return
        call write_points(file, title, scene, points, error)
        if (allocated(error)) return
        call print_summary(unit, title, scene, reference, points)
    end subroutine scene_chart

    !> The three sweeps of a scene: dt, N_g tolerance and (identified structures) modes.
    subroutine run_sweeps(scene, structure, reference, points, error)
        type(scene_type), intent(inout) :: scene
        type(structure_model), intent(in) :: structure
        type(reference_run), intent(in) :: reference
        type(accuracy_point), allocatable, intent(out) :: points(:)
        type(error_type), allocatable, intent(out) :: error

        integer :: m, k

        allocate (points(0))
        ! dt: every method, direct and fft truncated by the scene's rule.
        do m = 1, size(methods)
            call run_sweep(sweep_dt, m, strides*reference%dt, [(scene%truncation_tol, k=1, size(strides))], scene, &
                           structure, reference, points, error)
            if (allocated(error)) return
        end do
        ! The N_g tolerance: direct and fft at the scene's dt.
        do m = 1, size(kernel_methods)
            call run_sweep(sweep_tolerance, kernel_methods(m), [(scene%dt, k=1, size(tolerances))], tolerances, &
                           scene, structure, reference, points, error)
            if (allocated(error)) return
        end do
        where (points%sweep == sweep_dt .and. abs(points%dt - scene%dt) < 1.0e-3_dp*scene%dt &
               .and. (methods(points%method) == 'direct' .or. methods(points%method) == 'paper')) points%paper = .true.
        if (structure%identified) call run_order_sweep(scene, structure, reference, points, error)
    end subroutine run_sweeps

    !> Method number m at each (time step [s], truncation tolerance) pair, appended as
    !> points of the sweep `code`.
    subroutine run_sweep(code, m, dts, tols, scene, structure, reference, points, error)
        integer, intent(in) :: code, m
        real(dp), intent(in) :: dts(:), tols(:)
        type(scene_type), intent(in) :: scene
        type(structure_model), intent(in) :: structure
        type(reference_run), intent(in) :: reference
        type(accuracy_point), allocatable, intent(inout) :: points(:)
        type(error_type), allocatable, intent(out) :: error

        type(accuracy_point) :: point
        integer :: k

        do k = 1, size(dts)
            call measure(m, scene, structure, dts(k), tols(k), reference, point, error)
            if (allocated(error)) return
            point%sweep = code
            points = [points, point]
        end do
    end subroutine run_sweep

    !> recursive and exact at the scene's dt on LSCE models asked for 1 .. max_modes modes.
    !>
    !> The scan of each identification is capped at the order that the scene's own
    !> identification (`structure`) stopped at: LSCE stops at the first order whose stable
    !> poles number exactly the modes asked, and when no order up to the cap has that many it
    !> keeps the best fit it saw, whose number of modes (`n_m`) is then not the one asked.
    subroutine run_order_sweep(scene, structure, reference, points, error)
        type(scene_type), intent(inout) :: scene
        type(structure_model), intent(in) :: structure
        type(reference_run), intent(in) :: reference
        type(accuracy_point), allocatable, intent(inout) :: points(:)
        type(error_type), allocatable, intent(out) :: error

        type(structure_model), allocatable :: models(:)
        type(accuracy_point) :: point
        integer :: order, saved_order, saved_cap, i

        saved_order = scene%order
        saved_cap = scene%max_order
        allocate (models(max_modes))
        do order = 1, max_modes
            scene%order = order
            scene%max_order = max(order, structure%fit%order_modes)
            call build_structure(scene, models(order), error)
            if (allocated(error)) exit
        end do
        scene%order = saved_order
        scene%max_order = saved_cap
        if (allocated(error)) return
        do i = 1, size(mode_methods)
            do order = 1, max_modes
                call measure(mode_methods(i), scene, models(order), scene%dt, scene%truncation_tol, reference, point, &
                             error)
                if (allocated(error)) return
                point%sweep = sweep_order
                point%order = order
                points = [points, point]
            end do
        end do
    end subroutine run_order_sweep

    !> One timed contact run of method number m at time step dt, and its errors.
    subroutine measure(m, scene, structure, dt, tol, reference, point, error)
        integer, intent(in) :: m
        type(scene_type), intent(in) :: scene
        type(structure_model), intent(in) :: structure
        real(dp), intent(in) :: dt, tol
        type(reference_run), intent(in) :: reference
        type(accuracy_point), intent(out) :: point
        type(error_type), allocatable, intent(out) :: error

        class(convolver), allocatable :: conv
        type(contact_response) :: response
        character(len=:), allocatable :: accuracy, label
        real(dp), allocatable :: road(:)
        integer :: stride, size_of_model

        stride = nint(dt/reference%dt)
        point%method = m
        point%dt = dt
        point%tol = tol
        point%n_steps = scene%n_steps*fine_division/stride
        call make_convolver(trim(methods(m)), structure, dt, tol, point%n_steps, conv, accuracy, error)
        if (allocated(error)) return
        allocate (road(point%n_steps))
        road(:) = scene%road%sample(dt, point%n_steps)
        point%seconds = contact_seconds(conv, scene%law, road, scene%preload, response, repeat_seconds)
        call conv%model_size(size_of_model, label)
        if (label == 'N_g') point%n_g = size_of_model
        if (label == 'N_m') point%n_m = size_of_model
        if (label == 'N_m' .and. structure%identified) point%fit_e = structure%fit%e
        call free_convolver(conv)
        point%err_u = relative_l2(response%displacement, reference%u(::stride))
        point%err_f = relative_l2(response%force, reference%f(::stride))
        if (.not. (ieee_is_finite(point%err_u) .and. ieee_is_finite(point%err_f))) then
            call fatal_error(error, 'accuracy chart: '//trim(methods(m))//' diverged', stat_numerical)
        end if
    end subroutine measure

    !> ||x - reference||_2/||reference||_2.
    pure real(dp) function relative_l2(x, reference)
        real(dp), intent(in) :: x(:), reference(:)

        relative_l2 = norm2(x - reference)/norm2(reference)
    end function relative_l2

    !> The chart's column file of one scene.
    subroutine write_points(file, title, scene, points, error)
        character(len=*), intent(in) :: file, title
        type(scene_type), intent(in) :: scene
        type(accuracy_point), intent(in) :: points(:)
        type(error_type), allocatable, intent(out) :: error

        character(len=200) :: comments(6)
        real(dp), allocatable :: table(:, :)
        integer :: i

        write (comments(1), '(a,g0.3,a)') 'greenconv-bench speed against accuracy, '//title//', ', &
            scene%n_steps*scene%dt, ' s simulated'
        write (comments(2), '(a,es8.1,a)') 'err_u, err_f: relative L2 error of u and F against the modal ODE ' &
            //'(Dormand-Prince, rtol', reference_rtol, '); cpu_s: CPU time of one contact run'
        comments(3) = 'sweep: 1 dt, 2 N_g tolerance, 3 modes; method: 1 direct, 2 fft, 3 recursive, 4 paper, 5 exact;'
        comments(4) = 'order: modes asked of LSCE (sweep 3); fit_e: E of eq. (7) (0: not identified); ' &
                      //'paper: 1 on the paper''s setting'
        comments(5) = 'units: - - s - - - - - s - - - -'
        comments(6) = 'sweep method dt n_steps n_g n_m order tol cpu_s err_u err_f fit_e paper'
        allocate (table(size(points), 13))
        do i = 1, size(points)
            associate (p => points(i))
                table(i, :) = [real(p%sweep, dp), real(p%method, dp), p%dt, real(p%n_steps, dp), real(p%n_g, dp), &
                               real(p%n_m, dp), real(p%order, dp), p%tol, p%seconds, p%err_u, p%err_f, p%fit_e, &
                               merge(1.0_dp, 0.0_dp, p%paper)]
            end associate
        end do
        call write_columns(file, comments, table, error)
    end subroutine write_points

    !> Per method: the order of convergence in dt at the scene's dt, and the cheapest run
    !> (over all its sweeps) whose error of u reaches each target.
    subroutine print_summary(unit, title, scene, reference, points)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: title
        type(scene_type), intent(in) :: scene
        type(reference_run), intent(in) :: reference
        type(accuracy_point), intent(in) :: points(:)

        integer :: m, t

        write (unit, '(a,g0.3,a,f6.4,a)') '# Speed against accuracy ('//title//'), ', scene%n_steps*scene%dt, &
            ' s; reference: modal ODE by Dormand-Prince, rtol 1e-10, at dt ', reference%dt*1.0e3_dp, ' ms'
        write (unit, '(a)') '# per method and target, the cheapest run (over all sweeps) whose relative L2 error of u' &
            //' over the run is <= target,', &
            '# or the most accurate run, marked (not reached); p_dt: log2 err_u(2 dt)/err_u(dt) at the scene''s dt', &
            '# method      p_dt  target     cpu_s     err_u     err_f  sweep    dt_ms     N_g  N_m        E'
        do m = 1, size(methods)
            do t = 1, size(targets)
                call print_cheapest(unit, m, dt_order(m, scene%dt, points), targets(t), points)
            end do
        end do
        if (any(points%sweep == sweep_order)) call print_orders(unit, points)
        write (unit, '(a)') ''
    end subroutine print_summary

    !> The order sweep: per number of modes asked, the modes kept, E and the errors of u.
    subroutine print_orders(unit, points)
        integer, intent(in) :: unit
        type(accuracy_point), intent(in) :: points(:)

        integer :: order, i, recursive, exact

        write (unit, '(a)') '# modes asked of LSCE: modes kept (N_m), E of eq. (7), err_u of recursive and exact', &
            '# asked  N_m         E  err_u_recursive  err_u_exact'
        do order = 1, max_modes
            recursive = 0
            exact = 0
            do i = 1, size(points)
                if (points(i)%sweep /= sweep_order .or. points(i)%order /= order) cycle
                if (points(i)%method == mode_methods(1)) recursive = i
                if (points(i)%method == mode_methods(2)) exact = i
            end do
            if (recursive == 0 .or. exact == 0) cycle
            write (unit, '(i7,i5,es10.2,es17.2,es13.2)') order, points(recursive)%n_m, points(recursive)%fit_e, &
                points(recursive)%err_u, points(exact)%err_u
        end do
    end subroutine print_orders

    !> log2(err_u(2 dt)/err_u(dt)) of method m in the dt sweep.
    pure real(dp) function dt_order(m, dt, points) result(order)
        integer, intent(in) :: m
        real(dp), intent(in) :: dt
        type(accuracy_point), intent(in) :: points(:)

        real(dp) :: coarse, fine
        integer :: i

        coarse = 0.0_dp
        fine = 0.0_dp
        do i = 1, size(points)
            if (points(i)%sweep /= sweep_dt .or. points(i)%method /= m) cycle
            if (abs(points(i)%dt - dt) < 1.0e-3_dp*dt) fine = points(i)%err_u
            if (abs(points(i)%dt - 2*dt) < 1.0e-3_dp*dt) coarse = points(i)%err_u
        end do
        order = log(coarse/fine)/log(2.0_dp)
    end function dt_order

    !> One summary line: the cheapest run of method m with err_u <= target, or, when none
    !> reaches it, the most accurate one, flagged.
    subroutine print_cheapest(unit, m, order, target, points)
        integer, intent(in) :: unit, m
        real(dp), intent(in) :: order, target
        type(accuracy_point), intent(in) :: points(:)

        character(len=*), parameter :: row = '(a,t12,f6.2,es8.1,3es10.2,2x,a5,f9.4,i8,i5,es9.1,a)'
        integer :: i, best
        logical :: reached

        best = 0
        reached = .false.
        do i = 1, size(points)
            if (points(i)%method /= m) cycle
            if (points(i)%err_u <= target) then
                if (.not. reached) best = i
                if (points(i)%seconds < points(best)%seconds) best = i
                reached = .true.
            else if (.not. reached) then
                if (best == 0) best = i
                if (points(i)%err_u < points(best)%err_u) best = i
            end if
        end do
        associate (p => points(best))
            write (unit, row) trim(methods(m)), order, target, p%seconds, p%err_u, p%err_f, sweep_names(p%sweep), &
                p%dt*1.0e3_dp, p%n_g, p%n_m, p%fit_e, merge('               ', '  (not reached)', reached)
        end associate
    end subroutine print_cheapest

    !> `direct` on the SDOF scene made lightly damped and long: its error at each
    !> truncation tolerance against the untruncated sum and against the ODE reference.
    subroutine truncation_chart(unit, path, file, error)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: path, file
        type(error_type), allocatable, intent(out) :: error

        type(scene_type) :: scene
        type(structure_model) :: structure
        type(contact_response) :: full, cut
        real(dp), allocatable :: road(:), u_ref(:), f_ref(:), table(:, :)
        real(dp) :: tail
        integer :: n_steps, k, n_g

        call load_scene(path, scene, structure, error)
        if (allocated(error)) return
        scene%damping_ratio = light_damping
        call build_structure(scene, structure, error)
        if (allocated(error)) return
        n_steps = nint(truncation_duration/scene%dt)
        allocate (road(n_steps), table(size(truncation_tols), 8))
        road(:) = scene%road%sample(scene%dt, n_steps)
        call contact_reference(structure%exact, scene%law, scene%road, scene%preload, scene%dt, n_steps, u_ref, &
                               f_ref, reference_rtol)
        call direct_run(structure, scene, road, 0.0_dp, full, n_g, tail)
        do k = 1, size(truncation_tols)
            call direct_run(structure, scene, road, truncation_tols(k), cut, n_g, tail)
            table(k, :) = [truncation_tols(k), real(n_g, dp), n_g*scene%dt, tail, &
                           relative_l2(cut%displacement, full%displacement), relative_l2(cut%force, full%force), &
                           relative_l2(cut%displacement, u_ref), relative_l2(cut%force, f_ref)]
        end do
        call write_truncation(file, scene, n_steps, table, error)
        if (allocated(error)) return
        call print_truncation(unit, scene, n_steps, relative_l2(full%displacement, u_ref), table)
    end subroutine truncation_chart

    !> One contact run of `direct` with the kernel cut at tol (0: the whole run).
    subroutine direct_run(structure, scene, road, tol, response, n_g, tail)
        type(structure_model), intent(in) :: structure
        type(scene_type), intent(in) :: scene
        real(dp), intent(in) :: road(:), tol
        type(contact_response), intent(out) :: response
        integer, intent(out) :: n_g
        real(dp), intent(out) :: tail

        class(convolver), allocatable :: conv
        real(dp), allocatable :: kernel(:)

        call sample_kernel(structure%exact, scene%dt, tol, size(road), kernel, tail)
        n_g = size(kernel) - 1
        conv = new_direct_convolver(kernel, scene%dt)
        call run_contact(conv, scene%law, road, scene%preload, response)
    end subroutine direct_run

    !> The truncation study's column file.
    subroutine write_truncation(file, scene, n_steps, table, error)
        character(len=*), intent(in) :: file
        type(scene_type), intent(in) :: scene
        integer, intent(in) :: n_steps
        real(dp), intent(in) :: table(:, :)
        type(error_type), allocatable, intent(out) :: error

        character(len=200) :: comments(5)

        write (comments(1), '(a,f5.3,a,g0.3,a,f4.2,a,i0,a)') 'greenconv-bench truncation of a lightly damped g, ' &
            //'method direct: SDOF scene with xi = ', scene%damping_ratio, ', ', n_steps*scene%dt, ' s at dt = ', &
            scene%dt*1.0e3_dp, ' ms (', n_steps, ' steps)'
        comments(2) = 'err_*_full: relative L2 error against the untruncated direct sum; err_*_ref: against ' &
                      //'the modal ODE (rtol 1e-10)'
        comments(3) = 't_g = N_g*dt; tail: largest neglected |g|/max|g| within the run'
        comments(4) = 'units: - - s - - - - -'
        comments(5) = 'tol n_g t_g tail err_u_full err_f_full err_u_ref err_f_ref'
        call write_columns(file, comments, table, error)
    end subroutine write_truncation

    !> The truncation study as a table on `unit`.
    subroutine print_truncation(unit, scene, n_steps, floor, table)
        integer, intent(in) :: unit
        type(scene_type), intent(in) :: scene
        integer, intent(in) :: n_steps
        real(dp), intent(in) :: floor
        real(dp), intent(in) :: table(:, :)

        integer :: k

        write (unit, '(a,f5.3,a,g0.3,a,f4.2,a,es8.2)') '# Truncating a lightly damped g: SDOF scene with xi = ', &
            scene%damping_ratio, ', ', n_steps*scene%dt, ' s at dt ', scene%dt*1.0e3_dp, &
            ' ms, direct; untruncated direct against the ODE: err_u ', floor
        write (unit, '(a)') '# relative L2 errors of u and F against the untruncated direct sum (full) and the ODE' &
            //' (ref)', &
            '#      tol     N_g   t_g_s   err_u_full err_f_full  err_u_ref  err_f_ref'
        do k = 1, size(table, 1)
            write (unit, '(es10.1,i8,f8.3,4es11.2)') table(k, 1), nint(table(k, 2)), table(k, 3), table(k, 5:8)
        end do
        write (unit, '(a)') ''
    end subroutine print_truncation

end module bench_accuracy_mod
