!> The registry of identification methods (`&identification method`): each method is written
!> here once, with what it identifies (one receptance G, or the shared poles of a Green's
!> matrix), whether it accepts a fixed order, the models it is the default of, the procedure
!> that runs it and a one-line description.
!>
!> The scene's reading, the structure builders and the reports ask it: a name is resolved once,
!> when the scene is read, into its `ident_scheme` (an integer), and every later choice compares
!> schemes, never spellings. Adding an identification method: its module in `ident/`, one row
!> in `registry` with a new scheme, and its branch where the schemes are dispatched
!> (greenconv_ident_structure's `identify_timed` for one receptance, the `green_options` of
!> greenconv_ident_green_structure for a Green's matrix).
module greenconv_ident_methods
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: quoted_list, quoted_list_length
    implicit none
    private

    public :: ident_name_length, n_ident_methods
    public :: is_ident_method, ident_scheme, ident_name, ident_summary, ident_list
    public :: default_ident_method, check_ident_method

    !> Scheme of no identification (an unknown name, or a structure not identified).
    integer, parameter, public :: ident_none = 0
    !> `ml`: maximum likelihood, order by MDL, a standard deviation per mode (greenconv_ident_mlfit).
    integer, parameter, public :: ident_ml = 1
    !> `lsce`: least-squares complex exponential, eqs. (6)-(7) (greenconv_ident_lsce).
    integer, parameter, public :: ident_lsce = 2
    !> `poly_reference`: a Green's matrix's shared poles from every column (greenconv_ident_polyref).
    integer, parameter, public :: ident_poly_reference = 3
    !> `auto`: a Green's matrix's shared poles by `ml` and by `poly_reference`, the better kept.
    integer, parameter, public :: ident_auto = 4

    !> What a method identifies (`check_ident_method`, `default_ident_method`): one receptance G
    !> (a measured FRF file, or G sampled from modes).
    integer, parameter, public :: ident_one_receptance = 1
    !> What a method identifies: the shared poles of a Green's matrix (a file of points).
    integer, parameter, public :: ident_green_matrix = 2

    !> Length of a method name in the registry (names are shorter and blank-padded).
    integer, parameter :: ident_name_length = 14

    !> One identification method.
    type :: ident_entry
        !> Name a scene gives (`&identification method`).
        character(len=ident_name_length) :: name
        !> The scheme the identification dispatches on (`ident_ml`, ...).
        integer :: scheme
        !> Whether it identifies one receptance G (an FRF file, or G sampled from modes).
        logical :: one_receptance
        !> Whether it identifies the shared poles of a Green's matrix (a file of points).
        logical :: green_matrix
        !> Whether it takes a fixed order (`&identification order` > 0); else it chooses the order.
        logical :: fixed_order
        !> Whether it is the default for a measured receptance (`frf_file`).
        logical :: default_measured
        !> Whether it is the default for a receptance sampled from modes (`random_modes`).
        logical :: default_sampled
        !> Whether it is the default for a Green's matrix (`green_file`).
        logical :: default_matrix
        !> The procedure that runs it (module and name).
        character(len=48) :: procedure
        !> What it does, in one line.
        character(len=100) :: summary
    end type ident_entry

    !> The methods, in the order messages list them.
    type(ident_entry), parameter :: registry(*) = [ &
        ident_entry('ml', ident_ml, .true., .true., .false., .true., .false., .false., &
                    'greenconv_ident_mlfit: identify_ml', &
                    'maximum likelihood, order by MDL, sigma per mode (a matrix: its summed driving points)'), &
        ident_entry('lsce', ident_lsce, .true., .false., .true., .false., .true., .false., &
                    'greenconv_ident_lsce: identify', &
                    'least-squares complex exponential, eqs. (6)-(7), the smallest order meeting tol_e'), &
        ident_entry('poly_reference', ident_poly_reference, .false., .true., .false., .false., .false., .false., &
                    'greenconv_ident_polyref: polyref_poles', &
                    'the shared poles of a Green''s matrix from every column (modally dense structures)'), &
        ident_entry('auto', ident_auto, .false., .true., .false., .false., .false., .true., &
                    'greenconv_ident_green_structure: identify_green', &
                    'the shared poles by ml and by poly_reference, the one of smaller worst E kept')]

    !> Number of identification methods in the registry.
    integer, parameter :: n_ident_methods = size(registry)
    !> The methods' names, in the registry's order (one array, for the lists of names).
    character(len=ident_name_length), parameter :: registry_names(n_ident_methods) = registry%name
    !> Length of `ident_summary`'s line.
    integer, parameter :: summary_length = len(registry%summary) + len(registry%procedure) + 3

contains

    !> Whether a method identifies `what`.
    elemental logical function serves(entry, what)
        type(ident_entry), intent(in) :: entry
        integer, intent(in) :: what

        serves = (what == ident_one_receptance .and. entry%one_receptance) .or. &
                 (what == ident_green_matrix .and. entry%green_matrix)
    end function serves

    !> The entry of `name`, or a blank one (scheme `ident_none`, identifying nothing) when unknown.
    elemental function entry_of(name) result(entry)
        character(len=*), intent(in) :: name
        type(ident_entry) :: entry

        integer :: i

        entry = ident_entry('', ident_none, .false., .false., .false., .false., .false., .false., '', '')
        i = findloc(registry_names, name, dim=1)
        if (i > 0) entry = registry(i)
    end function entry_of

    !> Whether `name` is an identification method of the registry (trailing blanks ignored).
    elemental logical function is_ident_method(name)
        !> A method name.
        character(len=*), intent(in) :: name

        is_ident_method = findloc(registry_names, name, dim=1) > 0
    end function is_ident_method

    !> The scheme of a method (`ident_ml`, ...); `ident_none` for an unknown name.
    elemental integer function ident_scheme(name)
        !> A method name.
        character(len=*), intent(in) :: name

        type(ident_entry) :: entry

        entry = entry_of(name)
        ident_scheme = entry%scheme
    end function ident_scheme

    !> The name of a scheme ('' for `ident_none`), blank-padded.
    pure function ident_name(scheme) result(name)
        !> A scheme (`ident_ml`, ...).
        integer, intent(in) :: scheme
        !> Its name.
        character(len=ident_name_length) :: name

        integer :: i

        name = ''
        do i = 1, n_ident_methods
            if (registry(i)%scheme == scheme) name = registry(i)%name
        end do
    end function ident_name

    !> What a method does and the procedure that runs it, in one line, "summary (module:
    !> procedure)", blank-padded; '' for an unknown name.
    pure function ident_summary(name) result(text)
        !> A method name.
        character(len=*), intent(in) :: name
        !> Its line.
        character(len=summary_length) :: text

        type(ident_entry) :: entry

        entry = entry_of(name)
        text = ''
        if (entry%scheme /= ident_none) text = trim(entry%summary)//' ('//trim(entry%procedure)//')'
    end function ident_summary

    !> The names of the methods that identify `what` (`ident_one_receptance`,
    !> `ident_green_matrix`) for messages, "'ml' or 'lsce'".
    pure function ident_list(what) result(text)
        !> Keep only the methods that identify this.
        integer, intent(in) :: what
        !> The names.
        character(len=quoted_list_length(registry_names, serves(registry, what))) :: text

        text = quoted_list(registry_names, serves(registry, what))
    end function ident_list

    !> The method a structure gets when its scene names none: `what` is `ident_green_matrix`
    !> for a Green's matrix file, else `ident_one_receptance` with `measured` true for a
    !> measured receptance (an FRF file), false for one sampled from modes.
    pure function default_ident_method(what, measured) result(name)
        !> What is identified.
        integer, intent(in) :: what
        !> Whether a single receptance was measured (an FRF file) rather than sampled.
        logical, intent(in) :: measured
        !> The default method's name, blank-padded.
        character(len=ident_name_length) :: name

        integer :: i
        logical :: hit

        name = ''
        do i = 1, n_ident_methods
            if (what == ident_green_matrix) then
                hit = registry(i)%default_matrix
            else if (measured) then
                hit = registry(i)%default_measured
            else
                hit = registry(i)%default_sampled
            end if
            if (hit) then
                name = registry(i)%name
                return
            end if
        end do
    end function default_ident_method

    !> Check that method `name` can identify `what` (`ident_one_receptance` or
    !> `ident_green_matrix`) of a model called `model`, and takes the order asked (0: its own
    !> choice). The message says what to do and names no file: the caller puts its place
    !> (file:line, group, variable) in front, and `variable` tells which of method or order
    !> was refused.
    subroutine check_ident_method(name, what, model, order, variable, error)
        !> The method name.
        character(len=*), intent(in) :: name
        !> What the model needs identified.
        integer, intent(in) :: what
        !> The model's name, for the message.
        character(len=*), intent(in) :: model
        !> The order asked, 0 for the method's own choice.
        integer, intent(in) :: order
        !> Set to 'method' or 'order': the variable refused ('' when none).
        character(len=:), allocatable, intent(out) :: variable
        !> Set (status `stat_input`) when the method cannot identify it; its message is the
        !> expected value(s), without place.
        type(error_type), allocatable, intent(out) :: error

        integer :: i

        variable = ''
        i = findloc(registry_names, name, dim=1)
        if (i == 0) then
            variable = 'method'
            call fatal_error(error, quoted_list(registry_names))
        else if (.not. serves(registry(i), what)) then
            variable = 'method'
            if (what == ident_green_matrix) then
                call fatal_error(error, ident_list(what)//" for model '"//trim(model) &
                                 //"' (a Green's matrix file: its shared poles)")
            else
                call fatal_error(error, ident_list(what)//" for model '"//trim(model)//"' ("// &
                                 ident_list(ident_green_matrix)//" identify a Green's matrix file)")
            end if
        else if (order /= 0 .and. .not. registry(i)%fixed_order) then
            variable = 'order'
            call fatal_error(error, "0 with method '"//trim(name)//"' (it chooses the order from the data; " &
                             //'a fixed order needs method = '//fixed_order_list()//')')
        end if
    end subroutine check_ident_method

    !> The methods that take a fixed order, "'lsce'".
    pure function fixed_order_list() result(text)
        character(len=quoted_list_length(registry_names, registry%fixed_order)) :: text

        text = quoted_list(registry_names, registry%fixed_order)
    end function fixed_order_list

end module greenconv_ident_methods
