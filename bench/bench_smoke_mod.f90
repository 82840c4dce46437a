!> Smoke checks of the benchmark's own code, run by `greenconv-bench --smoke` (and so by
!> `make test`): the unit tests (`fpm test`) cannot see bench/, so the checks of the contact
!> stability map and of the multi-point cost table live here. Each check runs a small case,
!> prints one line `  pass  bench :: NAME` or `  FAIL  bench :: NAME: WHY`, and counts it.
module bench_smoke_mod
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_io_files, only: make_directory
    use greenconv_model_tyre, only: tyre_belt, tyre_mode_count, tyre_band
    use bench_contact_stability_mod, only: stability_cell, stability_map
    use bench_multipoint_mod, only: multipoint_cost_table
    use greenconv_conv_direct, only: direct_convolver, new_direct_convolver
    use bench_direct_mod, only: plain_loop, new_plain_loop
    implicit none
    private

    public :: run_smoke_checks

    !> Directory of the files the checks write.
    character(len=*), parameter :: scratch = 'build/bench_smoke'

    abstract interface
        !> One check: leaves `failure` unallocated when it passes.
        subroutine smoke_check(failure)
            import :: error_type
            implicit none
            !> Why the check failed.
            type(error_type), allocatable, intent(out) :: failure
        end subroutine smoke_check
    end interface

