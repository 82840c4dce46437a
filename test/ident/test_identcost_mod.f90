!> The bound of the cost of identifying a Green's matrix file (greenconv_ident_cost), known
!> before the identification starts, against the identification's own cost measured in the
!> same run: CPU seconds against the bound's floating-point operations at the rate of the fits'
!> Gram product measured here, and the pole fit's Levenberg-Marquardt iterations against the
!> bound's count of them.
module test_identcost_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_core_error, only: error_type
    use greenconv_ident_mlfit, only: ml_options
    use greenconv_ident_cost, only: green_cost, green_cost_bound, measured_rate
    use greenconv_ident_green_structure, only: green_options, green_structure, read_green_structure
    implicit none
    private

    public :: collect_identcost

contains

    !> Tests of the cost bound.
    subroutine collect_identcost(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('data/patch_green.uff (12 points, 301 lines), max_order 60, both pole fits: '// &
                                  'CPU under the bound at the measured rate', test_shipped_both), &
                     new_unittest('data/patch_green.uff, summed driving points alone: CPU and LM iterations '// &
                                  'under the bound', test_shipped_summed), &
                     new_unittest('the bound grows with the points, the lines, max_order and max_changes', &
                                  test_monotone)]
    end subroutine collect_identcost

    !> The shipped patch's identification as its scene runs it (ident_method 'auto': the summed
    !> driving points and the poly-reference fit, the better kept).
    subroutine test_shipped_both(error)
        type(test_error), allocatable, intent(out) :: error

        type(green_options) :: options

        options%fit%max_order = 60
        options%choose_poles = .true.
        call check_shipped(error, options, 'both fits')
    end subroutine test_shipped_both

    !> The same file through the summed driving points alone, whose LM iterations the bound counts.
    subroutine test_shipped_summed(error)
        type(test_error), allocatable, intent(out) :: error

        type(green_options) :: options

        options%fit%max_order = 60
        call check_shipped(error, options, 'summed')
        if (allocated(error)) return
    end subroutine test_shipped_summed

    !> Identify data/patch_green.uff and hold its CPU time (and, for the summed driving points,
    !> its LM iterations) under the bound computed before it started.
    subroutine check_shipped(error, options, label)
        type(test_error), allocatable, intent(out) :: error
        type(green_options), intent(in) :: options
        character(len=*), intent(in) :: label

        type(green_structure) :: structure
        type(error_type), allocatable :: failure
        real(dp) :: rate, bound_seconds

        call read_green_structure('data/patch_green.uff', options, structure, failure)
        if (allocated(failure)) call check(error, .false., failure%message)
        if (allocated(error)) return
        rate = measured_rate(0.05_dp)
        bound_seconds = structure%cost%total/rate
        call note(label//': measured CPU [s]', structure%cpu_time)
        call note(label//': bound [flop]', structure%cost%total)
        call note(label//': Gram product rate [flop/s]', rate)
        call note(label//': bound at that rate [s]', bound_seconds)
        call check(error, structure%cost%total > 0.0_dp .and. rate > 0.0_dp, label//': no bound or no rate')
        if (allocated(error)) return
        call check(error, structure%cpu_time <= bound_seconds, label//': the identification took longer than its bound')
        if (allocated(error)) return
        if (options%choose_poles .or. options%poly_reference) return
        call note(label//': LM iterations of the pole fit', real(structure%fit%pole_fit%iterations, dp))
        call note(label//': bound of them', structure%cost%lm_iterations)
        call check(error, structure%fit%pole_fit%iterations > 0 .and. &
                   structure%fit%pole_fit%iterations <= structure%cost%lm_iterations, &
                   label//': the pole fit took more LM iterations than its bound (or none)')
    end subroutine check_shipped

    !> More points, lines, modes or changes allowed never lower the bound (each count enters it
    !> as a factor of non-negative terms).
    subroutine test_monotone(error)
        type(test_error), allocatable, intent(out) :: error

        type(ml_options) :: options, more
        type(green_cost) :: base, grown
        integer :: case

        options%max_order = 30
        base = green_cost_bound(12, 301, .true., options, .true., .true.)
        call note('12 points, 301 lines, max_order 30 [flop]', base%total)
        do case = 1, 4
            more = options
            select case (case)
            case (1)
                grown = green_cost_bound(13, 301, .true., options, .true., .true.)
            case (2)
                grown = green_cost_bound(12, 4001, .true., options, .true., .true.)
            case (3)
                more%max_order = 60
                grown = green_cost_bound(12, 301, .true., more, .true., .true.)
            case default
                more%max_changes = 80
                grown = green_cost_bound(12, 301, .true., more, .true., .true.)
            end select
            call check(error, grown%total > base%total .and. grown%lm_iterations >= base%lm_iterations, &
                       'the bound did not grow with a larger count')
            if (allocated(error)) return
        end do
    end subroutine test_monotone

end module test_identcost_mod
