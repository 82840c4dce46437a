!> A scene read from a namelist file: task, time grid, structure, road, contact law,
!> identification and convolution methods. The file is first scanned (greenconv_scene_read_schema,
!> greenconv_scene_scan: unknown names, wrong kinds, NaN/Inf, required values, each with its
!> line); then each group is read with a namelist read, starting from the defaults of the
!> scene table (greenconv_scene_read_schema's `scene_table`: the paper's Tab. 1 and section 3.1,
!> section 3.2 for the random road and random modes), and its values checked, messages
!> carrying the line of the variable. So a scene file states only what differs. The table
!> lists every variable with its units; doc/scenes.md shows it.
module greenconv_scene_read_input
    use, intrinsic :: iso_fortran_env, only: iostat_end
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_nan
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_constants, only: two_pi
    use greenconv_core_text, only: real_text, int_text, sci_text, quoted_list
    use greenconv_model_road, only: road_profile, sine_road, new_random_road
    use greenconv_contact_single, only: contact_options
    use greenconv_contact_laws, only: law_kind, find_law, new_law, parameter_list, parameter_text, &
                                      first_bad_parameter, max_law_parameters
    use greenconv_model_tyre, only: tyre_belt, contact_positions
    use greenconv_model_plate, only: tyre_plate
    use greenconv_model_roughness, only: new_roughness_road, iso3095_wavelengths, iso3095_levels
    use greenconv_model_rail, only: rail_track, wheel_mass_type => wheel_mass, wheel_from_modes, hertz_constant
    ! The type renamed: the &road namelist has a variable `road_file`, which gfortran 12 would
    ! otherwise confuse with the type.
    use greenconv_model_road_file, only: road_file_type => road_file, read_road_file, file_road, &
                                         check_road_coverage, road_travel
    use greenconv_model_road_texture, only: road_texture, read_road_texture, check_texture_coverage
    use greenconv_scene_scan, only: namelist_scan
    use greenconv_scene_read_schema, only: scan_scene, max_methods, scene_default, group_defaults, scene_variable, &
                                      scene_row, admits, max_map_times, max_roughness_bands
    use greenconv_io_columns, only: read_lines
    use greenconv_scene_models_facade, only: structure_kind, find_model, model_id, model_names, model_requires, &
                                             multi_point_model
    use greenconv_core_number_text, only: compact_real
    use greenconv_conv_methods, only: default_truncation_tol, default_accuracy, is_method, method_names, &
                                      check_method
    use greenconv_scene_limits, only: max_spectrum_values, max_contact_points
    use greenconv_ident_methods, only: check_ident_method, default_ident_method, ident_scheme
    use greenconv_conv_builder, only: check_kernel_values
    use greenconv_scene_settings, only: scene_type, scene_files, place, name_length, place_error
    use greenconv_io_spectra, only: band_centre, first_band, edge_band, nominal_frequency, segment_for_band, &
                                    lowest_resolved_band, highest_band_below, default_lines_per_band
    implicit none
    private

    public :: scene_type, scene_files, read_scene, read_scene_lines, output_path, write_scene_template, &
              place_error

    !> Length of paths read from a namelist.
    integer, parameter :: path_length = 1024

    !> Marks a group source that reads (no unit to write on).
    integer, parameter :: no_unit = -1

    !> What the group readers read: a scene's lines, or nothing when they write each group
    !> with its defaults on a unit instead (a scene template).
    type :: group_source
        !> The scene's lines, each padded with blanks to the longest (none for a template).
        character(len=:), allocatable :: lines(:)
        !> The unit a template is written on; `no_unit` when reading.
        integer :: unit = no_unit
    end type group_source