contains

    !> Run every smoke check, print one line per check on `unit`, and add to the counts.
    subroutine run_smoke_checks(unit, n_passed, n_failed)
        !> Unit of the report.
        integer, intent(in) :: unit
        !> Number of checks passed, increased.
        integer, intent(inout) :: n_passed
        !> Number of checks failed, increased.
        integer, intent(inout) :: n_failed

        call run_one('stability map: edges near omega_c*dt = 2 and 2*sqrt(3)', check_stability_map)
        call run_one('cost table: header, rows, model sizes', check_cost_table)
        call run_one('plain loop: the sum of direct, to round-off', check_plain_loop)

    contains

        subroutine run_one(name, check)
            character(len=*), intent(in) :: name
            procedure(smoke_check) :: check

            type(error_type), allocatable :: failure

            call check(failure)
            if (allocated(failure)) then
                n_failed = n_failed + 1
                write (unit, '(a)') '  FAIL  bench :: '//name//': '//failure%message
            else
                n_passed = n_passed + 1
                write (unit, '(a)') '  pass  bench :: '//name
            end if
        end subroutine run_one

    end subroutine run_smoke_checks

    !> The plain loop of bench_direct_mod against `direct` on a 37-tap kernel over 300 steps (the
    !> ring wrapped, every step of direct's blocks, the loop's force array grown from room for
    !> 100): the same sum in two orders, so within 2*N_g*eps of sum |w_k|*max|q|.
    subroutine check_plain_loop(failure)
        type(error_type), allocatable, intent(out) :: failure

        integer, parameter :: n_g = 37, n_steps = 300
        type(direct_convolver) :: direct
        type(plain_loop) :: loop
        real(dp) :: kernel(0:n_g), q, worst, bound
        integer :: n, j

        kernel = [(sin(1.3_dp*j)*exp(-0.05_dp*j), j=0, n_g)]
        direct = new_direct_convolver(kernel, 1.0e-4_dp)
        loop = new_plain_loop(direct, 100)
        worst = 0.0_dp
        do n = 0, n_steps - 1
            worst = max(worst, abs(direct%history() - loop%history()))
            q = cos(0.7_dp*n) + 0.5_dp
            call direct%push(q)
            call loop%push(q)
        end do
        bound = 2.0_dp*n_g*epsilon(1.0_dp)*sum(abs(direct%weight))*1.5_dp
        if (.not. worst <= bound .or. loop%step /= n_steps) then
            call fatal_error(failure, 'plain loop and direct differ beyond round-off')
        end if
    end subroutine check_plain_loop

    !> A small map with A0 = 1 um (a closed contact, where the linear stability edges hold):
    !> k_c = 1e9 N/m and dt = 12.5 us * 2^k, k = 0..4, i.e. omega_c*dt = 0.40, 0.79, 1.58, 3.16,
    !> 6.33. A cell is good when it ran to the end with a relative error below 1e-2, failed when
    !> it was stopped or its error exceeds 1. The explicit step must be good at 0.40 and fail at
    !> 3.16 and 6.33 (edge 2); the implicit one good at 0.40 and 3.16, failed at 6.33 (edge
    !> 2*sqrt(3) = 3.46). The file must hold the units line, the names line and 5 rows.
    subroutine check_stability_map(failure)
        type(error_type), allocatable, intent(out) :: failure

        character(len=*), parameter :: path = scratch//'/map/contact_stability_map.dat'
        type(stability_cell), allocatable :: cells(:)
        character(len=200) :: line, previous
        integer :: unit, rows, stat

        call stability_map(path, failure, stiffness=[1.0e9_dp], dt_min=1.25e-5_dp, n_dt=5, amplitude=1.0e-6_dp, &
                           cells=cells)
        if (allocated(failure)) return
        if (.not. (good(cells(1)%explicit_bounded, cells(1)%explicit_error) &
                   .and. failed(cells(4)%explicit_bounded, cells(4)%explicit_error) &
                   .and. failed(cells(5)%explicit_bounded, cells(5)%explicit_error))) then
            call fatal_error(failure, 'explicit: expected good at omega_c*dt = 0.4, failed at 3.2 and 6.3')
            return
        end if
        if (.not. (good(cells(1)%implicit_bounded, cells(1)%implicit_error) &
                   .and. good(cells(4)%implicit_bounded, cells(4)%implicit_error) &
                   .and. failed(cells(5)%implicit_bounded, cells(5)%implicit_error))) then
            call fatal_error(failure, 'implicit: expected good at omega_c*dt = 0.4 and 3.2, failed at 6.3')
            return
        end if
        open (newunit=unit, file=path, status='old', action='read', iostat=stat)
        if (stat /= 0) then
            call fatal_error(failure, path//': the map file was not written')
            return
        end if
        previous = ''
        do
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (line(1:1) /= '#') cycle
            if (index(line, '# dt k_c omega_c_dt') == 1) exit
            previous = line
        end do
        rows = 0
        do
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            rows = rows + 1
        end do
        close (unit)
        if (index(previous, '# units: s N/m^p') /= 1 .or. rows /= 5) &
            call fatal_error(failure, path//': expected a units line, a names line and 5 rows')

    contains

        pure logical function good(bounded, relative)
            logical, intent(in) :: bounded
            real(dp), intent(in) :: relative

            good = bounded .and. relative >= 0.0_dp .and. relative < 1.0e-2_dp
        end function good

        pure logical function failed(bounded, relative)
            logical, intent(in) :: bounded
            real(dp), intent(in) :: relative

            failed = .not. bounded .or. relative > 1.0_dp
        end function failed

    end subroutine check_stability_map

    !> A small cost table (N_c = 1 and 4, dt = 0.1 ms, few steps): two `#` header lines, then
    !> one row per N_c with the tyre's mode count N_m at the band of the benchmark's speed and
    !> wavelength, more than 100 kernel samples N_g and non-negative times and ratio.
    subroutine check_cost_table(failure)
        type(error_type), allocatable, intent(out) :: failure

        character(len=*), parameter :: path = scratch//'/cost_table.txt'
        integer, parameter :: counts(2) = [1, 4]
        character(len=200) :: line(4)
        real(dp) :: row(7)
        integer :: unit, j, n_m, stat

        call make_directory(scratch, failure)
        if (allocated(failure)) return
        open (newunit=unit, file=path, status='replace', action='readwrite', iostat=stat)
        if (stat /= 0) then
            call fatal_error(failure, path//': cannot be written')
            return
        end if
        call multipoint_cost_table(unit, failure, n_points=counts, n_steps_modal=200, n_steps_direct=3, dt=1.0e-4_dp)
        rewind (unit)
        read (unit, '(a)', iostat=stat) line
        close (unit, status='delete')
        if (allocated(failure)) return
        if (stat /= 0 .or. line(1)(1:1) /= '#' .or. line(2)(1:5) /= '# N_c') then
            call fatal_error(failure, 'expected two # header lines and two rows')
            return
        end if
        n_m = tyre_mode_count(tyre_belt(), tyre_band(20.0_dp, 0.02_dp, 1.0e-4_dp))
        do j = 3, 4
            read (line(j), *, iostat=stat) row
            if (stat /= 0 .or. nint(row(1)) /= counts(j - 2) .or. nint(row(2)) /= n_m .or. nint(row(3)) <= 100 &
                .or. any(row(4:7) < 0.0_dp)) then
                call fatal_error(failure, 'row "'//trim(line(j))//'": expected N_c, N_m, N_g > 100 and times >= 0')
                return
            end if
        end do
    end subroutine check_cost_table

end module bench_smoke_mod
