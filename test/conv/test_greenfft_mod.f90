!> The multi-point `fft` engine (greenconv_conv_green_fft) against the multi-point `direct`
!> (greenconv_conv_green_sampled), which sums the same table W_ij(m) = dt*g_ij(t_m).
!>
!> Tolerance: 1e-12 relative, max over steps and points of |u_fft - u_direct| over the
!> largest |u_direct| of the run (histories). Random tables g_ij(t_m) in [-1, 1) and random
!> forces in [-10, 10) N; runs last at least 3*N_g steps, so that every level's delay line
!> and every ring wraps around several times. For long tables `direct` is asked for its
!> history (N_c^2*N_g operations) only every 13th step (odd, so every phase of every
!> power-of-two block is met); both engines are pushed every step.
module test_greenfft_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64, int64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_core_random, only: random_stream
    use greenconv_core_error, only: error_type
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_green_sampled, only: sampled_green_matrix, new_sampled_green_matrix
    use greenconv_conv_green_fft, only: fft_green_matrix, new_fft_green_matrix
    use greenconv_conv_builder, only: make_multipoint_convolver
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_tyre, only: tyre_belt, tyre_modes, contact_positions
    use greenconv_model_road, only: random_road, new_random_road
    use greenconv_contact_single, only: contact_law
    use greenconv_contact_multi, only: multi_contact_state, multi_contact_response, start_multi_contact, &
                                       multi_contact_block
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: collect_greenfft

    !> Largest force magnitude [N].
    real(dp), parameter :: force = 10.0_dp
    !> Time step of the random tables [s].
    real(dp), parameter :: dt = 1.0e-4_dp
    !> Relative tolerance of fft against direct.
    real(dp), parameter :: tolerance = 1.0e-12_dp

