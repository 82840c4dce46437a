!> The paper's timing tables, reproduced in one run: Tab. 2 (the SDOF scene of section 3.1
!> at two time steps and four run lengths) and Tab. 3 (the multi-mode scene of section 3.2),
!> then the speed targets as ratios measured in this same run.
!>
!> Every time is the CPU time of a whole contact run (`run_contact`: history, contact law,
!> push, stored histories), as in the paper, averaged over repeats of at least 0.25 s.
module bench_tables_mod
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_conv_convolver, only: convolver, free_convolver
    use greenconv_conv_direct, only: new_direct_convolver
    use greenconv_conv_kernel, only: lane_dot
    use greenconv_conv_paper, only: new_paper_convolver
    use greenconv_conv_recursive, only: new_recursive_convolver
    use greenconv_conv_fft, only: new_fft_convolver
    use greenconv_contact_single, only: contact_response
    use greenconv_scene_read_input, only: scene_type, read_scene
    use greenconv_ident_structure, only: structure_model
    use greenconv_scene_models_structure, only: build_structure
    use greenconv_scene_run_runner, only: make_convolver
    use bench_timing_mod, only: contact_seconds, step_seconds
    implicit none
    private

    public :: print_tables, load_scene, verdict

    !> Methods timed in the tables, in column order.
    character(len=9), parameter :: methods(5) = [character(len=9) :: 'direct', 'fft', 'recursive', 'paper', 'exact']

