!> What a scene is once read: `scene_type`, every value a run needs in SI units, and where
!> each value stood in its file (`place_error`, for messages). Below the registry of structure
!> models (greenconv_scene_models_registry) and the scene reader (greenconv_scene_read_input), so that each
!> structure model's builder takes a scene without depending on the reader that checks it.
module greenconv_scene_settings
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_core_text, only: int_text
    use greenconv_model_road, only: road_profile
    use greenconv_contact_single, only: contact_law, contact_options
    use greenconv_model_tyre, only: tyre_belt
    use greenconv_model_plate, only: tyre_plate
    use greenconv_model_rail, only: rail_track, wheel_mass
    use greenconv_model_road_file, only: road_file_type => road_file
    use greenconv_model_road_texture, only: road_texture
    use greenconv_scene_scan, only: namelist_scan
    use greenconv_ident_methods, only: ident_none
    implicit none
    private

    public :: scene_type, scene_files, file_print, place, name_length, place_error

    !> Length of names read from a namelist.
    integer, parameter :: name_length = 64
    !> Everything a contact run needs, in SI units. `read_scene` sets every component; the
    !> defaults are those of the scene table, not component initialisers.
    type :: scene_type
        !> The namelist file the scene came from.
        character(len=:), allocatable :: file
        !> Where each group and variable of the file stands (its lines), from the pre-scan.
        type(namelist_scan) :: input
        !> What to do: `contact` (simulate) or `identify` (fit modes to the structure's G only).
        character(len=:), allocatable :: task
        !> Base name of the output files.
        character(len=:), allocatable :: name
        !> Directory the column files are written to.
        character(len=:), allocatable :: output_dir
        !> Time step [s].
        real(dp) :: dt
        !> Number of time steps N_t.
        integer :: n_steps
        !> Write every this many steps to the column files (1: every step), >= 1.
        integer :: output_every
        !> How a contact run's rows are written: `text` (`.dat`) or `binary` (`.bin`, little-endian
        !> float64, with the text header file `.bin.txt`).
        character(len=8) :: output_format = 'text'
        !> Show a progress line on standard error for long runs (only when it is a terminal).
        logical :: progress
        !> Whether a contact run also writes the 1/3-octave spectrum of its contact force
        !> (greenconv_scene_run_spectra_output).
        logical :: spectra = .false.
        !> Exact centre frequencies [Hz] of the lowest and highest band of the spectra, as
        !> `check_spectra` resolved them from the file's values or the defaults.
        real(dp) :: spectra_f_low = 0.0_dp, spectra_f_high = 0.0_dp
        !> Whether the spectra of a multi-point run also give each point's level.
        logical :: spectra_points = .false.
        !> Per-point histories of a multi-point run: `auto` (all for N_c <= 100, none above),
        !> `all` or `none` (greenconv_scene_run_runner).
        character(len=8) :: point_histories = 'auto'
        !> Steps between two rows of the per-point histories (0: `output_every`).
        integer :: point_every = 0
        !> Times [s] of the force maps of a multi-point run, increasing (none: no map file).
        real(dp), allocatable :: map_times(:)
        !> Structure model: `sdof`, `random_modes`, `frf_file`, `tyre`, `tyre_plate`, `green_file` or `modes_file`.
        character(len=:), allocatable :: model
        !> Mass M [kg] of the sdof model.
        real(dp) :: mass
        !> Stiffness K [N/m] of the sdof model.
        real(dp) :: stiffness
        !> Damping ratio xi of the sdof model.
        real(dp) :: damping_ratio
        !> Number of modes of the random_modes model.
        integer :: n_modes
        !> Seed of the random_modes model.
        integer :: modes_seed
        !> Range of natural frequencies [Hz] of the random_modes model.
        real(dp) :: f_low, f_high
        !> Range of damping ratios of the random_modes model.
        real(dp) :: xi_low, xi_high
        !> Range of modal amplitudes A_k [1/kg] of the random_modes model.
        real(dp) :: a_low, a_high
        !> Receptance file of the frf_file model (columns f [Hz], Re G, Im G [m/N], or a universal file).
        character(len=:), allocatable :: frf_file
        !> Which dataset 58 of a universal frf_file to read (0: the file must hold one).
        integer :: frf_dataset = 0
        !> Universal file of the Green's matrix between the contact points (model `green_file`).
        character(len=:), allocatable :: green_file
        !> Universal file of normal modes (datasets 15/2411 and 55) of the modes_file model.
        character(len=:), allocatable :: modes_file
        !> Direction of the modes file's shapes normal to the road: +-1, +-2, +-3 for +-x, +-y, +-z.
        integer :: modes_direction = 3
        !> Length along x and width along y [m] of the patch of the modes file's nodes that touch
        !> the road, centred on the nodes' extent (0: no bound in that coordinate).
        real(dp) :: modes_patch_length = 0.0_dp, modes_patch_width = 0.0_dp
        !> The tyre belt of the tyre model (its damping ratio is `damping_ratio`).
        type(tyre_belt) :: tyre
        !> The 2D tyre belt of the tyre_plate model (its damping ratio is `damping_ratio`, its
        !> circumference `belt_length`).
        type(tyre_plate) :: plate
        !> The rail and its support of the wheel_rail model (SI: EI [N m^2], m [kg/m], per length
        !> stiffnesses [N/m^2] and dampings [N s/m^2]).
        type(rail_track) :: track
        !> The wheel of the wheel_rail model: mass [kg] on its primary suspension [N/m, N s/m].
        type(wheel_mass) :: wheel
        !> Universal file of the wheel's normal modes (dataset 55); '': the mass on its suspension.
        character(len=:), allocatable :: wheel_modes_file
        !> Highest natural frequency [Hz] of the tyre modes kept (0: the band rule of tyre_band).
        real(dp) :: f_modes
        !> Highest frequency [Hz] of the sampled G identified (random_modes); default 1/(2*dt).
        real(dp) :: f_max
        !> Number of frequency lines, 0 Hz to f_max, of the sampled G (random_modes).
        integer :: n_freq
        !> Target of the identification error E of eq. (7).
        real(dp) :: tol_e
        !> Largest number of modes the order scan tries.
        integer :: max_order
        !> Fixed number of modes (0: the smallest order that meets tol_e).
        integer :: order
        !> Identification of G as the scene names it: 'ml', 'lsce', 'poly_reference' or 'auto'
        !> (greenconv_ident_methods).
        character(len=:), allocatable :: ident_method
        !> The same resolved once by the registry (greenconv_ident_methods's `ident_scheme`):
        !> `ident_ml`, `ident_lsce`, ...; `ident_none` when the scene names none.
        integer :: identification = ident_none
        !> Noise model of the 'ml' identification: 'auto' (the default), 'relative', 'absolute',
        !> 'floor' or 'band' (ml_options%noise_model).
        character(len=:), allocatable :: ident_noise
        !> Order search of the 'ml' identification: 'global' or 'greedy' (ml_options%global_search).
        character(len=:), allocatable :: ident_search
        !> Road profile.
        class(road_profile), allocatable :: road
        !> The road file of profile 'file' (heights over x), for the multi-point scene.
        type(road_file_type) :: road_data
        !> The road texture of profile 'texture' (heights over x and y), for the multi-point scene.
        type(road_texture) :: texture
        !> Position [m] on the road file of the body (the patch centre) at t = 0.
        real(dp) :: x_start
        !> Lateral position [m] on the road texture of the patch centre (mean y of its points).
        real(dp) :: y_start
        !> Travel speed V [m/s] over the road.
        real(dp) :: speed
        !> Number of contact points N_c (tyre model; 1 otherwise).
        integer :: n_points
        !> Length [m] of the contact patch the N_c points share (tyre models).
        real(dp) :: patch_length
        !> Points of the patch grid along the travel (x) and across (y): N_c = n_x*n_y (a tyre
        !> line: n_y = 1).
        integer :: n_points_x = 1, n_points_y = 1
        !> Width [m] of the contact patch (tyre_plate; the tread width of a per-area law).
        real(dp) :: patch_width = 0.1_dp
        !> Tread stiffness per area k_a [N/m^(2+p)] the law's k_c was made from (k_c = k_a times
        !> each point's share of the patch); 0 when the scene gave k_c per point.
        real(dp) :: stiffness_per_area = 0.0_dp
        !> Single point: contact step (`explicit` or `implicit`) and divergence bound [m].
        type(contact_options) :: contact
        !> Contact law.
        class(contact_law), allocatable :: law
        !> Wheel radius R_w [m] Hertz's constant was computed from (0: `&contact stiffness` given).
        real(dp) :: wheel_radius = 0.0_dp
        !> Static preload F0 [N].
        real(dp) :: preload
        !> Convolution methods to run, in order.
        character(len=name_length), allocatable :: methods(:)
        !> Truncation fraction of max |g| for the direct method.
        real(dp) :: truncation_tol
        !> Relative accuracy the `auto` method must meet: the largest E (eq. 7) of a modal model
        !> it accepts; a scene that lists `auto` identifies modes with tol_e = accuracy.
        real(dp) :: accuracy
    end type scene_type

    !> A file a sweep's variants read: its path, the hash of its lines when a variant first read
    !> it (16 hexadecimal digits) and that variant's number.
    type :: file_print
        !> The file.
        character(len=:), allocatable :: path
        !> Hash of its lines when first read.
        character(len=16) :: hash = ''
        !> The variant that first read it.
        integer :: variant = 0
    end type file_print

    !> Road files and road textures read by scenes, each kept by its path: a caller that reads
    !> many scenes naming the same files (a sweep's variants) reads each file once.
    type :: scene_files
        !> The files a sweep's content keys read, each as first read (an edited one is refused).
        type(file_print), allocatable :: prints(:)
        !> The road files read, each with its path.
        type(road_file_type), allocatable :: roads(:)
        !> The road textures read, each with its path.
        type(road_texture), allocatable :: textures(:)
    end type scene_files

contains

    !> Put "file:line: &group variable: " before an error's message (the line of the variable
    !> when the file sets it, else of its group), for messages about a value of the scene or a
    !> file it names. A subroutine, not a text function: gfortran keeps the length of a
    !> function's deferred-length result in static storage, which threads share.
    subroutine place_error(error, scene, group, variable)
        !> The error, its message then "file:line: &group variable: message".
        type(error_type), intent(inout) :: error
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> Group name, lower case.
        character(len=*), intent(in) :: group
        !> Variable name, lower case.
        character(len=*), intent(in) :: variable

        error%message = place(scene, group, variable)//' '//variable//': '//error%message
    end subroutine place_error

    !> The line `place` names: of the first of `variables` the file sets, else of the group;
    !> 0 when the file has neither.
    pure integer function place_line(scene, group, variables)
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: group, variables

        character(len=:), allocatable :: rest
        integer :: comma

        place_line = 0
        rest = variables
        do while (place_line == 0 .and. len_trim(rest) > 0)
            comma = index(rest, ',')
            if (comma == 0) comma = len(rest) + 1
            place_line = scene%input%line_of(group, trim(adjustl(rest(:comma - 1))))
            rest = rest(min(comma + 1, len(rest) + 1):)
        end do
        if (place_line == 0) place_line = scene%input%line_of(group, '')
    end function place_line

    !> Length of `place(scene, group, variables)`.
    pure integer function place_length(scene, group, variables)
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: group, variables

        integer :: line

        line = place_line(scene, group, variables)
        place_length = len(scene%file) + 3 + len(group)
        if (line > 0) place_length = place_length + 1 + len(int_text(line))
    end function place_length

    !> "file:line: &group" with the line of the first variable of `variables` (a name or a list
    !> `a, b`) that the file sets, else that of the group, "file: &group" without the group.
    function place(scene, group, variables) result(text)
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> Group name, lower case.
        character(len=*), intent(in) :: group
        !> Variable names, lower case, comma-separated.
        character(len=*), intent(in) :: variables
        !> The place.
        character(len=place_length(scene, group, variables)) :: text

        integer :: line

        line = place_line(scene, group, variables)
        if (line > 0) then
            text = scene%file//':'//int_text(line)//': &'//group
        else
            text = scene%file//': &'//group
        end if
    end function place

end module greenconv_scene_settings
