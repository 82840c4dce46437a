!> A receptance G(omega) sampled on a uniform frequency grid from 0 Hz, as a user
!> with a measured or computed frequency response function (FRF) has it.
!>
!> File format (read_frf, write_frf): any number of lines starting with `#` (comments)
!> and blank lines, and data lines of exactly three numbers
!>
!>     f [Hz]   Re G [m/N]   Im G [m/N]
!>
!> with f_j = j*df, j = 0..n-1, n >= `min_frf_lines`, df > 0. A spacing is accepted when
!> every f_j is within 1e-6*df of j*df (df = f_{n-1}/(n - 1)); the grid is then stored
!> exactly as j*df. G must be finite. Each kind of bad file gets one message naming the
!> file, the line and what was expected and found.
module greenconv_model_frf
    use greenconv_core_kinds, only: dp
    use greenconv_core_text, only: int_text, real_text
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_model_modal_set, only: modal_set
    use greenconv_io_files, only: write_columns
    use greenconv_io_columns, only: read_columns
    implicit none
    private

    public :: frf_type, frf_from_modes, read_frf, write_frf, min_frf_lines

    !> Fewest data lines read_frf accepts: n lines give 2*(n - 1) impulse samples, and 8
    !> lines (14 samples) is the least for an overdetermined order-2 linear prediction
    !> (one mode) with a few spare equations, and a residue fit with redundancy.
    integer, parameter :: min_frf_lines = 8

    !> Relative tolerance on the uniformity of the grid and on its start at 0 Hz (fraction of df).
    real(dp), parameter :: grid_tolerance = 1.0e-6_dp

    real(dp), parameter :: two_pi = 6.283185307179586476925286766559_dp

    !> Receptance samples G(2*pi*f_j) [m/N] on the uniform grid f_j = j*df, j = 0..n-1 [Hz].
    type :: frf_type
        !> Frequencies f_j = j*df [Hz], f_0 = 0.
        real(dp), allocatable :: frequency(:)
        !> Receptance G [m/N] at each frequency.
        complex(dp), allocatable :: receptance(:)
    contains
        !> Number of frequency lines n.
        procedure :: n_freq => frf_n_freq
        !> Frequency step df [Hz].
        procedure :: df => frf_df
        !> Highest frequency f_max = (n - 1)*df [Hz].
        procedure :: f_max => frf_f_max
    end type frf_type

