!> The registry of contact laws: each law is written here once, with its parameters' names,
!> SI units and ranges and its constructor from a vector of parameter values. Scenes
!> (`&contact law`, `law_parameters`), the Fortran library, the C door `gc_law_new` and the
!> summaries build and describe laws only through it; the steppers see `class(contact_law)`.
!>
!> Adding a law: its module extending `contact_law` (contact/law_<name>.f90), one row in
!> `law_kinds`, and its line in doc/scenes.md.
module greenconv_contact_laws
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_contact_law, only: contact_law, law_name_length
    use greenconv_contact_law_power, only: power_law, build_power_law
    use greenconv_contact_law_exponential, only: exponential_law, build_exponential_law
    implicit none
    private

    public :: contact_law, power_law, exponential_law
    public :: law_kind, law_kinds, find_law, law_names, new_law, new_laws, describe_law, replicate_law
    public :: parameter_list, parameter_text, first_bad_parameter, law_choices
    public :: max_law_parameters

    !> Most parameters of a law in the registry.
    integer, parameter :: max_law_parameters = 3
    !> Number of laws in the registry.
    integer, parameter :: law_count = 2

    !> The power law of stiffness k_c [N/m^p] and exponent p, as a structure constructor of
    !> old: `contact_law(k_c, p)`, `contact_law(stiffness=..., exponent=...)`.
    interface contact_law
        module procedure power_contact_law
    end interface contact_law

    abstract interface
        !> Laws of the parameter values given, one a column (their count and ranges checked by
        !> `new_laws`).
        subroutine law_builder(values, laws)
            import :: contact_law, dp
            !> Parameter values, a column a law, in the row's order and units.
            real(dp), intent(in) :: values(:, :)
            !> The laws, of the row's type.
            class(contact_law), allocatable, intent(out) :: laws(:)
        end subroutine law_builder
    end interface

    !> One contact law: its name, its parameters and its constructor.
    type :: law_kind
        !> Row number (1, 2, ...); 0 for no law.
        integer :: id = 0
        !> Name scenes and doors give (`&contact law`, `gc_law_new`).
        character(len=law_name_length) :: name = ''
        !> Number of parameters.
        integer :: n_parameters = 0
        !> Their names, as messages and summaries write them.
        character(len=8) :: parameter_names(max_law_parameters) = ''
        !> Their SI units ('' for a pure number).
        character(len=8) :: units(max_law_parameters) = ''
        !> Their lower bounds: each value must be finite and strictly above it.
        real(dp) :: above(max_law_parameters) = 0.0_dp
        !> What the law is, in one line.
        character(len=80) :: summary = ''
        !> Whether a scene may give its parameters as `&contact stiffness` and `exponent` (the
        !> power law, as scenes always have) instead of `law_parameters`.
        logical :: from_stiffness = .false.
        !> Its constructor.
        procedure(law_builder), pointer, nopass :: build => null()
    end type law_kind

