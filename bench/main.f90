!> greenconv-bench: the paper's timing tables (Tabs. 2 and 3) and the targets, measured in one
!> run, printed on standard output with `#` headers; the stability map of the paper's
!> recursion (and the charts' data) written to out/bench/.
!>
!>     greenconv-bench [SDOF_SCENE [MDOF_SCENE]]
!>     greenconv-bench --smoke
!>     greenconv-bench --fft
!>     greenconv-bench --output [ANCHOR]
!>     greenconv-bench --ident
!>     greenconv-bench --scale
!>     greenconv-bench --instant
!>     greenconv-bench --woodbury [N_STEPS]
!>     greenconv-bench --direct [SDOF_SCENE]
!>
!> The scenes default to data/sdof_sine.nml and data/mdof_random.nml (run from the project
!> directory: `make bench`). `--smoke` runs only the smoke checks of the benchmark's code
!> (bench_smoke_mod, a few seconds, part of `make test`): one pass/FAIL line per check, then
!> `N passed, N failed`; the exit status is 1 when a check failed. `--fft` runs only the
!> multi-point fft part (bench_greenfft_mod: its cost table and the tyre scene); `--output`
!> only the output benchmark (bench_output_mod), with the C anchor ANCHOR (default
!> `anchor_program`, the compiled bench/anchor/printf_rows.c, skipped when it does not exist);
!> `--ident` only the identification's cost (bench_ident_mod); `--scale` only the multi-point
!> cost against N_c up to 4,000 points (bench_scale_mod, out/bench/scale_cost.dat); `--direct` only
!> `direct` against a plain compiled loop of the same sum (bench_direct_mod); `--instant` only
!> the implicit step's W0*x on a plate's patch, W0's low-rank factors against the separable
!> shapes' (bench_instant_mod); `--woodbury` only the implicit step on a plate's patch with W0's
!> factors by dense elimination against factors in the modes' span, N_STEPS (100) a run
!> (bench_woodbury_mod).
program greenconv_bench
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
    use greenconv_core_error, only: error_type
    use bench_tables_mod, only: print_tables
    use bench_stability_mod, only: overflow_map
    use bench_contact_stability_mod, only: stability_map
    use bench_multipoint_mod, only: multipoint_cost_table
    use bench_greenfft_mod, only: greenfft_cost_table, tyre_scene_speedup
    use bench_output_mod, only: output_table
    use bench_smoke_mod, only: run_smoke_checks
    use greenconv_io_files, only: make_directory
    use bench_accuracy_mod, only: accuracy_charts
    use bench_ident_mod, only: identification_table
    use bench_scale_mod, only: scale_cost_table
    use bench_direct_mod, only: direct_loop_table
    use bench_instant_mod, only: instant_product_table
    use bench_woodbury_mod, only: woodbury_table
    implicit none

    type(error_type), allocatable :: error
    character(len=:), allocatable :: sdof_file, mdof_file
    !> Whether one part of the benchmark was asked for alone (`--ident`, `--direct`, ...).
    logical :: one_part = .false.
    integer :: n_passed, n_failed
    !> Where the benchmark's column files go (plot/bench_*.gp read them there).
    character(len=*), parameter :: output_dir = 'out/bench'
    !> Where bench/output_bench.sh (and `make bench`) put the compiled bench/anchor/printf_rows.c.
    character(len=*), parameter :: anchor_program = 'build/printf_rows'

    if (argument(1, '') == '--smoke') then
        n_passed = 0
        n_failed = 0
        call run_smoke_checks(output_unit, n_passed, n_failed)
        write (output_unit, '(i0,a,i0,a)') n_passed, ' passed, ', n_failed, ' failed'
        if (n_failed > 0) stop 1, quiet=.true.
        stop
    end if
    select case (argument(1, ''))
    case ('--ident')
        ! The identification's cost alone.
        call identification_table(output_unit, error)
        one_part = .true.
    case ('--direct')
        ! direct against a plain compiled loop of the same sum alone.
        call direct_loop_table(output_unit, argument(2, 'data/sdof_sine.nml'), error)
        one_part = .true.
    case ('--instant')
        ! The implicit step's W0*x on a plate's patch: low-rank against separable factors.
        call instant_product_table(output_unit, error)
        one_part = .true.
    case ('--woodbury')
        ! The implicit step on a plate's patch: factors by dense elimination or in the modes' span.
        call woodbury_table(output_unit, error, steps_argument(argument(2, '100')))
        one_part = .true.
    case ('--scale')
        ! The multi-point cost at a patch's scale alone (exact and modal against N_c).
        call make_directory(output_dir, error)
        if (.not. allocated(error)) call scale_cost_table(output_unit, output_dir, error)
        one_part = .true.
    case ('--fft', '--output')
        ! One part alone: the multi-point fft (cost table, tyre scene) or the output benchmark.
        call make_directory(output_dir, error)
        if (.not. allocated(error) .and. argument(1, '') == '--fft') then
            call greenfft_cost_table(output_unit, error)
            if (.not. allocated(error)) call tyre_scene_speedup(output_unit, 'data/tyre_road.nml', output_dir, error)
        else if (.not. allocated(error)) then
            call output_table(output_unit, output_dir, error, anchor=anchor(argument(2, '')))
        end if
        one_part = .true.
    end select
    if (one_part) then
        if (allocated(error)) then
            write (error_unit, '(a)') 'greenconv-bench: '//error%message
            stop 2, quiet=.true.
        end if
        stop
    end if
    sdof_file = argument(1, 'data/sdof_sine.nml')
    mdof_file = argument(2, 'data/mdof_random.nml')
    call make_directory(output_dir, error)
    if (.not. allocated(error)) call print_tables(output_unit, sdof_file, mdof_file, error)
    if (.not. allocated(error)) call direct_loop_table(output_unit, sdof_file, error)
    if (.not. allocated(error)) call overflow_map(output_unit, output_dir//'/overflow_map.dat', error)
    if (.not. allocated(error)) call stability_map(output_dir//'/contact_stability_map.dat', error)
    if (.not. allocated(error)) write (output_unit, '(a)') '# Contact stability map (explicit and implicit step over ' &
        //'k_c and dt): '//output_dir//'/contact_stability_map.dat', ''
    if (.not. allocated(error)) call multipoint_cost_table(output_unit, error)
    if (.not. allocated(error)) call scale_cost_table(output_unit, output_dir, error)
    if (.not. allocated(error)) call greenfft_cost_table(output_unit, error)
    if (.not. allocated(error)) call tyre_scene_speedup(output_unit, 'data/tyre_road.nml', output_dir, error)
    if (.not. allocated(error)) call output_table(output_unit, output_dir, error, anchor=anchor(''))
    if (.not. allocated(error)) call accuracy_charts(output_unit, output_dir, sdof_file, mdof_file, error)
    if (.not. allocated(error)) call identification_table(output_unit, error)
    if (allocated(error)) then
        write (error_unit, '(a)') 'greenconv-bench: '//error%message
        stop 2, quiet=.true.
    end if

contains

    !> The anchor program: `path`, or `anchor_program` when it exists, else '' (no anchor).
    function anchor(path) result(program)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: program

        logical :: exists

        program = path
        if (len(program) > 0) return
        inquire (file=anchor_program, exist=exists)
        if (exists) program = anchor_program
    end function anchor

    !> Command-line argument i, or `default` when absent.
    !> A positive number of steps from text, or 100.
    integer function steps_argument(text)
        character(len=*), intent(in) :: text

        integer :: status

        read (text, *, iostat=status) steps_argument
        if (status /= 0 .or. steps_argument < 1) steps_argument = 100
    end function steps_argument

    function argument(i, default) result(value)
        integer, intent(in) :: i
        character(len=*), intent(in) :: default
        character(len=:), allocatable :: value

        integer :: length

        call get_command_argument(i, length=length)
        if (length == 0) then
            value = default
            return
        end if
        allocate (character(len=length) :: value)
        call get_command_argument(i, value)
    end function argument

end program greenconv_bench
