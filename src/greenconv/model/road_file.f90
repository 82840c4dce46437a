!> A road profile read from a file: heights over distance, linearly interpolated.
!>
!> File format: any number of lines starting with `#` (comments) and blank lines, and data
!> lines of exactly two finite numbers
!>
!>     x [m]   height [m]
!>
!> with x strictly increasing, at least two lines. A bad file gets one message naming the
!> file and the line (greenconv_io_columns). A body travelling at speed V [m/s] with contact
!> points at x_i + V*t sees u_r,i(t) = height(x_i + V*t); `sample_road_steps` gives those
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

    public :: road_surface, road_file, read_road_file, check_road_coverage, sample_road, sample_road_steps, file_road
    public :: road_travel, travel_span, travel_positions, locate, check_run_span

    !> Contact points travelling over a road (a profile or a texture): where they stand at
    !> t = 0 and how they move. Point i is at x_i + V*t_n along the road at t_n = n*dt.
    type :: road_travel
        !> Positions x_i [m] of the points along the road at t = 0.
        real(dp), allocatable :: x(:)
        !> Positions y_i [m] of the points across the road (read on a texture only).
        real(dp), allocatable :: y(:)
        !> Travel speed V [m/s] (the points move towards increasing x when V > 0).
        real(dp) :: speed = 0.0_dp
        !> Time step dt [s].
        real(dp) :: dt = 0.0_dp
    end type road_travel

    !> A road surface contact points travel over: a height at each position along (x) and
    !> across (y) the road.
    type, abstract :: road_surface
    contains
        !> Height [m] at x along and y across the road [m].
        procedure(surface_height_of), deferred :: surface_height
        !> An error when a run of N_t steps needs heights beyond the surface's data.
        procedure(coverage_check), deferred :: check_coverage
    end type road_surface

    abstract interface
        !> Height [m] of a road surface at x along and y across the road [m].
        elemental real(dp) function surface_height_of(self, x, y)
            import :: road_surface, dp
            class(road_surface), intent(in) :: self
            real(dp), intent(in) :: x, y
        end function surface_height_of

        !> Set `error` (status 2) when the points' `travel` over n_steps steps needs heights
        !> beyond the surface's data.
        subroutine coverage_check(surface, travel, n_steps, error)
            import :: road_surface, road_travel, error_type
            class(road_surface), intent(in) :: surface
            type(road_travel), intent(in) :: travel
            integer, intent(in) :: n_steps
            type(error_type), allocatable, intent(out) :: error
        end subroutine coverage_check
    end interface

    !> A road profile: heights at increasing positions, linear in between.
    type, extends(road_surface) :: road_file
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
        !> The profile's height as a surface's: the same at every y.
        procedure :: surface_height => profile_surface_height
        !> `check_road_coverage`.
        procedure :: check_coverage => check_road_coverage
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
    !> value (check with `covers`, as `check_road_coverage` does).
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

    elemental real(dp) function profile_surface_height(self, x, y)
        !> The profile.
        class(road_file), intent(in) :: self
        !> Position along the road [m].
        real(dp), intent(in) :: x
        !> Position across the road [m] (a profile is the same at every y).
        real(dp), intent(in) :: y

        profile_surface_height = self%height_at(x)
    end function profile_surface_height

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

    !> An error when a run of n_steps steps needs x beyond the file: some x_i + V*t_n,
    !> n = 0..n_steps-1, outside it.
    subroutine check_road_coverage(surface, travel, n_steps, error)
        !> The profile.
        class(road_file), intent(in) :: surface
        !> The points and their motion.
        type(road_travel), intent(in) :: travel
        !> Number of steps N_t.
        integer, intent(in) :: n_steps
        !> Set when some x_i + V*t_n lies outside the file.
        type(error_type), allocatable, intent(out) :: error

        call check_run_span(surface%path, 'road', surface%x, travel_span(travel, n_steps), error)
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
    pure function travel_span(travel, n_steps) result(span)
        !> The points and their motion.
        type(road_travel), intent(in) :: travel
        !> Number of steps N_t.
        integer, intent(in) :: n_steps
        !> Smallest and largest position [m].
        real(dp) :: span(2)

        real(dp) :: distance

        distance = travel%speed*(n_steps - 1)*travel%dt
        span(1) = min(minval(travel%x), minval(travel%x) + distance)
        span(2) = max(maxval(travel%x), maxval(travel%x) + distance)
    end function travel_span

    !> Where point i stands along the road [m] at the steps n = first..first+count-1:
    !> x_i + V*n*dt.
    pure function travel_positions(travel, i, first, count) result(x)
        !> The points and their motion.
        type(road_travel), intent(in) :: travel
        !> Index of the point.
        integer, intent(in) :: i
        !> Index of the first step.
        integer(int64), intent(in) :: first
        !> Number of steps.
        integer, intent(in) :: count
        !> Positions [m], one per step.
        real(dp) :: x(count)

        integer :: j

        x = [(travel%x(i) + travel%speed*((first + j)*travel%dt), j=0, count - 1)]
    end function travel_positions

    !> Heights under N_c points travelling over a road (profile or texture) for a whole run:
    !> heights(n, i) = h(x_i + V*n*dt, y_i), n = 0..n_steps-1, once the surface's
    !> `check_coverage` has found the run within its data.
    subroutine sample_road(surface, travel, n_steps, heights, error)
        !> The road: a profile or a texture.
        class(road_surface), intent(in) :: surface
        !> Where the points stand at t = 0 and how they move.
        type(road_travel), intent(in) :: travel
        !> Number of steps N_t.
        integer, intent(in) :: n_steps
        !> Road heights [m], (0:n_steps-1, N_c); not allocated on an error.
        real(dp), allocatable, intent(out) :: heights(:, :)
        !> The coverage check's error (status 2).
        type(error_type), allocatable, intent(out) :: error

        call surface%check_coverage(travel, n_steps, error)
        if (.not. allocated(error)) call sample_road_steps(surface, travel, 0_int64, n_steps, heights)
    end subroutine sample_road

    !> Heights under N_c points for the steps n = first..first+count-1 of a run (one block of
    !> a streamed run): heights(j, i) = h(x_i + V*t_n, y_i), n = first + j (y_i = 0 when the
    !> travel gives none); beyond the data the edge values (check the whole run once first with
    !> `check_road_coverage` or `check_texture_coverage`).
    subroutine sample_road_steps(surface, travel, first, count, heights)
        !> The road: a profile or a texture.
        class(road_surface), intent(in) :: surface
        !> The points and their motion.
        type(road_travel), intent(in) :: travel
        !> Index of the first step.
        integer(int64), intent(in) :: first
        !> Number of steps.
        integer, intent(in) :: count
        !> Road heights [m], (0:count-1, N_c).
        real(dp), allocatable, intent(out) :: heights(:, :)

        integer :: i
        real(dp) :: across

        allocate (heights(0:count - 1, size(travel%x)))
        do i = 1, size(travel%x)
            across = 0.0_dp
            if (allocated(travel%y)) across = travel%y(i)
            heights(:, i) = surface%surface_height(travel_positions(travel, i, first, count), across)
        end do
    end subroutine sample_road_steps

end module greenconv_model_road_file
