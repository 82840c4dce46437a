!> The vocabulary of universal files (greenconv_io_uff): what a dataset 58 function, a node of
!> datasets 15 and 2411 and a skipped dataset are, the ordinate kinds, and the names of the
!> codes the format uses (specific data types, function types), for messages and summaries.
module greenconv_io_uff_types
    use greenconv_core_kinds, only: dp
    use greenconv_core_text, only: int_text
    implicit none
    private

    public :: uff_axis, uff_function, uff_node, uff_skipped, uff_file
    public :: uff_kind_name, uff_data_type_name, uff_function_type_name
    public :: uff_other, uff_receptance, uff_mobility, uff_accelerance

    !> Ordinate kind of a dataset 58 that is none of the three below (see `uff_kind_name`).
    integer, parameter :: uff_other = 0
    !> Ordinate kind: displacement over force (records 9/10 specific data types 8 over 9 or 13),
    !> [m/N] in SI.
    integer, parameter :: uff_receptance = 1
    !> Ordinate kind: velocity over force (11 over 9 or 13), [m/(s N)] in SI.
    integer, parameter :: uff_mobility = 2
    !> Ordinate kind: acceleration over force (12 over 9 or 13), [m/(s^2 N)] in SI.
    integer, parameter :: uff_accelerance = 3

    !> Data characteristics of one axis of a dataset 58 (records 8 to 11).
    type :: uff_axis
        !> Specific data type (field 1): 0 unknown, 8 displacement, 9 reaction force,
        !> 11 velocity, 12 acceleration, 13 excitation force, 17 time, 18 frequency, ...
        !> (see `uff_data_type_name`).
        integer :: data_type = 0
        !> Length units exponent (field 2; meaningful for data type 1, general).
        integer :: length_exponent = 0
        !> Force units exponent (field 3).
        integer :: force_exponent = 0
        !> Temperature units exponent (field 4).
        integer :: temperature_exponent = 0
        !> Axis label (field 5, columns 27-46), trimmed; `NONE` when unused.
        character(len=:), allocatable :: label
        !> Axis units label (field 6, columns 48-67), trimmed; `NONE` when unused.
        character(len=:), allocatable :: units
    end type uff_axis

    !> One dataset 58: a function (FRF, time response, ...) at a response and a reference DOF.
    type :: uff_function
        !> Line of the file where the dataset starts (its opening `-1`), for messages.
        integer :: line = 0
        !> Records 1-5: ID lines (description, run, date, load case name, ...).
        character(len=80) :: id_lines(5) = ''
        !> Record 6 field 1: 0 general, 1 time response, 4 frequency response function, ...
        !> (see `uff_function_type_name`).
        integer :: function_type = 0
        !> Record 6 field 2: function identification number.
        integer :: function_id = 0
        !> Record 6 field 3: version or sequence number.
        integer :: version = 0
        !> Record 6 field 4: load case identification number (0: single point excitation).
        integer :: load_case = 0
        !> Record 6 field 5: response entity name, trimmed.
        character(len=:), allocatable :: response_entity
        !> Record 6 field 6: response node label.
        integer :: response_node = 0
        !> Record 6 field 7: response direction: 0 scalar, +-1/2/3 X/Y/Z translation,
        !> +-4/5/6 X/Y/Z rotation.
        integer :: response_direction = 0
        !> Record 6 field 8: reference entity name, trimmed.
        character(len=:), allocatable :: reference_entity
        !> Record 6 field 9: reference node label.
        integer :: reference_node = 0
        !> Record 6 field 10: reference direction (coded as the response direction).
        integer :: reference_direction = 0
        !> Record 7 field 1: 2 real single, 4 real double, 5 complex single, 6 complex double.
        integer :: ordinate_type = 0
        !> Record 7 field 3: whether the abscissa spacing is even (1) rather than uneven (0).
        logical :: even = .true.
        !> Record 7 field 6: z-axis value (0 when unused), in the units of `z_axis`.
        real(dp) :: z_value = 0.0_dp
        !> Record 8: abscissa data characteristics.
        type(uff_axis) :: abscissa_axis
        !> Record 9: ordinate (numerator) data characteristics.
        type(uff_axis) :: numerator
        !> Record 10: ordinate denominator data characteristics.
        type(uff_axis) :: denominator
        !> Record 11: z-axis data characteristics.
        type(uff_axis) :: z_axis
        !> From records 9 and 10: `uff_receptance`, `uff_mobility`, `uff_accelerance` or `uff_other`.
        integer :: kind = uff_other
        !> Abscissa of every point [Hz for frequency, s for time, as `abscissa_axis` says].
        real(dp), allocatable :: abscissa(:)
        !> Ordinate of every point, in the units records 9 and 10 say (e.g. [m/N]).
        complex(dp), allocatable :: ordinate(:)
        !> Line of the file holding each point's first value (record 12), for messages; not
        !> allocated for a function that was not read from a file.
        integer, allocatable :: point_line(:)
    end type uff_function

    !> One node of dataset 15 or 2411.
    type :: uff_node
        !> Node label.
        integer :: label = 0
        !> Definition (export) coordinate system number.
        integer :: definition_system = 0
        !> Displacement coordinate system number.
        integer :: displacement_system = 0
        !> Color number.
        integer :: color = 0
        !> x, y, z coordinates in the definition system [the model's length unit].
        real(dp) :: position(3) = 0.0_dp
        !> Dataset the node came from: 15 or 2411.
        integer :: dataset = 0
        !> Line of the file holding the node's (first) record.
        integer :: line = 0
    end type uff_node

    !> A dataset the reader does not read.
    type :: uff_skipped
        !> Dataset number.
        integer :: dataset = 0
        !> Line of the file where it starts (its opening `-1`).
        integer :: line = 0
    end type uff_skipped

    !> What `read_uff` found in a universal file, in file order.
    type :: uff_file
        !> The file read.
        character(len=:), allocatable :: path
        !> Every dataset 58.
        type(uff_function), allocatable :: functions(:)
        !> Every node of datasets 15 and 2411.
        type(uff_node), allocatable :: nodes(:)
        !> Every dataset skipped.
        type(uff_skipped), allocatable :: skipped(:)
    end type uff_file

    !> Names of the ordinate kinds, by kind (`uff_other` to `uff_accelerance`).
    character(len=*), parameter :: kind_names(uff_other:uff_accelerance) = [character(len=11) :: 'other', &
        'receptance', 'mobility', 'accelerance']

    !> Names of the specific data types of records 8-11, by code; blank: a code the format does not list.
    character(len=*), parameter :: data_type_names(0:20) = [character(len=16) :: 'unknown', 'general', 'stress', &
        'strain', '', 'temperature', 'heat flux', '', 'displacement', 'reaction force', '', 'velocity', &
        'acceleration', 'excitation force', '', 'pressure', 'mass', 'time', 'frequency', 'rpm', 'order']

    !> Names of the function types of record 6 field 1, by code.
    character(len=*), parameter :: function_type_names(0:27) = [character(len=34) :: 'general or unknown', &
        'time response', 'auto spectrum', 'cross spectrum', 'frequency response function', 'transmissibility', &
        'coherence', 'auto correlation', 'cross correlation', 'power spectral density', 'energy spectral density', &
        'probability density function', 'spectrum', 'cumulative frequency distribution', 'peaks valley', &
        'stress/cycles', 'strain/cycles', 'orbit', 'mode indicator function', 'force pattern', 'partial power', &
        'partial coherence', 'eigenvalue', 'eigenvector', 'shock response spectrum', &
        'finite impulse response filter', 'multiple coherence', 'order function']

contains

    !> The name of `code` in a table of names from code 0, blank-padded; `unknown` for a code
    !> outside the table or with a blank name (which gives the functions below a result of
    !> spec length).
    pure function code_name(names, code, unknown) result(name)
        !> The names of codes 0, 1, ...
        character(len=*), intent(in) :: names(0:)
        !> The code.
        integer, intent(in) :: code
        !> The name of a code the table does not name.
        character(len=*), intent(in) :: unknown
        character(len=max(len(names), len(unknown))) :: name

        name = unknown
        if (code < 0 .or. code > ubound(names, 1)) return
        if (len_trim(names(code)) > 0) name = names(code)
    end function code_name

    !> Name of an ordinate kind: `receptance`, `mobility`, `accelerance` or `other`.
    pure function uff_kind_name(kind) result(name)
        !> `uff_receptance`, `uff_mobility`, `uff_accelerance` or `uff_other`.
        integer, intent(in) :: kind
        character(len=len_trim(code_name(kind_names, kind, 'other'))) :: name

        name = code_name(kind_names, kind, 'other')
    end function uff_kind_name

    !> Name of a specific data type of records 8-11 (`displacement`, `excitation force`, ...);
    !> `type N` for a code the format does not list.
    pure function uff_data_type_name(code) result(name)
        !> Specific data type (record 8-11 field 1).
        integer, intent(in) :: code
        character(len=len_trim(code_name(data_type_names, code, 'type '//int_text(code)))) :: name

        name = code_name(data_type_names, code, 'type '//int_text(code))
    end function uff_data_type_name

    !> Name of a function type of record 6 field 1 (`time response`, `frequency response
    !> function`, ...); `type N` for a code the format does not list.
    pure function uff_function_type_name(code) result(name)
        !> Function type (record 6 field 1).
        integer, intent(in) :: code
        character(len=len_trim(code_name(function_type_names, code, 'type '//int_text(code)))) :: name

        name = code_name(function_type_names, code, 'type '//int_text(code))
    end function uff_function_type_name

end module greenconv_io_uff_types