contains

    !> Number of frequency lines.
    elemental integer function frf_n_freq(self)
        !> The FRF.
        class(frf_type), intent(in) :: self

        frf_n_freq = 0
        if (allocated(self%frequency)) frf_n_freq = size(self%frequency)
    end function frf_n_freq

    !> Frequency step df [Hz].
    elemental real(dp) function frf_df(self)
        !> The FRF (at least two lines).
        class(frf_type), intent(in) :: self

        frf_df = self%frequency(2) - self%frequency(1)
    end function frf_df

    !> Highest frequency f_max [Hz].
    elemental real(dp) function frf_f_max(self)
        !> The FRF (at least one line).
        class(frf_type), intent(in) :: self

        frf_f_max = self%frequency(size(self%frequency))
    end function frf_f_max

    !> Receptance of a modal set on n_freq lines from 0 to f_max [Hz] (eq. 6 for paper modes).
    pure function frf_from_modes(modes, f_max, n_freq) result(frf)
        !> The modes (pole-residue form of greenconv_model_modal_set).
        type(modal_set), intent(in) :: modes
        !> Highest frequency [Hz], > 0.
        real(dp), intent(in) :: f_max
        !> Number of lines, >= 2.
        integer, intent(in) :: n_freq
        type(frf_type) :: frf

        integer :: j

        allocate (frf%frequency(n_freq), frf%receptance(n_freq))
        frf%frequency(:) = [(j*(f_max/(n_freq - 1)), j=0, n_freq - 1)]
        frf%frequency(n_freq) = f_max
        frf%receptance(:) = modes%receptance(two_pi*frf%frequency)
    end function frf_from_modes

    !> Write an FRF in the format read_frf reads (atomically, through greenconv_io_files).
    subroutine write_frf(path, frf, error, comments)
        !> Target file.
        character(len=*), intent(in) :: path
        !> The FRF.
        type(frf_type), intent(in) :: frf
        !> Set when the file cannot be written.
        type(error_type), allocatable, intent(out) :: error
        !> Extra header lines (written after `# `) before the column names.
        character(len=*), intent(in), optional :: comments(:)

        character(len=*), parameter :: columns = 'f [Hz]  Re G [m/N]  Im G [m/N]'
        character(len=80), allocatable :: header(:)
        real(dp), allocatable :: table(:, :)
        integer :: n

        if (present(comments)) then
            n = size(comments)
            allocate (header(n + 1))
            header(1:n) = comments
        else
            n = 1
            allocate (header(2))
            header(1) = 'receptance G (m/N) on a uniform grid from 0 Hz'
        end if
        header(n + 1) = columns
        allocate (table(frf%n_freq(), 3))
        table(:, 1) = frf%frequency
        table(:, 2) = real(frf%receptance, dp)
        table(:, 3) = aimag(frf%receptance)
        call write_columns(path, header, table, error)
    end subroutine write_frf

    !> Read an FRF file (format in the module description) and check its grid.
    subroutine read_frf(path, frf, error)
        !> File to read.
        character(len=*), intent(in) :: path
        !> The FRF read, with the grid stored exactly as j*df.
        type(frf_type), intent(out) :: frf
        !> Set, with one message naming the file and line, when the file does not fit.
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: table(:, :)
        integer, allocatable :: line_of(:)
        integer :: n

        call read_columns(path, ['f   ', 'Re G', 'Im G'], ['Hz ', 'm/N', 'm/N'], table, line_of, error)
        if (allocated(error)) return
        n = size(table, 1)
        if (n == 0) then
            call fatal_error(error, path//': expected data lines f [Hz], Re G [m/N], Im G [m/N], found none ' &
                             //'(only comments or blank lines)')
            return
        end if
        if (n < min_frf_lines) then
            call fatal_error(error, path//': expected at least '//int_text(min_frf_lines)//' data lines (a uniform ' &
                             //'grid from 0 Hz), found '//int_text(n))
            return
        end if
        call check_grid(path, table(:, 1), line_of, error)
        if (allocated(error)) return
        allocate (frf%frequency(n), frf%receptance(n))
        frf%frequency(:) = grid(table(n, 1), n)
        frf%receptance(:) = cmplx(table(:, 2), table(:, 3), kind=dp)
    end subroutine read_frf

    !> The uniform grid j*f_max/(n - 1), j = 0..n-1, ending exactly at f_max.
    pure function grid(f_max, n) result(f)
        real(dp), intent(in) :: f_max
        integer, intent(in) :: n
        real(dp) :: f(n)

        integer :: j

        f = [(j*(f_max/(n - 1)), j=0, n - 1)]
        f(n) = f_max
    end function grid

    !> Check that the frequencies start at 0 and are uniformly spaced.
    subroutine check_grid(path, f, line_of, error)
        character(len=*), intent(in) :: path
        real(dp), intent(in) :: f(:)
        integer, intent(in) :: line_of(:)
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: df
        integer :: j, n

        n = size(f)
        df = f(n)/(n - 1)
        if (.not. (df > 0.0_dp) .or. f(2) <= f(1)) then
            call fatal_error(error, path//':'//int_text(line_of(2))//': expected frequencies increasing from 0 Hz, ' &
                             //'found '//real_text(f(1))//' Hz then '//real_text(f(2))//' Hz')
            return
        end if
        if (abs(f(1)) > grid_tolerance*df) then
            call fatal_error(error, path//':'//int_text(line_of(1))//': expected the grid to start at 0 Hz, found ' &
                             //real_text(f(1))//' Hz')
            return
        end if
        do j = 2, n
            if (f(j) <= f(j - 1)) then
                call fatal_error(error, path//':'//int_text(line_of(j))//': expected a frequency above ' &
                                 //real_text(f(j - 1))//' Hz (increasing), found '//real_text(f(j))//' Hz')
                return
            end if
            if (abs(f(j) - (j - 1)*df) > grid_tolerance*df) then
                call fatal_error(error, path//':'//int_text(line_of(j))//': expected a uniform grid, f = ' &
                                 //real_text((j - 1)*df)//' Hz (step '//real_text(df)//' Hz, relative tolerance ' &
                                 //'1e-6), found '//real_text(f(j))//' Hz')
                return
            end if
        end do
    end subroutine check_grid

end module greenconv_model_frf
