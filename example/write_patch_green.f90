!> Writes data/patch_green.uff, the shipped Green's matrix of a 2D contact patch:
!> the receptances G_ij(f) [m/N] between the 12 points of a 4 x 3 patch under a tyre belt
!> modelled as a pre-tensioned orthotropic plate on an elastic foundation
!> (greenconv_model_plate, its default passenger-car values), with measurement-like noise.
!>
!> - Patch: 4 points along x (travel) by 3 across y, centred at (L/2, b/2) = (0.9425, 0.1) m,
!>   0.12 m long and 0.15 m wide, each point the middle of its share (x spacing 0.03 m, y
!>   spacing 0.05 m); node labels 1..12, x fastest (node 1 at the rear left, 4 at the front
!>   left, 12 at the front right), z = 0; all DOFs +Z (radial, direction 3).
!> - Grid: 0 to 600 Hz by 2 Hz (301 lines), damping xi = 0.02: the 31 distinct mode
!>   frequencies seen by the patch below 600 Hz are then resolvable (half-power bandwidth
!>   2*xi*f = 3.9 Hz at 96 Hz, 24 Hz at 600 Hz; the closest pairs, 277.8/281.7 Hz and
!>   318.4/325.1 Hz, are 1.5 to 2 bandwidths apart), as a measurement would be planned, and
!>   g_ij(t) spans 0.5 s, 6 time constants of the slowest mode (1/(xi*omega) = 83 ms at
!>   96 Hz). With 0-1200 Hz and xi = 0.05 (this file's first version) the 66 modes in band overlap so much above a few hundred Hz
!>   that the shared-pole fit found 8 poles, E worst 0.40.
!> - Modes: every plate mode up to 10 kHz (1582 modes), so that the modes above the grid add
!>   their quasi-static compliance as they would in a measurement (the fit's residual terms
!>   carry them).
!> - Noise: each line of each G_ij (G_ij and G_ji drawn independently, as two measurements)
!>   is multiplied by 1 + 0.01*(a + i*b)/sqrt(2), a and b standard Gaussian (Box-Muller on
!>   SplitMix64, greenconv_core_random, seed 14): complex noise of 1 % of |G| rms per line.
!> - Format: header dataset 151, nodes dataset 15, then the 144 datasets 58 (function type 4,
!>   complex double, even spacing), response node i the slow index; written by
!>   greenconv_io_uff_write, so read_uff reads it back.
!>
!> `make test` rebuilds it and checks that it writes the shipped file byte for byte
!> (`make patch-green-check`). Build and run from the repository root against the plain
!> build (`make lib`), optionally with another output path as the argument:
!>
!>     gfortran -O2 -Ibuild/make/include example/write_patch_green.f90 build/make/libgreenconv.a \
!>         -llapack -lblas -lfftw3 -fopenmp -o build/write_patch_green && build/write_patch_green
program write_patch_green
    use, intrinsic :: iso_fortran_env, only: dp => real64, error_unit, output_unit
    use greenconv_core_error, only: error_type
    use greenconv_core_random, only: random_stream
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_plate, only: tyre_plate, plate_modes, patch_points, patch_receptance
    use greenconv_io_uff, only: uff_function, uff_node
    use greenconv_io_uff_write, only: uff_header, write_uff, receptance_function
    implicit none

    character(len=:), allocatable :: path
    integer, parameter :: n_x = 4, n_y = 3, n_c = n_x*n_y, n_f = 301, seed = 14
    real(dp), parameter :: df = 2.0_dp, f_modes = 1.0e4_dp, noise = 0.01_dp, xi = 0.02_dp
    real(dp), parameter :: pi = acos(-1.0_dp)

    type(tyre_plate) :: plate
    type(point_modes) :: description
    type(error_type), allocatable :: error
    type(random_stream) :: stream
    type(uff_function), allocatable :: functions(:)
    type(uff_node) :: nodes(n_c)
    real(dp) :: x(n_c), y(n_c), a, b
    complex(dp) :: g(n_c, n_c, n_f), line(n_f)
    character(len=80) :: how
    integer :: i, j, k

    ! The output path: the first argument, by default the shipped file.
    block
        integer :: length
        call get_command_argument(1, length=length)
        if (length > 0) then
            allocate (character(len=length) :: path)
            call get_command_argument(1, path)
        else
            path = 'data/patch_green.uff'
        end if
    end block
    call patch_points([plate%length/2, plate%width/2], [0.12_dp, 0.15_dp], n_x, n_y, x, y)
    plate%damping_ratio = xi
    call plate_modes(plate, x, y, f_modes, description, error)
    if (allocated(error)) then
        write (error_unit, '(a)') 'write_patch_green: '//error%message
        error stop 1
    end if
    do k = 1, n_f
        g(:, :, k) = patch_receptance(description, 2.0_dp*pi*df*(k - 1))
    end do
    stream = random_stream(seed)
    allocate (functions(n_c*n_c))
    write (how, '(a,i0,a,f4.2,a,f4.2,a,i0,a)') 'plate defaults, ', size(description%shape, 2), &
        ' modes <= 10 kHz, xi ', xi, ', noise ', 100*noise, ' % of |G| (seed ', seed, ')'
    do i = 1, n_c
        do j = 1, n_c
            do k = 1, n_f
                ! two statements: the order of two calls within one expression is the compiler's
                a = gaussian(stream)
                b = gaussian(stream)
                line(k) = g(i, j, k)*(1.0_dp + noise*cmplx(a, b, kind=dp)/sqrt(2.0_dp))
            end do
            functions((i - 1)*n_c + j) = receptance_function([i, 3], [j, 3], 0.0_dp, df, line, &
                                                             'G_ij receptance of a tyre belt plate, 4 x 3 patch')
            functions((i - 1)*n_c + j)%id_lines(2) = how
            functions((i - 1)*n_c + j)%id_lines(4) = 'made by example/write_patch_green.f90 (greenconv)'
        end do
        nodes(i) = uff_node(label=i, position=[x(i), y(i), 0.0_dp])
    end do
    call write_uff(path, functions, nodes, error, node_dataset=15, header=uff_header( &
                   model='greenconv patch_green: tyre belt plate, 4 x 3 contact patch', &
                   description='G_ij(f) 0-600 Hz by 2 Hz, 1 % complex Gaussian noise per line, seed 14'))
    if (allocated(error)) then
        write (error_unit, '(a)') 'write_patch_green: '//error%message
        error stop 1
    end if
    write (output_unit, '(a,i0,a,i0,a,i0,a)') 'wrote '//path//': ', n_c*n_c, ' receptances of ', n_f, &
        ' lines, ', n_c, ' nodes; '//trim(how)
    write (output_unit, '(a,es10.3,a,es10.3,a)') 'static point compliance G_11(0) = ', real(g(1, 1, 1)), &
        ' m/N, |G_11| at 96 Hz = ', abs(g(1, 1, 49)), ' m/N'

contains

    !> A standard Gaussian number (Box-Muller).
    real(dp) function gaussian(stream)
        type(random_stream), intent(inout) :: stream

        real(dp) :: u1, u2

        u1 = 1.0_dp - stream%uniform()
        u2 = stream%uniform()
        gaussian = sqrt(-2.0_dp*log(u1))*cos(2.0_dp*pi*u2)
    end function gaussian

end program write_patch_green
