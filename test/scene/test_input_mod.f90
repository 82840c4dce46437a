!> Bad input: every bad scene, receptance or road file gets one line with status 2
!> naming the file, the line where known, the group and variable, what was expected and
!> what was found. Each case writes its file to a scratch directory, reads it as the driver
!> does (read_scene, then build_structure for a receptance file) and checks the pieces of
!> the message, so that a case fails when the message loses any of them.
module test_input_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check
    use greenconv_io_files, only: make_directory
    use scene_text_mod, only: tab1_scene, write_text, omit
    use greenconv_api_all, only: scene_type, read_scene, error_type, structure_model, build_structure, modal_set, &
                                 structure_from_modes, frf_from_modes, frf_type, lsce_options, lsce_result, identify, &
                                 new_convolver, convolver, sdof_modes
    use greenconv_scene_read_input, only: write_scene_template
    use greenconv_scene_read_schema, only: scene_variable, scene_table, scene_group_names
    use greenconv_scene_models_registry, only: structure_kind, structure_models, model_names, model_requires
    use greenconv_scene_scan, only: value_real, value_integer, value_logical
    use greenconv_ident_methods, only: n_ident_methods, ident_name, ident_scheme, ident_list, ident_summary, &
                                       default_ident_method, check_ident_method, ident_one_receptance, &
                                       ident_green_matrix, ident_none, ident_ml, ident_lsce, ident_auto
    implicit none
    private

    public :: collect_input

    !> Scratch directory for the files the tests write.
    character(len=*), parameter :: scratch = 'build/test_scratch/input'
    !> Width of the expected pieces of a message.
    integer, parameter :: piece = 90

