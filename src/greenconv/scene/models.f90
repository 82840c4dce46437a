!> The structure models a scene may name (`&structure model`), each written once: its name,
!> the `&structure` variables it requires, and what it gives the convolution methods. The
!> scene's checks (greenconv_scene_schema, greenconv_scene_input) and its builder
!> (greenconv_scene_structure) ask this registry instead of comparing model names.
!>
!> A new structure model is one row here, its variables in the scene table
!> (greenconv_scene_schema) and its case in greenconv_scene_structure.
module greenconv_scene_models
    implicit none
    private

    public :: structure_kind, structure_models, find_model, model_id, model_names, model_requires
    public :: multi_point_model, quoted_list
    public :: model_sdof, model_random_modes, model_frf_file, model_tyre, model_green_file

    !> Identifier of the single-degree-of-freedom oscillator (M, K, xi) of Tab. 1.
    integer, parameter :: model_sdof = 1
    !> Identifier of the random modes of section 3.2 (G sampled from them, then identified).
    integer, parameter :: model_random_modes = 2
    !> Identifier of a receptance G read from a file (identified, g by inverse FFT).
    integer, parameter :: model_frf_file = 3
    !> Identifier of the tyre belt on an elastic foundation, contact over a patch of points.
    integer, parameter :: model_tyre = 4
    !> Identifier of a Green's matrix read from a universal file (shared poles identified, g_ij
    !> by inverse FFT or from the file), contact at its nodes.
    integer, parameter :: model_green_file = 5

    !> One structure model and what it requires and provides.
    type :: structure_kind
        !> Registry identifier (`model_sdof`, ...); 0 for a name not in the registry.
        integer :: id = 0
        !> Name a scene writes, `&structure model = '<name>'`.
        character(len=16) :: name = ''
        !> The `&structure` variables the model requires, blank-separated.
        character(len=48) :: requires = ''
        !> Whether the model has a mass M [kg], so that `&contact preload` may default to M*g.
        logical :: has_mass = .false.
        !> Whether the structure's own modes are known exactly.
        logical :: exact_modes = .false.
        !> Whether the modal methods run on modes identified by LSCE from a sampled G.
        logical :: identified_modes = .false.
        !> Whether `direct` and `fft` use g sampled from a receptance (bounded by its file),
        !> rather than g of the exact modes.
        logical :: sampled_g = .false.
        !> Whether the contact has several points (N_c >= 1, `&contact n_points`).
        logical :: multi_point = .false.
    end type structure_kind

    !> The registry, in the order messages list the names.
    type(structure_kind), parameter :: registry(5) = [ &
        structure_kind(model_sdof, 'sdof', 'mass stiffness damping_ratio', has_mass=.true., exact_modes=.true.), &
        structure_kind(model_random_modes, 'random_modes', '', exact_modes=.true., identified_modes=.true.), &
        structure_kind(model_frf_file, 'frf_file', 'frf_file', identified_modes=.true., sampled_g=.true.), &
        structure_kind(model_tyre, 'tyre', '', exact_modes=.true., multi_point=.true.), &
        structure_kind(model_green_file, 'green_file', 'green_file', identified_modes=.true., sampled_g=.true., &
                       multi_point=.true.)]

contains

    !> Every structure model of the registry.
    pure function structure_models() result(models)
        !> The registry, in the order messages list the names.
        type(structure_kind) :: models(size(registry))

        models = registry
    end function structure_models

    !> The model called `name` (exact, lower case); one with `id` 0 when there is none.
    pure function find_model(name) result(model)
        !> Model name as the scene writes it.
        character(len=*), intent(in) :: name
        !> Its registry entry, or an entry with id 0 and no capability.
        type(structure_kind) :: model

        integer :: i

        do i = 1, size(registry)
            if (trim(registry(i)%name) == trim(name)) then
                model = registry(i)
                return
            end if
        end do
    end function find_model

    !> The registry identifier of the model called `name` (exact, lower case); 0 when there is none.
    pure integer function model_id(name)
        !> Model name as the scene writes it.
        character(len=*), intent(in) :: name

        ! The names are distinct: at most one row matches.
        model_id = sum(registry%id, mask=registry%name == name)
    end function model_id

    !> The model names for messages: `'sdof', 'random_modes', 'frf_file', 'tyre' or 'green_file'`.
    pure function model_names() result(text)
        !> The quoted names, comma-separated, the last after `or`.
        character(len=:), allocatable :: text

        character(len=len(registry%name)) :: names(size(registry))

        names = registry%name
        text = quoted_list(names)
    end function model_names

    !> "'a', 'b' or 'c'": names for a message, each quoted and trimmed, the last after `or`.
    pure function quoted_list(names) result(text)
        !> The names (at least one).
        character(len=*), intent(in) :: names(:)
        !> The list.
        character(len=:), allocatable :: text

        integer :: i

        text = "'"//trim(names(1))//"'"
        do i = 2, size(names)
            if (i < size(names)) then
                text = text//", '"//trim(names(i))//"'"
            else
                text = text//" or '"//trim(names(i))//"'"
            end if
        end do
    end function quoted_list

    !> Whether a model requires a `&structure` variable.
    pure logical function model_requires(model, variable)
        !> The model's registry entry.
        type(structure_kind), intent(in) :: model
        !> Variable name, lower case.
        character(len=*), intent(in) :: variable

        model_requires = index(' '//trim(model%requires)//' ', ' '//trim(variable)//' ') > 0
    end function model_requires

    !> Whether the model called `name` touches the road at several points (N_c >= 1).
    pure logical function multi_point_model(name)
        !> Model name as the scene writes it.
        character(len=*), intent(in) :: name

        multi_point_model = any(registry%multi_point .and. registry%name == name)
    end function multi_point_model

end module greenconv_scene_models