contains

    !> Every law of the registry, in the order messages list them.
    pure function law_kinds() result(laws)
        !> The registry.
        type(law_kind) :: laws(law_count)

        laws(1) = law_kind(1, 'power', 2, ['k_c     ', 'p       ', '        '], ['N/m^p   ', '        ', '        '], &
                           [0.0_dp, 0.0_dp, 0.0_dp], 'F = k_c*delta^p (p = 3/2: Hertz, p = 1: linear spring)', &
                           from_stiffness=.true., build=build_power_law)
        laws(2) = law_kind(2, 'exponential', 2, ['F_s     ', 'delta_s ', '        '], ['N       ', 'm       ', &
                           '        '], [0.0_dp, 0.0_dp, 0.0_dp], &
                           'F = F_s*(exp(delta/delta_s) - 1), pressure-overclosure', build=build_exponential_law)
    end function law_kinds

    !> The law called `name` (exact, lower case); a row with `id` 0 when there is none.
    pure function find_law(name) result(kind)
        !> Law name.
        character(len=*), intent(in) :: name
        !> Its row.
        type(law_kind) :: kind

        type(law_kind) :: laws(law_count)
        integer :: i

        laws = law_kinds()
        do i = 1, law_count
            if (trim(laws(i)%name) == trim(name)) then
                kind = laws(i)
                return
            end if
        end do
    end function find_law

    !> The registry's names, one a row, blank-padded.
    pure function law_choices() result(names)
        !> The names.
        character(len=law_name_length) :: names(law_count)

        type(law_kind) :: laws(law_count)

        laws = law_kinds()
        names = laws%name
    end function law_choices

    !> Length of `law_names()`.
    pure integer function law_names_length()
        type(law_kind) :: laws(law_count)

        laws = law_kinds()
        law_names_length = sum(len_trim(laws%name)) + 2*law_count + 2*(law_count - 1)
    end function law_names_length

    !> The registry's names, quoted and separated by commas: "'power', 'exponential'" (a
    !> specification length: no static length per call site, which threads would share).
    pure function law_names() result(text)
        !> The list.
        character(len=law_names_length()) :: text

        type(law_kind) :: laws(law_count)
        integer :: i, at, width

        laws = law_kinds()
        text = ''
        at = 0
        do i = 1, law_count
            if (i > 1) then
                text(at + 1:at + 2) = ', '
                at = at + 2
            end if
            width = len_trim(laws(i)%name) + 2
            text(at + 1:at + width) = "'"//trim(laws(i)%name)//"'"
            at = at + width
        end do
    end function law_names
    !> The law `name` of the parameters `values`, checked: an unknown name, a wrong count or a
    !> value out of range sets `error` (status `stat_input`) with a message that names the law,
    !> the parameter, its unit and range, and the value found.
    subroutine new_law(name, values, law, error)
        !> Law name, as the registry writes it.
        character(len=*), intent(in) :: name
        !> Parameter values, in the row's order and units.
        real(dp), intent(in) :: values(:)
        !> The law; unallocated on error.
        class(contact_law), allocatable, intent(out) :: law
        !> Set when the name or a value is refused.
        type(error_type), allocatable, intent(out) :: error

        class(contact_law), allocatable :: laws(:)

        call new_laws(name, reshape(values, [size(values), 1]), laws, error)
        if (.not. allocated(error)) allocate (law, source=laws(1))
    end subroutine new_law

    !> The laws `name` of the parameters values(:, i), one a point, an array of one dynamic
    !> type as the steppers take it; checked as `new_law` checks one, the message naming the
    !> point when there are several.
    subroutine new_laws(name, values, laws, error)
        !> Law name, as the registry writes it.
        character(len=*), intent(in) :: name
        !> Parameter values, a column a point, in the row's order and units.
        real(dp), intent(in) :: values(:, :)
        !> The laws; unallocated on error.
        class(contact_law), allocatable, intent(out) :: laws(:)
        !> Set when the name or a value is refused.
        type(error_type), allocatable, intent(out) :: error

        type(law_kind) :: kind
        character(len=:), allocatable :: point
        integer :: i, j

        kind = find_law(name)
        if (kind%id == 0) then
            call fatal_error(error, "contact law: unknown law '"//trim(name)//"', expected one of "//law_names())
            return
        end if
        if (size(values, 1) /= kind%n_parameters) then
            call fatal_error(error, "contact law '"//trim(kind%name)//"': expected "//int_text(kind%n_parameters) &
                             //' parameters ('//parameter_list(kind)//'), found '//int_text(size(values, 1)))
            return
        end if
        do j = 1, size(values, 2)
            point = ''
            if (size(values, 2) > 1) point = 'point '//int_text(j)//': '
            i = first_bad_parameter(kind, values(:, j))
            if (i > 0) then
                call fatal_error(error, point//"contact law '"//trim(kind%name)//"': parameter " &
                                 //parameter_text(kind, i)//' must be finite and > '//sci_text(kind%above(i)) &
                                 //', found '//sci_text(values(i, j)))
                return
            end if
        end do
        call kind%build(values, laws)
        do j = 1, size(laws)
            call laws(j)%check(error)
            if (allocated(error)) then
                deallocate (laws)
                return
            end if
        end do
    end subroutine new_laws
    !> One line naming a law with its parameters, e.g. "power law k_c = 1.00E+06 N/m^p, p = 1.50E+00".
    subroutine describe_law(law, text)
        !> The law.
        class(contact_law), intent(in) :: law
        !> Its description.
        character(len=:), allocatable, intent(out) :: text

        type(law_kind) :: kind
        real(dp), allocatable :: values(:)
        integer :: i

        kind = find_law(law%name())
        values = law%parameters()
        text = trim(law%name())//' law'
        do i = 1, min(kind%n_parameters, size(values))
            if (i > 1) text = text//','
            text = text//' '//trim(kind%parameter_names(i))//' = '//sci_text(values(i))
            if (len_trim(kind%units(i)) > 0) text = text//' '//trim(kind%units(i))
        end do
    end subroutine describe_law
    !> `n` copies of one law, a polymorphic array of its dynamic type (one law at every point).
    subroutine replicate_law(law, n, laws)
        !> The law.
        class(contact_law), intent(in) :: law
        !> Number of copies, >= 0.
        integer, intent(in) :: n
        !> The copies.
        class(contact_law), allocatable, intent(out) :: laws(:)

        allocate(laws(n), source=law)
    end subroutine replicate_law

    !> The first of a row's parameter values that is not finite or not above its bound; 0 when
    !> all are in range (`values` holds the row's count).
    pure integer function first_bad_parameter(kind, values)
        !> The row.
        type(law_kind), intent(in) :: kind
        !> Parameter values, in the row's order and units.
        real(dp), intent(in) :: values(:)

        integer :: i

        first_bad_parameter = 0
        do i = 1, min(kind%n_parameters, size(values))
            if (.not. (values(i) > kind%above(i) .and. ieee_is_finite(values(i)))) then
                first_bad_parameter = i
                return
            end if
        end do
    end function first_bad_parameter

    !> Length of `parameter_list(kind)`.
    pure integer function parameter_list_length(kind)
        type(law_kind), intent(in) :: kind

        integer :: i

        parameter_list_length = 2*max(kind%n_parameters - 1, 0)
        do i = 1, kind%n_parameters
            parameter_list_length = parameter_list_length + parameter_text_length(kind, i)
        end do
    end function parameter_list_length

    !> "k_c [N/m^p], p": the parameters of a row with their units.
    pure function parameter_list(kind) result(text)
        !> The row.
        type(law_kind), intent(in) :: kind
        !> The list.
        character(len=parameter_list_length(kind)) :: text

        integer :: i, at, width

        text = ''
        at = 0
        do i = 1, kind%n_parameters
            if (i > 1) then
                text(at + 1:at + 2) = ', '
                at = at + 2
            end if
            width = parameter_text_length(kind, i)
            text(at + 1:at + width) = parameter_text(kind, i)
            at = at + width
        end do
    end function parameter_list

    !> Length of `parameter_text(kind, i)`.
    pure integer function parameter_text_length(kind, i)
        type(law_kind), intent(in) :: kind
        integer, intent(in) :: i

        parameter_text_length = len_trim(kind%parameter_names(i))
        if (len_trim(kind%units(i)) > 0) parameter_text_length = parameter_text_length + len_trim(kind%units(i)) + 3
    end function parameter_text_length

    !> "k_c [N/m^p]" or "p": one parameter of a row with its unit.
    pure function parameter_text(kind, i) result(text)
        !> The row.
        type(law_kind), intent(in) :: kind
        !> The parameter's index.
        integer, intent(in) :: i
        !> Its name and unit.
        character(len=parameter_text_length(kind, i)) :: text

        if (len_trim(kind%units(i)) > 0) then
            text = trim(kind%parameter_names(i))//' ['//trim(kind%units(i))//']'
        else
            text = trim(kind%parameter_names(i))
        end if
    end function parameter_text
    !> The power law k_c*delta^p (defaults: k_c = 1e6 N/m^p, p = 3/2), unchecked.
    elemental function power_contact_law(stiffness, exponent) result(law)
        !> Contact stiffness k_c [N/m^p].
        real(dp), intent(in), optional :: stiffness
        !> Exponent p.
        real(dp), intent(in), optional :: exponent
        !> The law.
        type(power_law) :: law

        if (present(stiffness)) law%stiffness = stiffness
        if (present(exponent)) law%exponent = exponent
    end function power_contact_law

end module greenconv_contact_laws
