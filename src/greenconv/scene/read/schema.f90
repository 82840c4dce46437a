!> The scene table: every variable a scene file may set, written once with its group, kind,
!> default, units, meaning and when it is required. Everything else derives from it: the
!> groups and kinds the pre-scan (greenconv_scene_scan) checks and suggests names from, the
!> required-value checks, the defaults greenconv_scene_read_input starts each namelist from, and
!> the scene table of doc/scenes.md. Which `&structure` variables a model requires comes from the
!> model registry (greenconv_scene_models_registry).
!>
!> Required:
!>
!>     &scene                        always; dt and n_steps for task 'contact'
!>     &structure model              always, and the variables its model requires
!>                                   (mass, stiffness, damping_ratio for 'sdof'; frf_file for 'frf_file';
!>                                   green_file for 'green_file')
!>     &road profile                 for task 'contact' (road_file for profile 'file', texture_file for
!>                                   profile 'texture')
!>     &contact stiffness, exponent  for task 'contact'
!>     &convolution methods          for task 'contact'
!>
!> Adding a scene variable: one `row` in `scene_table` (with its range and message, when a
!> value can be wrong), the variable in its group's namelist, its `check_value` and a
!> component of `scene_type` (greenconv_scene_read_input), and its use. test_input_mod fails
!> when a namelist and the table disagree.
module greenconv_scene_read_schema
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text, lower_text, exact_text, quoted_list
    use greenconv_core_kinds, only: dp
    use greenconv_conv_methods, only: default_truncation_tol, default_accuracy
    use greenconv_contact_laws, only: law_names, law_choices, max_law_parameters
    use greenconv_scene_scan, only: namelist_variable, namelist_group, namelist_scan, scan_namelist, &
                                 value_real, value_integer, value_logical, value_text, value_text_list
    use greenconv_scene_models_facade, only: structure_kind, find_model, model_names, model_requires
    use greenconv_scene_limits, only: max_random_modes, max_freq_lines, max_lsce_modes, max_road_terms, &
                                      max_contact_points
    implicit none
    private

    public :: scan_scene, max_methods, max_map_times, scene_variable, scene_table, scene_group_names, scene_groups
    public :: scene_default, group_defaults, required_text, scene_row, admits

    !> Largest number of methods one scene may list.
    integer, parameter :: max_methods = 8
    !> Largest number of force maps (`&scene map_times`) one scene may ask for.
    integer, parameter :: max_map_times = 16
    !> Most bands of a roughness spectrum (`&road roughness_wavelengths`).
    integer, parameter, public :: max_roughness_bands = 64

    !> One variable of a scene file.
    type :: scene_variable
        !> Group name, lower case, without the `&`.
        character(len=:), allocatable :: group
        !> Variable name, lower case.
        character(len=:), allocatable :: name
        !> Kind of its values (greenconv_scene_scan's value_real, ..., value_text_list).
        integer :: kind = value_real
        !> Number of elements: 1 for a scalar, max_methods for the list of methods.
        integer :: size = 1
        !> Default as the file would write it ('' for a text: empty); a formula naming other
        !> variables (`1/(2*dt)`, `mass*gravity`) is computed by greenconv_scene_read_input.
        character(len=:), allocatable :: default
        !> Units of its values ('' when dimensionless or a name).
        character(len=:), allocatable :: units
        !> What it is, a noun phrase ("the mass M"): messages say "expected <meaning> in <units>".
        character(len=:), allocatable :: meaning
        !> When a scene must state it: '' (never, unless its model requires it), 'always', or
        !> "<variable> '<value>'" (e.g. "task 'contact'"), the variable's value or default.
        character(len=:), allocatable :: required
        !> Another variable of the group that, when the file gives it, stands in for this one
        !> (not required then); '' for none.
        character(len=:), allocatable :: unless
        !> What a set value must be, as messages say it after "expected" ("a time step > 0 s");
        !> '' when the group's reader (greenconv_scene_read_input) checks the variable itself.
        character(len=:), allocatable :: expect
        !> Range of a real or integer value, in its units: above `low` (or at it, with
        !> `low_in`) and below `high` (or at it, with `high_in`); by default any finite value.
        real(dp) :: low = -huge(1.0_dp), high = huge(1.0_dp)
        !> Whether `low` and `high` themselves are in the range.
        logical :: low_in = .false., high_in = .false.
        !> The texts a text value may be, compared after trimming (none: any text).
        character(len=16), allocatable :: choices(:)
    end type scene_variable

    !> The groups in the order of a scene file.
    character(len=*), parameter :: group_names(6) = [character(len=14) :: 'scene', 'structure', &
        'identification', 'road', 'contact', 'convolution']
    !> When each group must be present (as `scene_variable%required`).
    character(len=*), parameter :: group_required(6) = [character(len=14) :: 'always', 'always', '', &
        "task 'contact'", "task 'contact'", "task 'contact'"]
    !> What a missing required group should hold, for its message.
    character(len=*), parameter :: group_holds(6) = [character(len=42) :: "dt and n_steps for task 'contact'", &
        'model', '', "profile, for task 'contact'", "stiffness and exponent, for task 'contact'", &
        "methods, for task 'contact'"]

    !> The table, built once (`build_table`) for `scene_row` and `group_defaults`, which every
    !> scene read asks: building it each time cost a sweep's variants more than their check.
    type(scene_variable), allocatable, save :: table_copy(:)

contains

    !> Every variable of a scene file, group by group in file order.
    function scene_table() result(table)
        !> The table.
        type(scene_variable), allocatable :: table(:)

        type(scene_variable) :: rows(160)
        integer :: n

        n = 0
        call add(rows, n, 'scene', 'task', value_text, 'contact', '', &
            "what to do, 'contact' (simulate) or 'identify' (fit modes to G only)", '', &
            choices=[character(len=16) :: 'contact', 'identify'])
        call add(rows, n, 'scene', 'name', value_text, 'sdof_sine', '', &
            'the base name of the output files', '')
        call add(rows, n, 'scene', 'output_dir', value_text, 'out', '', &
            'the directory the output files are written to', '')
        call add(rows, n, 'scene', 'dt', value_real, '1.0e-4', 's', &
            'a time step', "task 'contact'", &
            expect='a time step > 0 s', above=0.0_dp)
        call add(rows, n, 'scene', 'n_steps', value_integer, '2000', '', &
            'a number of steps', "task 'contact'", &
            expect='a step count > 0', above=0.0_dp)
        call add(rows, n, 'scene', 'output_every', value_integer, '1', '', &
            'the steps between written rows (1: every step)', '', &
            expect='a number of steps >= 1 between written rows', at_least=1.0_dp)
        call add(rows, n, 'scene', 'output_format', value_text, 'text', '', &
            "how a contact run's rows are written: 'text' (<name>_<method>.dat, exact 17-digit " &
            //"columns) or 'binary' (<name>_<method>.bin, little-endian float64, described by " &
            //"<name>_<method>.bin.txt)", '', &
            choices=[character(len=16) :: 'text', 'binary'])
        call add(rows, n, 'scene', 'progress', value_logical, '.true.', '', &
            'whether to show a progress line on a terminal', '')
        call add(rows, n, 'scene', 'spectra', value_logical, '.false.', '', &
            "whether a contact run also writes the 1/3-octave spectrum of its contact force, " &
            //"<name>_<method>_spectra.dat", '')
        call add(rows, n, 'scene', 'spectra_f_low', value_real, '20.0', 'Hz', &
            'the lowest band centre of the force spectra (default: 20 Hz or the lowest band the ' &
            //'record resolves)', '', &
            expect='a frequency > 0 Hz', above=0.0_dp)
        call add(rows, n, 'scene', 'spectra_f_high', value_real, '20000.0', 'Hz', &
            'the highest band centre of the force spectra (default: 20 kHz or the highest band below ' &
            //'the Nyquist frequency 1/(2*dt))', '', &
            expect='a frequency > 0 Hz', above=0.0_dp)
        call add(rows, n, 'scene', 'spectra_points', value_logical, '.false.', '', &
            'whether the force spectra of a multi-point run also give the level of each point', '')
        call add(rows, n, 'scene', 'point_histories', value_text, 'auto', '', &
            "which per-point histories a multi-point run writes (<name>_<method>.dat or .bin): 'auto' " &
            //"(all for at most 100 points, none above), 'all' or 'none'; the totals file is always written", '', &
            choices=[character(len=16) :: 'auto', 'all', 'none'])
        call add(rows, n, 'scene', 'point_every', value_integer, '0', '', &
            'the steps between rows of the per-point histories (0: output_every)', '', &
            expect='a number of steps >= 0 (0: output_every)', at_least=0.0_dp)
        call add(rows, n, 'scene', 'map_times', value_real, 'none', 's', &
            'the times of the force maps of a multi-point run (<name>_<method>_maps.dat), increasing, ' &
            //'within the run', '', count=max_map_times)
        call add(rows, n, 'structure', 'model', value_text, '', '', &
            "the structure model, "//model_names(), 'always')
        call add(rows, n, 'structure', 'mass', value_real, '1.0', 'kg', &
            'the mass M', '', &
            expect='a mass > 0 kg', above=0.0_dp)
        call add(rows, n, 'structure', 'stiffness', value_real, '1.0e6', 'N/m', &
            'the stiffness K', '', &
            expect='a stiffness > 0 N/m', above=0.0_dp)
        call add(rows, n, 'structure', 'damping_ratio', value_real, '0.02', '', &
            'the damping ratio in [0, 1)', '', &
            expect='a ratio in [0, 1)', at_least=0.0_dp, below=1.0_dp)
        call add(rows, n, 'structure', 'n_modes', value_integer, '10', '', &
            'the number of random modes', '', &
            expect='a number of modes from 1 to '//int_text(max_random_modes), at_least=1.0_dp, &
            at_most=real(max_random_modes, dp))
        call add(rows, n, 'structure', 'seed', value_integer, '2011', '', &
            'the seed of the random modes', '')
        call add(rows, n, 'structure', 'f_low', value_real, '100.0', 'Hz', &
            'the lowest natural frequency of the random modes', '')
        call add(rows, n, 'structure', 'f_high', value_real, '1000.0', 'Hz', &
            'the highest natural frequency of the random modes', '')
        call add(rows, n, 'structure', 'xi_low', value_real, '0.025', '', &
            'the lowest damping ratio of the random modes', '')
        call add(rows, n, 'structure', 'xi_high', value_real, '0.05', '', &
            'the highest damping ratio of the random modes', '')
        call add(rows, n, 'structure', 'a_low', value_real, '0.5', '1/kg', &
            'the smallest modal amplitude A_k of the random modes', '')
        call add(rows, n, 'structure', 'a_high', value_real, '2.0', '1/kg', &
            'the largest modal amplitude A_k of the random modes', '')
        call add(rows, n, 'structure', 'frf_file', value_text, '', '', &
            'a receptance file', '')
        call add(rows, n, 'structure', 'frf_dataset', value_integer, '0', '', &
            'which dataset 58 of a universal frf_file (0: its only one)', '', &
            expect='a dataset 58 number >= 1 of the universal file (0: its only one)', at_least=0.0_dp)
        call add(rows, n, 'structure', 'belt_length', value_real, '1.885', 'm', &
            'the tyre belt length', '')
        call add(rows, n, 'structure', 'belt_mass', value_real, '2.5', 'kg/m', &
            'the tyre belt mass per length', '')
        call add(rows, n, 'structure', 'belt_bending', value_real, '5.0', 'N*m^2', &
            'the tyre belt bending stiffness', '')
        call add(rows, n, 'structure', 'belt_tension', value_real, '1.2e4', 'N', &
            'the tyre belt tension', '')
        call add(rows, n, 'structure', 'belt_foundation', value_real, '7.0e5', 'N/m^2', &
            'the tyre foundation stiffness', '')
        call add(rows, n, 'structure', 'belt_width', value_real, '0.2', 'm', &
            'the tyre belt width b (tyre_plate)', '', &
            expect='a width b > 0 m', above=0.0_dp)
        call add(rows, n, 'structure', 'plate_mass', value_real, '12.5', 'kg/m^2', &
            'the belt mass per area rho_h (tyre_plate)', '', &
            expect='a mass per area > 0 kg/m^2', above=0.0_dp)
        call add(rows, n, 'structure', 'plate_bending_x', value_real, '25.0', 'N*m', &
            'the belt bending stiffness D_x along the circumference (tyre_plate)', '', &
            expect='a bending stiffness >= 0 N*m', at_least=0.0_dp)
        call add(rows, n, 'structure', 'plate_bending_y', value_real, '10.0', 'N*m', &
            'the belt bending stiffness D_y across (tyre_plate)', '', &
            expect='a bending stiffness >= 0 N*m', at_least=0.0_dp)
        call add(rows, n, 'structure', 'plate_bending_xy', value_real, '15.811388300841896', 'N*m', &
            'the belt effective torsional stiffness D_xy (tyre_plate; default sqrt(25*10))', '', &
            expect='a torsional stiffness >= 0 N*m', at_least=0.0_dp)
        call add(rows, n, 'structure', 'plate_tension_x', value_real, '6.6e4', 'N/m', &
            'the belt membrane tension T_x along the circumference (tyre_plate)', '', &
            expect='a tension >= 0 N/m', at_least=0.0_dp)
        call add(rows, n, 'structure', 'plate_tension_y', value_real, '1.0e4', 'N/m', &
            'the belt membrane tension T_y across (tyre_plate)', '', &
            expect='a tension >= 0 N/m', at_least=0.0_dp)
        call add(rows, n, 'structure', 'plate_foundation', value_real, '1.5e6', 'N/m^3', &
            'the foundation stiffness s per area of belt (tyre_plate)', '', &
            expect='a foundation stiffness > 0 N/m^3', above=0.0_dp)
        call add(rows, n, 'structure', 'f_modes', value_real, '0.0', 'Hz', &
            'the highest tyre mode kept (0: the band rule)', '', &
            expect='a frequency >= 0 Hz (0: the band rule)', at_least=0.0_dp)
        call add(rows, n, 'structure', 'green_file', value_text, '', '', &
            "a universal file of the Green's matrix between the contact points: receptances G_ij(f) " &
            //'in m/N (datasets 58 of function type 4) or impulse responses g_ij(t) in m/(N*s) (type 1), ' &
            //'the points at their node coordinates (dataset 15 or 2411, m)', '')
        call add(rows, n, 'structure', 'modes_file', value_text, '', '', &
            'a universal file of normal modes from an FE model: nodes (dataset 15 or 2411, m) and one ' &
            //'dataset 55 per mode (analysis type 2: frequency in Hz, modal mass, viscous damping ratio; ' &
            //'real shapes of 3 or 6 DOF per node); its nodes are the contact points', '')
        call add(rows, n, 'structure', 'modes_direction', value_text, '+z', '', &
            "the direction of the modes file's shapes normal to the road, '+z', '-z', '+x', '-x', '+y' " &
            //"or '-y' (modes_file, wheel_modes_file)", '', &
            choices=[character(len=16) :: '+z', '-z', '+x', '-x', '+y', '-y'])
        call add(rows, n, 'structure', 'modes_patch_length', value_real, '0.0', 'm', &
            "the length along x of the patch whose nodes touch the road, centred on the modes file's nodes " &
            //'(0: every node)', '', expect='a length >= 0 m (0: every node)', at_least=0.0_dp)
        call add(rows, n, 'structure', 'modes_patch_width', value_real, '0.0', 'm', &
            "the width along y of the patch whose nodes touch the road, centred on the modes file's nodes " &
            //'(0: every node)', '', expect='a width >= 0 m (0: every node)', at_least=0.0_dp)
        call add(rows, n, 'structure', 'rail_bending', value_real, '6.4e6', 'N*m^2', &
            'the bending stiffness EI of the rail (wheel_rail)', '', &
            expect='a bending stiffness > 0 N*m^2', above=0.0_dp)
        call add(rows, n, 'structure', 'rail_mass', value_real, '60.0', 'kg/m', &
            'the mass per length of the rail (wheel_rail)', '', &
            expect='a mass per length > 0 kg/m', above=0.0_dp)
        call add(rows, n, 'structure', 'rail_shear', value_real, '0.0', 'N', &
            'the shear stiffness kappa*G*A of a Timoshenko rail (0: Euler-Bernoulli) (wheel_rail)', '', &
            expect='a shear stiffness >= 0 N (0: Euler-Bernoulli)', at_least=0.0_dp)
        call add(rows, n, 'structure', 'rail_rotary', value_real, '0.0', 'kg*m', &
            'the rotary inertia rho*I per length of a Timoshenko rail (wheel_rail, with rail_shear)', '', &
            expect='a rotary inertia >= 0 kg*m', at_least=0.0_dp)
        call add(rows, n, 'structure', 'support_stiffness', value_real, '5.0e8', 'N/m^2', &
            'the stiffness per length of the support (one layer) or of the pad (two layers) (wheel_rail)', '', &
            expect='a stiffness per length > 0 N/m^2', above=0.0_dp)
        call add(rows, n, 'structure', 'support_damping', value_real, '5.0e4', 'N*s/m^2', &
            'the viscous damping per length of the support or of the pad (wheel_rail)', '', &
            expect='a damping per length >= 0 N*s/m^2', at_least=0.0_dp)
        call add(rows, n, 'structure', 'sleeper_mass', value_real, '0.0', 'kg/m', &
            'the sleeper mass per length between pad and ballast (0: a one-layer support) (wheel_rail)', '', &
            expect='a mass per length >= 0 kg/m (0: one layer)', at_least=0.0_dp)
        call add(rows, n, 'structure', 'ballast_stiffness', value_real, '1.0e8', 'N/m^2', &
            'the ballast stiffness per length under the sleepers (wheel_rail, sleeper_mass > 0)', '', &
            expect='a stiffness per length > 0 N/m^2', above=0.0_dp)
        call add(rows, n, 'structure', 'ballast_damping', value_real, '1.0e5', 'N*s/m^2', &
            'the ballast viscous damping per length (wheel_rail, sleeper_mass > 0)', '', &
            expect='a damping per length >= 0 N*s/m^2', at_least=0.0_dp)
        call add(rows, n, 'structure', 'wheel_mass', value_real, '600.0', 'kg', &
            'the unsprung mass of the wheel (wheel_rail)', '', &
            expect='a mass > 0 kg', above=0.0_dp)
        call add(rows, n, 'structure', 'suspension_stiffness', value_real, '1.0e6', 'N/m', &
            'the stiffness of the primary suspension between the wheel and a fixed bogie (wheel_rail)', '', &
            expect='a stiffness > 0 N/m', above=0.0_dp)
        call add(rows, n, 'structure', 'suspension_damping', value_real, '2.0e4', 'N*s/m', &
            'the viscous damping of the primary suspension (wheel_rail)', '', &
            expect='a damping >= 0 N*s/m', at_least=0.0_dp)
        call add(rows, n, 'structure', 'wheel_modes_file', value_text, '', '', &
            "a universal file of the wheel's normal modes instead of the mass on its suspension: nodes " &
            //'(dataset 15 or 2411) and one dataset 55 per mode (frequency > 0 Hz, modal mass, viscous ' &
            //"damping ratio, the scene's damping_ratio where 0), shapes in modes_direction (wheel_rail)", '')
        call add(rows, n, 'structure', 'wheel_node', value_integer, '0', '', &
            "the label of wheel_modes_file's node at the contact (0: its first node) (wheel_rail)", '', &
            expect='a node label >= 0 (0: the first node)', at_least=0.0_dp)
        call add(rows, n, 'identification', 'f_max', value_real, '1/(2*dt)', 'Hz', &
            'the highest frequency of the sampled G', '', &
            expect='a frequency > 0 Hz', above=0.0_dp)
        call add(rows, n, 'identification', 'n_freq', value_integer, '20001', '', &
            'the number of frequency lines of G, 0 Hz to f_max', '', &
            expect='from 16 to '//int_text(max_freq_lines)//' lines', at_least=16.0_dp, &
            at_most=real(max_freq_lines, dp))
        call add(rows, n, 'identification', 'tol_e', value_real, '1.0e-6', '', &
            'the target of the identification error E, eq. (7)', '', &
            expect='an error target in (0, 1)', above=0.0_dp, below=1.0_dp)
        call add(rows, n, 'identification', 'max_order', value_integer, '30', '', &
            'the largest number of modes the order scan tries', '', &
            expect='a number of modes from 1 to '//int_text(max_lsce_modes), at_least=1.0_dp, &
            at_most=real(max_lsce_modes, dp))
        call add(rows, n, 'identification', 'order', value_integer, '0', '', &
            'a fixed number of modes (0: the smallest meeting tol_e)', '', &
            expect='a number of modes from 0 (chosen by tol_e) to '//int_text(max_lsce_modes), &
            at_least=0.0_dp, at_most=real(max_lsce_modes, dp))
        call add(rows, n, 'identification', 'method', value_text, '', '', &
            "the identification, 'ml' or 'lsce' ('': 'ml' for frf_file, 'lsce' for random_modes); for green_file " &
            //"the shared poles: 'ml' (summed driving points), 'poly_reference' (every column) or 'auto' ('': " &
            //"both, the smaller worst E kept)", '')
        call add(rows, n, 'identification', 'noise_model', value_text, 'auto', '', &
            "the noise of G for method 'ml': 'auto' (of 'relative', 'absolute', 'floor' and 'band', the one of the " &
            //"highest likelihood with its MDL price), 'relative' (of |G|), 'absolute' (the same on every line), " &
            //"'floor' (relative plus a floor) or 'band' (relative, one level per band of lines)", '', &
            choices=[character(len=16) :: 'auto', 'relative', 'absolute', 'floor', 'band'])
        call add(rows, n, 'identification', 'search', value_text, 'global', '', &
            "the order search of method 'ml': 'global' (the MDL minimum: greedy rounds, death moves, projected " &
            //"fits; the greedy model when the residual is not explained by the noise) or 'greedy' (the rounds alone)", &
            '', choices=[character(len=16) :: 'global', 'greedy'])
        call add(rows, n, 'road', 'profile', value_text, 'sine', '', &
            "the road profile, 'sine', 'random', 'file', 'texture' or 'spectrum' (a roughness band spectrum)", &
            "task 'contact'", choices=[character(len=16) :: 'sine', 'random', 'file', 'texture', 'spectrum'])
        call add(rows, n, 'road', 'amplitude', value_real, '1.0e-3', 'm', &
            'the road amplitude', '', &
            expect='a finite height in m')
        call add(rows, n, 'road', 'omega', value_real, '100.0', 'rad/s', &
            'the angular frequency of the sine road', '', &
            expect='a finite angular frequency in rad/s')
        call add(rows, n, 'road', 'wavelength', value_real, '50.0e-3', 'm', &
            'the shortest wavelength of the random road', '', &
            expect='a wavelength > 0 m', above=0.0_dp)
        call add(rows, n, 'road', 'speed', value_real, '1.0', 'm/s', &
            'the travel speed V', '', &
            expect='a finite speed in m/s')
        call add(rows, n, 'road', 'n_terms', value_integer, '10', '', &
            'the number of terms of the random road, eq. (35)', '', &
            expect='a number of terms from 1 to '//int_text(max_road_terms), at_least=1.0_dp, &
            at_most=real(max_road_terms, dp))
        call add(rows, n, 'road', 'seed', value_integer, '35', '', &
            'the seed of the random road', '')
        call add(rows, n, 'road', 'road_file', value_text, '', '', &
            'a road file', "profile 'file'")
        call add(rows, n, 'road', 'x_start', value_real, '0.0', 'm', &
            'the position on the road file at t = 0', '', &
            expect='a finite position in m')
        call add(rows, n, 'road', 'texture_file', value_text, '', '', &
            'a road texture file (heights on an x-y grid)', "profile 'texture'")
        call add(rows, n, 'road', 'y_start', value_real, '0.0', 'm', &
            'the lateral position on the road texture of the patch centre', '', &
            expect='a finite position in m')
        call add(rows, n, 'road', 'roughness_wavelengths', value_real, 'ISO 3095', 'm', &
            "the band centre wavelengths of a roughness spectrum (profile 'spectrum'; default: the 22 bands " &
            //'of the ISO 3095 limit, 0.4 m to 3.15 mm)', '', count=max_roughness_bands)
        call add(rows, n, 'road', 'roughness_levels', value_real, 'ISO 3095', 'dB', &
            "the 1/3-octave band levels of the roughness, dB re 1 um, one per wavelength (profile 'spectrum'; " &
            //'default: the ISO 3095 limit)', '', count=max_roughness_bands)
        call add(rows, n, 'road', 'roughness_offset', value_real, '0.0', 'dB', &
            "a level added to every band of the roughness spectrum (profile 'spectrum')", '', &
            expect='a finite level in dB')
        call add(rows, n, 'road', 'terms_per_band', value_integer, '16', '', &
            "the cosines of random phase per band of the roughness profile (profile 'spectrum')", '', &
            expect='from 1 to 1000 terms', at_least=1.0_dp, at_most=1000.0_dp)
        call add(rows, n, 'road', 'contact_length', value_real, '0.0', 'm', &
            "the length 2a of the contact patch the roughness is averaged over, sin(ka)/(ka) (profile " &
            //"'spectrum'; 0: no contact filter)", '', &
            expect='a length >= 0 m (0: no filter)', at_least=0.0_dp)
        call add(rows, n, 'contact', 'stiffness', value_real, '1.0e6', 'N/m^p', &
            'the contact stiffness k_c', "task 'contact'", &
            expect='a stiffness k_c > 0 N/m^p', above=0.0_dp, unless='stiffness_per_area wheel_radius law_parameters')
        call add(rows, n, 'contact', 'exponent', value_real, '1.5', '', &
            'the contact exponent p', "task 'contact'", &
            expect='an exponent p > 0', above=0.0_dp, unless='law_parameters')
        call add(rows, n, 'contact', 'law', value_text, 'power', '', &
            "the contact law, a name of the law registry (contact/laws.f90): 'power' takes stiffness and " &
            //'exponent, every law law_parameters', '', &
            expect='one of '//law_names(), choices=law_choices())
        call add(rows, n, 'contact', 'law_parameters', value_real, 'none', 'SI', &
            "the law's parameters in its registry's order and units (power: k_c [N/m^p], p; exponential: " &
            //'F_s [N], delta_s [m])', '', count=max_law_parameters)
        call add(rows, n, 'contact', 'gravity', value_real, '9.81', 'm/s^2', &
            'the gravity g weighing the mass', '', &
            expect='an acceleration >= 0 m/s^2', at_least=0.0_dp)
        call add(rows, n, 'contact', 'preload', value_real, 'mass*gravity', 'N', &
            'the static preload F0', '', &
            expect='a finite force in N')
        call add(rows, n, 'contact', 'n_points', value_integer, '1', '', &
            'the number of contact points N_c (tyre)', '', &
            expect='at most '//int_text(max_contact_points)//' points', at_most=real(max_contact_points, dp))
        call add(rows, n, 'contact', 'patch_length', value_real, '0.1', 'm', &
            'the length of the contact patch (tyre, tyre_plate)', '')
        call add(rows, n, 'contact', 'n_points_x', value_integer, '0', '', &
            'the points along the travel of a tyre_plate patch (0: n_points)', '', &
            expect='a number of points >= 0 (0: n_points)', at_least=0.0_dp, at_most=real(max_contact_points, dp))
        call add(rows, n, 'contact', 'n_points_y', value_integer, '1', '', &
            'the points across a tyre_plate patch', '', &
            expect='a number of points >= 1', at_least=1.0_dp, at_most=real(max_contact_points, dp))
        call add(rows, n, 'contact', 'patch_width', value_real, '0.1', 'm', &
            'the width of the contact patch (tyre_plate; the tread width under stiffness_per_area)', '', &
            expect='a width > 0 m', above=0.0_dp)
        call add(rows, n, 'contact', 'stiffness_per_area', value_real, '0.0', 'N/m^(2+p)', &
            'the tread stiffness per area k_a (0: stiffness per point); each point gets k_a times its ' &
            //'share of the patch, patch_length*patch_width/N_c', '', &
            expect='a stiffness per area >= 0 N/m^(2+p) (0: stiffness per point)', at_least=0.0_dp)
        call add(rows, n, 'contact', 'scheme', value_text, 'explicit', '', &
            "the contact step, 'explicit' or 'implicit'", '', &
            choices=[character(len=16) :: 'explicit', 'implicit'])
        call add(rows, n, 'contact', 'divergence_bound', value_real, '0.1', 'm', &
            'the displacement beyond which a run diverged', '', &
            expect='a displacement > 0 m', above=0.0_dp)
        call add(rows, n, 'contact', 'wheel_radius', value_real, '0.0', 'm', &
            "the wheel's rolling radius R_w, for Hertz's constant from the radii (0: stiffness given)", '', &
            expect='a radius >= 0 m (0: stiffness given)', at_least=0.0_dp)
        call add(rows, n, 'contact', 'rail_head_radius', value_real, '0.3', 'm', &
            "the rail head's transverse radius R_r (with wheel_radius)", '', &
            expect='a radius > 0 m', above=0.0_dp)
        call add(rows, n, 'contact', 'young_modulus', value_real, '2.1e11', 'Pa', &
            "Young's modulus E of wheel and rail (with wheel_radius)", '', &
            expect='a modulus > 0 Pa', above=0.0_dp)
        call add(rows, n, 'contact', 'poisson_ratio', value_real, '0.3', '', &
            "Poisson's ratio of wheel and rail (with wheel_radius)", '', &
            expect='a ratio in [0, 0.5)', at_least=0.0_dp, below=0.5_dp)
        call add(rows, n, 'convolution', 'methods', value_text_list, '', '', &
            "the methods to run, e.g. 'direct', 'modal'", "task 'contact'")
        call add(rows, n, 'convolution', 'truncation_tol', value_real, exact_text(default_truncation_tol), '', &
            'the truncation fraction of max |g| (direct)', '', &
            expect='a fraction of max |g| in (0, 1)', above=0.0_dp, below=1.0_dp)
        call add(rows, n, 'convolution', 'accuracy', value_real, exact_text(default_accuracy), '', &
            'the largest error E that auto accepts', '', &
            expect='a relative error in (0, 1)', above=0.0_dp, below=1.0_dp)
        table = rows(:n)
    end function scene_table

    !> Append a row to the table; a checked value has its message `expect` and its range
    !> (`above` or `at_least`, `below` or `at_most`), a text its `choices`.
    subroutine add(rows, n, group, name, kind, default, units, meaning, required, expect, above, at_least, &
                   below, at_most, choices, unless, count)
        type(scene_variable), intent(inout) :: rows(:)
        integer, intent(inout) :: n
        character(len=*), intent(in) :: group, name, default, units, meaning, required
        integer, intent(in) :: kind
        character(len=*), intent(in), optional :: expect
        real(dp), intent(in), optional :: above, at_least, below, at_most
        character(len=*), intent(in), optional :: choices(:)
        character(len=*), intent(in), optional :: unless
        integer, intent(in), optional :: count

        n = n + 1
        rows(n)%group = group
        rows(n)%name = name
        rows(n)%kind = kind
        rows(n)%size = 1
        if (kind == value_text_list) rows(n)%size = max_methods
        if (present(count)) rows(n)%size = count
        rows(n)%default = default
        rows(n)%units = units
        rows(n)%meaning = meaning
        rows(n)%required = required
        rows(n)%unless = ''
        if (present(unless)) rows(n)%unless = unless
        rows(n)%expect = ''
        if (present(expect)) rows(n)%expect = expect
        if (present(above)) rows(n)%low = above
        if (present(at_least)) rows(n)%low = at_least
        rows(n)%low_in = present(at_least)
        if (present(below)) rows(n)%high = below
        if (present(at_most)) rows(n)%high = at_most
        rows(n)%high_in = present(at_most)
        if (present(choices)) then
            rows(n)%choices = choices
            rows(n)%expect = quoted_list(choices)
        end if
    end subroutine add

    !> Whether a value is one its table row admits: a real or integer in the row's range, a
    !> text among its choices (any text when it has none).
    logical function admits(variable, value)
        !> The table row.
        type(scene_variable), intent(in) :: variable
        !> The value: real(dp), integer or text (trailing blanks ignored).
        class(*), intent(in) :: value

        admits = .true.
        select type (value)
        type is (character(len=*))
            if (allocated(variable%choices)) admits = any(variable%choices == value)
        type is (integer)
            admits = in_range(real(value, dp))
        type is (real(dp))
            admits = in_range(value)
        end select
    contains
        logical function in_range(x)
            !> The value as a real number.
            real(dp), intent(in) :: x

            in_range = merge(x >= variable%low, x > variable%low, variable%low_in) .and. &
                       merge(x <= variable%high, x < variable%high, variable%high_in)
        end function in_range
    end function admits

    !> The group names of a scene file, in file order.
    pure function scene_group_names() result(names)
        !> Names, lower case, blank-padded.
        character(len=len(group_names)) :: names(size(group_names))

        names = group_names
    end function scene_group_names

    !> The groups of a scene file with their variables and kinds, for greenconv_scene_scan.
    function scene_groups() result(groups)
        !> One group per scene group, variables in table order.
        type(namelist_group), allocatable :: groups(:)

        type(scene_variable), allocatable :: table(:)
        integer :: g, i, k

        table = scene_table()
        allocate (groups(size(group_names)))
        do g = 1, size(group_names)
            groups(g)%name = trim(group_names(g))
            k = 0
            do i = 1, size(table)
                if (table(i)%group == groups(g)%name) k = k + 1
            end do
            allocate (groups(g)%variables(k))
            k = 0
            do i = 1, size(table)
                if (table(i)%group /= groups(g)%name) cycle
                k = k + 1
                groups(g)%variables(k)%name = table(i)%name
                groups(g)%variables(k)%kind = table(i)%kind
                groups(g)%variables(k)%size = table(i)%size
            end do
        end do
    end function scene_groups

    !> Scan a scene file (greenconv_scene_scan), then check that it states every required value.
    subroutine scan_scene(path, lines, scan, error)
        !> The scene file (for messages).
        character(len=*), intent(in) :: path
        !> Its lines, read once (greenconv_io_columns's read_lines).
        character(len=*), intent(in) :: lines(:)
        !> Groups and assignments found, with their lines.
        type(namelist_scan), intent(out) :: scan
        !> Set, with one line naming the file, line, group and variable, when the file is unusable.
        type(error_type), allocatable, intent(out) :: error

        call scan_namelist(path, lines, scene_groups(), scan, error)
        if (.not. allocated(error)) call check_required(scan, error)
    end subroutine scan_scene

    !> Length of `required_text(variable, when)`.
    pure integer function required_length(variable, when)
        type(scene_variable), intent(in) :: variable
        character(len=*), intent(in) :: when

        required_length = len(variable%meaning) + merge(4 + len(variable%units), 0, len(variable%units) > 0) &
                          + merge(11, 16 + len(when), when == 'always')
    end function required_length

    !> "<meaning> in <units> (required[ for <when>])", what a message expects of a required value.
    function required_text(variable, when) result(text)
        !> The table row.
        type(scene_variable), intent(in) :: variable
        !> The condition that makes it required ('always': none to name).
        character(len=*), intent(in) :: when
        character(len=required_length(variable, when)) :: text

        integer :: n

        text = variable%meaning
        n = len(variable%meaning)
        if (len(variable%units) > 0) text(n + 1:) = ' in '//variable%units
        if (len(variable%units) > 0) n = n + 4 + len(variable%units)
        if (when == 'always') then
            text(n + 1:) = ' (required)'
        else
            text(n + 1:) = ' (required for '//when//')'
        end if
    end function required_text

    !> The required groups and values, in table order: a group, then its variables.
    subroutine check_required(scan, error)
        type(namelist_scan), intent(in) :: scan
        type(error_type), allocatable, intent(out) :: error

        type(scene_variable), allocatable :: table(:)
        type(structure_kind) :: model
        character(len=:), allocatable :: model_name
        integer :: g, i

        table = scene_table()
        model_name = lower_text(scan%value_of('structure', 'model'))
        model = find_model(model_name)
        do g = 1, size(group_names)
            if (holds(scan, table, group_required(g)) .and. .not. scan%has_value(trim(group_names(g)), '')) then
                call fatal_error(error, scan%file//': &'//trim(group_names(g))//': expected the group &' &
                                 //trim(group_names(g))//' ... / (required: '//trim(group_holds(g))//'), found none')
                return
            end if
            if (len_trim(group_required(g)) > 0 .and. .not. holds(scan, table, group_required(g))) cycle
            do i = 1, size(table)
                if (table(i)%group /= trim(group_names(g))) cycle
                if (holds(scan, table, table(i)%required)) then
                    call need(scan, table(i), table(i)%required, error)
                else if (table(i)%group == 'structure' .and. model_requires(model, table(i)%name)) then
                    call need(scan, table(i), "model '"//model_name//"'", error)
                end if
                if (allocated(error)) return
            end do
        end do
    end subroutine check_required

    !> Whether a condition of the table holds for the scanned file: '' never, 'always', or
    !> "<variable> '<value>'" when the variable (its default when the file is silent) has
    !> that value, compared in lower case.
    logical function holds(scan, table, condition)
        type(namelist_scan), intent(in) :: scan
        type(scene_variable), intent(in) :: table(:)
        character(len=*), intent(in) :: condition

        character(len=:), allocatable :: name, wanted, value
        integer :: blank, i

        holds = condition == 'always'
        if (len_trim(condition) == 0 .or. holds) return
        blank = index(condition, ' ')
        name = condition(:blank - 1)
        wanted = condition(blank + 2:len_trim(condition) - 1)
        do i = 1, size(table)
            if (table(i)%name /= name) cycle
            value = lower_text(scan%value_of(table(i)%group, name))
            if (len(value) == 0) value = table(i)%default
            holds = value == wanted
            return
        end do
    end function holds

    !> A required value: `file:line: &group variable: expected what, found no value` (the
    !> line of the group).
    subroutine need(scan, variable, when, error)
        type(namelist_scan), intent(in) :: scan
        type(scene_variable), intent(in) :: variable
        character(len=*), intent(in) :: when
        type(error_type), allocatable, intent(inout) :: error

        character(len=:), allocatable :: others, rest, word

        if (scan%has_value(variable%group, variable%name)) return
        if (len(variable%unless) > 0) then
            ! any one of the alternatives, blank-separated, will do
            others = ''
            rest = variable%unless
            do while (len_trim(rest) > 0)
                word = rest(:index(rest//' ', ' ') - 1)
                rest = adjustl(rest(len(word) + 1:))
                if (scan%has_value(variable%group, word)) return
                others = others//' or '//word
            end do
            call fatal_error(error, scan%file//':'//int_text(scan%line_of(variable%group, ''))//': &' &
                             //variable%group//' '//variable%name//': expected '//required_text(variable, when) &
                             //others//', found neither')
            return
        end if
        call fatal_error(error, scan%file//':'//int_text(scan%line_of(variable%group, ''))//': &'//variable%group &
                         //' '//variable%name//': expected '//required_text(variable, when)//', found no value')
    end subroutine need

    !> Build `table_copy` once, for every caller (thread-safe).
    subroutine build_table()
        !$omp critical (greenconv_scene_table)
        if (.not. allocated(table_copy)) table_copy = scene_table()
        !$omp end critical (greenconv_scene_table)
    end subroutine build_table

    !> The table row of a variable; an empty row when the table lacks it.
    function scene_row(group, name) result(variable)
        !> Group name, lower case.
        character(len=*), intent(in) :: group
        !> Variable name, lower case.
        character(len=*), intent(in) :: name
        !> Its row.
        type(scene_variable) :: variable

        integer :: i

        call build_table()
        variable%group = ''
        variable%name = ''
        variable%default = ''
        do i = 1, size(table_copy)
            if (table_copy(i)%group == group .and. table_copy(i)%name == name) variable = table_copy(i)
        end do
    end function scene_row

    !> A namelist record that gives each variable of a group its default from the table
    !> ("&road profile='sine', amplitude=1.0e-3, ... /"), read before the file's group. A
    !> default that is a formula of other variables (`1/(2*dt)`, `mass*gravity`) and the list
    !> of methods (no default) are left out: the group's reader sets them.
    subroutine group_defaults(group, record)
        !> Group name, lower case.
        character(len=*), intent(in) :: group
        !> The record.
        character(len=:), allocatable, intent(out) :: record

        character(len=:), allocatable :: value
        integer :: i

        call build_table()
        record = '&'//group
        do i = 1, size(table_copy)
            if (table_copy(i)%group /= group .or. table_copy(i)%kind == value_text_list) cycle
            value = table_copy(i)%default
            if (table_copy(i)%kind == value_text) value = "'"//value//"'"
            if (any(table_copy(i)%kind == [value_real, value_integer]) .and. verify(value, '0123456789.eE+-') > 0) &
                cycle
            record = record//' '//table_copy(i)%name//'='//value//','
        end do
        record = record//' /'
    end subroutine group_defaults

    !> Give a namelist variable its default from the table (a real, integer, logical or text).
    subroutine scene_default(group, name, value)
        !> Group name, lower case.
        character(len=*), intent(in) :: group
        !> Variable name, lower case.
        character(len=*), intent(in) :: name
        !> The variable, set to its default (a text blank-padded).
        class(*), intent(inout) :: value

        type(scene_variable) :: variable

        variable = scene_row(group, name)
        select type (value)
        type is (real(dp))
            read (variable%default, *) value
        type is (integer)
            read (variable%default, *) value
        type is (logical)
            read (variable%default, *) value
        type is (character(len=*))
            value = variable%default
        end select
    end subroutine scene_default

end module greenconv_scene_read_schema
