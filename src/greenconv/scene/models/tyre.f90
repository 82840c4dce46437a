!> The tyre/road scene: a line of N_c contact points under the tyre belt of
!> greenconv_model_tyre, rolling over a road read from a file, all forces solved together at each
!> step (greenconv_contact_multi), with the conventions of greenconv_scene_models_patch (the points at
!> y = 0 on the belt). This module turns the scene into what a multi-point run
!> needs (the points, the belt's modes at them, where each point meets the road) and the
!> scene's summary line; greenconv_scene_run_runner streams each method's run into
!> `<output_dir>/<name>_<method>.dat`, one row per step and point (t x u_road u f_contact
!> delta f_total), as it streams the single-point runs.
!>
!> The methods are those of the registry (greenconv_conv_methods) that serve multi-point
!> contact, built by greenconv_conv_builder's `make_multipoint_convolver`.
module greenconv_scene_models_tyre
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_scene_settings, only: scene_type, place_error
    use greenconv_model_tyre, only: tyre_modes, tyre_band, contact_positions, tyre_frequency
    use greenconv_model_point_modes, only: point_modes
    use greenconv_scene_models_patch, only: place_patch, run_text, road_step
    implicit none
    private

    public :: tyre_points, place_band_error, tyre_band_top

    real(dp), parameter :: pi = acos(-1.0_dp)

contains

    !> The contact points of a tyre scene, the belt's modes at them and where they meet the
    !> road, and the scene's line ("# scene NAME: tyre belt, ...") for a caller who prints it.
    !>
    !> Without `across` (as the sweep, greenconv_scene_sweep, calls it), the caller samples the
    !> road file itself: a scene on a road texture, or of another model, is refused then.
    subroutine tyre_points(scene, modes, positions, road_positions, summary, error, across)
        !> The scene (model 'tyre', road profile 'file' or 'texture').
        type(scene_type), intent(in) :: scene
        !> Modes of the belt up to the scene's f_max and their shapes at the points.
        type(point_modes), intent(out) :: modes
        !> Position x_i [m] of each point on the belt.
        real(dp), allocatable, intent(out) :: positions(:)
        !> Position [m] of each point on the road file at t = 0.
        real(dp), allocatable, intent(out) :: road_positions(:)
        !> The scene's summary line.
        character(len=:), allocatable, intent(out) :: summary
        !> Set for an unusable scene: not a contact run on a road file, no modes, a road too short.
        type(error_type), allocatable, intent(out) :: error
        !> Position Y_i [m] of each point across the road (y_start: the belt's points lie at y = 0).
        real(dp), allocatable, intent(out), optional :: across(:)

        real(dp), allocatable :: road_y(:)
        character(len=:), allocatable :: line
        real(dp) :: f_max
        integer :: i

        if (scene%task /= 'contact' .or. .not. (allocated(scene%road_data%x) .or. allocated(scene%texture%x))) then
            call fatal_error(error, scene%file//": &structure model: tyre points need model 'tyre', task = " &
                             //"'contact' and &road profile = 'file' or 'texture', found model '"//scene%model//"'")
            return
        end if
        if (allocated(scene%texture%x) .and. .not. present(across)) then
            call fatal_error(error, scene%file//": &road profile: 'texture' is not run by this caller (a sweep " &
                             //"samples a road file): use profile 'file'")
            return
        end if
        positions = contact_positions(0.5_dp*scene%tyre%length, scene%patch_length, scene%n_points)
        f_max = tyre_band_top(scene)
        call tyre_modes(scene%tyre, positions, f_max, modes, error, band_name='f_modes')
        if (allocated(error)) then
            call place_band_error(error, scene)
            return
        end if
        call place_patch(scene, positions, [(0.0_dp, i=1, size(positions))], road_positions, road_y, error)
        if (allocated(error)) return
        if (present(across)) call move_alloc(road_y, across)
        allocate (character(len=1000) :: line)
        write (line, '(a,i0,a,f0.3,a,i0,a,f0.1,a,f0.0,a)') &
            '# scene '//scene%name//': tyre belt, ', scene%n_points, ' contact points over ', scene%patch_length, &
            ' m, ', modes%modes%n_modes(), &
            ' modes from ', tyre_frequency(scene%tyre, 1)/(2.0_dp*pi), ' Hz up to the band, ', f_max, ' Hz, ' &
            //run_text(scene)
        summary = trim(line)
    end subroutine tyre_points

    !> Top of the band of a tyre or plate scene's modes [Hz]: `f_modes`, or when it is 0 the band
    !> rule of `tyre_band` (from &road speed, the road's step and &scene dt).
    real(dp) function tyre_band_top(scene)
        !> The scene (model 'tyre' or 'tyre_plate').
        type(scene_type), intent(in) :: scene

        tyre_band_top = scene%f_modes
        if (tyre_band_top <= 0.0_dp) tyre_band_top = tyre_band(abs(scene%speed), 2.0_dp*road_step(scene), scene%dt)
    end function tyre_band_top

    !> Place an error of the tyre or plate model's modes up to the band at `&structure
    !> f_modes`, the variable that sets the band, saying where the band came from when the
    !> scene leaves f_modes at 0 (the band rule of `tyre_band`).
    subroutine place_band_error(error, scene)
        !> The model's error ("... no mode below f_modes = 12.5 Hz ...: raise f_modes").
        type(error_type), intent(inout) :: error
        !> The scene (model 'tyre' or 'tyre_plate').
        type(scene_type), intent(in) :: scene

        if (scene%f_modes <= 0.0_dp) error%message = error%message//' (f_modes = 0 takes the band ' &
            //'min(2*V/lambda_min, 1/(10*dt)) from &road speed, the road''s step and &scene dt)'
        call place_error(error, scene, 'structure', 'f_modes')
    end subroutine place_band_error

end module greenconv_scene_models_tyre
