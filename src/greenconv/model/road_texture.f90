!> A road texture read from a file: heights over a grid of positions x along the road and y
!> across it, for a contact patch whose width sees the texture (greenconv_scene_models_patch).
!>
!> File format: lines starting with `#` (comments) and blank lines anywhere; the first data
!> line holds the lateral positions, every later data line a position along the road and
!> the heights there:
!>
!>     # comments
!>         y_1     y_2   ...   y_m         lateral positions [m], m >= 2, strictly increasing
!>     x_1   h_11    h_12  ...   h_1m      x [m] then the heights [m] at (x_1, y_1) ... (x_1, y_m)
!>     x_2   h_21    h_22  ...   h_2m      x strictly increasing, at least two such lines
!>
!> Every number must be finite; a line with another count, a word, NaN or Inf, or a position
!> out of order gets one message naming the file and the line (status 2), e.g.
!>
!>     texture.dat:7: expected 4 values (x [m], then the heights [m] at the 3 y of line 3), found 3: "0.1 0 0"
!>
!> **Interpolation**: bilinear, h(x, y) = (1 - b)*((1 - a)*h_ij + a*h_i+1,j) + b*((1 - a)*h_i,j+1
!> + a*h_i+1,j+1) for x = (1 - a)*x_i + a*x_i+1, y = (1 - b)*y_j + b*y_j+1: linear in x as a road
!> profile file (greenconv_model_road_file) and linear in y, so any plane h = c0 + c1*x + c2*y
!> is reproduced to round-off. Beyond the grid the nearest edge value; a run checks that it
!> stays on the grid (`check_texture_coverage`).
module greenconv_model_road_texture
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_text, only: int_text, real_text
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_io_columns, only: read_lines, parse_row, count_tokens
    use greenconv_model_road_file, only: road_surface, road_travel, travel_span, locate, check_run_span
    implicit none
    private

    public :: road_texture, read_road_texture, check_texture_coverage

    !> Heights on an x-y grid, bilinear in between.
    type, extends(road_surface) :: road_texture
        !> File the texture was read from (for messages).
        character(len=:), allocatable :: path
        !> Positions along the road x_i [m], strictly increasing.
        real(dp), allocatable :: x(:)
        !> Positions across the road y_j [m], strictly increasing.
        real(dp), allocatable :: y(:)
        !> Heights height(i, j) [m] at (x_i, y_j).
        real(dp), allocatable :: height(:, :)
    contains
        !> Height [m] at (x, y) [m], bilinear; the nearest edge value beyond the grid.
        procedure :: height_at => texture_height
        !> The same height, as a road surface's.
        procedure :: surface_height => texture_height
        !> `check_texture_coverage`.
        procedure :: check_coverage => check_texture_coverage
    end type road_texture

