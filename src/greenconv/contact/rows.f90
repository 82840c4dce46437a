!> The histories of a contact run cut to the steps done: a fault stops a run, single- or
!> multi-point alike, and the response keeps its first n rows (steps 0..n-1), the lower
!> bound 0 kept.
module greenconv_contact_rows
    use greenconv_core_kinds, only: dp
    implicit none
    private

    public :: keep_first, keep_all

    !> values(0:n-1) (a history per step) or values(0:n-1, :) (per step and point), reallocated
    !> only when it is not that already; an unallocated history gets n = 0 rows.
    interface keep_first
        module procedure keep_first_real, keep_first_table, keep_first_count
    end interface keep_first

    !> The first n rows of several histories of one response at once, all per step or all
    !> per step and point (those absent skipped).
    interface keep_all
        module procedure keep_all_real, keep_all_table
    end interface keep_all

contains

    !> keep_first on up to four histories per step.
    subroutine keep_all_real(n, first, second, third, fourth)
        !> Rows to keep, >= 0.
        integer, intent(in) :: n
        !> A history per step [any unit].
        real(dp), allocatable, intent(inout) :: first(:)
        !> More histories per step, or absent.
        real(dp), allocatable, intent(inout), optional :: second(:), third(:), fourth(:)

        call keep_first(first, n)
        if (present(second)) call keep_first(second, n)
        if (present(third)) call keep_first(third, n)
        if (present(fourth)) call keep_first(fourth, n)
    end subroutine keep_all_real

    !> keep_first on up to four histories per step and point.
    subroutine keep_all_table(n, first, second, third, fourth)
        !> Rows to keep, >= 0.
        integer, intent(in) :: n
        !> A history per step and point [any unit].
        real(dp), allocatable, intent(inout) :: first(:, :)
        !> More histories per step and point, or absent.
        real(dp), allocatable, intent(inout), optional :: second(:, :), third(:, :), fourth(:, :)

        call keep_first(first, n)
        if (present(second)) call keep_first(second, n)
        if (present(third)) call keep_first(third, n)
        if (present(fourth)) call keep_first(fourth, n)
    end subroutine keep_all_table

    !> The first n values of a real history [any unit].
    subroutine keep_first_real(values, n)
        !> The history, indexed from 0.
        real(dp), allocatable, intent(inout) :: values(:)
        !> Rows to keep, >= 0 (at most those held).
        integer, intent(in) :: n

        real(dp), allocatable :: kept(:)

        if (allocated(values)) then
            if (size(values) == n) return
        end if
        allocate (kept(0:n - 1))
        if (n > 0) kept(:) = values(0:n - 1)
        call move_alloc(kept, values)
    end subroutine keep_first_real

    !> The first n rows of a history per step and point [any unit].
    subroutine keep_first_table(values, n)
        !> The history, rows indexed from 0.
        real(dp), allocatable, intent(inout) :: values(:, :)
        !> Rows to keep, >= 0 (at most those held).
        integer, intent(in) :: n

        real(dp), allocatable :: kept(:, :)
        integer :: columns

        columns = 0
        if (allocated(values)) then
            if (size(values, 1) == n) return
            columns = size(values, 2)
        end if
        allocate (kept(0:n - 1, columns))
        if (n > 0) kept(:, :) = values(0:n - 1, :)
        call move_alloc(kept, values)
    end subroutine keep_first_table

    !> The first n values of a count per step (iterations).
    subroutine keep_first_count(values, n)
        !> The counts, indexed from 0.
        integer, allocatable, intent(inout) :: values(:)
        !> Rows to keep, >= 0 (at most those held).
        integer, intent(in) :: n

        integer :: kept(0:n - 1)

        if (n > 0) kept(:) = values(0:n - 1)
        if (allocated(values)) deallocate (values)
        allocate (values(0:n - 1), source=kept)
    end subroutine keep_first_count

end module greenconv_contact_rows
