!> Writes data/noisy_receptance.uff, the receptance the shipped identification scene
!> (data/identify_sample.nml) fits: the 12-mode structure, as a measurement would
!> give it.
!>
!> - Modes (paper form, eq. 6, A_k = c_k*xi_k*omega_k^2 so that each peak |G| is about c_k/2):
!>   f = 95, 412, 418 (a close pair), 730, 1150, 1600, 2100, 2650, 3200, 3800, 4300, 4750 Hz;
!>   xi = 0.01, 0.003, 0.005, 0.02, 0.12, 0.008, 0.05, 0.2, 0.015, 0.03, 0.006, 0.04;
!>   c = 1, -0.6, 0.8, 1.5, -2, 0.7, 3, -4, 1.2, -0.9, 0.5, 2 (x 1e-6 m/N; mixed signs).
!>   The same structure as case (a) of the mlfit test suite.
!> - Grid: 0 to 5 kHz, 8193 lines (df = 0.6104 Hz).
!> - Noise: each line multiplied by 1 + rho*(a + i*b)/sqrt(2), a and b standard Gaussian
!>   (Box-Muller on SplitMix64, greenconv_core_random): complex noise of rho*|G| rms per
!>   line, rho = 1 % and seed 13 by default.
!> - Format: a header (dataset 151) and one dataset 58 (function type 4, receptance,
!>   complex double, even spacing), response and reference node 1 +Z, written by
!>   greenconv_io_uff_write.
!>
!> Arguments (all optional, for the benchmark bench/ident_peer.py): noise fraction rho, seed,
!> output path. Build and run from the repository root against the plain build (`make lib`):
!>
!>     gfortran -O2 -Ibuild/make/include example/write_noisy_receptance.f90 build/make/libgreenconv.a \
!>         -llapack -lblas -lfftw3 -fopenmp -o build/write_noisy_receptance && build/write_noisy_receptance
program write_noisy_receptance
    use, intrinsic :: iso_fortran_env, only: dp => real64, error_unit, output_unit
    use greenconv_core_error, only: error_type
    use greenconv_core_random, only: random_stream
    use greenconv_model_modal_set, only: modal_set, modes_from_paper
    use greenconv_model_frf, only: frf_type, frf_from_modes
    use greenconv_io_uff, only: uff_function, uff_node
    use greenconv_io_uff_write, only: uff_header, write_uff, receptance_function
    implicit none

    real(dp), parameter :: pi = acos(-1.0_dp)
    real(dp), parameter :: f_max = 5000.0_dp
    integer, parameter :: n_f = 8193
    real(dp), parameter :: frequency(12) = [95.0_dp, 412.0_dp, 418.0_dp, 730.0_dp, 1150.0_dp, 1600.0_dp, &
                                            2100.0_dp, 2650.0_dp, 3200.0_dp, 3800.0_dp, 4300.0_dp, 4750.0_dp]
    real(dp), parameter :: damping(12) = [0.01_dp, 0.003_dp, 0.005_dp, 0.02_dp, 0.12_dp, 0.008_dp, 0.05_dp, &
                                          0.2_dp, 0.015_dp, 0.03_dp, 0.006_dp, 0.04_dp]
    real(dp), parameter :: height(12) = 1.0e-6_dp*[1.0_dp, -0.6_dp, 0.8_dp, 1.5_dp, -2.0_dp, 0.7_dp, 3.0_dp, &
                                                    -4.0_dp, 1.2_dp, -0.9_dp, 0.5_dp, 2.0_dp]

    type(modal_set) :: modes
    type(frf_type) :: frf
    type(error_type), allocatable :: error
    type(random_stream) :: stream
    type(uff_function) :: functions(1)
    type(uff_node) :: nodes(0)
    character(len=256) :: argument, path
    character(len=80) :: how
    real(dp) :: rho, a, b
    integer :: seed, k

    rho = 0.01_dp
    seed = 13
    path = 'data/noisy_receptance.uff'
    if (command_argument_count() >= 1) then
        call get_command_argument(1, argument)
        read (argument, *) rho
    end if
    if (command_argument_count() >= 2) then
        call get_command_argument(2, argument)
        read (argument, *) seed
    end if
    if (command_argument_count() >= 3) call get_command_argument(3, path)
    modes = modes_from_paper(height*damping*(2.0_dp*pi*frequency)**2, 2.0_dp*pi*frequency, damping)
    frf = frf_from_modes(modes, f_max, n_f)
    stream = random_stream(seed)
    do k = 1, n_f
        ! two statements: the order of two calls within one expression is the compiler's
        a = gaussian(stream)
        b = gaussian(stream)
        frf%receptance(k) = frf%receptance(k)*(1.0_dp + rho*cmplx(a, b, kind=dp)/sqrt(2.0_dp))
    end do
    write (how, '(a,es8.2,a,i0,a)') '12 modes, 0-5 kHz, 8193 lines, noise ', rho, ' of |G| (seed ', &
        seed, ')'
    functions(1) = receptance_function([1, 3], [1, 3], 0.0_dp, frf%frequency(2), frf%receptance, &
                                       'noisy point receptance of a 12-mode structure')
    functions(1)%id_lines(2) = how
    functions(1)%id_lines(4) = 'made by example/write_noisy_receptance.f90 (greenconv)'
    call write_uff(trim(path), functions, nodes, error, header=uff_header(model='greenconv noisy_receptance', &
                   description=how))
    if (allocated(error)) then
        write (error_unit, '(a)') 'write_noisy_receptance: '//error%message
        error stop 1
    end if
    write (output_unit, '(a)') 'wrote '//trim(path)//': '//trim(how)

contains

    !> A standard Gaussian number (Box-Muller).
    real(dp) function gaussian(stream)
        type(random_stream), intent(inout) :: stream

        real(dp) :: u1, u2

        u1 = 1.0_dp - stream%uniform()
        u2 = stream%uniform()
        gaussian = sqrt(-2.0_dp*log(u1))*cos(2.0_dp*pi*u2)
    end function gaussian

end program write_noisy_receptance
