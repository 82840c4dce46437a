!> The registry of convolution methods: each method is written here once, with its aliases,
!> what it convolves with (sampled g, modes, or both), whether it serves single-point and
!> multi-point contact, and a one-line description; the defaults of the methods' options too.
!>
!> The scene check, the builder (greenconv_conv_builder), the runner and the library ask it,
!> so a scene `--check` refuses exactly what a run refuses. This is the only place a method's
!> name is compared: everyone else asks for its `scheme` (`method_scheme`), an integer turned
!> into constructors at one place, greenconv_conv_engines's `engine_of` (the builder calls what
!> it gives). Adding an engine: its module, one row in `registry` with a new scheme, and its
!> `case` in `engine_of`.
module greenconv_conv_methods
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: quoted_list, quoted_list_length
    implicit none
    private

    public :: default_truncation_tol, default_accuracy
    public :: method_name_length, n_methods
    public :: is_method, canonical_method, method_engine, method_names, method_list, method_summary
    public :: method_needs, check_method, method_scheme, is_modal_recursion, method_order
    public :: method_cost, cost_model

    !> What a method may need of a structure (`method_needs`): the sampled impulse response g.
    integer, parameter, public :: needs_sampled_g = 1
    !> What a method may need of a structure (`method_needs`): modes (poles and residues).
    integer, parameter, public :: needs_modes = 2

    !> Scheme of no method (an unknown name).
    integer, parameter, public :: scheme_none = 0
    !> `direct`: the truncated direct sum over sampled g.
    integer, parameter, public :: scheme_direct = 1
    !> `fft`: the same sum by partitioned FFT convolution.
    integer, parameter, public :: scheme_fft = 2
    !> `paper`: the modal recursion as eqs. (15)-(17) write it.
    integer, parameter, public :: scheme_paper = 3
    !> `recursive` (`modal`): the decaying recursion, rectangle rule, explicit.
    integer, parameter, public :: scheme_rectangle = 4
    !> `exact`: the decaying recursion with the force linear within a step (first-order hold).
    integer, parameter, public :: scheme_first_order = 5
    !> `backward`: the decaying recursion with the force constant over the step ending at its sample.
    integer, parameter, public :: scheme_backward = 6
    !> `auto`: picks one of the others.
    integer, parameter, public :: scheme_auto = 7

    !> Truncation of g for `direct` and `fft` when none is given: the paper's 1 % of max |g|.
    real(dp), parameter :: default_truncation_tol = 0.01_dp
    !> Relative accuracy `auto` must meet when none is given: the largest E (eq. 7) it accepts.
    real(dp), parameter :: default_accuracy = 1.0e-3_dp

    !> Length of a method name in the registry (names are shorter and blank-padded).
    integer, parameter :: method_name_length = 9

    !> What a step and a run of a method cost, as multiples of its sizes: N_c contact points,
    !> N_m modes, N_T modal terms at each point (N_m, or N_m*N_c for a Green's matrix), N_g
    !> kernel samples. A step's multiply-adds are the sum of the `work_*` coefficients times
    !> their sizes, the memory [bytes] the sum of the `bytes_*` ones; a method that picks
    !> another (`auto`) names in `dearer_of` the methods whose dearer cost bounds its own.
    type :: cost_model
        !> Multiply-adds per past force of each pair of points (N_c^2*N_g): a direct sum.
        real(dp) :: work_pair_kernel = 0.0_dp
        !> Multiply-adds per pair of points and per log2 of the block length 2*N_g (N_c^2*log2(2*N_g)):
        !> a partitioned FFT convolution's kernel products.
        real(dp) :: work_pair_fft = 0.0_dp
        !> Multiply-adds per modal term at each point (N_c*N_T): the state update, the force's
        !> convolution term and the displacement's sum.
        real(dp) :: work_point_term = 0.0_dp
        !> Multiply-adds per mode at each point (N_c*N_m) of the implicit step's Newton iterations
        !> (about three, each a recursion's work over the modes at the points: the low-rank solve).
        real(dp) :: work_point_mode = 0.0_dp
        !> Bytes per kernel sample of each pair of points (N_c^2*N_g): the kernel, its spectra.
        real(dp) :: bytes_pair_kernel = 0.0_dp
        !> Bytes per pair of points (N_c^2): the spectra's extra line.
        real(dp) :: bytes_pair = 0.0_dp
        !> Bytes per past force at each point (N_c*N_g): the force history, the FFT's blocks.
        real(dp) :: bytes_point_kernel = 0.0_dp
        !> Bytes per modal term (N_T): states and factors.
        real(dp) :: bytes_term = 0.0_dp
        !> Bytes per modal term at each point (N_c*N_T): residues and shapes at the points.
        real(dp) :: bytes_point_term = 0.0_dp
        !> Bytes per pair of points of a multi-point run (N_c^2 when N_c > 1): the implicit
        !> step's instantaneous matrix.
        real(dp) :: bytes_pair_implicit = 0.0_dp
        !> The methods whose dearer cost bounds this one's (a method that picks one of them).
        character(len=method_name_length) :: dearer_of(2) = ''
    end type cost_model

    !> Multiply-adds of one modal term at one point per step of a modal recursion.
    real(dp), parameter :: term_work = 4.0_dp
    !> Newton iterations of an implicit step that the cost assumes.
    real(dp), parameter :: newton_iterations = 3.0_dp

    !> The cost of the direct sum: N_c^2*N_g multiply-adds a step; the kernel and the histories.
    type(cost_model), parameter :: direct_cost = cost_model(work_pair_kernel=1.0_dp, bytes_pair_kernel=8.0_dp, &
                                                            bytes_point_kernel=16.0_dp)
    !> The cost of the partitioned FFT convolution: eight multiply-adds per kernel product and
    !> log2 of the block; the kernel, its complex spectra (twice N_g) and the blocks.
    type(cost_model), parameter :: fft_cost = cost_model(work_pair_fft=8.0_dp, bytes_pair_kernel=24.0_dp, &
                                                         bytes_pair=16.0_dp, bytes_point_kernel=32.0_dp)
    !> The cost of an explicit modal recursion: its states, residues and shapes at the points.
    type(cost_model), parameter :: recursion_cost = cost_model(work_point_term=term_work, bytes_term=32.0_dp, &
                                                               bytes_point_term=24.0_dp)
    !> The cost of an implicit modal recursion (`exact`, `backward`): the recursion's, the
    !> Newton iterations over the modes at the points and the instantaneous matrix.
    type(cost_model), parameter :: implicit_cost = cost_model(work_point_term=term_work, &
                                                              work_point_mode=newton_iterations*term_work, &
                                                              bytes_term=32.0_dp, bytes_point_term=24.0_dp, &
                                                              bytes_pair_implicit=8.0_dp)

    !> One method.
    type :: method_entry
        !> Name a scene or a caller gives.
        character(len=method_name_length) :: name
        !> Name of the method it runs (itself, or the method it is an alias of).
        character(len=method_name_length) :: canonical
        !> The engine that steps it: `direct`, `fft`, `paper` or `recursive` (the decaying modal
        !> recursion of greenconv_conv_recursive, single-point, and greenconv_conv_green_modal,
        !> multi-point); '' for `auto`, which picks another method.
        character(len=method_name_length) :: engine
        !> The scheme the constructors dispatch on (`scheme_direct`, ...).
        integer :: scheme
        !> Whether it convolves with the sampled impulse response g (or samples it to weigh a choice).
        logical :: needs_g
        !> Whether it recurs on modes (poles and residues).
        logical :: needs_modes
        !> Whether it serves one contact point (a `convolver`).
        logical :: single_point
        !> Whether it serves several contact points (a `multipoint_convolver`).
        logical :: multi_point
        !> Its order p in dt, which the error budget's step doubling assumes (its contact forces
        !> converge as dt^p): 1 for the force held over the step ending at its sample, else 2.
        integer :: order
        !> What it computes, in one line.
        character(len=96) :: summary
        !> What a step and a run of it cost (`cost_model`).
        type(cost_model) :: cost
    end type method_entry

    !> The methods, in the order messages list them.
    type(method_entry), parameter :: registry(*) = [ &
        method_entry('direct', 'direct', 'direct', scheme_direct, .true., .false., .true., .true., 2, &
                     'the direct sum with g truncated by the paper''s rule (N_g multiply-adds a step)', &
                     direct_cost), &
        method_entry('fft', 'fft', 'fft', scheme_fft, .true., .false., .true., .true., 2, &
                     'the same truncated sum by partitioned FFT convolution', &
                     fft_cost), &
        method_entry('modal', 'recursive', 'recursive', scheme_rectangle, .false., .true., .true., .true., 2, &
                     'the modal recursion of the paper with decaying factors (an alias of recursive)', &
                     recursion_cost), &
        method_entry('paper', 'paper', 'paper', scheme_paper, .false., .true., .true., .false., 2, &
                     'the modal recursion as eqs. (15)-(17) write it', &
                     recursion_cost), &
        method_entry('recursive', 'recursive', 'recursive', scheme_rectangle, .false., .true., .true., .true., 2, &
                     'the modal recursion (rectangle rule) with decaying factors, explicit', &
                     recursion_cost), &
        method_entry('exact', 'exact', 'recursive', scheme_first_order, .false., .true., .true., .true., 2, &
                     'the modal recursion with the force linear within a step (first-order hold)', &
                     implicit_cost), &
        method_entry('backward', 'backward', 'recursive', scheme_backward, .false., .true., .true., .false., 1, &
                     'the modal recursion with the force constant over the step ending at its sample', &
                     implicit_cost), &
        method_entry('auto', 'auto', '', scheme_auto, .true., .true., .true., .false., 2, &
                     'the cheapest of direct, exact and fft that meets the requested accuracy', &
                     cost_model(dearer_of=['direct   ', 'exact    ']))]

    !> Number of methods in the registry.
    integer, parameter :: n_methods = size(registry)
    !> The methods' names, in the registry's order (one array, for the lists of names).
    character(len=method_name_length), parameter :: registry_names(n_methods) = registry%name


    !> The method names for messages, "'direct', 'fft' or 'exact'": those for one kind of
    !> contact (`method_list(multi_point)`) or those one engine steps (`method_list(engine=...)`);
    !> all of them are `quoted_list(method_names())`.
    interface method_list
        module procedure method_list_for
        module procedure method_list_of
    end interface method_list

    !> Fields of a method's entry for `entry_field`.
    integer, parameter :: field_canonical = 1, field_engine = 2, field_summary = 3

contains

    !> One text field of a method's entry (`field_canonical`, `field_engine`, `field_summary`),
    !> blank-padded; blank for an unknown name.
    pure function entry_field(name, which) result(field)
        !> A method name.
        character(len=*), intent(in) :: name
        !> Which field.
        integer, intent(in) :: which
        !> The field.
        character(len=96) :: field

        type(method_entry) :: entry

        entry = entry_of(name)
        select case (which)
        case (field_canonical)
            field = entry%canonical
        case (field_engine)
            field = entry%engine
        case default
            field = entry%summary
        end select
    end function entry_field

    !> Whether `name` is a method of the registry (trailing blanks ignored).
    elemental logical function is_method(name)
        !> A method name.
        character(len=*), intent(in) :: name

        is_method = findloc(registry_names, name, dim=1) > 0
    end function is_method

    !> The method a name runs: the method itself, or the one it is an alias of (`modal`
    !> gives `recursive`); '' for an unknown name.
    pure function canonical_method(name) result(canonical)
        !> A method name.
        character(len=*), intent(in) :: name
        !> The method it runs.
        character(len=len_trim(entry_field(name, field_canonical))) :: canonical

        canonical = entry_field(name, field_canonical)
    end function canonical_method

    !> The names of the methods, in the registry's order (blank-padded to `method_name_length`).
    pure function method_names() result(names)
        character(len=method_name_length) :: names(n_methods)

        names(:) = registry_names
    end function method_names

    !> The method names that serve single-point (`multi_point` false) or multi-point contact.
    pure function method_list_for(multi_point) result(text)
        !> Keep only the methods for this kind of contact.
        logical, intent(in) :: multi_point
        !> The names.
        character(len=quoted_list_length(registry_names, &
                                         merge(registry%multi_point, registry%single_point, multi_point))) :: text

        text = quoted_list(registry_names, merge(registry%multi_point, registry%single_point, multi_point))
    end function method_list_for

    !> The method names one engine steps (see `method_engine`).
    pure function method_list_of(engine) result(text)
        !> Keep only the methods this engine steps.
        character(len=*), intent(in) :: engine
        !> The names.
        character(len=quoted_list_length(registry_names, registry%engine == engine)) :: text

        text = quoted_list(registry_names, registry%engine == engine)
    end function method_list_of

    !> The engine that steps a method: `direct`, `fft`, `paper` or `recursive`; '' for `auto`
    !> (it picks another method) and for an unknown name.
    pure function method_engine(name) result(engine)
        !> A method name.
        character(len=*), intent(in) :: name
        !> Its engine.
        character(len=len_trim(entry_field(name, field_engine))) :: engine

        engine = entry_field(name, field_engine)
    end function method_engine

    !> The scheme a method's constructor dispatches on (`scheme_direct`, ..., `scheme_auto`),
    !> aliases resolved (`modal` gives `scheme_rectangle`); `scheme_none` for an unknown name.
    elemental integer function method_scheme(name)
        !> A method name.
        character(len=*), intent(in) :: name

        integer :: i

        method_scheme = scheme_none
        i = findloc(registry_names, name, dim=1)
        if (i > 0) method_scheme = registry(i)%scheme
    end function method_scheme

    !> A method's order p in dt (its registry row), 2 for an unknown name.
    elemental integer function method_order(name)
        !> A method name.
        character(len=*), intent(in) :: name

        integer :: i

        method_order = 2
        i = findloc(registry_names, name, dim=1)
        if (i > 0) method_order = registry(i)%order
    end function method_order

    !> What a step and a run of a method cost (its registry row's `cost_model`); no cost for an
    !> unknown name.
    elemental function method_cost(name) result(cost)
        !> A method name.
        character(len=*), intent(in) :: name
        !> Its cost coefficients.
        type(cost_model) :: cost

        type(method_entry) :: entry

        entry = entry_of(name)
        cost = entry%cost
    end function method_cost

    !> Whether a method is stepped by the decaying modal recursion of greenconv_conv_recursive
    !> (`recursive`, `modal`, `exact`, `backward`).
    logical function is_modal_recursion(name)
        !> A method name.
        character(len=*), intent(in) :: name

        is_modal_recursion = method_engine(name) == 'recursive'
    end function is_modal_recursion

    !> What a method computes, in one line; '' for an unknown name.
    pure function method_summary(name) result(text)
        !> A method name.
        character(len=*), intent(in) :: name
        !> Its line.
        character(len=len_trim(entry_field(name, field_summary))) :: text

        text = entry_field(name, field_summary)
    end function method_summary

    !> Whether a method needs `what` of the structure: `needs_sampled_g` (true for `direct`,
    !> `fft`, and `auto`, which samples g to weigh the cost of a direct sum) or `needs_modes`
    !> (the modal recursions and `auto`); false for an unknown name.
    elemental logical function method_needs(name, what)
        !> A method name.
        character(len=*), intent(in) :: name
        !> `needs_sampled_g` or `needs_modes`.
        integer, intent(in) :: what

        type(method_entry) :: entry

        entry = entry_of(name)
        method_needs = (what == needs_sampled_g .and. entry%needs_g) .or. (what == needs_modes .and. entry%needs_modes)
    end function method_needs

    !> Check that method `name` can run on a structure: known, serving this kind of contact
    !> (single- or multi-point), and given what it needs (g, modes). The message says what
    !> to do and names no file: the caller puts its place (file:line, procedure) in front.
    subroutine check_method(name, multi_point, has_g, has_modes, error)
        !> The method name.
        character(len=*), intent(in) :: name
        !> Whether the structure has several contact points.
        logical, intent(in) :: multi_point
        !> Whether the structure has a sampled g (or modes to sample it from).
        logical, intent(in) :: has_g
        !> Whether the structure has modes.
        logical, intent(in) :: has_modes
        !> Set (status `stat_input`) when the method cannot run on it.
        type(error_type), allocatable, intent(out) :: error

        type(method_entry) :: method
        integer :: i

        i = findloc(registry_names, name, dim=1)
        if (i == 0) then
            call fatal_error(error, "unknown convolution method '"//trim(name)//"': expected "//quoted_list(registry_names))
            return
        end if
        method = registry(i)
        if (multi_point .and. .not. method%multi_point) then
            call fatal_error(error, "method '"//trim(name)//"' is not available for multi-point contact: " &
                             //'expected '//method_list(.true.))
        else if (.not. multi_point .and. .not. method%single_point) then
            call fatal_error(error, "method '"//trim(name)//"' is not available for single-point contact: " &
                             //'expected '//method_list(.false.))
        else if (method%needs_g .and. .not. has_g) then
            call fatal_error(error, "method '"//trim(name)//"' needs g: give the structure modes, samples of " &
                             //'g, or an FRF with dt > 0')
        else if (method%needs_modes .and. .not. has_modes) then
            call fatal_error(error, "method '"//trim(name)//"' needs modes, and this structure has none " &
                             //'(only sampled g): use '//g_only_list())
        end if
    end subroutine check_method

    !> The entry of `name`, or a blank one (empty names, needing and serving nothing) when unknown.
    elemental function entry_of(name) result(entry)
        character(len=*), intent(in) :: name
        type(method_entry) :: entry

        integer :: i

        i = findloc(registry_names, name, dim=1)
        if (i > 0) then
            entry = registry(i)
        else
            entry = method_entry('', '', '', scheme_none, .false., .false., .false., .false., 2, '', cost_model())
        end if
    end function entry_of

    !> The methods that need g alone, "'direct' or 'fft'".
    pure function g_only_list() result(text)
        character(len=quoted_list_length(registry_names, registry%needs_g .and. .not. registry%needs_modes)) :: text

        text = quoted_list(registry_names, registry%needs_g .and. .not. registry%needs_modes)
    end function g_only_list

end module greenconv_conv_methods
