!> A road profile read from a file: heights over distance, linearly interpolated.
!>
!> File format: any number of lines starting with `#` (comments) and blank lines, and data
!> lines of exactly two finite numbers
!>
!>     x [m]   height [m]
!>
!> with x strictly increasing, at least two lines. A bad file gets one message naming the
!> file and the line (greenconv_io_columns). A body travelling at speed V [m/s] with contact
!> points at x_i + V*t sees u_r,i(t) = height(x_i + V*t); `sample_road_file` gives those
!> heights at t_n = n*dt and refuses a run that needs x beyond the file.
module greenconv_model_road_file
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_text, only: int_text, real_text
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_io_columns, only: read_columns
    use greenconv_model_road, only: road_profile
    implicit none
    private

    public :: road_file, read_road_file, sample_road_file, check_road_coverage, sample_road_steps, file_road
    public :: travel_span, locate, check_run_span

    !> A road profile: heights at increasing positions, linear in between.
    type :: road_file
        !> File the profile was read from (for messages).
        character(len=:), allocatable :: path
        !> Positions x_j [m], strictly increasing.
        real(dp), allocatable :: x(:)
        !> Heights at x_j [m].
        real(dp), allocatable :: height(:)
    contains
        !> Height [m] at position x [m], linear between samples; the end value beyond them.
        procedure :: height_at
        !> Whether [x_low, x_high] lies within the file.
        procedure :: covers
    end type road_file

    !> A road file seen in time by one point travelling at constant speed:
    !> u_r(t) = height(x_start + V*t), the end value beyond the file.
    type, extends(road_profile) :: file_road
        !> The profile.
        type(road_file) :: profile
        !> Position x [m] of the point at t = 0.
        real(dp) :: x_start = 0.0_dp
        !> Travel speed V [m/s].
        real(dp) :: speed = 1.0_dp
    contains
        procedure :: height => file_road_height
    end type file_road

