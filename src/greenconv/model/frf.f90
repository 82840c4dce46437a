!> A receptance G(omega) sampled on an increasing grid of frequencies f >= 0, as a user
!> with a measured or computed frequency response function (FRF) has it: the uniform grid
!> from 0 Hz an FFT gives, or what an analyser exports (a uniform grid from the first line
!> above 0 Hz, a band f_min..f_max, uneven or log-spaced lines).
!>
!> File format (read_frf, write_frf): any number of lines starting with `#` (comments)
!> and blank lines, and data lines of exactly three numbers
!>
!>     f [Hz]   Re G [m/N]   Im G [m/N]
!>
!> with 0 <= f_1 < f_2 < ... < f_n, n >= `min_frf_lines`. When the grid is the uniform grid
!> from 0 Hz (f_j = (j - 1)*df, every f_j within 1e-6*df of it, df = f_n/(n - 1)) it is
!> stored exactly as (j - 1)*df, as the inverse FFT wants it (`uniform_from_zero`); any other
!> grid is stored as read. G must be finite, |Re G| and |Im G| at most `max_green_magnitude`.
!> Each kind of bad file (a negative, repeated or decreasing frequency, too few lines, a non-number) gets one message naming the file, the
!> line and what was expected and found.
!>
!> What needs which grid: the maximum-likelihood identification (greenconv_ident_mlfit) fits
!> the lines given, any grid; LSCE and the impulse response g by inverse FFT (`direct`, `fft`
!> on g from G) need the uniform grid from 0 Hz, and `fft_grid_problem` says, naming the file
!> line, why a grid is not it.
!>
!> A universal file (recognised by its content, a first non-blank line holding `-1` in
!> columns 1-6, or by the extension .uff or .unv) is read too (greenconv_io_uff): one
!> dataset 58 of function type 4 (FRF) with a frequency abscissa, or the one `dataset`
!> names when the file holds several; its abscissa even or uneven, the same grids as a
!> column file. Its abscissae are E13.5 fields (six digits): a grid that lies within that
!> rounding of a uniform grid from its first line is taken to be that grid (`rounded_grid`:
!> df = 5000/8192 Hz written 6.10352E-01 is 3.6e-3 Hz off at 5 kHz when read as written). Its ordinate is converted to a receptance:
!> - receptance (displacement over force): taken as it is [m/N];
!> - mobility (velocity over force): G = Y/(i*omega);
!> - accelerance (acceleration over force): G = A/(i*omega)^2 = -A/omega^2;
!> and for the two converted kinds a 0 Hz line, where the division is 0/0, is the real
!> part of the linear extrapolation from the next two lines (2*G(df) - G(2*df) on a uniform
!> grid; G(0) of a real impulse response is real). Other kinds (e.g. a coherence, or units
!> the file does not say) are refused.
module greenconv_model_frf
    use greenconv_core_kinds, only: dp
    use greenconv_core_text, only: int_text, real_text
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_random, only: random_stream
    use greenconv_model_modal_set, only: modal_set
    use greenconv_io_files, only: write_columns
    use greenconv_io_columns, only: read_columns
    use greenconv_io_uff, only: uff_file, uff_function, read_uff, uff_kind_name, uff_function_type_name, &
                                uff_data_type_name, uff_receptance, uff_mobility, uff_accelerance
    implicit none
    private

    public :: frf_type, frf_from_modes, frf_grid, read_frf, write_frf, min_frf_lines, frf_from_uff, is_universal_file
    public :: add_relative_noise, check_contact_function, max_green_magnitude, green_values

    !> Largest magnitude a value of a universal file's Green's function may have, in its own
    !> unit ([m/N] for a receptance, [m/(N*s)] for an impulse response, [m/(N*s)] or [m/(N*s^2)]
    !> for a mobility or accelerance): no structure comes near it, and larger values overflow
    !> the sums of squares of the checks and fits that follow (1e308 would give Infinity).
    real(dp), parameter :: max_green_magnitude = 1.0e10_dp

    !> Fewest data lines read_frf accepts: n lines give 2*(n - 1) impulse samples, and 8
    !> lines (14 samples) is the least for an overdetermined order-2 linear prediction
    !> (one mode) with a few spare equations, and a residue fit with redundancy.
    integer, parameter :: min_frf_lines = 8

    !> Relative tolerance on the uniformity of the grid and on its start at 0 Hz (fraction of df).
    real(dp), parameter :: grid_tolerance = 1.0e-6_dp

    real(dp), parameter :: two_pi = 6.283185307179586476925286766559_dp

    !> Receptance samples G(2*pi*f_j) [m/N] on increasing frequencies f_j >= 0 [Hz] (the
    !> uniform grid f_j = j*df, j = 0..n-1, for the inverse FFT).
    type :: frf_type
        !> Frequencies [Hz], increasing, >= 0 (f_j = j*df from f_0 = 0 on the uniform grid).
        real(dp), allocatable :: frequency(:)
        !> Receptance G [m/N] at each frequency.
        complex(dp), allocatable :: receptance(:)
        !> Where G came from, in words, for a summary (set for a universal file: the dataset,
        !> its kind and conversion, response and reference node and direction); '' otherwise.
        character(len=:), allocatable :: source
        !> Line of the file each frequency was read from (the dataset's first line for a
        !> universal file), for messages; not allocated when G was not read from a file.
        integer, allocatable :: line(:)
    contains
        !> Number of frequency lines n.
        procedure :: n_freq => frf_n_freq
        !> Frequency step df [Hz] (of the first two lines).
        procedure :: df => frf_df
        !> Highest frequency f_max = (n - 1)*df [Hz].
        procedure :: f_max => frf_f_max
        !> Whether the grid is the uniform grid from 0 Hz the inverse FFT needs.
        procedure :: uniform_from_zero => frf_uniform_from_zero
        !> Why the grid is not the uniform grid from 0 Hz, naming the file line ('' when it is).
        procedure :: fft_grid_problem => frf_fft_grid_problem
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

    !> Whether the frequencies are the uniform grid f_j = j*df from 0 Hz, each within
    !> 1e-6*df of it (df = f_max/(n - 1)): what the inverse FFT of G needs.
    elemental logical function frf_uniform_from_zero(self)
        !> The FRF.
        class(frf_type), intent(in) :: self

        frf_uniform_from_zero = .false.
        if (self%n_freq() < 2) return
        frf_uniform_from_zero = off_grid(self%frequency) == 0
    end function frf_uniform_from_zero

    !> `frf_fft_grid_problem` blank-padded to a fixed length (numbers only, so it fits), which
    !> gives that function a result of spec length.
    pure function grid_problem_buffer(self) result(text)
        !> The FRF.
        class(frf_type), intent(in) :: self
        character(len=256) :: text

        real(dp) :: df
        integer :: j, n

        text = ''
        n = self%n_freq()
        if (n < 2) then
            text = 'expected the uniform grid from 0 Hz, found '//int_text(n)//' line(s)'
            return
        end if
        j = off_grid(self%frequency)
        if (j == 0) return
        df = self%frequency(n)/(n - 1)
        if (allocated(self%line)) then
            text = 'line '//int_text(self%line(j))//':'
        else
            text = 'grid line '//int_text(j)//':'
        end if
        text(len_trim(text) + 2:) = 'expected the uniform grid from 0 Hz (f = '//real_text((j - 1)*df)//' Hz there, step ' &
               //real_text(df)//' Hz), found '//real_text(self%frequency(j))//' Hz'
    end function grid_problem_buffer

    !> Why the grid is not the uniform grid from 0 Hz, e.g. "line 12: expected the uniform grid
    !> from 0 Hz (f = j*df, df = 5 Hz), found the first line at 5 Hz", '' when it is.
    pure function frf_fft_grid_problem(self) result(text)
        !> The FRF.
        class(frf_type), intent(in) :: self
        character(len=len_trim(grid_problem_buffer(self))) :: text

        text = grid_problem_buffer(self)
    end function frf_fft_grid_problem

    !> First index j whose frequency is off the uniform grid (j - 1)*df from 0 Hz by more than
    !> grid_tolerance*df (df = f(n)/(n - 1)); 0 when none is.
    pure integer function off_grid(f) result(first)
        real(dp), intent(in) :: f(:)

        real(dp) :: df
        integer :: n

        n = size(f)
        df = f(n)/(n - 1)
        do first = 1, n
            if (.not. (abs(f(first) - (first - 1)*df) <= grid_tolerance*df)) return
        end do
        first = 0
        if (.not. (df > 0.0_dp)) first = 1
    end function off_grid

    !> Receptance of a modal set on n_freq lines from 0 to f_max [Hz] (eq. 6 for paper modes).
    pure function frf_from_modes(modes, f_max, n_freq) result(frf)
        !> The modes (pole-residue form of greenconv_model_modal_set).
        type(modal_set), intent(in) :: modes
        !> Highest frequency [Hz], > 0.
        real(dp), intent(in) :: f_max
        !> Number of lines, >= 2.
        integer, intent(in) :: n_freq
        type(frf_type) :: frf

        frf%frequency = frf_grid(f_max, n_freq)
        frf%receptance = modes%receptance(two_pi*frf%frequency)
    end function frf_from_modes

    !> The uniform grid of n_freq lines from 0 to f_max [Hz] (the last line exactly f_max), on
    !> which a receptance computed from a model is sampled.
    pure function frf_grid(f_max, n_freq) result(frequency)
        !> Highest frequency [Hz], > 0.
        real(dp), intent(in) :: f_max
        !> Number of lines, >= 2.
        integer, intent(in) :: n_freq
        !> The lines [Hz].
        real(dp) :: frequency(n_freq)

        integer :: j

        frequency(:) = [(j*(f_max/(n_freq - 1)), j=0, n_freq - 1)]
        frequency(n_freq) = f_max
    end function frf_grid

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

    !> Read an FRF file, a column file or a universal file (formats in the module
    !> description), and check its grid.
    subroutine read_frf(path, frf, error, dataset)
        !> File to read.
        character(len=*), intent(in) :: path
        !> The FRF read, with the grid stored exactly as j*df.
        type(frf_type), intent(out) :: frf
        !> Set, with one message naming the file and line, when the file does not fit.
        type(error_type), allocatable, intent(out) :: error
        !> Universal file: which of its datasets 58 to read (1 = the first); 0 or absent: the
        !> file must hold exactly one.
        integer, intent(in), optional :: dataset

        real(dp), allocatable :: table(:, :)
        integer, allocatable :: line_of(:)
        integer :: n, chosen

        if (is_universal_file(path)) then
            chosen = 0
            if (present(dataset)) chosen = dataset
            call read_universal(path, chosen, frf, error)
            return
        end if
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
        n = findloc(max(abs(table(:, 2)), abs(table(:, 3))) > max_green_magnitude, .true., dim=1)
        if (n > 0) then
            call fatal_error(error, path//':'//int_text(line_of(n))//': expected Re G and Im G of at most ' &
                             //real_text(max_green_magnitude)//' m/N in magnitude, found '//real_text(table(n, 2)) &
                             //' and '//real_text(table(n, 3))//'; check the value and the file''s units')
            return
        end if
        n = size(table, 1)
        allocate (frf%receptance(n))
        frf%frequency = stored_grid(table(:, 1))
        frf%receptance(:) = cmplx(table(:, 2), table(:, 3), kind=dp)
        frf%line = line_of
        frf%source = ''
    end subroutine read_frf

    !> Whether a file is a universal file: its extension is .uff or .unv (any case), or its
    !> first non-blank line is a dataset delimiter (`-1` right-justified in columns 1-6).
    function is_universal_file(path) result(universal)
        !> The file.
        character(len=*), intent(in) :: path
        logical :: universal

        character(len=4) :: extension
        character(len=256) :: line
        integer :: unit, stat, i

        extension = ''
        if (len_trim(path) >= 4) extension = path(len_trim(path) - 3:len_trim(path))
        do i = 1, 4
            if (extension(i:i) >= 'A' .and. extension(i:i) <= 'Z') &
                extension(i:i) = achar(iachar(extension(i:i)) + 32)
        end do
        universal = extension == '.uff' .or. extension == '.unv'
        if (universal) return
        ! One file open at a time in the process, as greenconv_io_columns and _uff_records read.
        !$omp critical (greenconv_input_files)
        open (newunit=unit, file=path, status='old', action='read', iostat=stat)
        if (stat == 0) then
            do
                read (unit, '(a)', iostat=stat) line
                if (stat /= 0) exit
                if (len_trim(line) == 0) cycle
                universal = line(1:6) == '    -1' .and. len_trim(line(7:)) == 0
                exit
            end do
            close (unit)
        end if
        !$omp end critical (greenconv_input_files)
    end function is_universal_file

    !> Read a universal file and take one of its datasets 58 as the FRF.
    subroutine read_universal(path, dataset, frf, error)
        character(len=*), intent(in) :: path
        integer, intent(in) :: dataset
        type(frf_type), intent(out) :: frf
        type(error_type), allocatable, intent(out) :: error

        type(uff_file) :: file
        character(len=:), allocatable :: list
        integer :: i, n

        call read_uff(path, file, error)
        if (allocated(error)) return
        n = size(file%functions)
        if (n == 0) then
            call fatal_error(error, path//': expected a dataset 58 (a function at nodal DOF) in this universal ' &
                             //'file, found none')
            return
        end if
        if (dataset > n) then
            call list_functions(file, list)
            call fatal_error(error, path//': frf_dataset = '//int_text(dataset)//' asks for dataset 58 number ' &
                             //int_text(dataset)//', but the file holds '//int_text(n)//': '//list)
            return
        end if
        if (dataset < 1 .and. n > 1) then
            call list_functions(file, list)
            call fatal_error(error, path//': the file holds '//int_text(n)//' datasets 58; say which one with ' &
                             //'&structure frf_dataset = N (1 to '//int_text(n)//'): '//list)
            return
        end if
        i = max(dataset, 1)
        call frf_from_uff(file%functions(i), frf, error, path)
        if (allocated(error)) return
        frf%source = path//' dataset 58 number '//int_text(i)//' of '//int_text(n)//' (line ' &
                     //int_text(file%functions(i)%line)//'): '//frf%source
    end subroutine read_universal

    !> The datasets 58 of a file in one line: `#1 line 1: frequency response function,
    !> receptance, 3+Z/1+Z; #2 ...`.
    pure subroutine list_functions(file, text)
        !> The universal file.
        type(uff_file), intent(in) :: file
        !> The listing.
        character(len=:), allocatable, intent(out) :: text

        integer :: i

        text = ''
        do i = 1, size(file%functions)
            associate (f => file%functions(i))
                if (i > 1) text = text//'; '
                text = text//'#'//int_text(i)//' line '//int_text(f%line)//': ' &
                       //uff_function_type_name(f%function_type)//', '//uff_kind_name(f%kind)//', response ' &
                       //dof_text(f%response_node, f%response_direction)//' / reference ' &
                       //dof_text(f%reference_node, f%reference_direction)
            end associate
        end do
    end subroutine list_functions

    !> `dof_text` blank-padded to a fixed length, which gives that function a result of spec length.
    pure function dof_buffer(node, direction) result(text)
        integer, intent(in) :: node, direction
        character(len=16) :: text

        character(len=*), parameter :: axes(6) = ['X ', 'Y ', 'Z ', 'RX', 'RY', 'RZ']

        text = int_text(node)
        if (direction == 0) return
        text = int_text(node)//merge('+', '-', direction > 0)//trim(axes(min(abs(direction), 6)))
    end function dof_buffer

    !> A node and direction as `3+Z` (translation), `3-RX` (rotation) or `3` (scalar).
    pure function dof_text(node, direction) result(text)
        integer, intent(in) :: node, direction
        character(len=len_trim(dof_buffer(node, direction))) :: text

        text = dof_buffer(node, direction)
    end function dof_text

    !> A receptance from one dataset 58 of a universal file (function type 4, frequency
    !> abscissa), converted from mobility or accelerance as the module description says.
    !> `frf%source` says what was read: `receptance, response 3+Z, reference 1+Z` (with
    !> `, converted from mobility: G = Y/(i*omega)` when converted).
    subroutine frf_from_uff(function, frf, error, path)
        !> The dataset 58.
        type(uff_function), intent(in) :: function
        !> The receptance on the uniform grid from 0 Hz.
        type(frf_type), intent(out) :: frf
        !> Set, naming the file and the dataset's line, when the function cannot be a receptance.
        type(error_type), allocatable, intent(out) :: error
        !> The file, for messages.
        character(len=*), intent(in) :: path

        character(len=:), allocatable :: place
        integer, allocatable :: line_of(:)
        integer :: n, sign

        place = path//':'//int_text(function%line)//': dataset 58'
        n = 0
        if (allocated(function%ordinate)) n = size(function%ordinate)
        if (function%function_type /= 4) then
            call fatal_error(error, place//': expected function type 4 (frequency response function) in record 6, ' &
                             //'found '//int_text(function%function_type)//' ('// &
                             uff_function_type_name(function%function_type)//')')
        else if (n < min_frf_lines) then
            call fatal_error(error, place//': expected at least '//int_text(min_frf_lines)//' points, found ' &
                             //int_text(n))
        end if
        if (allocated(error)) return
        call check_contact_function(path, function, .true., sign, error)
        if (allocated(error)) return
        allocate (line_of(n))
        line_of(:) = function%line
        call check_grid(path, function%abscissa, line_of, error)
        if (allocated(error)) then
            error%message = error%message//' (dataset 58 abscissa, '//trim(merge('even  ', 'uneven', function%even)) &
                            //' spacing)'
            return
        end if
        frf%frequency = rounded_grid(function%abscissa, function%even)
        frf%line = line_of
        call green_values(path, function, frf%frequency, frf%uniform_from_zero(), frf%receptance, frf%source, error)
        if (allocated(error)) return
        if (sign < 0) then
            frf%receptance = -frf%receptance
            frf%source = frf%source//', sign changed to +/+ (driving point)'
        end if
        frf%source = frf%source//', response '//dof_text(function%response_node, function%response_direction) &
                     //', reference '//dof_text(function%reference_node, function%reference_direction)
    end subroutine frf_from_uff

    !> The values of a dataset 58 as the Green's function the convolution needs, from what
    !> records 8 to 10 say (the one reading of units for a single FRF and a Green's matrix):
    !>
    !> - function type 4 (frequency response), abscissa frequency (record 8 data type 18, or 0
    !>   unknown): a receptance (displacement over force, records 9/10 data types 8 over 9 or
    !>   13) is taken [m/N]; a mobility (velocity 11 over force) gives G = Y/(i*omega), an
    !>   accelerance (acceleration 12 over force) G = -A/omega^2, a 0 Hz line (0/0) being the
    !>   real part of the line through the next two lines at 0 Hz;
    !> - function type 1 (time response), abscissa time (data type 17, or 0): an impulse
    !>   response g(t) [m/(N*s)], displacement per unit impulse of force (records 9/10: 8 over
    !>   9 or 13), taken as it is;
    !> - anything else (a pressure in Pa, a velocity impulse response, an acceleration time
    !>   history, a coherence) is refused naming the file, the dataset's line, the record and
    !>   the data types found.
    pure subroutine green_values(path, function, abscissa, uniform, values, source, error)
        !> The file, for messages.
        character(len=*), intent(in) :: path
        !> The dataset 58.
        type(uff_function), intent(in) :: function
        !> Its abscissa as stored [Hz or s], increasing, >= 0.
        real(dp), intent(in) :: abscissa(:)
        !> Whether `abscissa` is the uniform grid from 0 Hz (its 0 Hz line is then extrapolated
        !> as 2*G(df) - G(2*df)).
        logical, intent(in) :: uniform
        !> The receptance G [m/N] (function type 4) or impulse response g [m/(N*s)] (type 1).
        complex(dp), allocatable, intent(out) :: values(:)
        !> What was read and how it was converted, e.g. `mobility converted by G = Y/(i*omega)`.
        character(len=:), allocatable, intent(out) :: source
        !> Set (status 2) for a function that is no Green's function in the units above.
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: place, found
        real(dp), allocatable :: omega(:)
        integer :: first, axis

        place = path//':'//int_text(function%line)//': dataset 58 '
        found = 'found '//uff_data_type_name(function%numerator%data_type)//' ('//int_text( &
                function%numerator%data_type)//') over '//uff_data_type_name(function%denominator%data_type)//' (' &
                //int_text(function%denominator%data_type)//')'
        source = ''
        axis = 18
        if (function%function_type == 1) axis = 17
        if (function%abscissa_axis%data_type /= axis .and. function%abscissa_axis%data_type /= 0) then
            call fatal_error(error, place//'record 8 field 1: expected the abscissa '//uff_data_type_name(axis) &
                             //' (specific data type '//int_text(axis)//') for function type ' &
                             //int_text(function%function_type)//', found '// &
                             uff_data_type_name(function%abscissa_axis%data_type)//' (' &
                             //int_text(function%abscissa_axis%data_type)//')')
            return
        end if
        if (function%function_type == 1) then
            if (function%kind /= uff_receptance) then
                call fatal_error(error, place//'records 9/10 field 1: expected an impulse response in m/(N*s), ' &
                                 //'displacement (8) over force (9 or 13), for a time response (function ' &
                                 //'type 1), '//found//'; write g_ij(t), the displacement per unit impulse')
                return
            end if
            values = function%ordinate
            source = 'impulse response'
            return
        end if
        if (all(function%kind /= [uff_receptance, uff_mobility, uff_accelerance])) then
            call fatal_error(error, place//'records 9/10 field 1: expected a receptance, mobility or ' &
                             //'accelerance (displacement 8, velocity 11 or acceleration 12 over force 9 or 13), ' &
                             //found)
            return
        end if
        allocate (values(size(function%ordinate)))
        omega = two_pi*abscissa
        ! Above 0 Hz the conversion divides; a 0 Hz line (the first, if any) is extrapolated below.
        first = 1
        if (abscissa(1) == 0.0_dp) first = 2
        source = uff_kind_name(function%kind)
        select case (function%kind)
        case (uff_receptance)
            values(:) = function%ordinate
        case (uff_mobility)
            values(first:) = function%ordinate(first:)/cmplx(0.0_dp, omega(first:), dp)
            source = source//' converted by G = Y/(i*omega)'
        case (uff_accelerance)
            values(first:) = -function%ordinate(first:)/omega(first:)**2
            source = source//' converted by G = -A/omega^2'
        end select
        if (function%kind /= uff_receptance .and. first == 2) then
            if (uniform) then
                values(1) = real(2.0_dp*values(2) - values(3), dp)
            else
                ! The line through the next two lines, at 0 Hz.
                associate (f => abscissa, g => values)
                    g(1) = real(g(2) - f(2)*(g(3) - g(2))/(f(3) - f(2)), dp)
                end associate
            end if
            source = source//' (0 Hz line extrapolated)'
        end if
    end subroutine green_values

    !> Check a dataset 58 taken as a Green's function. Between points of contact (`any_direction`
    !> false) the response and reference directions must lie along Z, the direction of contact
    !> (3 = +Z or -3 = -Z); `sign` is the product of their signs, which turns the values into
    !> +Z/+Z (a file in -Z/-Z needs no change, one in +Z/-Z its sign changed). A single FRF
    !> (`any_direction`: a driving point, or a transfer function to identify) may have any
    !> directions; only a driving point given with opposite signs on one axis (3+Z/3-Z) gets
    !> its sign changed. Also complex values for a frequency response (function type 4: real
    !> data types 2 and 4 would be taken with a zero imaginary part, which no receptance has),
    !> real or complex ones for an impulse response (type 1), and no value larger than
    !> `max_green_magnitude`. Each refusal names the file, line, record and field, what was
    !> expected and what was found.
    subroutine check_contact_function(path, function, any_direction, sign, error)
        !> The file, for messages.
        character(len=*), intent(in) :: path
        !> The dataset 58.
        type(uff_function), intent(in) :: function
        !> Whether any directions are accepted (a single FRF) rather than Z alone.
        logical, intent(in) :: any_direction
        !> +1 or -1: the factor that turns the values into the +/+ function (0 when refused).
        integer, intent(out) :: sign
        !> Set (status 2) for another direction, a real-valued frequency response or a value
        !> out of range.
        type(error_type), allocatable, intent(out) :: error

        integer :: i, line

        sign = 0
        if (.not. any_direction .and. &
            (abs(function%response_direction) /= 3 .or. abs(function%reference_direction) /= 3)) then
            call fatal_error(error, path//':'//int_text(function%line + 7)//': universal file dataset 58 record 6: ' &
                             //'expected the response and reference directions along Z, the direction of contact ' &
                             //'(3 or -3 in columns 52-55 and 77-80), found response ' &
                             //dof_text(function%response_node, function%response_direction)//' and reference ' &
                             //dof_text(function%reference_node, function%reference_direction) &
                             //'; give G_ij for vertical forces and displacements')
            return
        end if
        if (function%function_type == 4 .and. (function%ordinate_type == 2 .or. function%ordinate_type == 4)) then
            call fatal_error(error, path//':'//int_text(function%line + 8)//': universal file dataset 58 record 7: ' &
                             //'expected complex values (ordinate data type 5 or 6 in columns 1-10) for a ' &
                             //'frequency response ('//uff_data_type_name(function%numerator%data_type)//' over ' &
                             //uff_data_type_name(function%denominator%data_type)//'), found real-valued data ' &
                             //'(type '//int_text(function%ordinate_type)//'); its imaginary part would be taken ' &
                             //'as zero, which no receptance has: write Re and Im')
            return
        end if
        do i = 1, size(function%ordinate)
            associate (value => function%ordinate(i))
                if (max(abs(value%re), abs(value%im)) <= max_green_magnitude) cycle
                line = function%line
                if (allocated(function%point_line)) line = function%point_line(i)
                call fatal_error(error, path//':'//int_text(line)//': universal file dataset 58 record 12: ' &
                                 //'expected values of at most '//real_text(max_green_magnitude)//' in magnitude ' &
                                 //'(a Green''s function in m/N or m/(N*s)), found '//real_text(value%re) &
                                 //' + '//real_text(value%im)//'i at point '//int_text(i)//' ('//real_text( &
                                 function%abscissa(i))//' '//trim(merge('Hz', 's ', function%function_type /= 1)) &
                                 //'); check the value and the file''s units')
                return
            end associate
        end do
        sign = merge(-1, 1, function%response_direction*function%reference_direction < 0)
        if (any_direction .and. (function%response_node /= function%reference_node .or. &
                                 abs(function%response_direction) /= abs(function%reference_direction))) sign = 1
    end subroutine check_contact_function

    !> The grid to store: the uniform grid j*f_max/(n - 1), j = 0..n-1, ending exactly at f_max,
    !> when the frequencies read are that grid within the tolerance; else the frequencies read.
    pure function stored_grid(read) result(f)
        real(dp), intent(in) :: read(:)
        real(dp) :: f(size(read))

        integer :: j, n

        n = size(read)
        if (off_grid(read) /= 0) then
            f = read
            return
        end if
        f = [(j*(read(n)/(n - 1)), j=0, n - 1)]
        f(n) = read(n)
    end function stored_grid

    !> The grid a universal file states. Its abscissae went through E13.5 fields (six
    !> significant digits): record 7's increment for even spacing, each line's value for uneven.
    !> A grid such a file states as uniform (an analyser's df = 5000/8192 Hz written 6.10352E-01,
    !> 0.33806761... written 3.38068E-01) then comes back with an error of up to half a unit in
    !> the sixth digit, which grows along the lines (2e-3 Hz at the 5000th line): a systematic
    !> shift of every resonance. When every line lies within its rounding t_j of a uniform grid
    !> from the first line, the grid is taken to be that one: its last line F is the decimal
    !> with fewest significant digits within t_n of the last line read (the end a user chose,
    !> 1700 or 5000 Hz), else the last line itself, and f_j = f_1 + (j - 1)*(F - f_1)/(n - 1),
    !> f_n = F (from 0 Hz, j*F/(n - 1) exactly, as stored_grid gives). The rounding is
    !> t_j = (j - 1)*h(df) for even spacing (the minimum is the first line as stated) and
    !> t_j = h(f_j) for uneven, h(x) half a unit in the sixth significant digit of x. Any other
    !> grid is stored as stored_grid stores it.
    pure function rounded_grid(read, even) result(f)
        real(dp), intent(in) :: read(:)
        logical, intent(in) :: even
        real(dp) :: f(size(read))

        real(dp) :: tolerance(size(read)), last, step
        integer :: j, n, try

        n = size(read)
        if (even) then
            tolerance = [(j*half_unit(read(2) - read(1)), j=0, n - 1)]
        else
            tolerance = [(half_unit(read(j)), j=1, n)]
        end if
        do try = 1, 2
            if (try == 1) then
                last = shortest_decimal(read(n) - tolerance(n), read(n) + tolerance(n), read(n))
            else
                last = read(n)
            end if
            step = (last - read(1))/(n - 1)
            f = [(read(1) + j*step, j=0, n - 1)]
            f(n) = last
            ! The decimal read may be a few units in the last binary place off the decimal written.
            if (all(abs(read - f) <= tolerance + 8*spacing(abs(read)))) return
        end do
        f = stored_grid(read)
    end function rounded_grid

    !> Half a unit in the sixth significant digit of x, the rounding of an E13.5 field [as x].
    elemental real(dp) function half_unit(x)
        real(dp), intent(in) :: x

        half_unit = 0.0_dp
        if (x /= 0.0_dp) half_unit = 0.5_dp*10.0_dp**(floor(log10(abs(x))) - 5)
    end function half_unit

    !> The decimal with fewest significant digits in [low, high] (low <= high), the one nearest
    !> `near` among those; `near` itself when none has fewer than 17 digits.
    pure real(dp) function shortest_decimal(low, high, near) result(x)
        real(dp), intent(in) :: low, high, near

        real(dp) :: scale, candidate, best
        integer :: k, top, step

        x = near
        if (.not. (high > low) .or. .not. (high > 0.0_dp)) return
        top = floor(log10(max(abs(low), abs(high)))) + 1
        do k = top, top - 16, -1
            ! Multiples of 10^k, as integer/10^-k below 1 so that 0.001 is the double nearest it.
            scale = 10.0_dp**abs(k)
            best = huge(1.0_dp)
            do step = -1, 1
                if (k >= 0) then
                    candidate = (anint(near/scale) + step)*scale
                else
                    candidate = (anint(near*scale) + step)/scale
                end if
                if (candidate >= low .and. candidate <= high .and. abs(candidate - near) < best) then
                    x = candidate
                    best = abs(candidate - near)
                end if
            end do
            if (best < huge(1.0_dp)) return
        end do
        x = near
    end function shortest_decimal

    !> Check that the frequencies are >= 0 and increase (a grid from 0 Hz within the tolerance
    !> counts as starting at 0).
    subroutine check_grid(path, f, line_of, error)
        character(len=*), intent(in) :: path
        real(dp), intent(in) :: f(:)
        integer, intent(in) :: line_of(:)
        type(error_type), allocatable, intent(out) :: error

        integer :: j

        if (.not. (f(2) > f(1))) then
            call fatal_error(error, path//':'//int_text(line_of(2))//': expected frequencies increasing from 0 Hz, ' &
                             //'found '//real_text(f(1))//' Hz then '//real_text(f(2))//' Hz')
            return
        end if
        if (f(1) < 0.0_dp .and. off_grid(f) /= 0) then
            call fatal_error(error, path//':'//int_text(line_of(1))//': expected frequencies >= 0 Hz, found ' &
                             //real_text(f(1))//' Hz')
            return
        end if
        do j = 2, size(f)
            if (.not. (f(j) > f(j - 1))) then
                call fatal_error(error, path//':'//int_text(line_of(j))//': expected a frequency above ' &
                                 //real_text(f(j - 1))//' Hz (increasing), found '//real_text(f(j))//' Hz')
                return
            end if
        end do
    end subroutine check_grid

    !> Add complex Gaussian noise of standard deviation level*|G_l| to each line, as a measured
    !> receptance has it: Re and Im independent, each of variance (level*|G_l|)^2/2 (Box-Muller on
    !> greenconv_core_random's portable stream, so a seed gives the same draws everywhere). For
    !> tests and benchmarks of the identification.
    subroutine add_relative_noise(frf, level, seed)
        !> The receptance, changed in place.
        type(frf_type), intent(inout) :: frf
        !> Noise standard deviation as a fraction of |G| on each line.
        real(dp), intent(in) :: level
        !> Seed of the random stream.
        integer, intent(in) :: seed

        real(dp), parameter :: two_pi = 2.0_dp*acos(-1.0_dp)
        type(random_stream) :: stream
        real(dp) :: radius, angle
        integer :: l

        stream = random_stream(seed)
        do l = 1, size(frf%receptance)
            radius = sqrt(-2.0_dp*log(1.0_dp - stream%uniform()))
            angle = two_pi*stream%uniform()
            frf%receptance(l) = frf%receptance(l) + level*abs(frf%receptance(l))*sqrt(0.5_dp) &
                                *cmplx(radius*cos(angle), radius*sin(angle), dp)
        end do
    end subroutine add_relative_noise

end module greenconv_model_frf
