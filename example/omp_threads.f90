!> Two independent simulations in two OpenMP threads at once, each against the same
!> simulation run alone first.
!>
!> Thread 1: the paper's mass-spring on the sine road at dt = 10 us (20000 steps) with the
!> `fft` method, whose FFTW plans are made during the run and destroyed by `free_convolver`.
!> Thread 2: a structure of 4 random modes known only by its receptance G: LSCE
!> identification (one-shot FFTs) and g by inverse FFT, then `fft` and `modal` contact runs.
!> Each thread repeats its simulation `n_rounds` times, so FFTW's planner is called from
!> both threads over and over; the library serialises it (OpenMP critical section
!> `greenconv_fftw_planner`). Every result must equal the one computed alone, to 1e-12 of
!> its largest value (FFTW plans depend on the alignment of arrays, which may differ
!> between runs, in the last bits only). Exit status 1 on a mismatch.
program omp_threads
    !$ use omp_lib, only: omp_get_thread_num, omp_get_num_threads
    use greenconv, only: dp, error_type, convolver, contact_law, contact_response, run_contact, sdof_modes, &
                         random_modes, frf_from_modes, lsce_options, structure_model, structure_from_modes, &
                         structure_from_frf, new_convolver, free_convolver
    implicit none

    !> Repetitions of each simulation in its thread.
    integer, parameter :: n_rounds = 6
    !> Tolerance relative to the largest displacement of a run.
    real(dp), parameter :: tolerance = 1.0e-12_dp

    real(dp), allocatable :: alone_sdof(:), alone_modes(:)
    real(dp) :: worst(2)
    integer :: threads_seen, round

    call simulate_sdof(alone_sdof)
    call simulate_modes(alone_modes)
    worst(:) = 0.0_dp
    threads_seen = 1
    !$omp parallel sections num_threads(2) shared(worst, threads_seen) private(round)
    !$omp section
    !$ threads_seen = omp_get_num_threads()
    do round = 1, n_rounds
        worst(1) = max(worst(1), deviation_sdof())
    end do
    !$omp section
    do round = 1, n_rounds
        worst(2) = max(worst(2), deviation_modes())
    end do
    !$omp end parallel sections
    write (*, '(a,i0,a,i0,a)') 'omp_threads: ', threads_seen, ' threads, ', n_rounds, ' rounds each'
    write (*, '(a,es9.2,a)') 'omp_threads: sdof, fft:                  max|u - u_alone|/max|u| = ', worst(1), &
        merge(' ok      ', ' MISMATCH', worst(1) <= tolerance)
    write (*, '(a,es9.2,a)') 'omp_threads: 4 modes from G, fft, modal: max|u - u_alone|/max|u| = ', worst(2), &
        merge(' ok      ', ' MISMATCH', worst(2) <= tolerance)
    ! The main program's arrays are not freed at its end: free them, for valgrind's sake.
    deallocate (alone_sdof, alone_modes)
    if (.not. all(worst <= tolerance)) error stop 'omp_threads: FAILED'
    write (*, '(a)') 'omp_threads: all checks passed'

contains

    !> Largest relative difference of one sdof simulation from the one run alone.
    function deviation_sdof() result(worst)
        real(dp) :: worst

        real(dp), allocatable :: u(:)

        call simulate_sdof(u)
        worst = maxval(abs(u - alone_sdof))/maxval(abs(alone_sdof))
    end function deviation_sdof

    !> Largest relative difference of one modal simulation from the one run alone.
    function deviation_modes() result(worst)
        real(dp) :: worst

        real(dp), allocatable :: u(:)

        call simulate_modes(u)
        worst = maxval(abs(u - alone_modes))/maxval(abs(alone_modes))
    end function deviation_modes

    !> The mass-spring of the paper on its sine road, dt = 10 us, with `fft`: u [m].
    subroutine simulate_sdof(u)
        real(dp), allocatable, intent(out) :: u(:)

        integer, parameter :: n_steps = 20000
        real(dp), parameter :: dt = 1.0e-5_dp

        call contact_run(structure_from_modes(sdof_modes(1.0_dp, 1.0e6_dp, 0.02_dp)), 'fft', dt, n_steps, 9.81_dp, u)
    end subroutine simulate_sdof

    !> 4 random modes identified from G (0 to 5 kHz, 2001 lines), then `fft` on g from the
    !> inverse FFT of G and `modal` on the modes, dt = 0.1 ms: both u [m], one after the other.
    subroutine simulate_modes(u)
        real(dp), allocatable, intent(out) :: u(:)

        integer, parameter :: n_steps = 4000
        real(dp), parameter :: dt = 1.0e-4_dp
        type(structure_model) :: structure
        type(lsce_options) :: options
        type(error_type), allocatable :: error
        real(dp), allocatable :: u_fft(:), u_modal(:)

        call structure_from_frf(frf_from_modes(random_modes(7, 4, 100.0_dp, 1000.0_dp, 0.02_dp, 0.05_dp, 0.5_dp, &
                                                            2.0_dp), 5000.0_dp, 2001), options, dt, structure, error)
        if (allocated(error)) error stop 'omp_threads: identification failed'
        call contact_run(structure, 'fft', dt, n_steps, 100.0_dp, u_fft)
        call contact_run(structure, 'modal', dt, n_steps, 100.0_dp, u_modal)
        u = [u_fft, u_modal]
    end subroutine simulate_modes

    !> One contact run on the sine road of 1 mm at 100 rad/s (Hertz, k_c = 1e6 N/m^1.5): u [m].
    subroutine contact_run(structure, method, dt, n_steps, preload, u)
        type(structure_model), intent(in) :: structure
        character(len=*), intent(in) :: method
        real(dp), intent(in) :: dt, preload
        integer, intent(in) :: n_steps
        real(dp), allocatable, intent(out) :: u(:)

        class(convolver), allocatable :: conv
        type(error_type), allocatable :: error
        type(contact_response) :: response
        integer :: n

        call new_convolver(method, structure, dt, n_steps, conv, error)
        if (allocated(error)) error stop 'omp_threads: no convolver'
        call run_contact(conv, contact_law(1.0e6_dp, 1.5_dp), [(1.0e-3_dp*sin(100.0_dp*n*dt), n=0, n_steps - 1)], &
                         preload, response)
        call free_convolver(conv)
        u = response%displacement
    end subroutine contact_run

end program omp_threads