contains

    !> Road height [m] under the point at time t [s].
    elemental real(dp) function file_road_height(self, t)
        !> The road.
        class(file_road), intent(in) :: self
        !> Time [s].
        real(dp), intent(in) :: t

        file_road_height = self%profile%height_at(self%x_start + self%speed*t)
    end function file_road_height

    !> Read and check a road profile file (format in the module description).
    subroutine read_road_file(path, road, error)
        !> File to read.
        character(len=*), intent(in) :: path
        !> The profile.
        type(road_file), intent(out) :: road
        !> Set, with one line naming the file and line, when the file does not fit.
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: table(:, :)
        integer, allocatable :: line_of(:)
        integer :: j, n

        call read_columns(path, ['x     ', 'height'], ['m', 'm'], table, line_of, error)
        if (allocated(error)) return
        n = size(table, 1)
        if (n < 2) then
            call fatal_error(error, path//': expected at least 2 data lines (x [m], height [m]), found ' &
                             //int_text(n))
            return
        end if
        do j = 2, n
            if (table(j, 1) <= table(j - 1, 1)) then
                call fatal_error(error, path//':'//int_text(line_of(j))//': expected x above ' &
                                 //real_text(table(j - 1, 1))//' m (x must increase), found '//real_text(table(j, 1)) &
                                 //' m')
                return
            end if
        end do
        road%path = path
        allocate (road%x(n), road%height(n))
        road%x(:) = table(:, 1)
        road%height(:) = table(:, 2)
    end subroutine read_road_file

    !> Height [m] at x [m] by linear interpolation; x outside the file gives the nearest end
    !> value (check with `covers`, as `sample_road_file` does).
    elemental real(dp) function height_at(self, x)
        !> The profile.
        class(road_file), intent(in) :: self
        !> Position [m].
        real(dp), intent(in) :: x

        integer :: low
        real(dp) :: weight

        call locate(self%x, x, low, weight)
        height_at = (1.0_dp - weight)*self%height(low) + weight*self%height(low + 1)
    end function height_at

    !> The interval of a grid that holds v and where v lies in it: grid(low) <= v <= grid(low + 1),
    !> v = (1 - weight)*grid(low) + weight*grid(low + 1); beyond the grid the end interval with
    !> weight 0 or 1, so that an interpolation gives the end value there.
    pure subroutine locate(grid, v, low, weight)
        !> Strictly increasing positions, at least two.
        real(dp), intent(in) :: grid(:)
        !> The position.
        real(dp), intent(in) :: v
        !> Index of the interval's left end, 1..size(grid) - 1.
        integer, intent(out) :: low
        !> Fraction of the interval, in [0, 1].
        real(dp), intent(out) :: weight

        integer :: high, middle

        low = 1
        high = size(grid)
        if (v <= grid(1)) then
            weight = 0.0_dp
            return
        end if
        if (v >= grid(high)) then
            low = high - 1
            weight = 1.0_dp
            return
        end if
        do while (high - low > 1)
            middle = (low + high)/2
            if (grid(middle) <= v) then
                low = middle
            else
                high = middle
            end if
        end do
        weight = (v - grid(low))/(grid(low + 1) - grid(low))
    end subroutine locate

    !> Whether the file spans [x_low, x_high] [m].
    elemental logical function covers(self, x_low, x_high)
        !> The profile.
        class(road_file), intent(in) :: self
        !> Smallest position needed [m].
        real(dp), intent(in) :: x_low
        !> Largest position needed [m].
        real(dp), intent(in) :: x_high

        covers = x_low >= self%x(1) .and. x_high <= self%x(size(self%x))
    end function covers

    !> Heights under N_c points travelling at speed V: heights(n, i) = height(x_i + V*n*dt),
    !> n = 0..n_steps-1; an error when the run needs x beyond the file.
    subroutine sample_road_file(road, positions, speed, dt, n_steps, heights, error)
        !> The profile.
        type(road_file), intent(in) :: road
        !> Positions x_i [m] of the points on the road at t = 0.
        real(dp), intent(in) :: positions(:)
        !> Travel speed V [m/s] (the points move towards increasing x when V > 0).
        real(dp), intent(in) :: speed
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Number of steps N_t.
        integer, intent(in) :: n_steps
        !> Road heights [m], (0:n_steps-1, N_c).
        real(dp), allocatable, intent(out) :: heights(:, :)
        !> Set when some x_i + V*t_n lies outside the file.
        type(error_type), allocatable, intent(out) :: error

        call check_road_coverage(road, positions, speed, dt, n_steps, error)
        if (.not. allocated(error)) call sample_road_steps(road, positions, speed, dt, 0_int64, n_steps, heights)
    end subroutine sample_road_file

    !> An error when a run of n_steps steps needs x beyond the file: some x_i + V*t_n,
    !> n = 0..n_steps-1, outside it.
    subroutine check_road_coverage(road, positions, speed, dt, n_steps, error)
        !> The profile.
        type(road_file), intent(in) :: road
        !> Positions x_i [m] of the points on the road at t = 0.
        real(dp), intent(in) :: positions(:)
        !> Travel speed V [m/s].
        real(dp), intent(in) :: speed
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Number of steps N_t.
        integer, intent(in) :: n_steps
        !> Set when some x_i + V*t_n lies outside the file.
        type(error_type), allocatable, intent(out) :: error

        call check_run_span(road%path, 'road', road%x, travel_span(positions, speed, dt, n_steps), error)
    end subroutine check_road_coverage

    !> An error when a run visits positions beyond the data along the road: `what` (`road`,
    !> `texture`) of file `path` spans grid(1) to grid(n) [m], the run `span` [m].
    subroutine check_run_span(path, what, grid, span, error)
        !> File of the data (for the message).
        character(len=*), intent(in) :: path
        !> Name of the data in the message.
        character(len=*), intent(in) :: what
        !> Positions x [m] of the data, increasing.
        real(dp), intent(in) :: grid(:)
        !> Smallest and largest position [m] the run visits (`travel_span`).
        real(dp), intent(in) :: span(2)
        !> Set when span is not within [grid(1), grid(n)].
        type(error_type), allocatable, intent(out) :: error

        if (.not. (span(1) >= grid(1) .and. span(2) <= grid(size(grid)))) then
            call fatal_error(error, path//': expected a '//what//' from x = '//real_text(span(1))//' m to ' &
                             //real_text(span(2))//' m (the run), found '//real_text(grid(1))//' m to ' &
                             //real_text(grid(size(grid)))//' m')
        end if
    end subroutine check_run_span

    !> The positions [m] a run of n_steps steps visits: [min, max] of x_i + V*t_n over the
    !> points and n = 0..n_steps-1.
    pure function travel_span(positions, speed, dt, n_steps) result(span)
        !> Positions x_i [m] of the points on the road at t = 0.
        real(dp), intent(in) :: positions(:)
        !> Travel speed V [m/s].
        real(dp), intent(in) :: speed
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Number of steps N_t.
        integer, intent(in) :: n_steps
        !> Smallest and largest position [m].
        real(dp) :: span(2)

        real(dp) :: travel

        travel = speed*(n_steps - 1)*dt
        span(1) = min(minval(positions), minval(positions) + travel)
        span(2) = max(maxval(positions), maxval(positions) + travel)
    end function travel_span

    !> Heights under N_c points for the steps n = first..first+count-1 of a run (one block of
    !> a streamed run): heights(j, i) = height(x_i + V*t_n), n = first + j; beyond the file
    !> the end values (check the whole run once with `check_road_coverage`).
    subroutine sample_road_steps(road, positions, speed, dt, first, count, heights)
        !> The profile.
        type(road_file), intent(in) :: road
        !> Positions x_i [m] of the points on the road at t = 0.
        real(dp), intent(in) :: positions(:)
        !> Travel speed V [m/s].
        real(dp), intent(in) :: speed
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Index of the first step.
        integer(int64), intent(in) :: first
        !> Number of steps.
        integer, intent(in) :: count
        !> Road heights [m], (0:count-1, N_c).
        real(dp), allocatable, intent(out) :: heights(:, :)

        integer :: i, j

        allocate (heights(0:count - 1, size(positions)))
        do i = 1, size(positions)
            heights(:, i) = road%height_at([(positions(i) + speed*((first + j)*dt), j=0, count - 1)])
        end do
    end subroutine sample_road_steps

end module greenconv_model_road_file