contains

    !> Tests of the multi-point partitioned FFT engine.
    subroutine collect_greenfft(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('multi-point fft equals direct: N_c = 1, N_g = 1 to 6000', test_one_point), &
                     new_unittest('multi-point fft equals direct: N_c = 3, N_g = 5 to 5000', test_three_points), &
                     new_unittest('multi-point fft equals direct: N_c = 20, N_g = 40 and 700', test_twenty_points), &
                     new_unittest('multi-point fft equals direct: heads of 1, 5 and 64 taps', test_heads), &
                     new_unittest('multi-point fft: reset then rerun, release mid-run: identical', test_rerun), &
                     new_unittest('multi-point fft: tyre contact in blocks of 1, 7, 1000 = one block', test_blocks), &
                     new_unittest('multi-point fft: built by the registry, equals direct on the tyre', test_builder)]
    end subroutine collect_greenfft

    !> A table g_ij(m*dt) in [-1, 1) [m/(N*s)], m = 0..n_g, i, j = 1..n_c, from a seed.
    function random_table(n_g, n_c, seed) result(kernel)
        integer, intent(in) :: n_g, n_c, seed
        real(dp), allocatable :: kernel(:, :, :)

        type(random_stream) :: stream
        integer :: i, j, m

        allocate (kernel(0:n_g, n_c, n_c))
        stream = random_stream(seed)
        do j = 1, n_c
            do i = 1, n_c
                do m = 0, n_g
                    kernel(m, i, j) = stream%between(-1.0_dp, 1.0_dp)
                end do
            end do
        end do
    end function random_table

    !> Largest relative difference of the histories of fft and direct on one random table,
    !> over max(3*n_g, 200) steps of random forces; direct's history every `every` steps.
    function fft_error(n_g, n_c, seed, every, head) result(worst)
        integer, intent(in) :: n_g, n_c, seed, every
        integer, intent(in), optional :: head
        real(dp) :: worst

        type(sampled_green_matrix) :: direct
        type(fft_green_matrix) :: partitioned
        type(error_type), allocatable :: failure
        type(random_stream) :: stream
        real(dp), allocatable :: kernel(:, :, :)
        real(dp) :: q(n_c), u_direct(n_c), u_fft(n_c), peak, gap
        integer :: n, i

        kernel = random_table(n_g, n_c, seed)
        call new_sampled_green_matrix(kernel, dt, direct, failure)
        if (.not. allocated(failure)) call new_fft_green_matrix(kernel, dt, partitioned, failure, head)
        if (allocated(failure)) error stop 'test_greenfft_mod: '//failure%message
        stream = random_stream(seed + 1000)
        peak = 0.0_dp
        gap = 0.0_dp
        do n = 0, max(3*n_g, 200) - 1
            if (mod(n, every) == 0) then
                call direct%history(u_direct)
                call partitioned%history(u_fft)
                peak = max(peak, maxval(abs(u_direct)))
                gap = max(gap, maxval(abs(u_fft - u_direct)))
            end if
            do i = 1, n_c
                q(i) = force*(stream%between(-1.0_dp, 1.0_dp))
            end do
            call direct%push(q)
            call partitioned%push(q)
        end do
        call partitioned%release()
        worst = gap/max(peak, tiny(1.0_dp))
    end function fft_error

    subroutine test_one_point(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: lengths(*) = [1, 2, 31, 32, 33, 100, 257, 1000, 6000]
        real(dp) :: worst
        integer :: k, every

        worst = 0.0_dp
        do k = 1, size(lengths)
            every = 1
            if (lengths(k) > 1000) every = 13
            worst = max(worst, fft_error(lengths(k), 1, 10 + k, every))
        end do
        call note('largest relative difference', worst)
        call check(error, worst <= tolerance, 'fft differs from direct beyond 1e-12 at one point')
    end subroutine test_one_point

    subroutine test_three_points(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: lengths(*) = [5, 64, 300, 2741, 5000]
        real(dp) :: worst
        integer :: k, every

        worst = 0.0_dp
        do k = 1, size(lengths)
            every = 1
            if (lengths(k) > 1000) every = 13
            worst = max(worst, fft_error(lengths(k), 3, 20 + k, every))
        end do
        call note('largest relative difference', worst)
        call check(error, worst <= tolerance, 'fft differs from direct beyond 1e-12 at three points')
    end subroutine test_three_points

    subroutine test_twenty_points(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp) :: worst

        worst = max(fft_error(40, 20, 31, 1), fft_error(700, 20, 32, 13))
        call note('largest relative difference', worst)
        call check(error, worst <= tolerance, 'fft differs from direct beyond 1e-12 at twenty points')
    end subroutine test_twenty_points

    subroutine test_heads(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp) :: worst

        worst = max(fft_error(500, 2, 41, 1, head=1), fft_error(500, 2, 42, 1, head=5), &
                    fft_error(500, 2, 43, 1, head=64))
        call note('largest relative difference', worst)
        call check(error, worst <= tolerance, 'fft with a small or large head differs from direct beyond 1e-12')
    end subroutine test_heads

    !> The histories of n_steps random steps (seed) of a convolver, from its current state;
    !> `release_at` > 0: release the plans after that many steps.
    function stepped(conv, n_steps, seed, release_at) result(u)
        type(fft_green_matrix), intent(inout) :: conv
        integer, intent(in) :: n_steps, seed, release_at
        real(dp), allocatable :: u(:, :)

        type(random_stream) :: stream
        real(dp) :: q(conv%n_points())
        integer :: n, i

        allocate (u(conv%n_points(), n_steps))
        stream = random_stream(seed)
        do n = 1, n_steps
            call conv%history(u(:, n))
            do i = 1, size(q)
                q(i) = force*(stream%between(-1.0_dp, 1.0_dp))
            end do
            call conv%push(q)
            if (n == release_at) call conv%release()
        end do
    end function stepped

    subroutine test_rerun(error)
        type(test_error), allocatable, intent(out) :: error

        type(fft_green_matrix) :: conv
        type(error_type), allocatable :: failure
        real(dp), allocatable :: first(:, :), again(:, :), released(:, :)

        call new_fft_green_matrix(random_table(1500, 3, 51), dt, conv, failure)
        if (allocated(failure)) error stop 'test_greenfft_mod: '//failure%message
        first = stepped(conv, 4000, 52, 0)
        call check(error, conv%rings%plan_count() > 0, 'a run that reached the levels owns plans')
        if (allocated(error)) return
        call conv%reset()
        again = stepped(conv, 4000, 52, 0)
        call conv%reset()
        released = stepped(conv, 4000, 52, 1234)
        call conv%release()
        call check(error, conv%rings%plan_count() == 0, 'release leaves no plan')
        if (allocated(error)) return
        call check(error, all(first == again), 'a rerun after reset is identical to the bit')
        if (allocated(error)) return
        call check(error, all(first == released), 'release mid-run changes nothing')
    end subroutine test_rerun

    !> The tyre (modes up to 1 kHz) at n_c points over a patch, Hertz springs, and the road of
    !> eq. (35) (A0 = 0.5 mm) at 20 m/s under each point.
    subroutine tyre_case(n_c, n_steps, step, description, laws, preload, road)
        integer, intent(in) :: n_c, n_steps
        real(dp), intent(in) :: step
        type(point_modes), intent(out) :: description
        type(power_law), allocatable, intent(out) :: laws(:)
        real(dp), allocatable, intent(out) :: preload(:), road(:, :)

        type(error_type), allocatable :: failure
        type(random_road) :: profile
        type(tyre_belt) :: tyre
        real(dp) :: positions(n_c)
        integer :: i, m

        positions = contact_positions(0.5_dp*tyre%length, 0.12_dp, n_c)
        call tyre_modes(tyre, positions, 1000.0_dp, description, failure)
        if (allocated(failure)) error stop 'test_greenfft_mod: '//failure%message
        allocate (laws(n_c), preload(n_c), road(0:n_steps - 1, n_c))
        preload(:) = 3000.0_dp/n_c
        laws(:) = power_law(preload(1)/1.0e-3_dp**1.5_dp, 1.5_dp)
        profile = new_random_road(35, 10, 0.5e-3_dp, 0.05_dp, 20.0_dp)
        do i = 1, n_c
            road(:, i) = profile%height([(m*step + (positions(i) - positions(1))/20.0_dp, m=0, n_steps - 1)])
        end do
    end subroutine tyre_case

    !> Forces of a tyre contact run stepped in blocks of `block` steps.
    function blocked_forces(conv, laws, preload, road, block) result(forces)
        class(multipoint_convolver), intent(inout) :: conv
        type(power_law), intent(in) :: laws(:)
        real(dp), intent(in) :: preload(:), road(0:, :)
        integer, intent(in) :: block
        real(dp), allocatable :: forces(:, :)

        type(multi_contact_state) :: state
        type(multi_contact_response) :: response
        type(error_type), allocatable :: failure
        integer :: first, last

        allocate (forces(0:size(road, 1) - 1, size(laws)))
        call start_multi_contact(conv, laws, preload, state, failure)
        if (allocated(failure)) error stop 'test_greenfft_mod: '//failure%message
        first = 0
        do while (first < size(road, 1))
            last = min(first + block, size(road, 1)) - 1
            call multi_contact_block(conv, state, road(first:last, :), response, failure)
            if (allocated(failure)) error stop 'test_greenfft_mod: '//failure%message
            forces(first:last, :) = response%force
            first = last + 1
        end do
    end function blocked_forces

    subroutine test_blocks(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_steps = 3000, blocks(*) = [1, 7, 1000]
        type(point_modes) :: description
        type(power_law), allocatable :: laws(:)
        real(dp), allocatable :: preload(:), road(:, :), whole(:, :)
        class(multipoint_convolver), allocatable :: conv
        character(len=:), allocatable :: accuracy
        type(error_type), allocatable :: failure
        integer :: k

        call tyre_case(5, n_steps, 5.0e-5_dp, description, laws, preload, road)
        call make_multipoint_convolver('fft', description, 5.0e-5_dp, 0.01_dp, n_steps, conv, accuracy, failure)
        if (allocated(failure)) error stop 'test_greenfft_mod: '//failure%message
        whole = blocked_forces(conv, laws, preload, road, n_steps)
        call check(error, maxval(whole) > 0.0_dp, 'the tyre touches the road')
        do k = 1, size(blocks)
            if (allocated(error)) exit
            call check(error, all(blocked_forces(conv, laws, preload, road, blocks(k)) == whole), &
                       'blocks of '//trim(adjustl(int_image(blocks(k))))//' steps differ from one block')
        end do
        call conv%release()
    end subroutine test_blocks

    !> Decimal image of an integer.
    function int_image(i) result(text)
        integer, intent(in) :: i
        character(len=12) :: text

        write (text, '(i0)') i
    end function int_image

    subroutine test_builder(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_steps = 4000
        type(point_modes) :: description
        type(power_law), allocatable :: laws(:)
        real(dp), allocatable :: preload(:), road(:, :), with_fft(:, :), with_direct(:, :)
        class(multipoint_convolver), allocatable :: conv
        character(len=:), allocatable :: accuracy, label
        type(error_type), allocatable :: failure
        integer :: n_fft, n_direct
        real(dp) :: worst

        call tyre_case(4, n_steps, 5.0e-5_dp, description, laws, preload, road)
        call make_multipoint_convolver('fft', description, 5.0e-5_dp, 0.01_dp, n_steps, conv, accuracy, failure)
        if (allocated(failure)) error stop 'test_greenfft_mod: '//failure%message
        call check(error, conv%name == 'fft', 'the registry builds the engine called fft')
        if (allocated(error)) return
        call conv%model_size(n_fft, label)
        with_fft = blocked_forces(conv, laws, preload, road, 500)
        call conv%release()
        call make_multipoint_convolver('direct', description, 5.0e-5_dp, 0.01_dp, n_steps, conv, accuracy, failure)
        if (allocated(failure)) error stop 'test_greenfft_mod: '//failure%message
        call conv%model_size(n_direct, label)
        with_direct = blocked_forces(conv, laws, preload, road, 500)
        call check(error, n_fft == n_direct, 'fft and direct truncate the table alike')
        if (allocated(error)) return
        worst = maxval(abs(with_fft - with_direct))/maxval(abs(with_direct))
        call note('largest relative difference of the forces', worst)
        call check(error, worst <= tolerance, 'fft and direct tyre contact forces differ beyond 1e-12')
    end subroutine test_builder

end module test_greenfft_mod
