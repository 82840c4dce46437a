!> Files and inputs that suites of several layers write or read alike: a Green's matrix as a
!> universal file of receptances, a smooth road file, the roads of a modes file's nodes, the
!> shipped plate's modes file, and a reader of 1/3-octave band files.
module fixture_files_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, check
    use greenconv_core_error, only: error_type
    use greenconv_io_columns, only: read_columns
    use greenconv_io_uff, only: uff_function, uff_node
    use greenconv_io_uff_write, only: write_uff, receptance_function
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_plate, only: patch_receptance
    use greenconv_model_modes_file, only: file_modes
    use greenconv_model_road_file, only: road_file, file_road
    implicit none
    private

    public :: write_receptance_file, write_wave_road, wave_roads, read_bands, plate_file

    !> The shipped modes file of an aluminium plate (test/data/uff, written by pyuff).
    character(len=*), parameter :: plate_file = 'test/data/uff/modes_plate.uff'

    real(dp), parameter :: pi = acos(-1.0_dp)

contains

    !> Receptances of modes at points, lines 0, df, ..., (n - 1)*df, as a universal file with the nodes.
    subroutine write_receptance_file(path, modes, x, y, df, n, fail)
        character(len=*), intent(in) :: path
        type(point_modes), intent(in) :: modes
        real(dp), intent(in) :: x(:), y(:), df
        integer, intent(in) :: n
        type(error_type), allocatable, intent(out) :: fail

        type(uff_function), allocatable :: functions(:)
        type(uff_node), allocatable :: nodes(:)
        complex(dp), allocatable :: g(:, :, :)
        integer :: i, j, l, n_c

        n_c = size(x)
        allocate (g(n_c, n_c, n), functions(n_c*n_c), nodes(n_c))
        do l = 1, n
            g(:, :, l) = patch_receptance(modes, 2.0_dp*pi*df*(l - 1))
        end do
        do i = 1, n_c
            do j = 1, n_c
                functions((i - 1)*n_c + j) = receptance_function([i, 3], [j, 3], 0.0_dp, df, g(i, j, :), 'G')
            end do
            nodes(i) = uff_node(label=i, position=[x(i), y(i), 0.0_dp])
        end do
        call write_uff(path, functions, nodes, fail, node_dataset=2411)
    end subroutine write_receptance_file

    !> A smooth road, 0 to 1 m every 0.1 mm: 0.1 mm at a 50 mm wavelength plus 0.05 mm at 21 mm.
    subroutine write_wave_road(path)
        character(len=*), intent(in) :: path

        integer :: unit, j
        real(dp) :: x

        open (newunit=unit, file=path, status='replace', action='write')
        write (unit, '(a)') '# x [m], height [m]: test_modesfile_mod''s wave road'
        do j = 0, 10000
            x = 1.0e-4_dp*j
            write (unit, '(es24.16,1x,es24.16)') x, 1.0e-4_dp*sin(2.0_dp*pi*x/0.05_dp) &
                + 0.5e-4_dp*sin(2.0_dp*pi*x/0.021_dp)
        end do
        close (unit)
    end subroutine write_wave_road

    !> The wave road under each of the plate's nodes: the patch's middle at x = 0.3 m at t = 0,
    !> travelling at 5 m/s.
    function wave_roads(modes, road) result(roads)
        type(file_modes), intent(in) :: modes
        type(road_file), intent(in) :: road
        type(file_road), allocatable :: roads(:)

        integer :: i

        allocate (roads(size(modes%x)))
        do i = 1, size(roads)
            roads(i)%profile = road
            roads(i)%x_start = 0.3_dp + modes%x(i) - sum(modes%x)/size(modes%x)
            roads(i)%speed = 5.0_dp
        end do
    end function wave_roads

    !> The first n columns of a 1/3-octave band file (7 for a run's, with spread_db; 6 for a
    !> linear reference's).
    subroutine read_bands(path, n, rows, error)
        character(len=*), intent(in) :: path
        integer, intent(in) :: n
        real(dp), allocatable, intent(out) :: rows(:, :)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: fault
        integer, allocatable :: line_of(:)
        character(len=12) :: names(7)
        integer :: i

        names = [character(len=12) :: 'f_nominal', 'f_centre', 'f_lower', 'f_upper', 'power', 'level', 'spread_db']
        call read_columns(path, names(:n), [(' ', i=1, n)], rows, line_of, fault)
        call check(error, .not. allocated(fault), 'read '//path)
    end subroutine read_bands

end module fixture_files_mod