contains

    !> Print Tabs. 2 and 3 and the targets on `unit`; `sdof_file`, `mdof_file` are the
    !> shipped scenes (data/sdof_sine.nml, data/mdof_random.nml).
    subroutine print_tables(unit, sdof_file, mdof_file, error)
        !> Unit the tables are printed on.
        integer, intent(in) :: unit
        !> Scene files of sections 3.1 and 3.2.
        character(len=*), intent(in) :: sdof_file, mdof_file
        !> Set when a scene cannot be read or built.
        type(error_type), allocatable, intent(out) :: error

        type(scene_type) :: scene
        type(structure_model) :: structure

        call load_scene(sdof_file, scene, structure, error)
        if (allocated(error)) return
        call print_table2(unit, scene, structure, error)
        if (allocated(error)) return
        call print_targets(unit, scene, structure)
        call load_scene(mdof_file, scene, structure, error)
        if (allocated(error)) return
        call print_table3(unit, scene, structure, error)
    end subroutine print_tables

    !> Read a scene file and build its structure (identifying it when the scene says so).
    subroutine load_scene(path, scene, structure, error)
        !> Scene file.
        character(len=*), intent(in) :: path
        !> The scene.
        type(scene_type), intent(out) :: scene
        !> Its structure.
        type(structure_model), intent(out) :: structure
        !> Set when the scene cannot be read or built.
        type(error_type), allocatable, intent(out) :: error

        call read_scene(path, scene, error)
        if (allocated(error)) return
        call build_structure(scene, structure, error)
    end subroutine load_scene

    !> Tab. 2: the SDOF scene at (dt, N_t) = (0.1 ms, 2000), (0.1 ms, 20000), (0.01 ms, 20000),
    !> (0.01 ms, 200000), N_g from the scene's truncation rule, next to the paper's times.
    subroutine print_table2(unit, scene, structure, error)
        integer, intent(in) :: unit
        type(scene_type), intent(in) :: scene
        type(structure_model), intent(in) :: structure
        type(error_type), allocatable, intent(out) :: error

        real(dp), parameter :: row_dt(4) = [1.0e-4_dp, 1.0e-4_dp, 1.0e-5_dp, 1.0e-5_dp]
        integer, parameter :: row_steps(4) = [2000, 20000, 20000, 200000]
        ! The paper's Tab. 2: N_g, standard and modal times [s] (its machine, 2011).
        integer, parameter :: paper_ng(4) = [1900, 1900, 19000, 19000]
        real(dp), parameter :: paper_direct(4) = [0.06_dp, 1.01_dp, 5.50_dp, 105.14_dp]
        real(dp), parameter :: paper_modal(4) = [0.02_dp, 0.10_dp, 0.15_dp, 1.50_dp]
        real(dp) :: seconds(size(methods))
        integer :: row, n_g, n_m

        write (unit, '(a)') '# Tab. 2 (section 3.1, SDOF on the sine road): CPU seconds of one contact run', &
            '# columns 8-9: the paper''s N_g and its standard/modal times (2011); ratios from this run', &
            '# dt_ms      N_t    N_g  direct_s     fft_s recursive_s   paper_s   exact_s  paper_N_g' &
            //' paper_std_s paper_modal_s direct/recursive direct/fft paper/recursive'
        do row = 1, size(row_dt)
            call time_methods(scene, structure, row_dt(row), row_steps(row), seconds, n_g, n_m, error)
            if (allocated(error)) return
            write (unit, '(f6.2,i9,i7,5es10.2,i11,2f12.2,f17.1,f11.1,f16.2)') row_dt(row)*1.0e3_dp, row_steps(row), &
                n_g, seconds, paper_ng(row), paper_direct(row), paper_modal(row), seconds(1)/seconds(3), &
                seconds(1)/seconds(2), seconds(4)/seconds(3)
        end do
        write (unit, '(a)') ''
    end subroutine print_table2

    !> Tab. 3: the multi-mode scene at its own dt and N_t, N_m identified by LSCE.
    subroutine print_table3(unit, scene, structure, error)
        integer, intent(in) :: unit
        type(scene_type), intent(in) :: scene
        type(structure_model), intent(in) :: structure
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: seconds(size(methods))
        integer :: n_g, n_m

        write (unit, '(a)') '# Tab. 3 (section 3.2, 10 random modes identified by LSCE, random road): CPU seconds', &
            '# the paper: dt 0.1 ms, N_t 10000, N_g 2930 standard 1.14 s, N_m 10 modal 0.23 s (ratio 5.0)', &
            '# dt_ms      N_t    N_g  N_m  direct_s     fft_s recursive_s   paper_s   exact_s' &
            //' direct/recursive direct/fft paper/recursive'
        call time_methods(scene, structure, scene%dt, scene%n_steps, seconds, n_g, n_m, error)
        if (allocated(error)) return
        write (unit, '(f6.2,i9,i7,i5,5es10.2,f17.1,f11.1,f16.2)') scene%dt*1.0e3_dp, scene%n_steps, n_g, n_m, &
            seconds, seconds(1)/seconds(3), seconds(1)/seconds(2), seconds(4)/seconds(3)
        write (unit, '(a)') ''
    end subroutine print_table3

    !> CPU seconds of one contact run of the scene with each method at (dt, n_steps).
    subroutine time_methods(scene, structure, dt, n_steps, seconds, n_g, n_m, error)
        type(scene_type), intent(in) :: scene
        type(structure_model), intent(in) :: structure
        real(dp), intent(in) :: dt
        integer, intent(in) :: n_steps
        real(dp), intent(out) :: seconds(:)
        integer, intent(out) :: n_g, n_m
        type(error_type), allocatable, intent(out) :: error

        class(convolver), allocatable :: conv
        type(contact_response) :: response
        character(len=:), allocatable :: accuracy, label
        real(dp), allocatable :: road(:)
        integer :: i, n

        allocate (road(n_steps))
        road(:) = scene%road%sample(dt, n_steps)
        n_g = 0
        n_m = 0
        do i = 1, size(methods)
            call make_convolver(trim(methods(i)), structure, dt, scene%truncation_tol, n_steps, conv, accuracy, error)
            if (allocated(error)) return
            seconds(i) = contact_seconds(conv, scene%law, road, scene%preload, response)
            call conv%model_size(n, label)
            if (label == 'N_g') n_g = n
            if (label == 'N_m') n_m = n
            call free_convolver(conv)
        end do
    end subroutine time_methods

    !> The speed targets, each a ratio measured here, with the paper's N_g = 19000 at
    !> dt = 0.01 ms, N_t = 200000 on the SDOF scene.
    subroutine print_targets(unit, scene, structure)
        integer, intent(in) :: unit
        type(scene_type), intent(in) :: scene
        type(structure_model), intent(in) :: structure

        integer, parameter :: n_steps = 200000, n_g = 19000
        real(dp), parameter :: dt = 1.0e-5_dp
        class(convolver), allocatable :: direct, fft, recursive, paper
        type(contact_response) :: r_direct, r_fft, r_recursive, r_paper
        real(dp), allocatable :: kernel(:), road(:)
        real(dp) :: t_direct, t_fft, t_recursive, t_paper, s_recursive, s_paper, s_direct, mac_direct, mac_dot
        integer :: j

        allocate (kernel(0:n_g), road(n_steps))
        kernel(:) = structure%exact%impulse([(j*dt, j=0, n_g)])
        road(:) = scene%road%sample(dt, n_steps)
        direct = new_direct_convolver(kernel, dt)
        fft = new_fft_convolver(kernel, dt)
        recursive = new_recursive_convolver(structure%model, dt)
        paper = new_paper_convolver(structure%model, dt)
        t_direct = contact_seconds(direct, scene%law, road, scene%preload, r_direct)
        t_fft = contact_seconds(fft, scene%law, road, scene%preload, r_fft)
        t_recursive = contact_seconds(recursive, scene%law, road, scene%preload, r_recursive)
        t_paper = contact_seconds(paper, scene%law, road, scene%preload, r_paper)
        ! Bare steps over the same run length: the direct history sums min(n, N_g) products
        ! at step n, which is what its MAC rate counts.
        s_direct = step_seconds(direct, n_steps)
        s_recursive = step_seconds(recursive, n_steps)
        s_paper = step_seconds(paper, n_steps)
        mac_direct = (0.5_dp*n_g*(n_g - 1.0_dp) + real(n_steps - n_g, dp)*n_g)/(s_direct*n_steps)
        mac_dot = plain_dot_rate(n_g)
        write (unit, '(a)') '# Targets (SDOF scene, dt 0.01 ms, N_t 200000, the paper''s N_g = 19000), this run:'
        call verdict(unit, 'recursive vs direct, whole contact run', t_direct/t_recursive, 300.0_dp)
        call verdict(unit, 'recursive vs direct, convolution alone per step', s_direct/s_recursive, 300.0_dp)
        call verdict(unit, 'fft vs direct, whole contact run', t_direct/t_fft, 20.0_dp)
        write (unit, '(a,es9.2)') '#   fft vs direct: max|u_fft - u_direct|/max|u_direct| = ', &
            maxval(abs(r_fft%displacement - r_direct%displacement))/maxval(abs(r_direct%displacement))
        call verdict(unit, 'recursive vs paper per step, convolution alone', s_paper/s_recursive, 4.0_dp)
        call verdict(unit, 'recursive vs paper, whole contact run', t_paper/t_recursive, 4.0_dp)
        write (unit, '(a,es9.2)') '#   recursive vs paper: max|u_rec - u_paper|/max|u_paper| = ', &
            maxval(abs(r_recursive%displacement - r_paper%displacement))/maxval(abs(r_paper%displacement))
        write (unit, '(a,2(f6.2,a))') '#   direct history: ', mac_direct*1.0e-9_dp, &
            ' GMAC/s; plain vectorised dot product: ', mac_dot*1.0e-9_dp, &
            ' GMAC/s (best of dot_product, BLAS ddot, 8-lane loop)'
        call verdict(unit, 'direct MAC rate vs the plain dot product', mac_direct/mac_dot, 0.5_dp)
        write (unit, '(a,3(f9.1,a))') '#   mean CPU per step, convolution alone: direct ', s_direct*1.0e9_dp, &
            ' ns, recursive ', s_recursive*1.0e9_dp, ' ns, paper ', s_paper*1.0e9_dp, ' ns'
        write (unit, '(a,3(f9.1,a))') '#   mean CPU per step, whole contact run: direct ', t_direct/n_steps*1.0e9_dp, &
            ' ns, recursive ', t_recursive/n_steps*1.0e9_dp, ' ns, paper ', t_paper/n_steps*1.0e9_dp, ' ns'
        write (unit, '(a)') ''
        call free_convolver(fft)
    end subroutine print_targets

    !> One line: what is compared, the measured ratio, the target and whether it is met.
    subroutine verdict(unit, what, ratio, target)
        !> Unit the line is printed on.
        integer, intent(in) :: unit
        !> What is compared.
        character(len=*), intent(in) :: what
        !> The measured ratio and its target.
        real(dp), intent(in) :: ratio, target

        character(len=*), parameter :: yes = 'met', no = 'NOT met'

        write (unit, '(a,t64,f9.2,a,f7.2,a)') '#   '//what//':', ratio, 'x  (target >= ', target, &
            'x: '//merge(yes//'    ', no, ratio >= target)//')'
    end subroutine verdict

    !> Multiply-adds per second [1/s] of the fastest plain dot product of length n on two
    !> fixed arrays: the intrinsic dot_product, BLAS ddot or an 8-lane loop.
    function plain_dot_rate(n) result(rate)
        integer, intent(in) :: n
        real(dp) :: rate

        interface
            pure function ddot(n, x, incx, y, incy)
                import :: dp
                implicit none
                integer, intent(in) :: n, incx, incy
                real(dp), intent(in) :: x(*), y(*)
                real(dp) :: ddot
            end function ddot
        end interface
        real(dp), allocatable :: a(:), b(:)
        real(dp) :: start, finish, total, best
        integer :: kind_of_dot, repeats, r

        allocate (a(n), b(n))
        a(:) = [(1.0_dp/r, r=1, n)]
        b(:) = [(1.0_dp - 1.0_dp/r, r=1, n)]
        best = 0.0_dp
        do kind_of_dot = 1, 3
            repeats = 0
            total = 0.0_dp
            call cpu_time(start)
            do
                do r = 1, 100
                    select case (kind_of_dot)
                    case (1)
                        total = total + dot_product(a, b)
                    case (2)
                        total = total + ddot(n, a, 1, b, 1)
                    case default
                        total = total + lane_dot(n, a, b)
                    end select
                    b(1) = b(1) + 1.0e-300_dp*total
                end do
                repeats = repeats + 100
                call cpu_time(finish)
                if (finish - start >= 0.25_dp) exit
            end do
            best = max(best, real(n, dp)*repeats/(finish - start))
        end do
        rate = best
    end function plain_dot_rate

end module bench_tables_mod