contains

    !> Read and check a road texture file (format in the module description).
    subroutine read_road_texture(path, texture, error)
        !> File to read.
        character(len=*), intent(in) :: path
        !> The texture.
        type(road_texture), intent(out) :: texture
        !> Set (status 2), naming the file and the line, when the file does not fit the format.
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: lines(:)
        character(len=16), allocatable :: names(:), units(:)
        real(dp), allocatable :: rows(:, :), row(:)
        integer :: k, n, m, header, n_values

        call read_lines(path, 'road texture file', lines, error)
        if (allocated(error)) return
        header = 0
        do k = 1, size(lines)
            if (is_data(lines(k))) then
                header = k
                exit
            end if
        end do
        if (header == 0) then
            call fatal_error(error, path//': expected a header line of lateral positions y [m], then lines of x [m] ' &
                             //'and the heights [m] at each y, found no data line')
            return
        end if
        m = count_tokens(lines(header))
        call column_names('y_', m, .false., names, units)
        allocate (texture%y(m))
        call parse_row(path//':'//int_text(header)//': ', names, units, lines(header), texture%y, error)
        if (allocated(error)) return
        if (m < 2) then
            call fatal_error(error, path//':'//int_text(header)//': expected at least 2 lateral positions y [m] on ' &
                             //'the header line (the heights are interpolated in y), found '//int_text(m))
            return
        end if
        do k = 2, m
            if (texture%y(k) <= texture%y(k - 1)) then
                call fatal_error(error, path//':'//int_text(header)//': y_'//int_text(k)//': expected a position ' &
                                 //'above '//real_text(texture%y(k - 1))//' m (y must increase), found ' &
                                 //real_text(texture%y(k))//' m')
                return
            end if
        end do
        call column_names('h(y_', m, .true., names, units)
        allocate (rows(m + 1, size(lines)), row(m + 1))
        n = 0
        do k = header + 1, size(lines)
            if (.not. is_data(lines(k))) cycle
            n_values = count_tokens(lines(k))
            if (n_values /= m + 1) then
                call fatal_error(error, path//':'//int_text(k)//': expected '//int_text(m + 1)//' values (x [m], ' &
                                 //'then the heights [m] at the '//int_text(m)//' y of line '//int_text(header) &
                                 //'), found '//int_text(n_values)//': "'//trim(adjustl(lines(k)))//'"')
                return
            end if
            call parse_row(path//':'//int_text(k)//': ', names, units, lines(k), row, error)
            if (allocated(error)) return
            if (n > 0) then
                if (row(1) <= rows(1, n)) then
                    call fatal_error(error, path//':'//int_text(k)//': expected x above '//real_text(rows(1, n)) &
                                     //' m (x must increase), found '//real_text(row(1))//' m')
                    return
                end if
            end if
            n = n + 1
            rows(:, n) = row
        end do
        if (n < 2) then
            call fatal_error(error, path//': expected at least 2 lines of x [m] and heights [m] after the header ' &
                             //'line '//int_text(header)//', found '//int_text(n))
            return
        end if
        texture%path = path
        texture%x = rows(1, :n)
        texture%height = transpose(rows(2:, :n))
    end subroutine read_road_texture

    !> Whether a line holds data (not blank, not a `#` comment).
    pure logical function is_data(line)
        character(len=*), intent(in) :: line

        is_data = len_trim(line) > 0
        if (is_data) is_data = index(adjustl(line), '#') /= 1
    end function is_data

    !> Column names for messages: `x` first when `with_x`, then `<stem>k)` or `<stem>k`
    !> (closed when `stem` opens a parenthesis), k = 1..m; every unit `m`.
    pure subroutine column_names(stem, m, with_x, names, units)
        character(len=*), intent(in) :: stem
        integer, intent(in) :: m
        logical, intent(in) :: with_x
        character(len=16), allocatable, intent(out) :: names(:), units(:)

        integer :: k, shift

        shift = merge(1, 0, with_x)
        allocate (names(m + shift), units(m + shift))
        units(:) = 'm'
        if (with_x) names(1) = 'x'
        do k = 1, m
            names(k + shift) = stem//int_text(k)
            if (index(stem, '(') > 0) names(k + shift) = trim(names(k + shift))//')'
        end do
    end subroutine column_names

    !> Height [m] at (x, y) [m], bilinear (see the module description).
    elemental real(dp) function texture_height(self, x, y) result(height)
        !> The texture.
        class(road_texture), intent(in) :: self
        !> Position along the road [m].
        real(dp), intent(in) :: x
        !> Position across the road [m].
        real(dp), intent(in) :: y

        real(dp) :: a, b
        integer :: i, j

        call locate(self%x, x, i, a)
        call locate(self%y, y, j, b)
        height = (1.0_dp - b)*((1.0_dp - a)*self%height(i, j) + a*self%height(i + 1, j)) &
                 + b*((1.0_dp - a)*self%height(i, j + 1) + a*self%height(i + 1, j + 1))
    end function texture_height

    !> An error when a run of n_steps steps leaves the grid: some x_i + V*t_n, n = 0..n_steps-1,
    !> or some y_i outside it.
    subroutine check_texture_coverage(surface, travel, n_steps, error)
        !> The texture.
        class(road_texture), intent(in) :: surface
        !> The points (x_i and y_i) and their motion.
        type(road_travel), intent(in) :: travel
        !> Number of steps N_t.
        integer, intent(in) :: n_steps
        !> Set when the run needs heights beyond the grid.
        type(error_type), allocatable, intent(out) :: error

        call check_run_span(surface%path, 'texture', surface%x, travel_span(travel, n_steps), error)
        if (allocated(error)) return
        associate (y => travel%y)
            if (minval(y) < surface%y(1) .or. maxval(y) > surface%y(size(surface%y))) then
                call fatal_error(error, surface%path//': expected a texture from y = '//real_text(minval(y))//' m to ' &
                                 //real_text(maxval(y))//' m (the patch), found '//real_text(surface%y(1))//' m to ' &
                                 //real_text(surface%y(size(surface%y)))//' m')
            end if
        end associate
    end subroutine check_texture_coverage

end module greenconv_model_road_texture
