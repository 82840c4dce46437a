!> Dataset 164 of universal files (units): the factors that turn the file's lengths and forces
!> into SI, for the readers of modes files (greenconv_io_uff_dataset55) and of functions
!> (greenconv_io_uff).
!>
!> | record | format       | holds                                                            |
!> |--------|--------------|------------------------------------------------------------------|
!> | 1      | I10,20A1,I10 | units code (1 SI: m, N; 2 BG: foot, pound f; ... 5 MM: mm, mN;   |
!> |        |              | 9 user defined; 10 MN: mm, N), description, temperature mode     |
!> | 2      | 3D25.17      | factors length, force, temperature; then the temperature offset  |
!>
!> The specification: "to convert from universal file units to SI divide by the appropriate
!> factor" (a file in millimetres gives the length factor 1000). The factors are read as
!> written, whatever the code (a user-defined system has no other source); each must be a
!> finite number > 0. Time is in seconds in every system, so a frequency needs nothing; a mass
!> is a force over an acceleration, m_SI = m_file*length/force (`mass_factor`).
module greenconv_io_uff_units
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_io_uff_records, only: text_line, dataset_extent, record_prefix, integer_field, real_field, &
                                        columns
    implicit none
    private

    public :: uff_units, read_units, file_units

    !> The unit system of a file (dataset 164), SI when the file has none.
    type :: uff_units
        !> Line of the file where the dataset 164 starts (its opening `-1`); 0: none in the file.
        integer :: line = 0
        !> Units code of record 1 (1: SI).
        integer :: code = 1
        !> Description of record 1 (for messages), e.g. `mm (newton)`.
        character(len=20) :: description = 'SI'
        !> Factors of record 2: a length [file units] / length_factor = metres; a force / force_factor = newtons.
        real(dp) :: length_factor = 1.0_dp, force_factor = 1.0_dp
    contains
        !> Whether lengths and forces are already SI (both factors 1).
        procedure :: is_si
        !> The factor m_SI/m_file of a mass: length_factor/force_factor.
        procedure :: mass_factor
        !> `units of dataset 164 at line 3 (mm (newton): length factor 1000, force factor 1)`.
        procedure :: describe
    end type uff_units

contains

    !> Read one dataset 164.
    subroutine read_units(path, lines, set, units, error)
        !> File the lines come from (for messages).
        character(len=*), intent(in) :: path
        !> The file's lines.
        type(text_line), intent(in) :: lines(:)
        !> Where the dataset 164 lies in them.
        type(dataset_extent), intent(in) :: set
        !> The unit system read.
        type(uff_units), intent(out) :: units
        !> Set (status 2) for a malformed record or a factor that is not a finite number > 0.
        type(error_type), allocatable, intent(out) :: error

        character(len=*), parameter :: names(2) = ['length', 'force ']
        real(dp) :: factor(2)
        integer :: i, line

        units%line = set%first
        if (set%last - set%first < 4) then
            call fatal_error(error, path//':'//int_text(set%last)//': universal file dataset 164: expected records ' &
                             //'1 and 2 (the units code, then the factors to SI), found ' &
                             //int_text(max(set%last - set%first - 2, 0))//' lines before the -1 that ends the dataset')
            return
        end if
        line = set%first + 2
        call integer_field(record_prefix(path, line, 164, 1), lines(line)%text, 1, 10, 'the units code', .true., &
                           units%code, error)
        if (allocated(error)) return
        units%description = adjustl(columns(lines(line)%text, 11, 30))
        line = set%first + 3
        do i = 1, 2
            call real_field(record_prefix(path, line, 164, 2), lines(line)%text, 25*i - 24, 25*i, 'the ' &
                            //trim(names(i))//' factor', '3D25.17', .true., factor(i), error)
            if (allocated(error)) return
            if (.not. (factor(i) > 0.0_dp)) then
                call fatal_error(error, record_prefix(path, line, 164, 2)//'expected the '//trim(names(i)) &
                                 //' factor to SI > 0 (columns '//int_text(25*i - 24)//'-'//int_text(25*i) &
                                 //', 3D25.17: the file''s value / factor = SI), found '//sci_text(factor(i)))
                return
            end if
        end do
        units%length_factor = factor(1)
        units%force_factor = factor(2)
    end subroutine read_units

    !> The unit system of a file: its datasets 164 (`sets` and `lines` of the whole file); SI
    !> when there is none. Two datasets 164 that disagree on a factor are refused (which would
    !> hold for the data between them is not said), naming both lines.
    subroutine file_units(path, lines, sets, units, error)
        !> File the lines come from (for messages).
        character(len=*), intent(in) :: path
        !> The file's lines.
        type(text_line), intent(in) :: lines(:)
        !> The file's datasets.
        type(dataset_extent), intent(in) :: sets(:)
        !> Its unit system.
        type(uff_units), intent(out) :: units
        !> Set (status 2) for a malformed dataset 164 or two that disagree.
        type(error_type), allocatable, intent(out) :: error

        type(uff_units) :: other
        logical :: found
        integer :: i

        found = .false.
        do i = 1, size(sets)
            if (sets(i)%number /= 164) cycle
            if (.not. found) then
                call read_units(path, lines, sets(i), units, error)
                found = .true.
                if (allocated(error)) return
                cycle
            end if
            call read_units(path, lines, sets(i), other, error)
            if (allocated(error)) return
            if (other%length_factor /= units%length_factor .or. other%force_factor /= units%force_factor) then
                call fatal_error(error, record_prefix(path, other%line + 3, 164, 2)//'expected the units of the ' &
                                 //'dataset 164 at line '//int_text(units%line)//' (length factor ' &
                                 //sci_text(units%length_factor)//', force factor '//sci_text(units%force_factor) &
                                 //'), found length factor '//sci_text(other%length_factor)//', force factor ' &
                                 //sci_text(other%force_factor)//': give the file one unit system')
                return
            end if
        end do
    end subroutine file_units

    !> Whether lengths and forces are SI already.
    pure logical function is_si(self)
        !> The unit system.
        class(uff_units), intent(in) :: self

        is_si = self%length_factor == 1.0_dp .and. self%force_factor == 1.0_dp
    end function is_si

    !> m_SI/m_file for a mass (force/acceleration, time in seconds): length_factor/force_factor.
    pure real(dp) function mass_factor(self)
        !> The unit system.
        class(uff_units), intent(in) :: self

        mass_factor = self%length_factor/self%force_factor
    end function mass_factor

    !> The unit system in words, for messages.
    subroutine describe(self, text)
        !> The unit system.
        class(uff_units), intent(in) :: self
        !> `dataset 164 at line 1 (code 10, mm (newton): length factor 1.000E+03, force factor 1.000E+00)`.
        character(len=:), allocatable, intent(out) :: text

        text = 'dataset 164 at line '//int_text(self%line)//' (code '//int_text(self%code)//', ' &
               //trim(self%description)//': length factor '//sci_text(self%length_factor)//', force factor ' &
               //sci_text(self%force_factor)//')'
    end subroutine describe

end module greenconv_io_uff_units
