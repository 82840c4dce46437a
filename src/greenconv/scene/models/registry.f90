!> The structure models a scene may name (`&structure model`), each one row of the registry:
!> its name, the `&structure` variables it requires, what it gives the convolution methods,
!> and the procedures that build it (a single-point structure, or the contact points of a
!> multi-point one), bound its kernel's length and check its file for `--check`. The scene's
!> checks (greenconv_scene_read_schema, greenconv_scene_read_input), its builders
!> (greenconv_scene_models_structure's `build_structure`; the runner and the sweep call a multi-point
!> model's `find_points`) and `--check` (greenconv_scene_run_runner) ask this registry, and nothing
!> else compares model names.
!>
!> A new structure model is its module (its builder or its points' finder, as
!> greenconv_scene_models_single and greenconv_scene_models_multi hold the shipped ones) and
!> its row in `structure_models`, plus the rows of any new `&structure` variable in the scene
!> table (greenconv_scene_read_schema).
module greenconv_scene_models_registry
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_core_text, only: quoted_list, quoted_list_length
    use greenconv_ident_structure, only: structure_model
    use greenconv_ident_methods, only: ident_one_receptance, ident_green_matrix
    use greenconv_scene_settings, only: scene_type
    use greenconv_scene_models_point_set, only: scene_points
    use greenconv_scene_models_single, only: sdof_structure, sdof_decay, random_modes_structure, random_modes_decay, &
                                             frf_file_structure, check_frf_file, wheel_rail_structure, &
                                             wheel_rail_receptance
    use greenconv_scene_models_multi, only: tyre_scene_points, tyre_decay, plate_scene_points, plate_decay, &
                                            green_file_points, check_green_file, modes_file_points, check_modes_file
    implicit none
    private

    public :: structure_kind, structure_models, find_model, model_id, model_names, model_requires
    public :: multi_point_model
    public :: structure_builder, points_finder, decay_bound, file_check, contact_receptance, mode_counter

    abstract interface
        !> Build a single-point model's structure from a scene.
        subroutine structure_builder(scene, structure, error)
            import :: scene_type, structure_model, error_type
            !> The scene.
            type(scene_type), intent(in) :: scene
            !> The structure.
            type(structure_model), intent(out) :: structure
            !> Set when the structure cannot be built, the scene's place in front.
            type(error_type), allocatable, intent(out) :: error
        end subroutine structure_builder

        !> Find a multi-point model's contact points, placed on the road, and what their
        !> convolvers are built from.
        subroutine points_finder(scene, points, summary, error)
            import :: scene_type, scene_points, error_type
            !> The scene (task 'contact').
            type(scene_type), intent(in) :: scene
            !> The points.
            type(scene_points), intent(out) :: points
            !> The scene's summary lines ("# scene NAME: ..."), separated by new_line('a').
            character(len=:), allocatable, intent(out) :: summary
            !> Set for an unusable scene, the scene's place in front.
            type(error_type), allocatable, intent(out) :: error
        end subroutine points_finder

        !> Decay rate [1/s] of the slowest mode of a model with exact modes, from the scene's
        !> values (it bounds the length of a sampled kernel before any is built).
        pure real(dp) function decay_bound(scene)
            import :: dp, scene_type
            !> The scene.
            type(scene_type), intent(in) :: scene
        end function decay_bound

        !> The receptance [m/N] a single-point model's contact sees, from the scene's values in
        !> closed form (for the linear frequency-domain reference beside its runs).
        subroutine contact_receptance(scene, omega, alpha)
            import :: dp, scene_type
            !> The scene.
            type(scene_type), intent(in) :: scene
            !> Angular frequencies [rad/s], >= 0.
            real(dp), intent(in) :: omega(:)
            !> The receptance at each.
            complex(dp), intent(out) :: alpha(:)
        end subroutine contact_receptance

        !> For `--check`: the number of modes N_m a model's modal methods step, from the scene's
        !> values before anything is built (or its upper bound, `modes_bounded`).
        pure integer function mode_counter(scene)
            import :: scene_type
            !> The scene.
            type(scene_type), intent(in) :: scene
        end function mode_counter

        !> For `--check`: read the file a model names without building the structure and
        !> append what was found to the check's line.
        subroutine file_check(scene, line, n_points, error)
            import :: scene_type, error_type
            !> The scene.
            type(scene_type), intent(in) :: scene
            !> The check's line.
            character(len=:), allocatable, intent(inout) :: line
            !> Number of contact points N_c (the file's, for a multi-point model).
            integer, intent(inout) :: n_points
            !> Set for an unusable file, the scene's place in front.
            type(error_type), allocatable, intent(out) :: error
        end subroutine file_check
    end interface

    !> Longest model name a scene may write.
    integer, parameter :: model_name_length = 16
    !> Number of models in the registry (`structure_models`).
    integer, parameter :: model_count = 8

    !> One structure model: what it requires and provides, and its procedures.
    type :: structure_kind
        !> Row of the registry; 0 for a name not in the registry.
        integer :: id = 0
        !> Name a scene writes, `&structure model = '<name>'`.
        character(len=model_name_length) :: name = ''
        !> The `&structure` variables the model requires, blank-separated.
        character(len=64) :: requires = ''
        !> Whether the model has a mass M [kg], so that `&contact preload` may default to M*g.
        logical :: has_mass = .false.
        !> Whether the structure's own modes are known exactly.
        logical :: exact_modes = .false.
        !> Whether the modal methods run on modes identified by LSCE from a sampled G.
        logical :: identified_modes = .false.
        !> Whether `direct` and `fft` use g sampled from a receptance (bounded by its file),
        !> rather than g of the exact modes.
        logical :: sampled_g = .false.
        !> Dimensions of the patch grid the scene lays its contact points on: 0 (one point, or
        !> points from a file), 1 (`&contact n_points` on a line), 2 (`n_points_x` by
        !> `n_points_y`).
        integer :: grid_dimensions = 0
        !> Whether each mode carries a full residue matrix over the points (shared poles identified
        !> from a Green's matrix: N_c terms a mode in a modal recursion), not a mode shape.
        logical :: residue_matrices = .false.
        !> Builder of a single-point model's structure; unassociated for a multi-point model.
        procedure(structure_builder), pointer, nopass :: build => null()
        !> Finder of a multi-point model's contact points (N_c >= 1, `&contact n_points`);
        !> unassociated for a single-point model.
        procedure(points_finder), pointer, nopass :: find_points => null()
        !> Decay rate of the slowest exact mode, for a model whose `direct` and `fft` sample
        !> its exact g (not `sampled_g`); else unassociated.
        procedure(decay_bound), pointer, nopass :: slowest_decay => null()
        !> `--check` of the file the model names; unassociated when it names none.
        procedure(file_check), pointer, nopass :: check_file => null()
        !> The receptance of a model known in closed form: its runs get the linear reference
        !> (greenconv_scene_run_linear_reference) and report loss of contact; else unassociated.
        procedure(contact_receptance), pointer, nopass :: receptance => null()
        !> `--check`'s number of modes N_m from the scene's values; unassociated for a
        !> multi-point model whose points carry their modes (counted once they are found).
        procedure(mode_counter), pointer, nopass :: mode_count => null()
        !> Whether `mode_count` is only an upper bound (the largest order an identification
        !> may choose), which `--check` prints as "<= N_m".
        logical :: modes_bounded = .false.
        !> A multi-point model's kind of scene, first words of its runs' file titles
        !> ("greenconv tyre/road scene NAME, method M").
        character(len=16) :: title = 'patch'
        !> Whether those titles name the scene's Green's matrix file after the scene's name.
        logical :: title_names_file = .true.
        !> What an identification of the model identifies: `ident_one_receptance` or
        !> `ident_green_matrix` (greenconv_ident_methods), for the default method and its check.
        integer :: identifies = ident_one_receptance
        !> Whether the receptance identified is a measured one (a file), not one sampled from the
        !> scene's values: the identification registry's default differs.
        logical :: measured = .false.
    contains
        !> Whether the contact has several points (the model finds its points).
        procedure :: multi_point => kind_multi_point
    end type structure_kind

contains

    !> Every structure model of the registry, in the order messages list the names.
    pure function structure_models() result(models)
        !> The registry.
        type(structure_kind) :: models(model_count)

        models(1) = structure_kind(1, 'sdof', 'mass stiffness damping_ratio', has_mass=.true., exact_modes=.true., &
                                   build=sdof_structure, slowest_decay=sdof_decay, mode_count=one_mode)
        models(2) = structure_kind(2, 'random_modes', '', exact_modes=.true., identified_modes=.true., &
                                   build=random_modes_structure, slowest_decay=random_modes_decay, &
                                   mode_count=scene_modes)
        models(3) = structure_kind(3, 'frf_file', 'frf_file', identified_modes=.true., sampled_g=.true., &
                                   build=frf_file_structure, check_file=check_frf_file, mode_count=largest_order, &
                                   modes_bounded=.true., measured=.true.)
        models(4) = structure_kind(4, 'tyre', '', exact_modes=.true., grid_dimensions=1, &
                                   find_points=tyre_scene_points, slowest_decay=tyre_decay, title='tyre/road', &
                                   title_names_file=.false.)
        models(5) = structure_kind(5, 'tyre_plate', '', exact_modes=.true., grid_dimensions=2, &
                                   find_points=plate_scene_points, slowest_decay=plate_decay)
        models(6) = structure_kind(6, 'green_file', 'green_file', identified_modes=.true., sampled_g=.true., &
                                   residue_matrices=.true., find_points=green_file_points, &
                                   check_file=check_green_file, mode_count=largest_order, modes_bounded=.true., &
                                   identifies=ident_green_matrix)
        ! a modes file's modes are known once it is read, not from the scene's values: no decay
        ! bound before the run (its direct and fft kernels are sized when they are built)
        models(7) = structure_kind(7, 'modes_file', 'modes_file', find_points=modes_file_points, &
                                   check_file=check_modes_file)
        ! the rail's receptance is no finite sum of modes: sampled and identified as a file's
        models(8) = structure_kind(8, 'wheel_rail', 'rail_bending rail_mass support_stiffness wheel_mass', &
                                   identified_modes=.true., sampled_g=.true., build=wheel_rail_structure, &
                                   receptance=wheel_rail_receptance, mode_count=scene_modes)
    end function structure_models

    !> One mode (a mass-spring system).
    pure integer function one_mode(scene)
        !> The scene.
        type(scene_type), intent(in) :: scene

        associate (unused => scene%n_modes)
        end associate
        one_mode = 1
    end function one_mode

    !> The scene's `&structure n_modes`.
    pure integer function scene_modes(scene)
        !> The scene.
        type(scene_type), intent(in) :: scene

        scene_modes = scene%n_modes
    end function scene_modes

    !> The largest order the identification may choose, `&identification max_order`.
    pure integer function largest_order(scene)
        !> The scene.
        type(scene_type), intent(in) :: scene

        largest_order = scene%max_order
    end function largest_order

    !> The model called `name` (exact, lower case); one with `id` 0 when there is none.
    function find_model(name) result(model)
        !> Model name as the scene writes it.
        character(len=*), intent(in) :: name
        !> Its registry entry, or an entry with id 0 and no capability.
        type(structure_kind) :: model

        type(structure_kind), allocatable :: models(:)
        integer :: i

        models = structure_models()
        do i = 1, size(models)
            if (trim(models(i)%name) == trim(name)) then
                model = models(i)
                return
            end if
        end do
    end function find_model

    !> The registry row of the model called `name` (exact, lower case); 0 when there is none.
    integer function model_id(name)
        !> Model name as the scene writes it.
        character(len=*), intent(in) :: name

        type(structure_kind) :: model

        model = find_model(name)
        model_id = model%id
    end function model_id

    !> Whether the model touches the road at several points: it finds its points.
    elemental logical function kind_multi_point(self)
        !> The model's registry entry.
        class(structure_kind), intent(in) :: self

        kind_multi_point = associated(self%find_points)
    end function kind_multi_point

    !> The registry's model names, in its order.
    pure function model_name_list() result(names)
        !> The names, each padded to the registry's name length.
        character(len=model_name_length) :: names(model_count)

        type(structure_kind) :: models(model_count)

        models = structure_models()
        names = models%name
    end function model_name_list

    !> The model names for messages: `'sdof', 'random_modes', ..., 'green_file' or 'modes_file'`.
    function model_names() result(text)
        !> The quoted names, comma-separated, the last after `or`.
        character(len=quoted_list_length(model_name_list())) :: text

        text = quoted_list(model_name_list())
    end function model_names

    !> Whether a model requires a `&structure` variable.
    pure logical function model_requires(model, variable)
        !> The model's registry entry.
        type(structure_kind), intent(in) :: model
        !> Variable name, lower case.
        character(len=*), intent(in) :: variable

        model_requires = index(' '//trim(model%requires)//' ', ' '//trim(variable)//' ') > 0
    end function model_requires

    !> Whether the model called `name` touches the road at several points (N_c >= 1).
    logical function multi_point_model(name)
        !> Model name as the scene writes it.
        character(len=*), intent(in) :: name

        type(structure_kind) :: model

        model = find_model(name)
        multi_point_model = model%multi_point()
    end function multi_point_model

end module greenconv_scene_models_registry