contains

    !> Path of the column file of one method: `<output_dir>/<name>_<method>.dat`, or `.bin`
    !> with `output_format = 'binary'`.
    function output_path(scene, method) result(path)
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> Method name.
        character(len=*), intent(in) :: method
        character(len=len(scene%output_dir) + len(scene%name) + len(method) + 6) :: path

        path = scene%output_dir//'/'//scene%name//'_'//method//'.dat'
        if (scene%output_format == 'binary') path = scene%output_dir//'/'//scene%name//'_'//method//'.bin'
    end function output_path

    !> Read and check a scene namelist file. The file is read once, from start to end (a pipe,
    !> a FIFO or a process substitution works), and scanned and parsed from memory.
    subroutine read_scene(path, scene, error)
        !> Path of the namelist file.
        character(len=*), intent(in) :: path
        !> The scene, with defaults where the file is silent.
        type(scene_type), intent(out) :: scene
        !> Set, naming the file, group and variable, when the input is unusable.
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: lines(:)

        scene%file = path
        call read_lines(path, 'scene file', lines, error)
        if (allocated(error)) return
        call read_scene_lines(path, lines, scene, error)
    end subroutine read_scene

    !> Read and check a scene from its lines in memory (as `read_scene` does a file's; a
    !> sweep's variant is read so). `name` stands for the file in the scene and its messages.
    subroutine read_scene_lines(name, lines, scene, error, files)
        !> What the messages call the scene (a path, or a sweep file and its variant).
        character(len=*), intent(in) :: name
        !> The scene's lines, each padded with blanks to the longest.
        character(len=*), intent(in) :: lines(:)
        !> The scene, with defaults where the lines are silent.
        type(scene_type), intent(out) :: scene
        !> Set, naming `name`, the group and the variable, when the input is unusable.
        type(error_type), allocatable, intent(out) :: error
        !> Files read by earlier scenes, taken from here rather than read again; files this
        !> scene reads are added.
        type(scene_files), intent(inout), optional :: files

        type(group_source) :: source

        scene%file = name
        call scan_scene(name, lines, scene%input, error)
        if (allocated(error)) return
        source%lines = lines
        call read_groups(source, scene, error, files)
        if (.not. allocated(error)) call check_scene_road(scene, error)
        if (.not. allocated(error)) call check_multipoint_scene(scene, error)
        if (.not. allocated(error)) call check_spectra(scene, error)
        if (.not. allocated(error)) call check_map_times(scene, error)
    end subroutine read_scene_lines

    !> Write every group of a scene file with its namelist, each variable at its default (a
    !> scene template; `preload` shows -1 for its default M*g). Written by the same namelists
    !> that read a scene, so it also shows which variables they hold.
    subroutine write_scene_template(unit, error)
        !> An open formatted unit.
        integer, intent(in) :: unit
        !> Set when a group cannot be written.
        type(error_type), allocatable, intent(out) :: error

        type(scene_type) :: scene
        type(group_source) :: source

        scene%file = 'scene template'
        call scene_default('scene', 'dt', scene%dt)
        allocate (character(len=1) :: source%lines(0))
        source%unit = unit
        call read_groups(source, scene, error)
    end subroutine write_scene_template

    !> Read (or write, for a template) every group in file order, each starting from its
    !> defaults in the scene table; stop at the first error.
    subroutine read_groups(source, this, error, files)
        type(group_source), intent(in) :: source
        type(scene_type), intent(inout) :: this
        type(error_type), allocatable, intent(out) :: error
        !> Road files and textures read before (see `read_scene_lines`).
        type(scene_files), intent(inout), optional :: files

        character(len=:), allocatable :: defaults

        call group_defaults('scene', defaults)
        call read_scene_group(source, defaults, this, error)
        call group_defaults('structure', defaults)
        if (.not. allocated(error)) call read_structure_group(source, defaults, this, error)
        call group_defaults('identification', defaults)
        if (.not. allocated(error)) call read_identification_group(source, defaults, this, error)
        call group_defaults('road', defaults)
        if (.not. allocated(error)) call read_road_group(source, defaults, this, error, files)
        call group_defaults('contact', defaults)
        if (.not. allocated(error)) call read_contact_group(source, defaults, this, error)
        call group_defaults('convolution', defaults)
        if (.not. allocated(error)) call read_convolution_group(source, defaults, this, error)
    end subroutine read_groups

    !> &scene: task, name, output_dir, dt [s], n_steps, output_every, output_format, progress.
    subroutine read_scene_group(source, defaults, this, error)
        type(group_source), intent(in) :: source
        !> The group's defaults, a namelist record (greenconv_scene_read_schema's `group_defaults`).
        character(len=*), intent(in) :: defaults
        type(scene_type), intent(inout) :: this
        type(error_type), allocatable, intent(out) :: error

        character(len=name_length) :: task, name, output_format, point_histories
        character(len=path_length) :: output_dir
        real(dp) :: dt, spectra_f_low, spectra_f_high, map_times(max_map_times)
        integer :: n_steps, output_every, stat, point_every
        logical :: progress, spectra, spectra_points
        character(len=512) :: message
        namelist /scene/ task, name, output_dir, dt, n_steps, output_every, output_format, progress, spectra, &
            spectra_f_low, spectra_f_high, spectra_points, point_histories, point_every, map_times

        ! a time no file can give (the scan refuses NaN) marks the map times not given
        map_times = ieee_value(1.0_dp, ieee_quiet_nan)
        read (defaults, nml=scene)
        if (source%unit /= no_unit) write (source%unit, nml=scene, delim='quote', iostat=stat, iomsg=message)
        if (source%unit == no_unit) read (source%lines, nml=scene, iostat=stat, iomsg=message)
        if (group_failed(this, 'scene', source, stat, message, error)) return
        call check_value(this, 'scene', 'task', task, error)
        call require(len_trim(name) > 0, error, this, 'scene', 'name', 'a file base name')
        call require(len_trim(output_dir) > 0, error, this, 'scene', 'output_dir', 'a directory path')
        call check_value(this, 'scene', 'dt', dt, error)
        call check_value(this, 'scene', 'n_steps', n_steps, error)
        call check_value(this, 'scene', 'output_every', output_every, error)
        call check_value(this, 'scene', 'output_format', output_format, error)
        call check_value(this, 'scene', 'point_histories', point_histories, error)
        call check_value(this, 'scene', 'point_every', point_every, error)
        call check_values(this, 'scene', [character(len=16) :: 'spectra_f_low', 'spectra_f_high'], &
                          [spectra_f_low, spectra_f_high], error)
        this%task = trim(task)
        this%name = trim(name)
        this%output_dir = trim(output_dir)
        this%dt = dt
        this%n_steps = n_steps
        this%output_every = output_every
        this%output_format = trim(output_format)
        this%progress = progress
        this%spectra = spectra
        this%spectra_f_low = spectra_f_low
        this%spectra_f_high = spectra_f_high
        this%spectra_points = spectra_points
        this%point_histories = trim(point_histories)
        this%point_every = point_every
        this%map_times = map_times(:count(.not. ieee_is_nan(map_times)))
        if (.not. allocated(error) .and. any(ieee_is_nan(this%map_times))) &
            call expect(error, this, 'scene', 'map_times', 'the times given from the first element on, without gaps')
    end subroutine read_scene_group

    !> &structure: the model and its parameters.
    subroutine read_structure_group(source, defaults, this, error)
        type(group_source), intent(in) :: source
        !> The group's defaults, a namelist record (greenconv_scene_read_schema's `group_defaults`).
        character(len=*), intent(in) :: defaults
        type(scene_type), intent(inout) :: this
        type(error_type), allocatable, intent(out) :: error

        character(len=name_length) :: model
        character(len=path_length) :: frf_file, green_file, modes_file, wheel_modes_file
        character(len=name_length) :: modes_direction
        real(dp) :: mass, stiffness, damping_ratio, f_low, f_high, xi_low, xi_high, a_low, a_high
        real(dp) :: belt_length, belt_mass, belt_bending, belt_tension, belt_foundation, f_modes
        real(dp) :: belt_width, plate_mass, plate_bending_x, plate_bending_y, plate_bending_xy, plate_tension_x, &
                    plate_tension_y, plate_foundation, modes_patch_length, modes_patch_width
        real(dp) :: rail_bending, rail_mass, rail_shear, rail_rotary, support_stiffness, support_damping, &
                    sleeper_mass, ballast_stiffness, ballast_damping, wheel_mass, suspension_stiffness, &
                    suspension_damping
        integer :: n_modes, seed, stat, frf_dataset, wheel_node
        character(len=512) :: message
        namelist /structure/ model, mass, stiffness, damping_ratio, n_modes, seed, f_low, f_high, &
            xi_low, xi_high, a_low, a_high, frf_file, frf_dataset, belt_length, belt_mass, belt_bending, &
            belt_tension, belt_foundation, belt_width, plate_mass, plate_bending_x, plate_bending_y, &
            plate_bending_xy, plate_tension_x, plate_tension_y, plate_foundation, f_modes, green_file, modes_file, &
            modes_direction, modes_patch_length, modes_patch_width, rail_bending, rail_mass, rail_shear, rail_rotary, &
            support_stiffness, support_damping, sleeper_mass, ballast_stiffness, ballast_damping, wheel_mass, &
            suspension_stiffness, suspension_damping, wheel_modes_file, wheel_node

        read (defaults, nml=structure)
        if (source%unit /= no_unit) write (source%unit, nml=structure, delim='quote', iostat=stat, iomsg=message)
        if (source%unit == no_unit) read (source%lines, nml=structure, iostat=stat, iomsg=message)
        if (group_failed(this, 'structure', source, stat, message, error)) return
        call require(model_id(trim(model)) > 0, error, this, 'structure', 'model', model_names(), model)
        call check_values(this, 'structure', [character(len=16) :: 'mass', 'stiffness', 'damping_ratio'], &
                          [mass, stiffness, damping_ratio], error)
        call check_value(this, 'structure', 'n_modes', n_modes, error)
        call require(f_low > 0.0_dp .and. f_high > f_low .and. f_high < huge(f_high), &
                     error, this, 'structure', 'f_low, f_high', '0 < f_low < f_high (Hz)', f_high)
        call require(xi_low > 0.0_dp .and. xi_high >= xi_low .and. xi_high < 1.0_dp, &
                     error, this, 'structure', 'xi_low, xi_high', '0 < xi_low <= xi_high < 1', xi_high)
        call require(a_low > 0.0_dp .and. a_high >= a_low .and. a_high < huge(a_high), &
                     error, this, 'structure', 'a_low, a_high', '0 < a_low <= a_high (1/kg)', a_high)
        call require(.not. model_requires(find_model(trim(model)), 'frf_file') .or. len_trim(frf_file) > 0, &
                     error, this, 'structure', 'frf_file', "a receptance file for model '"//trim(model)//"'")
        call require(.not. model_requires(find_model(trim(model)), 'green_file') .or. len_trim(green_file) > 0, &
                     error, this, 'structure', 'green_file', "a universal file of the Green's matrix for model '" &
                              //trim(model)//"'")
        call require(.not. model_requires(find_model(trim(model)), 'modes_file') .or. len_trim(modes_file) > 0, &
                     error, this, 'structure', 'modes_file', "a universal file of normal modes for model '" &
                              //trim(model)//"'")
        call check_value(this, 'structure', 'modes_direction', modes_direction, error)
        call check_values(this, 'structure', [character(len=18) :: 'modes_patch_length', 'modes_patch_width'], &
                          [modes_patch_length, modes_patch_width], error)
        this%model = trim(model)
        this%mass = mass
        this%stiffness = stiffness
        this%damping_ratio = damping_ratio
        this%n_modes = n_modes
        this%modes_seed = seed
        this%f_low = f_low
        this%f_high = f_high
        this%xi_low = xi_low
        this%xi_high = xi_high
        this%a_low = a_low
        this%a_high = a_high
        call require(all([belt_length, belt_mass] > 0.0_dp) .and. &
                     all([belt_bending, belt_tension, belt_foundation] >= 0.0_dp) .and. &
                     all([belt_length, belt_mass, belt_bending, belt_tension, belt_foundation] < huge(1.0_dp)), &
                     error, this, 'structure', 'belt_*', 'belt_length, belt_mass > 0 and belt_bending, ' &
                              //'belt_tension, belt_foundation >= 0, all finite')
        call check_values(this, 'structure', [character(len=16) :: 'belt_width', 'plate_mass', 'plate_bending_x', &
                          'plate_bending_y', 'plate_bending_xy', 'plate_tension_x', 'plate_tension_y', &
                          'plate_foundation'], [belt_width, plate_mass, plate_bending_x, plate_bending_y, &
                          plate_bending_xy, plate_tension_x, plate_tension_y, plate_foundation], error)
        call check_value(this, 'structure', 'f_modes', f_modes, error)
        call check_value(this, 'structure', 'frf_dataset', frf_dataset, error)
        call check_value(this, 'structure', 'wheel_node', wheel_node, error)
        this%frf_file = trim(frf_file)
        this%frf_dataset = frf_dataset
        this%green_file = trim(green_file)
        this%modes_file = trim(modes_file)
        this%modes_patch_length = modes_patch_length
        this%modes_patch_width = modes_patch_width
        this%modes_direction = index('xyz', modes_direction(2:2))*merge(-1, 1, modes_direction(1:1) == '-')
        this%tyre = tyre_belt(length=belt_length, mass_per_length=belt_mass, bending_stiffness=belt_bending, &
                              tension=belt_tension, foundation_stiffness=belt_foundation, &
                              damping_ratio=damping_ratio)
        this%plate = tyre_plate(length=belt_length, width=belt_width, mass_per_area=plate_mass, &
                                bending_x=plate_bending_x, bending_y=plate_bending_y, bending_xy=plate_bending_xy, &
                                tension_x=plate_tension_x, tension_y=plate_tension_y, foundation=plate_foundation, &
                                damping_ratio=damping_ratio)
        this%f_modes = f_modes
        call check_values(this, 'structure', [character(len=20) :: 'rail_bending', 'rail_mass', 'rail_shear', &
                          'rail_rotary', 'support_stiffness', 'support_damping', 'sleeper_mass', 'ballast_stiffness', &
                          'ballast_damping', 'wheel_mass', 'suspension_stiffness', 'suspension_damping'], &
                          [rail_bending, rail_mass, rail_shear, rail_rotary, support_stiffness, support_damping, &
                          sleeper_mass, ballast_stiffness, ballast_damping, wheel_mass, suspension_stiffness, &
                          suspension_damping], error)
        this%track = rail_track(bending=rail_bending, mass=rail_mass, shear=rail_shear, rotary=rail_rotary, &
                                pad_stiffness=support_stiffness, pad_damping=support_damping, &
                                sleeper_mass=sleeper_mass, ballast_stiffness=ballast_stiffness, &
                                ballast_damping=ballast_damping)
        this%wheel = wheel_mass_type(mass=wheel_mass, stiffness=suspension_stiffness, damping=suspension_damping)
        this%wheel_modes_file = trim(wheel_modes_file)
        call read_wheel_modes(this, wheel_node, error)
        call check_track(this, error)
    end subroutine read_structure_group

    !> The wheel_rail model's wheel from the modes of `wheel_modes_file` at `wheel_node`, when a
    !> file is named: one line naming the variable at fault.
    subroutine read_wheel_modes(this, wheel_node, error)
        type(scene_type), intent(inout) :: this
        integer, intent(in) :: wheel_node
        type(error_type), allocatable, intent(inout) :: error

        type(error_type), allocatable :: fault
        character(len=:), allocatable :: name

        if (allocated(error) .or. len(this%wheel_modes_file) == 0) return
        if (.not. model_requires(find_model(this%model), 'rail_bending')) return
        call wheel_from_modes(this%wheel_modes_file, this%modes_direction, wheel_node, this%damping_ratio, &
                              this%wheel, fault)
        if (allocated(fault)) then
            name = fault%message(:index(fault%message, ':') - 1)
            call fatal_error(error, place(this, 'structure', name)//' '//fault%message)
        end if
    end subroutine read_wheel_modes

    !> The wheel_rail model's track and wheel: the model's own checks (a message naming the
    !> variable) and, for a contact run, the highest resonance of the track's masses on their
    !> springs below the Nyquist frequency 1/(2*dt), which g sampled at dt must resolve.
    subroutine check_track(this, error)
        type(scene_type), intent(in) :: this
        type(error_type), allocatable, intent(inout) :: error

        type(error_type), allocatable :: fault
        real(dp) :: top
        character(len=:), allocatable :: name

        if (allocated(error) .or. .not. model_requires(find_model(this%model), 'rail_bending')) return
        call this%track%check(fault)
        if (.not. allocated(fault)) call this%wheel%check(fault)
        if (allocated(fault)) then
            name = fault%message(:index(fault%message, ':') - 1)
            call fatal_error(error, place(this, 'structure', name)//' '//fault%message)
            return
        end if
        if (this%task /= 'contact') return
        top = this%track%top_resonance()
        name = 'support_stiffness'
        if (top > sqrt(this%track%pad_stiffness/this%track%mass)/two_pi) name = 'sleeper_mass'
        call require(top < 0.5_dp/this%dt, error, this, 'structure', name, 'a track whose resonance ' &
                     //'(the rail on its pad, the sleepers between pad and ballast) lies below the Nyquist ' &
                     //'frequency 1/(2*dt) = '//sci_text(0.5_dp/this%dt)//' Hz, found one at '//sci_text(top) &
                     //' Hz: a smaller dt, or a softer support')
    end subroutine check_track

    !> &identification: frequency grid of the sampled G and LSCE options.
    subroutine read_identification_group(source, defaults, this, error)
        type(group_source), intent(in) :: source
        !> The group's defaults, a namelist record (greenconv_scene_read_schema's `group_defaults`).
        character(len=*), intent(in) :: defaults
        type(scene_type), intent(inout) :: this
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: f_max, tol_e
        integer :: n_freq, max_order, order, stat
        character(len=name_length) :: method, noise_model, search
        character(len=512) :: message
        character(len=:), allocatable :: refused
        type(error_type), allocatable :: why
        integer :: what
        type(structure_kind) :: model
        namelist /identification/ f_max, n_freq, tol_e, max_order, order, method, noise_model, search

        ! The table's default `1/(2*dt)`: G up to the Nyquist frequency of the run's step.
        f_max = 0.5_dp/this%dt
        read (defaults, nml=identification)
        if (source%unit /= no_unit) write (source%unit, nml=identification, delim='quote', iostat=stat, iomsg=message)
        if (source%unit == no_unit) read (source%lines, nml=identification, iostat=stat, iomsg=message)
        if (group_failed(this, 'identification', source, stat, message, error)) return
        call check_value(this, 'identification', 'f_max', f_max, error)
        call check_value(this, 'identification', 'n_freq', n_freq, error)
        call check_value(this, 'identification', 'tol_e', tol_e, error)
        call check_value(this, 'identification', 'max_order', max_order, error)
        call check_value(this, 'identification', 'order', order, error)
        this%f_max = f_max
        this%n_freq = n_freq
        this%tol_e = tol_e
        this%max_order = max_order
        model = find_model(this%model)
        what = model%identifies
        if (len_trim(method) == 0) method = default_ident_method(what, model%measured)
        call check_ident_method(trim(method), what, this%model, order, refused, why)
        if (allocated(why)) then
            if (refused == 'order') then
                call require(.false., error, this, 'identification', 'order', why%message, order)
            else
                call require(.false., error, this, 'identification', 'method', why%message, method)
            end if
        end if
        this%order = order
        this%ident_method = trim(method)
        this%identification = ident_scheme(method)
        call require(any(trim(noise_model) == ['auto    ', 'relative', 'absolute', 'floor   ', 'band    ']), error, &
                     this, 'identification', 'noise_model', "'auto', 'relative', 'absolute', 'floor' or 'band'", &
                     noise_model)
        this%ident_noise = trim(noise_model)
        call require(any(trim(search) == ['global', 'greedy']), error, this, 'identification', 'search', &
                     "'global' (greedy rounds, death moves, projected fits) or 'greedy' (the rounds alone)", search)
        this%ident_search = trim(search)
    end subroutine read_identification_group

    !> &road: profile and its parameters.
    subroutine read_road_group(source, defaults, this, error, files)
        type(group_source), intent(in) :: source
        !> The group's defaults, a namelist record (greenconv_scene_read_schema's `group_defaults`).
        character(len=*), intent(in) :: defaults
        type(scene_type), intent(inout) :: this
        type(error_type), allocatable, intent(out) :: error
        !> Road files and textures read before (see `read_scene_lines`).
        type(scene_files), intent(inout), optional :: files

        character(len=name_length) :: profile
        type(sine_road) :: sine
        character(len=path_length) :: road_file, texture_file
        real(dp) :: amplitude, omega, wavelength, speed, x_start, y_start, roughness_offset, contact_length
        real(dp) :: roughness_wavelengths(max_roughness_bands), roughness_levels(max_roughness_bands)
        integer :: n_terms, seed, stat, terms_per_band
        character(len=512) :: message
        namelist /road/ profile, amplitude, omega, wavelength, speed, n_terms, seed, road_file, x_start, &
            texture_file, y_start, roughness_wavelengths, roughness_levels, roughness_offset, terms_per_band, &
            contact_length

        ! a value no file can give (the scan refuses NaN) marks the bands not given
        roughness_wavelengths = ieee_value(1.0_dp, ieee_quiet_nan)
        roughness_levels = ieee_value(1.0_dp, ieee_quiet_nan)

        read (defaults, nml=road)
        if (source%unit /= no_unit) write (source%unit, nml=road, delim='quote', iostat=stat, iomsg=message)
        if (source%unit == no_unit) read (source%lines, nml=road, iostat=stat, iomsg=message)
        if (group_failed(this, 'road', source, stat, message, error)) return
        call check_value(this, 'road', 'profile', profile, error)
        call require(trim(profile) /= 'file' .or. len_trim(road_file) > 0, &
                     error, this, 'road', 'road_file', "a road file (x [m], height [m]) for profile 'file'")
        call require(trim(profile) /= 'texture' .or. len_trim(texture_file) > 0, &
                     error, this, 'road', 'texture_file', "a road texture file (heights [m] on an x-y grid) " &
                              //"for profile 'texture'")
        call check_values(this, 'road', [character(len=16) :: 'x_start', 'y_start', 'amplitude', 'omega', &
                          'wavelength', 'speed'], [x_start, y_start, amplitude, omega, wavelength, speed], error)
        call check_value(this, 'road', 'n_terms', n_terms, error)
        if (allocated(error)) return
        this%speed = speed
        this%x_start = x_start
        this%y_start = y_start
        select case (trim(profile))
        case ('sine')
            sine%amplitude = amplitude
            sine%omega = omega
            this%road = sine
        case ('random')
            this%road = new_random_road(seed, n_terms, amplitude, wavelength, speed)
        case ('spectrum')
            call spectrum_road(this, roughness_wavelengths, roughness_levels, roughness_offset, seed, contact_length, &
                               terms_per_band, error)
        case ('texture')
            call read_texture_once(trim(texture_file), this%texture, error, files)
            if (allocated(error)) call place_error(error, this, 'road', 'texture_file')
        case default
            call read_file_road(this, trim(road_file), error, files)
        end select
    end subroutine read_road_group

    !> Profile 'spectrum': the roughness profile of a band spectrum (the ISO 3095 limit when the
    !> file gives no bands), run over at `speed` from `x_start`.
    subroutine spectrum_road(this, wavelengths, levels, offset, seed, contact_length, terms_per_band, error)
        type(scene_type), intent(inout) :: this
        real(dp), intent(in) :: wavelengths(:), levels(:), offset, contact_length
        integer, intent(in) :: seed, terms_per_band
        type(error_type), allocatable, intent(inout) :: error

        real(dp), allocatable :: lambda(:), level(:)
        integer :: n

        call check_values(this, 'road', [character(len=16) :: 'roughness_offset', 'contact_length'], &
                          [offset, contact_length], error)
        call check_value(this, 'road', 'terms_per_band', terms_per_band, error)
        n = count(.not. ieee_is_nan(wavelengths))
        call require(n == count(.not. ieee_is_nan(levels)) .and. all(.not. ieee_is_nan(wavelengths(:n))) .and. &
                     all(.not. ieee_is_nan(levels(:n))), error, this, 'road', 'roughness_wavelengths, ' &
                     //'roughness_levels', 'as many levels as wavelengths, each list given from its first element ' &
                     //'without gaps')
        call require(all(wavelengths(:n) > 0.0_dp), error, this, 'road', 'roughness_wavelengths', &
                     'wavelengths > 0 m', minval([wavelengths(:n), 1.0_dp]))
        call require(this%speed > 0.0_dp, error, this, 'road', 'speed', "a speed > 0 m/s for profile 'spectrum'", &
                     this%speed)
        if (allocated(error)) return
        if (n == 0) then
            lambda = iso3095_wavelengths
            level = iso3095_levels
        else
            lambda = wavelengths(:n)
            level = levels(:n)
        end if
        this%road = new_roughness_road(lambda, level + offset, seed, this%speed, this%x_start, contact_length, &
                                       terms_per_band)
    end subroutine spectrum_road

    !> Profile 'texture': read the road texture (or take it from `files`).
    subroutine read_texture_once(path, texture, error, files)
        character(len=*), intent(in) :: path
        type(road_texture), intent(out) :: texture
        type(error_type), allocatable, intent(out) :: error
        type(scene_files), intent(inout), optional :: files

        integer :: i, k

        i = 0
        if (present(files)) then
            if (.not. allocated(files%textures)) allocate (files%textures(0))
            i = findloc([(files%textures(k)%path == path, k=1, size(files%textures))], .true., 1)
        end if
        if (i > 0) then
            texture = files%textures(i)
        else
            call read_road_texture(path, texture, error)
            if (present(files) .and. .not. allocated(error)) files%textures = [files%textures, texture]
        end if
    end subroutine read_texture_once

    !> Profile 'file': read the road file; a single contact point must stay on it for the
    !> whole run (the tyre scene checks its patch when it samples the road).
    subroutine read_file_road(this, path, error, files)
        type(scene_type), intent(inout) :: this
        character(len=*), intent(in) :: path
        type(error_type), allocatable, intent(out) :: error
        type(scene_files), intent(inout), optional :: files

        type(file_road), allocatable :: road
        integer :: i, k

        i = 0
        if (present(files)) then
            if (.not. allocated(files%roads)) allocate (files%roads(0))
            i = findloc([(files%roads(k)%path == path, k=1, size(files%roads))], .true., 1)
        end if
        if (i > 0) then
            this%road_data = files%roads(i)
        else
            call read_road_file(path, this%road_data, error)
            if (present(files) .and. .not. allocated(error)) files%roads = [files%roads, this%road_data]
        end if
        if (allocated(error)) then
            call place_error(error, this, 'road', 'road_file')
            return
        end if
        ! Built in place and moved: gfortran 12 loses the allocatable components of a
        ! structure constructor assigned to a polymorphic variable (80 KB per road file).
        allocate (road)
        road%profile = this%road_data
        road%x_start = this%x_start
        road%speed = this%speed
        call move_alloc(road, this%road)
    end subroutine read_file_road

    !> Profile 'file' or 'texture': every contact point stays on the road for the whole run (a
    !> single point at x_start + V*t; the tyre's points spread over the patch around it, at
    !> y_start across a texture), so that `--check` finds a road too short as a run would. A
    !> Green's matrix file's points are known once the file is read (greenconv_scene_run_points).
    subroutine check_scene_road(this, error)
        type(scene_type), intent(in) :: this
        type(error_type), allocatable, intent(inout) :: error

        real(dp), allocatable :: x(:)
        type(road_travel) :: travel

        if (allocated(error)) return
        if (this%task /= 'contact' .or. model_requires(find_model(this%model), 'green_file')) return
        x = this%x_start + contact_positions(0.0_dp, this%patch_length, this%n_points)
        travel = road_travel(x, spread(this%y_start, 1, size(x)), this%speed, this%dt)
        if (allocated(this%road_data%x)) then
            call check_road_coverage(this%road_data, travel, this%n_steps, error)
        else if (allocated(this%texture%x)) then
            call check_texture_coverage(this%texture, travel, this%n_steps, error)
        end if
        if (allocated(error)) call place_error(error, this, 'road', 'x_start')
    end subroutine check_scene_road

    !> A multi-point model (the tyre, a Green's matrix file) runs a contact over a road file or
    !> texture; a texture needs a multi-point model: anything else is refused here, with the
    !> scene's line, as the run would refuse it.
    subroutine check_multipoint_scene(this, error)
        type(scene_type), intent(in) :: this
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: road
        logical :: on_file

        on_file = allocated(this%road_data%x) .or. allocated(this%texture%x)
        if (.not. multi_point_model(this%model)) then
            if (allocated(this%texture%x)) then
                call fatal_error(error, "expected 'sine', 'random' or 'file' for model '"//this%model &
                                 //"' (one contact point), found 'texture' (a texture needs a patch of points: " &
                                 //"model 'tyre' or 'green_file')")
                call place_error(error, this, 'road', 'profile')
            end if
            return
        end if
        if (this%task == 'contact' .and. on_file) return
        road = ' and no road file'
        if (on_file) road = ' with a road file'
        call fatal_error(error, "expected task = 'contact' and &road profile = 'file' or 'texture' for model '" &
                         //this%model//"' (its contact points are spread over a road file), found task '" &
                         //this%task//"'"//road)
        call place_error(error, this, 'structure', 'model')
    end subroutine check_multipoint_scene

    !> The times of the force maps (&scene map_times [s]): a multi-point contact run's, each
    !> within the run (0 to (N_t - 1)*dt), increasing, each at a step of its own (the nearest).
    subroutine check_map_times(this, error)
        type(scene_type), intent(in) :: this
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: last
        integer :: k

        if (size(this%map_times) == 0) return
        if (.not. multi_point_model(this%model) .or. this%task /= 'contact') then
            call expect(error, this, 'scene', 'map_times', "no value for model '"//this%model//"' (maps are of a " &
                        //'multi-point contact run)')
            return
        end if
        last = (this%n_steps - 1)*this%dt
        do k = 1, size(this%map_times)
            if (this%map_times(k) < 0.0_dp) then
                call expect(error, this, 'scene', 'map_times', 'times >= 0 s', this%map_times(k))
            else if (this%map_times(k) > last*(1.0_dp + epsilon(1.0_dp))) then
                call expect(error, this, 'scene', 'map_times', 'times within the run, at most (n_steps - 1)*dt = ' &
                            //sci_text(last)//' s', this%map_times(k))
            else if (k > 1) then
                if (nint(this%map_times(k)/this%dt) <= nint(this%map_times(k - 1)/this%dt)) &
                    call expect(error, this, 'scene', 'map_times', 'increasing times, each at a step of its own ' &
                                //'(dt = '//sci_text(this%dt)//' s)', this%map_times(k))
            end if
            if (allocated(error)) return
        end do
    end subroutine check_map_times

    !> The band range of the force spectra of a contact run (&scene spectra): every band must
    !> lie below the Nyquist frequency 1/(2*dt), and the record (N_t steps) must hold a Welch
    !> segment long enough for the lowest band (greenconv_io_spectra). A value the file gives
    !> is refused when the run cannot resolve it; a default (20 Hz, 20 kHz, the audible range)
    !> is narrowed to what the run resolves. The range is replaced by the exact centres of its
    !> lowest and highest band.
    subroutine check_spectra(this, error)
        type(scene_type), intent(inout) :: this
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: record
        real(dp) :: nyquist, values
        integer :: low, high, top, bottom, channels

        if (.not. this%spectra .or. this%task /= 'contact') return
        nyquist = 0.5_dp/this%dt
        top = highest_band_below(nyquist)
        bottom = huge(0)
        if (this%n_steps >= 2) bottom = lowest_resolved_band(this%n_steps, this%dt, default_lines_per_band)
        record = 'N_t = '//int_text(this%n_steps)//' steps of '//compact_real(this%dt)//' s ('//compact_real( &
                 this%n_steps*this%dt)//' s)'
        if (bottom > top) then
            call expect(error, this, 'scene', 'spectra', 'a record that resolves a band below the ' &
                //'Nyquist frequency '//compact_real(nyquist)//' Hz: '//record//' resolve none (at ' &
                //int_text(default_lines_per_band)//' lines in a band); raise n_steps or set spectra = .false.')
            return
        end if
        low = max(first_band(this%spectra_f_low), bottom)
        if (this%input%has_value('scene', 'spectra_f_low')) then
            low = first_band(this%spectra_f_low)
            if (low > top) then
                call expect(error, this, 'scene', 'spectra_f_low', 'a lowest band centre below the ' &
                    //'Nyquist frequency 1/(2*dt) = '//compact_real(nyquist)//' Hz (the highest band below it is ' &
                    //band_name(top)//'); lower spectra_f_low or dt', this%spectra_f_low)
                return
            end if
            if (low < bottom) then
                call expect(error, this, 'scene', 'spectra_f_low', 'a lowest band centre the record ' &
                    //'resolves: '//record//' resolve bands from '//band_name(bottom)//' up (the '//band_name(low) &
                    //' band needs '//int_text(segment_for_band(low, this%dt, default_lines_per_band)) &
                    //' samples for '//int_text(default_lines_per_band)//' lines in it); raise spectra_f_low ' &
                    //'or n_steps', this%spectra_f_low)
                return
            end if
        end if
        high = min(edge_band(this%spectra_f_high, 1), top)
        if (this%input%has_value('scene', 'spectra_f_high')) then
            high = edge_band(this%spectra_f_high, 1)
            if (high > top) then
                call expect(error, this, 'scene', 'spectra_f_high', 'a highest band centre whose band ' &
                    //'ends below the Nyquist frequency 1/(2*dt) = '//compact_real(nyquist)//' Hz (at most ' &
                    //band_name(top)//'); lower spectra_f_high or dt', this%spectra_f_high)
                return
            end if
        end if
        if (high < low) then
            call expect(error, this, 'scene', 'spectra_f_high', 'a highest band centre at or above ' &
                //'the lowest, '//band_name(low)//' (no 1/3-octave band between them; default 20 kHz)', &
                this%spectra_f_high)
            return
        end if
        channels = 1
        if (this%spectra_points .and. multi_point_model(this%model)) channels = 1 + this%n_points
        values = real(segment_for_band(low, this%dt, default_lines_per_band), dp)*channels
        if (values > max_spectrum_values) then
            call expect(error, this, 'scene', 'spectra_f_low', 'force spectra of at most ' &
                //sci_text(real(max_spectrum_values, dp))//' values held (segment length times ' &
                //int_text(channels)//' histories); raise spectra_f_low or turn spectra_points off, found ' &
                //sci_text(values)//' values')
            return
        end if
        this%spectra_f_low = band_centre(low)
        this%spectra_f_high = band_centre(high)
    end subroutine check_spectra

    !> "400 Hz", the nominal name of band x.
    function band_name(x) result(text)
        integer, intent(in) :: x
        character(len=len(compact_real(nominal_frequency(band_centre(x)))) + 3) :: text

        text = compact_real(nominal_frequency(band_centre(x)))//' Hz'
    end function band_name

    !> &contact: the law (`law`, its `law_parameters`, or the power law's stiffness [N/m^p] and
    !> exponent), gravity [m/s^2], preload [N], the points and the contact step.
    subroutine read_contact_group(source, defaults, this, error)
        type(group_source), intent(in) :: source
        !> The group's defaults, a namelist record (greenconv_scene_read_schema's `group_defaults`).
        character(len=*), intent(in) :: defaults
        type(scene_type), intent(inout) :: this
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: stiffness, exponent, gravity, preload, patch_length, divergence_bound, patch_width, &
                    stiffness_per_area, wheel_radius, rail_head_radius, young_modulus, poisson_ratio
        real(dp) :: law_parameters(max_law_parameters)
        character(len=name_length) :: scheme, law
        type(structure_kind) :: model
        integer :: stat, n_points, n_points_x, n_points_y
        character(len=512) :: message
        namelist /contact/ stiffness, exponent, law, law_parameters, gravity, preload, n_points, patch_length, &
            n_points_x, n_points_y, patch_width, stiffness_per_area, scheme, divergence_bound, wheel_radius, &
            rail_head_radius, young_modulus, poisson_ratio

        ! The table's default `mass*gravity`, set below when the file is silent.
        preload = -1.0_dp
        ! a value no file can give (the scan refuses NaN) marks the parameters not given
        law_parameters = ieee_value(1.0_dp, ieee_quiet_nan)
        read (defaults, nml=contact)
        if (source%unit /= no_unit) write (source%unit, nml=contact, delim='quote', iostat=stat, iomsg=message)
        if (source%unit == no_unit) read (source%lines, nml=contact, iostat=stat, iomsg=message)
        if (group_failed(this, 'contact', source, stat, message, error)) return
        call check_values(this, 'contact', [character(len=18) :: 'stiffness', 'exponent', 'gravity', 'preload', &
                          'patch_width', 'stiffness_per_area'], &
                          [stiffness, exponent, gravity, preload, patch_width, stiffness_per_area], error)
        model = find_model(this%model)
        call require(preload >= 0.0_dp .or. model%has_mass .or. this%task /= 'contact', &
                     error, this, 'contact', 'preload', &
                     "a static force >= 0 N (model '"//this%model//"' has no mass to weigh)", preload)
        call check_values(this, 'contact', [character(len=16) :: 'n_points', 'n_points_x', 'n_points_y'], &
                          [n_points, n_points_x, n_points_y], error)
        call check_patch_grid(this, model, n_points, n_points_x, n_points_y, error)
        call require(.not. (model%multi_point() .and. model%grid_dimensions == 0 .and. &
                            this%input%has_value('contact', 'patch_length')), error, this, 'contact', &
                     'patch_length', "no value for model '"//this%model//"' (the file's node coordinates place " &
                     //'its points)')
        call require(patch_length > 0.0_dp .and. patch_length < this%tyre%length, error, this, 'contact', &
                     'patch_length', 'a length > 0 m and below belt_length', patch_length)
        call require(model%grid_dimensions == 2 .or. stiffness_per_area > 0.0_dp .or. &
                     .not. this%input%has_value('contact', 'patch_width'), error, this, 'contact', 'patch_width', &
                     "no value for model '"//this%model//"' without stiffness_per_area (it is the tread width " &
                     //'a per-area law shares out)')
        call require(model%grid_dimensions < 2 .or. patch_width < this%plate%width, error, this, 'contact', &
                     'patch_width', 'a width below belt_width', patch_width)
        call require(stiffness_per_area == 0.0_dp .or. model%grid_dimensions > 0, error, this, 'contact', &
                     'stiffness_per_area', "0 for model '"//this%model//"' (a law per area needs a patch grid: " &
                     //"model 'tyre' or 'tyre_plate'); give the stiffness per point", stiffness_per_area)
        call require(stiffness_per_area == 0.0_dp .or. .not. this%input%has_value('contact', 'stiffness'), &
                     error, this, 'contact', 'stiffness', 'no value beside stiffness_per_area (each point''s ' &
                     //'stiffness is k_a times its share of the patch)')
        call check_value(this, 'contact', 'scheme', scheme, error)
        call check_value(this, 'contact', 'divergence_bound', divergence_bound, error)
        call check_values(this, 'contact', [character(len=16) :: 'wheel_radius', 'rail_head_radius', &
                          'young_modulus', 'poisson_ratio'], [wheel_radius, rail_head_radius, young_modulus, &
                          poisson_ratio], error)
        call require(wheel_radius == 0.0_dp .or. .not. this%input%has_value('contact', 'stiffness'), error, this, &
                     'contact', 'stiffness', 'no value beside wheel_radius (Hertz''s constant then comes from the ' &
                     //'radii and the material)')
        call require(wheel_radius == 0.0_dp .or. exponent == 1.5_dp, error, this, 'contact', 'exponent', &
                     '1.5 (Hertz) beside wheel_radius', exponent)
        this%wheel_radius = wheel_radius
        if (wheel_radius > 0.0_dp) stiffness = hertz_constant(wheel_radius, rail_head_radius, young_modulus, &
                                                              poisson_ratio)
        this%patch_length = patch_length
        this%patch_width = patch_width
        this%stiffness_per_area = stiffness_per_area
        ! a law per area: each point carries its element's share, patch_length*patch_width/N_c
        if (stiffness_per_area > 0.0_dp) stiffness = stiffness_per_area*patch_length*patch_width/this%n_points
        call check_value(this, 'contact', 'law', law, error)
        if (.not. allocated(error)) call contact_law_of(this, trim(law), law_parameters, stiffness, exponent, error)
        this%contact%scheme = trim(scheme)
        this%contact%divergence_bound = divergence_bound
        this%preload = preload
        if (preload < 0.0_dp) this%preload = this%mass*gravity
    end subroutine read_contact_group

    !> The scene's contact law, built by the law registry (greenconv_contact_laws): from
    !> `law_parameters` when given, else, for a law that takes them (the power law), from
    !> `stiffness` and `exponent`. A message names the variable, what the law expects (its
    !> parameters with their units and ranges) and what was found.
    subroutine contact_law_of(this, name, values, stiffness, exponent, error)
        type(scene_type), intent(inout) :: this
        !> The law's name, one of the registry's.
        character(len=*), intent(in) :: name
        !> `law_parameters`, NaN where the file gives none.
        real(dp), intent(in) :: values(:)
        !> The power law's k_c [N/m^p] (from stiffness, stiffness_per_area or wheel_radius) and p.
        real(dp), intent(in) :: stiffness, exponent
        type(error_type), allocatable, intent(inout) :: error

        type(law_kind) :: kind
        character(len=:), allocatable :: expected
        integer :: n_given, bad

        kind = find_law(name)
        expected = int_text(kind%n_parameters)//" values for law '"//name//"' ("//parameter_list(kind)//')'
        n_given = count(.not. ieee_is_nan(values))
        call require(all(.not. ieee_is_nan(values(:n_given))), error, this, 'contact', 'law_parameters', &
                     expected//' without gaps')
        call require(n_given == 0 .or. .not. any([this%input%has_value('contact', 'stiffness'), &
                     this%input%has_value('contact', 'exponent'), this%input%has_value('contact', &
                     'stiffness_per_area'), this%input%has_value('contact', 'wheel_radius')]), error, this, &
                     'contact', 'law_parameters', 'no value beside stiffness, exponent, stiffness_per_area or ' &
                     //'wheel_radius (they are the power law''s k_c and p)')
        call require(n_given > 0 .or. kind%from_stiffness, error, this, 'contact', 'law_parameters', expected, &
                     'none')
        call require(kind%from_stiffness .or. .not. any([this%input%has_value('contact', 'stiffness'), &
                     this%input%has_value('contact', 'exponent')]), error, this, 'contact', 'stiffness, exponent', &
                     "no value for law '"//name//"' (its parameters are law_parameters: "//parameter_list(kind)//')')
        call require(n_given == 0 .or. n_given == kind%n_parameters, error, this, 'contact', 'law_parameters', &
                     expected, n_given)
        if (allocated(error)) return
        if (allocated(this%law)) deallocate (this%law)
        if (n_given == 0) then
            ! the power law's own check, as at every door (the table's rows already bound its values)
            call new_law(name, [stiffness, exponent], this%law, error)
            if (allocated(error)) error%message = place(this, 'contact', 'stiffness, exponent')//': '//error%message
            return
        end if
        bad = first_bad_parameter(kind, values(:n_given))
        if (bad > 0) then
            call expect(error, this, 'contact', 'law_parameters', 'a finite '//parameter_text(kind, bad)//' > ' &
                        //compact_real(kind%above(bad))//" (value "//int_text(bad)//" of law '"//name//"')", &
                        values(bad))
            return
        end if
        call new_law(name, values(:n_given), this%law, error)
        if (allocated(error)) error%message = place(this, 'contact', 'law_parameters')//': '//error%message
    end subroutine contact_law_of

    !> The contact points a scene asks for: one (single-point models); n_points on a line
    !> (`tyre`); n_points_x*n_points_y on a patch grid (`tyre_plate`, n_points_x = 0 taking
    !> n_points); none for a model whose points come from a file. Sets n_points, n_points_x
    !> and n_points_y.
    subroutine check_patch_grid(this, model, n_points, n_points_x, n_points_y, error)
        type(scene_type), intent(inout) :: this
        type(structure_kind), intent(in) :: model
        integer, intent(in) :: n_points, n_points_x, n_points_y
        type(error_type), allocatable, intent(inout) :: error

        integer :: along

        if (allocated(error)) return
        call require(.not. (model%multi_point() .and. model%grid_dimensions == 0 .and. &
                            this%input%has_value('contact', 'n_points')), &
                     error, this, 'contact', 'n_points', "no value for model '"//this%model//"' (its contact " &
                              //'points are the nodes of the file)')
        call require(n_points >= 1 .and. (n_points == 1 .or. model%grid_dimensions > 0), &
                     error, this, 'contact', 'n_points', "1, or a number of points >= 1 for model 'tyre' or " &
                              //"'tyre_plate'", n_points)
        call require(model%grid_dimensions == 2 .or. .not. (this%input%has_value('contact', 'n_points_x') .or. &
                     this%input%has_value('contact', 'n_points_y')), error, this, 'contact', 'n_points_x, n_points_y', &
                     "no value for model '"//this%model//"' (a patch grid is model 'tyre_plate''s; "//"'tyre' " &
                     //'takes n_points)')
        along = n_points
        if (n_points_x > 0) along = n_points_x
        this%n_points_x = along
        this%n_points_y = 1
        if (model%grid_dimensions == 2) this%n_points_y = n_points_y
        call require(real(along, dp)*this%n_points_y <= max_contact_points, error, this, 'contact', &
                     'n_points_x, n_points_y', 'at most '//int_text(max_contact_points)//' points in all, found ' &
                     //int_text(along)//' x '//int_text(this%n_points_y))
        if (.not. allocated(error)) this%n_points = along*this%n_points_y
    end subroutine check_patch_grid

    !> &convolution: methods (list of names), truncation_tol, accuracy.
    subroutine read_convolution_group(source, defaults, this, error)
        type(group_source), intent(in) :: source
        !> The group's defaults, a namelist record (greenconv_scene_read_schema's `group_defaults`).
        character(len=*), intent(in) :: defaults
        type(scene_type), intent(inout) :: this
        type(error_type), allocatable, intent(out) :: error

        character(len=name_length) :: methods(max_methods)
        real(dp) :: truncation_tol, accuracy
        integer :: stat, i
        character(len=512) :: message
        namelist /convolution/ methods, truncation_tol, accuracy

        ! No default list: a contact scene must name its methods (the scan requires it), and
        ! a list that started from defaults would keep the defaults the file does not overwrite.
        methods = ''
        read (defaults, nml=convolution)
        if (source%unit /= no_unit) write (source%unit, nml=convolution, delim='quote', iostat=stat, iomsg=message)
        if (source%unit == no_unit) read (source%lines, nml=convolution, iostat=stat, iomsg=message)
        if (group_failed(this, 'convolution', source, stat, message, error)) return
        do i = 1, max_methods
            if (methods(i) == '' .or. is_method(methods(i))) cycle
            call expect(error, this, 'convolution', 'methods', quoted_list(method_names()), methods(i))
            return
        end do
        call check_value(this, 'convolution', 'truncation_tol', truncation_tol, error)
        this%methods = pack(methods, methods /= '')
        call require(size(this%methods) > 0 .or. this%task /= 'contact', &
                     error, this, 'convolution', 'methods', 'at least one method')
        do i = 2, size(this%methods)
            call require(all(this%methods(:i - 1) /= this%methods(i)), error, this, 'convolution', 'methods', &
                         'each method once (its file would be written twice)', this%methods(i))
        end do
        call check_value(this, 'convolution', 'accuracy', accuracy, error)
        this%truncation_tol = truncation_tol
        this%accuracy = accuracy
        if (.not. allocated(error)) call check_methods_on_model(this, error)
        if (.not. allocated(error)) call check_kernel_size(this, error)
    end subroutine read_convolution_group

    !> Every method must run on the scene's structure, as the registry (greenconv_conv_methods)
    !> says and the run would find: a tyre has several contact points; every model has g and
    !> modes (exact, of the tyre's belt, or identified from G).
    subroutine check_methods_on_model(this, error)
        type(scene_type), intent(in) :: this
        type(error_type), allocatable, intent(out) :: error

        integer :: i

        if (this%task /= 'contact') return
        do i = 1, size(this%methods)
            call check_method(trim(this%methods(i)), multi_point_model(this%model), .true., .true., error)
            if (allocated(error)) then
                call place_error(error, this, 'convolution', 'methods')
                return
            end if
        end do
    end subroutine check_methods_on_model

    !> A sampled kernel (`direct`, `fft`, and `auto`, which samples it to weigh its cost) must
    !> fit in max_kernel_values, its length bounded by the slowest decay of the model's exact
    !> modes; a file's g is bounded by the file and not checked here.
    subroutine check_kernel_size(this, error)
        type(scene_type), intent(in) :: this
        type(error_type), allocatable, intent(out) :: error

        type(structure_kind) :: model
        real(dp) :: decay_rate
        integer :: i

        model = find_model(this%model)
        if (this%task /= 'contact' .or. .not. associated(model%slowest_decay)) return
        decay_rate = model%slowest_decay(this)
        do i = 1, size(this%methods)
            call check_kernel_values(trim(this%methods(i)), decay_rate, this%dt, this%truncation_tol, &
                                     this%n_steps, this%n_points, error)
            if (allocated(error)) then
                error%message = place(this, 'convolution', 'methods')//' methods: '//error%message
                return
            end if
        end do
    end subroutine check_kernel_size

    !> Whether a group reader stops after its namelist read or write: it failed (the status
    !> made an error, "file:line: &group: message") or wrote a template. A missing group is no
    !> error here (greenconv_scene_read_schema checks the required ones).
    logical function group_failed(scene, group, source, stat, message, error)
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: group, message
        type(group_source), intent(in) :: source
        integer, intent(in) :: stat
        type(error_type), allocatable, intent(out) :: error

        if (stat /= 0 .and. stat /= iostat_end) call fatal_error(error, scene%file//':' &
            //int_text(scene%input%line_of(group, ''))//': &'//group//': '//trim(message))
        group_failed = allocated(error) .or. source%unit /= no_unit
    end function group_failed

    !> Set `error` to "file:line: &group variable: expected what[, found value]", the line that
    !> of the variable (the first of a list `a, b`) when the file sets it, else the group's; value
    !> is a real, an integer or a text. A subroutine, not a text function: gfortran keeps the
    !> length of a deferred-length function result in static storage, which threads share.
    subroutine expect(error, scene, group, variable, what, found)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: group, variable, what
        class(*), intent(in), optional :: found

        character(len=:), allocatable :: line
        character(len=32) :: value

        line = place(scene, group, variable)//' '//variable//': expected '//what
        if (present(found)) then
            select type (found)
            type is (real(dp))
                line = line//', found '//compact_real(found)
            type is (integer)
                write (value, '(i0)') found
                line = line//', found '//trim(value)
            type is (character(len=*))
                line = line//", found '"//trim(found)//"'"
            end select
        end if
        call fatal_error(error, line)
    end subroutine expect

    !> Check a value a group read against its row of the scene table (greenconv_scene_read_schema):
    !> its range or choices; its message says what the row expects and what was found.
    subroutine check_value(this, group, name, value, error)
        type(scene_type), intent(in) :: this
        character(len=*), intent(in) :: group, name
        class(*), intent(in) :: value
        type(error_type), allocatable, intent(inout) :: error

        type(scene_variable) :: row

        if (allocated(error)) return
        row = scene_row(group, name)
        if (.not. admits(row, value)) call expect(error, this, group, name, row%expect, value)
    end subroutine check_value

    !> `check_value` for several values of one kind, in order.
    subroutine check_values(this, group, names, values, error)
        type(scene_type), intent(in) :: this
        character(len=*), intent(in) :: group, names(:)
        class(*), intent(in) :: values(:)
        type(error_type), allocatable, intent(inout) :: error

        integer :: i

        do i = 1, size(names)
            call check_value(this, group, trim(names(i)), values(i), error)
        end do
    end subroutine check_values

    !> Unless `ok` holds or an earlier check already failed, set `error` as `expect` does.
    subroutine require(ok, error, scene, group, variable, what, found)
        logical, intent(in) :: ok
        type(error_type), allocatable, intent(inout) :: error
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: group, variable, what
        class(*), intent(in), optional :: found

        if (ok .or. allocated(error)) return
        call expect(error, scene, group, variable, what, found)
    end subroutine require

end module greenconv_scene_read_input
