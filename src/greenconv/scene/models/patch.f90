!> The conventions of a multi-point scene, written once for every model whose body touches the
!> road at several points (the tyre belt's line of points, greenconv_scene_models_tyre; the nodes of a
!> Green's matrix file, greenconv_scene_run_points):
!>
!> - the body rests in static equilibrium under the total preload F0 (`&contact preload`)
!>   shared evenly by its N_c points, F0_i = F0/N_c, each compressed by delta0_i = the law's
!>   compression under F0_i; its displacements u_i are measured from that state;
!> - point i at (x_i, y_i) on the body sees the road at
!>
!>       X_i(t) = x_start + (x_i - x_mean) + V*t   along it,   Y_i = y_start + (y_i - y_mean)   across,
!>
!>   x_mean, y_mean the mean position of the points (the patch centre sits at x_start + V*t,
!>   y_start): u_r,i(t) = h(X_i(t)) for a road profile file (the same for every y), or
!>   h(X_i(t), Y_i) for a road texture (greenconv_model_road_texture, bilinear);
!> - compression delta_i = delta0_i + u_r,i - u_i, force F_i from the law, and the body is
!>   loaded by F_i - F0_i (greenconv_contact_multi).
module greenconv_scene_models_patch
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_model_road_file, only: road_travel, check_road_coverage, sample_road_steps
    use greenconv_model_road_texture, only: check_texture_coverage
    use greenconv_scene_settings, only: scene_type, place_error
    implicit none
    private

    public :: place_patch, sample_patch_road, run_text, road_step, point_share

contains

    !> Where the points of a body meet the road at t = 0 (see the module description), checked
    !> against the road for the whole run.
    subroutine place_patch(scene, x, y, road_x, road_y, error)
        !> The scene (road profile 'file' or 'texture').
        type(scene_type), intent(in) :: scene
        !> Positions x_i [m] of the points on the body, along the travel.
        real(dp), intent(in) :: x(:)
        !> Positions y_i [m] of the points on the body, across.
        real(dp), intent(in) :: y(:)
        !> Position X_i(0) [m] of each point along the road.
        real(dp), allocatable, intent(out) :: road_x(:)
        !> Position Y_i [m] of each point across the road (used by a texture).
        real(dp), allocatable, intent(out) :: road_y(:)
        !> Set (status 2) when the run leaves the road, naming the road file and the scene's x_start.
        type(error_type), allocatable, intent(out) :: error

        road_x = scene%x_start + (x - sum(x)/size(x))
        road_y = scene%y_start + (y - sum(y)/size(y))
        if (allocated(scene%texture%x)) then
            call check_texture_coverage(scene%texture, road_travel(road_x, road_y, scene%speed, scene%dt), scene%n_steps, error)
        else
            call check_road_coverage(scene%road_data, road_travel(road_x, road_y, scene%speed, scene%dt), scene%n_steps, error)
        end if
        if (allocated(error)) call place_error(error, scene, 'road', 'x_start')
    end subroutine place_patch

    !> Road heights u_r,i [m] under the points at steps first..first + count - 1,
    !> heights(j, i) for step first + j.
    subroutine sample_patch_road(scene, road_x, road_y, first, count, heights)
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> Positions X_i(0) [m] along the road (`place_patch`).
        real(dp), intent(in) :: road_x(:)
        !> Positions Y_i [m] across the road (`place_patch`).
        real(dp), intent(in) :: road_y(:)
        !> First step.
        integer(int64), intent(in) :: first
        !> Number of steps.
        integer, intent(in) :: count
        !> Heights (0:count - 1, N_c) [m].
        real(dp), allocatable, intent(out) :: heights(:, :)

        if (allocated(scene%texture%x)) then
            call sample_road_steps(scene%texture, road_travel(road_x, road_y, scene%speed, scene%dt), first, count, heights)
        else
            call sample_road_steps(scene%road_data, road_travel(road_x, road_y, scene%speed, scene%dt), first, count, heights)
        end if
    end subroutine sample_patch_road

    !> The area [m^2] each of a multi-point scene's N_c points stands for, what it adds to the
    !> contact area when in contact: on a patch grid (models 'tyre', 'tyre_plate') its share
    !> patch_length*patch_width/N_c, the share a law per area gives its spring; on the nodes of
    !> a file, the cell of the nodes' grid, the smallest gaps between their distinct x and
    !> between their distinct y (patch_width across for nodes on one line).
    pure real(dp) function point_share(scene, x, y, on_grid)
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> Positions x_i, y_i [m] of the points on the body.
        real(dp), intent(in) :: x(:), y(:)
        !> Whether the scene's model places its points on a patch grid (greenconv_scene_models_registry's
        !> `grid_dimensions` > 0).
        logical, intent(in) :: on_grid

        if (on_grid) then
            point_share = scene%patch_length*scene%patch_width/size(x)
        else
            point_share = smallest_gap(x, scene%patch_length)*smallest_gap(y, scene%patch_width)
        end if
    end function point_share

    !> The smallest positive gap between two of the values; `none` when they are all equal.
    pure real(dp) function smallest_gap(values, none)
        real(dp), intent(in) :: values(:), none

        integer :: i, j

        smallest_gap = huge(1.0_dp)
        do i = 1, size(values)
            do j = 1, size(values)
                if (values(j) > values(i)) smallest_gap = min(smallest_gap, values(j) - values(i))
            end do
        end do
        if (smallest_gap == huge(1.0_dp)) smallest_gap = none
    end function smallest_gap

    !> The smallest step [m] between the positions x of the scene's road file or texture.
    pure real(dp) function road_step(scene)
        !> The scene (road profile 'file' or 'texture').
        type(scene_type), intent(in) :: scene

        if (allocated(scene%texture%x)) then
            road_step = minval(scene%texture%x(2:) - scene%texture%x(:size(scene%texture%x) - 1))
        else
            road_step = minval(scene%road_data%x(2:) - scene%road_data%x(:size(scene%road_data%x) - 1))
        end if
    end function road_step

    !> "N steps of dt s at V m/s", blank-padded.
    pure function run_numbers(scene) result(numbers)
        type(scene_type), intent(in) :: scene
        character(len=80) :: numbers

        write (numbers, '(i0,a,es9.2,a,f0.1,a)') scene%n_steps, ' steps of ', scene%dt, ' s at ', scene%speed, ' m/s'
    end function run_numbers

    !> Length of `run_road(scene)`.
    pure integer function road_length(scene)
        type(scene_type), intent(in) :: scene

        road_length = 0
        if (allocated(scene%texture%x)) then
            road_length = 18 + len(scene%texture%path)
        else if (allocated(scene%road_data%path)) then
            road_length = 6 + len(scene%road_data%path)
        end if
    end function road_length

    !> " over the texture <path>", " over <path>" or '': the road of `run_text`.
    pure function run_road(scene) result(text)
        type(scene_type), intent(in) :: scene
        character(len=road_length(scene)) :: text

        if (allocated(scene%texture%x)) then
            text = ' over the texture '//scene%texture%path
        else if (allocated(scene%road_data%path)) then
            text = ' over '//scene%road_data%path
        end if
    end function run_road

    !> The end of a multi-point scene's summary line: "N steps of dt s at V m/s over <road>".
    function run_text(scene) result(text)
        !> The scene.
        type(scene_type), intent(in) :: scene
        character(len=len_trim(run_numbers(scene)) + len(run_road(scene))) :: text

        text = trim(run_numbers(scene))//run_road(scene)
    end function run_text

end module greenconv_scene_models_patch
