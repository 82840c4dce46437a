!> The portable generator against published SplitMix64 outputs, and the random road and
!> modal system built from it.
module test_random_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check
    use greenconv_core_random, only: random_stream
    use greenconv, only: modal_set, random_modes, random_road, new_random_road
    implicit none
    private

    public :: collect_random

contains

    !> Tests of greenconv_core_random, the random road of eq. (35) and random_modes.
    subroutine collect_random(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('SplitMix64 from seed 0: first outputs', test_splitmix), &
                     new_unittest('random modes: ranges, order, reproducible', test_modes), &
                     new_unittest('random road: eq. (35) term by term', test_road)]
    end subroutine collect_random

    !> The first outputs of SplitMix64 seeded with 0 are 0xE220A8397B1DCDAF and
    !> 0x6E789E6AA1B965F4; their top 53 bits over 2^53 are the uniforms below
    !> (computed with Python's exact integers).
    subroutine test_splitmix(error)
        type(test_error), allocatable, intent(out) :: error

        type(random_stream) :: stream

        stream = random_stream(0)
        call check(error, stream%uniform(), 0.8833108082136426_dp, 'first output', thr=1.0e-16_dp)
        if (allocated(error)) return
        call check(error, stream%uniform(), 0.43152799704850997_dp, 'second output', thr=1.0e-17_dp)
    end subroutine test_splitmix

    subroutine test_modes(error)
        type(test_error), allocatable, intent(out) :: error

        type(modal_set) :: modes, again
        real(dp), allocatable :: frequency(:), ratio(:)

        modes = random_modes(7, 10, 20.0_dp, 400.0_dp, 0.02_dp, 0.05_dp, 0.2_dp, 1.0_dp)
        again = random_modes(7, 10, 20.0_dp, 400.0_dp, 0.02_dp, 0.05_dp, 0.2_dp, 1.0_dp)
        frequency = abs(modes%pole)/(2.0_dp*acos(-1.0_dp))
        ratio = -real(modes%pole, dp)/abs(modes%pole)
        call check(error, modes%n_modes() == 10, 'ten modes')
        if (allocated(error)) return
        call check(error, all(frequency >= 20.0_dp .and. frequency < 400.0_dp), 'frequencies in range')
        if (allocated(error)) return
        call check(error, all(ratio >= 0.02_dp - 1.0e-15_dp .and. ratio < 0.05_dp + 1.0e-15_dp), 'damping in range')
        if (allocated(error)) return
        call check(error, all(frequency(2:) >= frequency(:9)), 'sorted by frequency')
        if (allocated(error)) return
        call check(error, all(modes%pole == again%pole) .and. all(modes%residue == again%residue), 'reproducible')
    end subroutine test_modes

    subroutine test_road(error)
        type(test_error), allocatable, intent(out) :: error

        type(random_road) :: road
        real(dp) :: t, expected
        integer :: k

        road = new_random_road(3, 10, 5.0e-3_dp, 50.0e-3_dp, 2.0_dp)
        call check(error, all(road%weight > 0.0_dp .and. road%weight < 1.0_dp) .and. &
                   all(road%wavenumber_factor > 0.0_dp .and. road%wavenumber_factor < 1.0_dp), 'draws in (0, 1)')
        if (allocated(error)) return
        t = 0.0123_dp
        expected = 0.0_dp
        do k = 1, 10
            expected = expected + road%weight(k)*5.0e-3_dp*sin(road%wavenumber_factor(k)*2.0_dp*acos(-1.0_dp) &
                                                               /50.0e-3_dp*2.0_dp*t)
        end do
        call check(error, road%height(t), expected, 'u_r(t) term by term', thr=1.0e-15_dp)
        if (allocated(error)) return
        call check(error, road%height(0.0_dp), 0.0_dp, 'u_r(0)', thr=0.0_dp)
    end subroutine test_road

end module test_random_mod