contains

    !> Tests of greenconv_scene_scan, greenconv_scene_read_schema, greenconv_scene_read_input's checks and the
    !> file readers.
    subroutine collect_input(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('missing scene file', test_missing_file), &
                     new_unittest('unknown group or variable, with the closest name', test_unknown_names), &
                     new_unittest('layout: text outside groups, unclosed, cut, repeated groups', test_layout), &
                     new_unittest('wrong type: integer, real, text, logical, counts', test_wrong_type), &
                     new_unittest('NaN, Inf and 1e999 in any real', test_not_finite), &
                     new_unittest('missing required groups and values', test_required), &
                     new_unittest('ranges: M, K, xi, dt, N_t, k_c, p', test_ranges), &
                     new_unittest('absurd sizes and kernels', test_sizes), &
                     new_unittest('valid syntax: lines, comments, repeats, elements', test_valid_syntax), &
                     new_unittest('receptance files: empty, grid, columns, garbage, NaN', test_frf_files), &
                     new_unittest('road files: order, length, garbage', test_road_files), &
                     new_unittest('LSCE drops a pole with Re lambda >= 0 and warns', test_unstable_pole), &
                     new_unittest('library: modes with Re lambda >= 0 or NaN refused', test_library_modes), &
                     new_unittest('scene table: each namelist holds the table''s variables', test_table_namelists), &
                     new_unittest('scene table: defaults read as their kind', test_table_defaults), &
                     new_unittest('model registry: names, required variables, one builder per row', &
                                  test_model_registry), &
                     new_unittest('identification registry: defaults, names, refusals by kind and order', &
                                  test_ident_registry)]
    end subroutine collect_input

    !> Write `text` as scratch/name, read it as the driver does (read_scene, and
    !> build_structure when `build`), and check: an error, status 2, a message starting with
    !> the file name and containing every piece.
    subroutine expect_error(error, name, text, pieces, build)
        type(test_error), allocatable, intent(out) :: error
        character(len=*), intent(in) :: name, text
        character(len=*), intent(in) :: pieces(:)
        logical, intent(in), optional :: build

        type(scene_type) :: scene
        type(structure_model) :: structure
        type(error_type), allocatable :: input_error
        integer :: i

        call make_directory(scratch, input_error)
        call write_text(scratch//'/'//name, text)
        call read_scene(scratch//'/'//name, scene, input_error)
        if (present(build) .and. .not. allocated(input_error)) then
            if (build) call build_structure(scene, structure, input_error)
        end if
        call check(error, allocated(input_error), name//': no error for: '//text)
        if (allocated(error)) return
        call check(error, input_error%stat == 2 .and. index(input_error%message, scratch//'/'//name) == 1 &
                   .and. index(input_error%message, new_line('a')) == 0, &
                   name//': status 2 and one line starting with the file: '//input_error%message)
        if (allocated(error)) return
        do i = 1, size(pieces)
            call check(error, index(input_error%message, trim(pieces(i))) > 0, &
                       name//': message "'//input_error%message//'" lacks "'//trim(pieces(i))//'"')
            if (allocated(error)) return
        end do
    end subroutine expect_error

    subroutine test_missing_file(error)
        type(test_error), allocatable, intent(out) :: error

        type(scene_type) :: scene
        type(error_type), allocatable :: input_error

        call read_scene(scratch//'/no_such_scene.nml', scene, input_error)
        call check(error, allocated(input_error), 'a missing file is refused')
        if (allocated(error)) return
        call check(error, input_error%stat == 2 .and. &
                   index(input_error%message, scratch//'/no_such_scene.nml: cannot open the scene file') == 1, &
                   'message: '//input_error%message)
    end subroutine test_missing_file

    subroutine test_unknown_names(error)
        type(test_error), allocatable, intent(out) :: error

        call expect_error(error, 'group.nml', tab1_scene()//"&roads profile = 'sine' /", [character(len=piece) :: &
                          ':6: &roads: expected a group &scene, &structure, &identification, &road, &contact or ' &
                          //'&convolution', "found '&roads'; did you mean '&road'?"])
        if (allocated(error)) return
        call expect_error(error, 'variable.nml', tab1_scene(structure="model = 'sdof', mass = 1.0, " &
                                                                      //'stifness = 1.0e6, damping_ratio = 0.02'), &
                          [character(len=piece) :: ':2: &structure stifness: expected a variable of &structure ' &
                           //'(model, mass, stiffness,', "found 'stifness'; did you mean 'stiffness'?"])
        if (allocated(error)) return
        call expect_error(error, 'far.nml', tab1_scene(contact='stiffness = 1.0e6, exponent = 1.5, colour = 1'), &
                          [character(len=piece) :: ":4: &contact colour: expected a variable of &contact", &
                           "found 'colour'"])
        if (allocated(error)) return
        call check(error, .not. message_has('far.nml', 'did you mean'), 'no suggestion for a name far from all')
    end subroutine test_unknown_names

    !> Whether reading scratch/name gives a message containing `text`.
    logical function message_has(name, text)
        character(len=*), intent(in) :: name, text

        type(scene_type) :: scene
        type(error_type), allocatable :: input_error

        call read_scene(scratch//'/'//name, scene, input_error)
        message_has = .false.
        if (allocated(input_error)) message_has = index(input_error%message, text) > 0
    end function message_has

    subroutine test_layout(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=:), allocatable :: full

        call expect_error(error, 'outside.nml', 'hello'//new_line('a')//tab1_scene(), [character(len=piece) :: &
                          ":1: expected a group '&name ... /' or a comment '! ...', found 'hello'"])
        if (allocated(error)) return
        call expect_error(error, 'unclosed.nml', tab1_scene(convolution=omit)//"&convolution methods = 'direct'", &
                          [character(len=piece) :: ":5: &convolution: expected '/' to close the group, found " &
                           //'the end of the file'])
        if (allocated(error)) return
        full = tab1_scene()
        call expect_error(error, 'cut.nml', full(:index(full, '&contact') + 25), [character(len=piece) :: &
                          ":4: &contact: expected '/' to close the group, found the end of the file"])
        if (allocated(error)) return
        call expect_error(error, 'swallowed.nml', tab1_scene(road="profile = 'sine' ! no slash here /"), &
                          [character(len=piece) :: ":3: &road: expected '/' to close the group, found '&contact' " &
                           //'on line 4'])
        if (allocated(error)) return
        call expect_error(error, 'twice.nml', tab1_scene()//"&scene name = 'again' /", [character(len=piece) :: &
                          ':6: &scene: expected each group once, found it again (first on line 1)'])
        if (allocated(error)) return
        call expect_error(error, 'repeat.nml', tab1_scene(scene='dt = 1.0e-4, n_steps = 2000,'//new_line('a') &
                                                                //'dt = 2.0e-4'), [character(len=piece) :: &
                          ':2: &scene dt: expected one assignment per group, found a second (first on line 1)'])
    end subroutine test_layout

    subroutine test_wrong_type(error)
        type(test_error), allocatable, intent(out) :: error

        call expect_error(error, 'int_text.nml', tab1_scene(scene='dt = 1.0e-4, n_steps = abc'), &
                          [character(len=piece) :: ":1: &scene n_steps: expected an integer, found 'abc'"])
        if (allocated(error)) return
        call expect_error(error, 'int_real.nml', tab1_scene(scene='dt = 1.0e-4, n_steps = 2.5'), &
                          [character(len=piece) :: ":1: &scene n_steps: expected an integer, found '2.5'"])
        if (allocated(error)) return
        call expect_error(error, 'int_range.nml', tab1_scene(scene='dt = 1.0e-4, n_steps = 99999999999'), &
                          [character(len=piece) :: ':1: &scene n_steps: expected an integer within +-2147483647, ' &
                           //"found '99999999999'"])
        if (allocated(error)) return
        call expect_error(error, 'real_text.nml', tab1_scene(structure="model = 'sdof', mass = heavy, " &
                                                                       //'stiffness = 1.0e6, damping_ratio = 0.02'), &
                          [character(len=piece) :: ":2: &structure mass: expected a real number, found 'heavy'"])
        if (allocated(error)) return
        call expect_error(error, 'real_quoted.nml', tab1_scene(contact="stiffness = '1.0e6', exponent = 1.5"), &
                          [character(len=piece) :: ":4: &contact stiffness: expected a real number, found the " &
                           //"text '1.0e6'"])
        if (allocated(error)) return
        call expect_error(error, 'text.nml', tab1_scene(road='profile = sine'), &
                          [character(len=piece) :: ":3: &road profile: expected a text in quotes, found 'sine' " &
                           //'without quotes'])
        if (allocated(error)) return
        call expect_error(error, 'logical.nml', tab1_scene(scene='dt = 1.0e-4, n_steps = 2000, progress = maybe'), &
                          [character(len=piece) :: ":1: &scene progress: expected .true. or .false., found 'maybe'"])
        if (allocated(error)) return
        call expect_error(error, 'two_values.nml', tab1_scene(scene='dt = 1.0e-4 2.0e-4, n_steps = 2000'), &
                          [character(len=piece) :: ':1: &scene dt: expected one value, found 2'])
        if (allocated(error)) return
        call expect_error(error, 'no_value.nml', tab1_scene(scene='dt = , n_steps = 2000'), &
                          [character(len=piece) :: ':1: &scene dt: expected a real number, found no value'])
        if (allocated(error)) return
        call expect_error(error, 'many.nml', tab1_scene(convolution="methods = 9*'direct'"), &
                          [character(len=piece) :: ':5: &convolution methods: expected at most 8 values, found 9'])
        if (allocated(error)) return
        call expect_error(error, 'element.nml', tab1_scene(convolution="methods(9) = 'fft'"), &
                          [character(len=piece) :: ":5: &convolution methods: expected an index from 1 to 8, " &
                           //"found 'methods(9)'"])
    end subroutine test_wrong_type

    subroutine test_not_finite(error)
        type(test_error), allocatable, intent(out) :: error

        call expect_error(error, 'nan.nml', tab1_scene(scene='dt = NaN, n_steps = 2000'), &
                          [character(len=piece) :: ":1: &scene dt: expected a finite real number, found 'NaN'"])
        if (allocated(error)) return
        call expect_error(error, 'inf.nml', tab1_scene(contact='stiffness = +Inf, exponent = 1.5'), &
                          [character(len=piece) :: ":4: &contact stiffness: expected a finite real number, found " &
                           //"'+Inf'"])
        if (allocated(error)) return
        call expect_error(error, 'infinity.nml', tab1_scene(road="profile = 'sine', amplitude = -Infinity"), &
                          [character(len=piece) :: ":3: &road amplitude: expected a finite real number, found " &
                           //"'-Infinity'"])
        if (allocated(error)) return
        call expect_error(error, 'overflow.nml', tab1_scene(structure="model = 'sdof', mass = 1e999, " &
                                                                      //'stiffness = 1.0e6, damping_ratio = 0.02'), &
                          [character(len=piece) :: ':2: &structure mass: expected a real number within double ' &
                           //"precision (|x| < 1.8e308), found '1e999'"])
    end subroutine test_not_finite

    subroutine test_required(error)
        type(test_error), allocatable, intent(out) :: error

        call expect_error(error, 'empty.nml', '! nothing here', [character(len=piece) :: &
                          ": &scene: expected the group &scene ... / (required: dt and n_steps for task 'contact')" &
                          //', found none'])
        if (allocated(error)) return
        call expect_error(error, 'no_dt.nml', tab1_scene(scene='n_steps = 2000'), [character(len=piece) :: &
                          ":1: &scene dt: expected a time step in s (required for task 'contact'), found no value"])
        if (allocated(error)) return
        call expect_error(error, 'no_mass.nml', tab1_scene(structure="model = 'sdof', stiffness = 1.0e6, " &
                                                                     //'damping_ratio = 0.02'), &
                          [character(len=piece) :: ":2: &structure mass: expected the mass M in kg (required for " &
                           //"model 'sdof'), found no value"])
        if (allocated(error)) return
        call expect_error(error, 'no_model.nml', tab1_scene(structure='mass = 1.0'), [character(len=piece) :: &
                          ':2: &structure model: expected the structure model', 'found no value'])
        if (allocated(error)) return
        call expect_error(error, 'no_exponent.nml', tab1_scene(contact='stiffness = 1.0e6'), &
                          [character(len=piece) :: ':4: &contact exponent: expected the contact exponent p ' &
                           //"(required for task 'contact') or law_parameters, found neither"])
        if (allocated(error)) return
        call expect_error(error, 'no_methods.nml', tab1_scene(convolution=omit), [character(len=piece) :: &
                          ": &convolution: expected the group &convolution ... / (required: methods, for task " &
                          //"'contact'), found none"])
        if (allocated(error)) return
        call expect_error(error, 'no_road_file.nml', tab1_scene(road="profile = 'file'"), [character(len=piece) :: &
                          ":3: &road road_file: expected a road file (required for profile 'file'), found no value"])
        if (allocated(error)) return
        call expect_error(error, 'no_frf.nml', tab1_scene(structure="model = 'frf_file'"), [character(len=piece) :: &
                          ":2: &structure frf_file: expected a receptance file (required for model 'frf_file')"])
    end subroutine test_required

    subroutine test_ranges(error)
        type(test_error), allocatable, intent(out) :: error

        call expect_error(error, 'mass.nml', tab1_scene(structure=sdof('0.0', '1.0e6', '0.02')), &
                          [character(len=piece) :: ':2: &structure mass: expected a mass > 0 kg, found 0'])
        if (allocated(error)) return
        call expect_error(error, 'stiffness.nml', tab1_scene(structure=sdof('1.0', '-1.0e6', '0.02')), &
                          [character(len=piece) :: ':2: &structure stiffness: expected a stiffness > 0 N/m, ' &
                           //'found -1.0E+06'])
        if (allocated(error)) return
        call expect_error(error, 'xi_one.nml', tab1_scene(structure=sdof('1.0', '1.0e6', '1.0')), &
                          [character(len=piece) :: ':2: &structure damping_ratio: expected a ratio in [0, 1), found 1'])
        if (allocated(error)) return
        call expect_error(error, 'xi_negative.nml', tab1_scene(structure=sdof('1.0', '1.0e6', '-0.1')), &
                          [character(len=piece) :: ':2: &structure damping_ratio: expected a ratio in [0, 1), ' &
                           //'found -0.1'])
        if (allocated(error)) return
        call expect_error(error, 'dt.nml', tab1_scene(scene='dt = -1.0e-4, n_steps = 2000'), &
                          [character(len=piece) :: ':1: &scene dt: expected a time step > 0 s, found -1.0E-04'])
        if (allocated(error)) return
        call expect_error(error, 'steps.nml', tab1_scene(scene='dt = 1.0e-4, n_steps = 0'), &
                          [character(len=piece) :: ':1: &scene n_steps: expected a step count > 0, found 0'])
        if (allocated(error)) return
        call expect_error(error, 'kc.nml', tab1_scene(contact='stiffness = 0.0, exponent = 1.5'), &
                          [character(len=piece) :: ':4: &contact stiffness: expected a stiffness k_c > 0 N/m^p, ' &
                           //'found 0'])
        if (allocated(error)) return
        call expect_error(error, 'p.nml', tab1_scene(contact='stiffness = 1.0e6, exponent = -1.5'), &
                          [character(len=piece) :: ':4: &contact exponent: expected an exponent p > 0, found -1.5'])
    end subroutine test_ranges

    !> The &structure body of an sdof.
    pure function sdof(mass, stiffness, damping_ratio) result(body)
        character(len=*), intent(in) :: mass, stiffness, damping_ratio
        character(len=:), allocatable :: body

        body = "model = 'sdof', mass = "//mass//', stiffness = '//stiffness//', damping_ratio = '//damping_ratio
    end function sdof

    subroutine test_sizes(error)
        type(test_error), allocatable, intent(out) :: error

        call expect_error(error, 'points.nml', tab1_scene(contact='stiffness = 1.0e6, exponent = 1.5, ' &
                                                                  //'n_points = 1000000'), &
                          [character(len=piece) :: ':4: &contact n_points: expected at most 5000 points, ' &
                           //'found 1000000'])
        if (allocated(error)) return
        call expect_error(error, 'lines.nml', tab1_scene(structure="model = 'random_modes'", &
                                                         identification='n_freq = 2000000000', &
                                                         contact='stiffness = 1.0e6, exponent = 1.5, preload = 10.0'), &
                          [character(len=piece) :: ':3: &identification n_freq: expected from 16 to 10000001 lines, ' &
                           //'found 2000000000'])
        if (allocated(error)) return
        call expect_error(error, 'order.nml', tab1_scene(structure="model = 'random_modes'", &
                                                         identification='max_order = 100000', &
                                                         contact='stiffness = 1.0e6, exponent = 1.5, preload = 10.0'), &
                          [character(len=piece) :: ':3: &identification max_order: expected a number of modes from 1 ' &
                           //'to 200, found 100000'])
        if (allocated(error)) return
        call expect_error(error, 'terms.nml', tab1_scene(road="profile = 'random', n_terms = 2000000000"), &
                          [character(len=piece) :: ':3: &road n_terms: expected a number of terms from 1 to 100000'])
        if (allocated(error)) return
        call expect_error(error, 'kernel.nml', tab1_scene(scene='dt = 1.0e-4, n_steps = 2000000000', &
                                                          structure=sdof('1.0', '1.0e6', '0.0'), &
                                                          convolution="methods = 'direct'"), &
                          [character(len=piece) :: ':5: &convolution methods: method ''direct'': expected a sampled ' &
                           //'kernel (direct, fft, auto) of at most', 'or a modal method', 'found 6.00E+09 values'])
    end subroutine test_sizes

    !> What the scan must accept: values over lines, comments holding quotes and slashes,
    !> repeat counts, array elements, both quotes, upper case names.
    subroutine test_valid_syntax(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: nl = new_line('a')
        type(scene_type) :: scene
        type(error_type), allocatable :: input_error

        call make_directory(scratch, input_error)
        call write_text(scratch//'/valid.nml', "! a comment with 'quotes' and a / slash"//nl &
                        //'&SCENE DT = 1.0D-4,'//nl//'    n_steps = 2000 ! N_t'//nl//'/'//nl &
                        //"&structure model = ""sdof"", mass = 1., stiffness = 1e6,"//nl &
                        //'    damping_ratio = 0.02 /'//nl &
                        //"&road profile = 'sine' /"//nl//'&contact stiffness = 1.0e6 exponent = 1.5 /'//nl &
                        //"&convolution methods = 'direct', methods(3) = 'modal',"//nl &
                        //"  truncation_tol = 0.01 /"//nl//'! the end')
        call read_scene(scratch//'/valid.nml', scene, input_error)
        if (allocated(input_error)) then
            call check(error, .false., 'a valid scene is refused: '//input_error%message)
            return
        end if
        call check(error, scene%dt == 1.0e-4_dp .and. scene%n_steps == 2000 .and. scene%model == 'sdof' .and. &
                   size(scene%methods) == 2, 'values read')
        if (allocated(error)) return
        call check(error, scene%methods(1) == 'direct' .and. scene%methods(2) == 'modal', &
                   'element: direct, (blank), modal gives direct, modal')
        if (allocated(error)) return
        ! A repeat count is read as that many values: three times the same method is refused.
        call write_text(scratch//'/repeat.nml', tab1_scene(convolution="methods = 3*'direct'"))
        call read_scene(scratch//'/repeat.nml', scene, input_error)
        call check(error, allocated(input_error), 'a method listed three times by a repeat count is refused')
        if (allocated(error)) return
        call check(error, index(input_error%message, "&convolution methods: expected each method once (its file " &
                                //"would be written twice), found 'direct'") > 0, input_error%message)
    end subroutine test_valid_syntax

    !> A scene identifying the receptance file scratch/name.
    function frf_scene(name) result(text)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: text

        text = "&scene task = 'identify', name = 'bad_frf', output_dir = '"//scratch//"' /"//new_line('a') &
               //"&structure model = 'frf_file', frf_file = '"//scratch//'/'//name//"' /"
    end function frf_scene

    !> Write data lines (separated by ';') as scratch/name.
    subroutine write_rows(name, rows)
        character(len=*), intent(in) :: name, rows

        character(len=:), allocatable :: text
        integer :: i

        text = rows
        do i = 1, len(text)
            if (text(i:i) == ';') text(i:i) = new_line('a')
        end do
        call write_text(scratch//'/'//name, text)
    end subroutine write_rows

    subroutine test_frf_files(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: head = '# f ReG ImG;0 1e-6 0;1 1e-6 -1e-8;2 1e-6 -2e-8;3 1e-6 -3e-8;'
        character(len=*), parameter :: tail = '5 1e-6 -5e-8;6 1e-6 -6e-8;7 1e-6 -7e-8;8 1e-6 -8e-8'
        character(len=*), parameter :: where = ':2: &structure frf_file: '//scratch
        type(error_type), allocatable :: ignored

        call make_directory(scratch, ignored)
        call frf_case(error, 'empty.frf', '# only a comment', [character(len=piece) :: where//'/empty.frf: ' &
                      //'expected data lines f [Hz], Re G [m/N], Im G [m/N], found none'])
        if (allocated(error)) return
        call frf_case(error, 'negative.frf', '-1 1e-6 0;2 1e-6 0;3 1e-6 0;4 1e-6 0;5 1e-6 0;6 1e-6 0;7 1e-6 0;8 1e-6 0', &
                      [character(len=piece) :: where//'/negative.frf:1: expected frequencies >= 0 Hz, found -1'])
        if (allocated(error)) return
        call frf_case(error, 'columns.frf', head//'4 1e-6;'//tail, [character(len=piece) :: where//'/columns.frf:6: ' &
                      //'expected 3 columns (f [Hz], Re G [m/N], Im G [m/N]), found 2'])
        if (allocated(error)) return
        call frf_case(error, 'garbage.frf', head//'4 1e-6 oops;'//tail, [character(len=piece) :: &
                      where//'/garbage.frf:6: column 3 (Im G): expected a number, found "oops"'])
        if (allocated(error)) return
        call frf_case(error, 'nan.frf', head//'4 NaN 0;'//tail, [character(len=piece) :: &
                      where//'/nan.frf:6: column 2 (Re G): expected a finite number, found "NaN"'])
        if (allocated(error)) return
        call frf_case(error, 'short.frf', '0 1e-6 0;1 1e-6 0;2 1e-6 0', [character(len=piece) :: &
                      where//'/short.frf: expected at least 8 data lines (a uniform grid from 0 Hz), found 3'])
        if (allocated(error)) return
        call frf_case(error, 'repeated.frf', head//'3 1e-6 0;'//tail, [character(len=piece) :: &
                      where//'/repeated.frf:6: expected a frequency above 3', '(increasing), found 3'])
        if (allocated(error)) return
        call frf_case(error, 'missing.frf', '', [character(len=piece) :: where//'/absent.frf: cannot open'], &
                      'absent.frf')
    end subroutine test_frf_files

    !> Write a receptance file and expect the scene naming it to fail on build_structure.
    subroutine frf_case(error, name, rows, pieces, named)
        type(test_error), allocatable, intent(out) :: error
        character(len=*), intent(in) :: name, rows
        character(len=*), intent(in) :: pieces(:)
        character(len=*), intent(in), optional :: named

        call write_rows(name, rows)
        if (present(named)) then
            call expect_error(error, name//'.nml', frf_scene(named), pieces, build=.true.)
        else
            call expect_error(error, name//'.nml', frf_scene(name), pieces, build=.true.)
        end if
    end subroutine frf_case

    subroutine test_road_files(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: where = ':3: &road road_file: '//scratch
        type(error_type), allocatable :: ignored

        call make_directory(scratch, ignored)
        call write_rows('decreasing.dat', '# x h;0 0;0.1 1e-4;0.05 0;0.2 0')
        call expect_error(error, 'decreasing.nml', road_scene('decreasing.dat'), [character(len=piece) :: &
                          where//'/decreasing.dat:4: expected x above 0.1', '(x must increase), found 5.0E-02'])
        if (allocated(error)) return
        call write_rows('garbage.dat', '0 0;0.1 high')
        call expect_error(error, 'garbage.nml', road_scene('garbage.dat'), [character(len=piece) :: &
                          where//'/garbage.dat:2: column 2 (height): expected a number, found "high"'])
        if (allocated(error)) return
        call write_rows('short.dat', '0 0;0.1 1e-4')
        call expect_error(error, 'short.nml', road_scene('short.dat'), [character(len=piece) :: &
                          ':3: &road x_start: '//scratch//'/short.dat: expected a road from x = 0.0 m to ' &
                          //'0.1999 m (the run)', 'found 0.0 m to 0.1 m'])
    end subroutine test_road_files

    !> The Tab. 1 scene on a road file, 2000 steps at 1 m/s (0.2 m of road).
    function road_scene(name) result(text)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: text

        text = tab1_scene(road="profile = 'file', road_file = '"//scratch//'/'//name//"'")
    end function road_scene

    !> A receptance with one growing mode (Re lambda = +2/s) beside a damped one: its inverse
    !> FFT grows towards the end of the period, LSCE's prediction polynomial gets a root with
    !> |z| > 1, which must be dropped, counted and named in the warning.
    subroutine test_unstable_pole(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: two_pi = 2.0_dp*acos(-1.0_dp)
        type(modal_set) :: modes
        type(frf_type) :: frf
        type(lsce_options) :: options
        type(lsce_result) :: result
        type(error_type), allocatable :: fit_error

        modes%pole = [cmplx(-0.02_dp*two_pi*100.0_dp, two_pi*100.0_dp, dp), &
                      cmplx(2.0_dp, two_pi*250.0_dp, dp)]
        modes%residue = [(0.0_dp, -1.0e-3_dp), (0.0_dp, -1.0e-3_dp)]
        frf = frf_from_modes(modes, 1000.0_dp, 4001)
        options%max_modes = 6
        call identify(frf, options, result, fit_error)
        call check(error, .not. allocated(fit_error), 'the identification runs')
        if (allocated(error)) return
        call check(error, all(real(result%modes%pole, dp) < 0.0_dp), 'no pole with Re lambda >= 0 kept')
        if (allocated(error)) return
        call check(error, result%n_unstable > 0 .and. index(result%warning, 'with Re lambda >= 0 (unstable') > 0, &
                   'counted and named in the warning: "'//result%warning//'"')
    end subroutine test_unstable_pole

    subroutine test_library_modes(error)
        type(test_error), allocatable, intent(out) :: error

        type(modal_set) :: modes
        class(convolver), allocatable :: conv
        type(error_type), allocatable :: build_error

        modes = sdof_modes(1.0_dp, 1.0e6_dp, 0.02_dp)
        modes%pole(1) = cmplx(abs(real(modes%pole(1), dp)), aimag(modes%pole(1)), dp)
        call new_convolver('modal', structure_from_modes(modes), 1.0e-4_dp, 100, conv, build_error)
        call check(error, allocated(build_error), 'a growing mode is refused')
        if (allocated(error)) return
        call check(error, build_error%stat == 2 .and. index(build_error%message, 'new_convolver: mode 1: expected ' &
                   //'a pole with Re lambda <= 0 and Im lambda > 0 rad/s (a damped or undamped mode), found ' &
                   //'lambda = (2.00E+01') &
                   == 1, 'message: '//build_error%message)
        if (allocated(error)) return
        modes = sdof_modes(1.0_dp, 1.0e6_dp, 0.02_dp)
        modes%residue(1) = cmplx(ieee_value(1.0_dp, ieee_quiet_nan), 0.0_dp, dp)
        call new_convolver('direct', structure_from_modes(modes), 1.0e-4_dp, 100, conv, build_error)
        call check(error, allocated(build_error), 'a NaN residue is refused')
        if (allocated(error)) return
        call check(error, index(build_error%message, 'new_convolver: mode 1: expected a finite pole and residue') &
                   == 1, 'message: '//build_error%message)
    end subroutine test_library_modes

    !> The namelists that read a scene, written with write_scene_template, hold exactly the
    !> variables of the scene table, group by group and in table order: a variable added to
    !> one and not the other fails here.
    subroutine test_table_namelists(error)
        type(test_error), allocatable, intent(out) :: error

        type(scene_variable), allocatable :: table(:)
        type(error_type), allocatable :: write_error
        character(len=:), allocatable :: groups(:), listed, expected
        character(len=4096) :: line
        character(len=32) :: name
        integer :: unit, stat, g, i, equals

        table = scene_table()
        groups = scene_group_names()
        open (newunit=unit, status='scratch', action='readwrite', form='formatted')
        call write_scene_template(unit, write_error)
        call check(error, .not. allocated(write_error), 'the template is written')
        if (allocated(error)) return
        rewind (unit)
        g = 0
        listed = ''
        do
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) line = '&'
            line = adjustl(line)
            if (line(1:1) == '&' .or. line(1:1) == '/') then
                if (g > 0 .and. len(listed) > 0) then
                    expected = ''
                    do i = 1, size(table)
                        if (table(i)%group == trim(groups(g))) expected = expected//' '//table(i)%name
                    end do
                    call check(error, listed == expected, '&'//trim(groups(g))//': namelist"'//listed &
                               //'", table"'//expected//'"')
                    if (allocated(error)) return
                    listed = ''
                end if
                if (stat /= 0) exit
                if (line(1:1) == '&') then
                    g = g + 1
                    call check(error, g <= size(groups), 'more groups written than the table has')
                    if (allocated(error)) return
                    call check(error, lower(line(2:)) == groups(g), 'group '//trim(line)//', expected &'//groups(g))
                    if (allocated(error)) return
                end if
                cycle
            end if
            equals = index(line, '=')
            if (equals < 2) cycle
            if (verify(line(:equals - 1), 'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz_0123456789') /= 0) cycle
            name = lower(line(:equals - 1))
            listed = listed//' '//trim(name)
        end do
        close (unit)
        call check(error, g == size(groups), 'every group of the table is written')
    end subroutine test_table_namelists

    !> Lower case of a name.
    pure function lower(text) result(low)
        character(len=*), intent(in) :: text
        character(len=len_trim(text)) :: low

        integer :: i

        low = text
        do i = 1, len(low)
            if (low(i:i) >= 'A' .and. low(i:i) <= 'Z') low(i:i) = achar(iachar(low(i:i)) + 32)
        end do
    end function lower

    !> Every default of a real, integer or logical variable reads as that kind, but for the two
    !> computed from other variables (f_max = 1/(2*dt), preload = mass*gravity), the list
    !> map_times, none by default, the roughness band lists, the ISO 3095 limit by default, and
    !> law_parameters, none by default (the power law's come from stiffness and exponent).
    subroutine test_table_defaults(error)
        type(test_error), allocatable, intent(out) :: error

        type(scene_variable), allocatable :: table(:)
        real(dp) :: x
        integer :: i, n, stat
        logical :: flag

        table = scene_table()
        do i = 1, size(table)
            stat = 0
            select case (table(i)%kind)
            case (value_real)
                read (table(i)%default, *, iostat=stat) x
            case (value_integer)
                read (table(i)%default, *, iostat=stat) n
            case (value_logical)
                read (table(i)%default, *, iostat=stat) flag
            end select
            if (any(table(i)%name == [character(len=21) :: 'f_max', 'preload', 'map_times', 'roughness_wavelengths', &
                                      'roughness_levels', 'law_parameters'])) stat = 0
            call check(error, stat == 0, '&'//table(i)%group//' '//table(i)%name//': default "' &
                       //table(i)%default//'" does not read as its kind')
            if (allocated(error)) return
            call check(error, len(table(i)%meaning) > 0, table(i)%name//' has no meaning')
            if (allocated(error)) return
        end do
    end subroutine test_table_defaults

    !> The registry's names are listed in messages as before, and every variable a model
    !> requires is a &structure variable of the table.
    subroutine test_model_registry(error)
        type(test_error), allocatable, intent(out) :: error

        type(structure_kind), allocatable :: models(:)
        type(scene_variable), allocatable :: table(:)
        integer :: i, m, n

        call check(error, model_names() == "'sdof', 'random_modes', 'frf_file', 'tyre', 'tyre_plate', " &
                   //"'green_file', 'modes_file' or 'wheel_rail'", model_names())
        if (allocated(error)) return
        models = structure_models()
        table = scene_table()
        do m = 1, size(models)
            n = 0
            do i = 1, size(table)
                if (table(i)%group == 'structure' .and. model_requires(models(m), table(i)%name)) n = n + 1
            end do
            call check(error, n == count_words(models(m)%requires), trim(models(m)%name)//' requires "' &
                       //trim(models(m)%requires)//'": not all are &structure variables of the table')
            if (allocated(error)) return
            ! each model is built one way: a single-point structure, or the points of several
            call check(error, associated(models(m)%build) .neqv. associated(models(m)%find_points), &
                       trim(models(m)%name)//': expected a builder or a points finder, exactly one')
            if (allocated(error)) return
            ! a model whose direct/fft sample its exact g bounds that kernel's length
            call check(error, associated(models(m)%slowest_decay) .eqv. &
                       (models(m)%exact_modes .and. .not. models(m)%sampled_g), &
                       trim(models(m)%name)//': a decay bound exactly when g is sampled from exact modes')
            if (allocated(error)) return
        end do
    end subroutine test_model_registry

    !> Number of blank-separated words.
    pure integer function count_words(text)
        character(len=*), intent(in) :: text

        integer :: i

        count_words = 0
        do i = 1, len(text)
            if (text(i:i) /= ' ' .and. (i == 1 .or. text(max(i - 1, 1):max(i - 1, 1)) == ' ')) &
                count_words = count_words + 1
        end do
    end function count_words

    !> The identification registry against what doc/scenes.md documents: `ml` the default of a
    !> measured receptance, `lsce` of one sampled from modes, `auto` of a Green's matrix; every
    !> name resolves to its scheme and back; a method refused for what it cannot identify and a
    !> fixed order refused by a method that chooses its own, each naming the variable.
    subroutine test_ident_registry(error)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: refused
        character(len=:), allocatable :: variable
        integer :: k

        call check(error, default_ident_method(ident_one_receptance, .true.) == 'ml' .and. &
                   default_ident_method(ident_one_receptance, .false.) == 'lsce' .and. &
                   default_ident_method(ident_green_matrix, .false.) == 'auto', 'defaults: ml, lsce, auto')
        if (allocated(error)) return
        do k = 1, n_ident_methods
            call check(error, ident_scheme(ident_name(k)) == k .and. len_trim(ident_summary(ident_name(k))) > 0, &
                       'scheme '//ident_name(k)//' round trip')
            if (allocated(error)) return
        end do
        call check(error, ident_scheme('ml') == ident_ml .and. ident_scheme('lsce') == ident_lsce .and. &
                   ident_scheme('auto') == ident_auto .and. ident_scheme('mle') == ident_none .and. &
                   ident_scheme('') == ident_none, 'schemes of the documented names')
        if (allocated(error)) return
        call check(error, ident_list(ident_one_receptance) == "'ml' or 'lsce'", &
                   'list for one receptance: '//ident_list(ident_one_receptance))
        if (allocated(error)) return
        call check_ident_method('lsce', ident_one_receptance, 'frf_file', 4, variable, refused)
        call check(error, .not. allocated(refused), 'lsce with a fixed order accepted')
        if (allocated(error)) return
        call check_ident_method('lsce', ident_green_matrix, 'green_file', 0, variable, refused)
        call check(error, allocated(refused) .and. variable == 'method', 'lsce refused for a Green''s matrix')
        if (allocated(error)) return
        call check_ident_method('poly_reference', ident_one_receptance, 'frf_file', 0, variable, refused)
        call check(error, allocated(refused) .and. variable == 'method', 'poly_reference refused for one receptance')
        if (allocated(error)) return
        call check_ident_method('ml', ident_one_receptance, 'frf_file', 3, variable, refused)
        call check(error, allocated(refused) .and. variable == 'order', 'ml refused a fixed order')
        if (allocated(error)) return
        call check(error, index(refused%message, "method = 'lsce'") > 0, 'order message: '//refused%message)
        if (allocated(error)) return
        call check_ident_method('mle', ident_one_receptance, 'frf_file', 0, variable, refused)
        call check(error, allocated(refused) .and. variable == 'method' .and. &
                   refused%message == "'ml', 'lsce', 'poly_reference' or 'auto'", &
                   'an unknown name refused with the list of every name')
    end subroutine test_ident_registry

end module test_input_mod
