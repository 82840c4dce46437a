!> Sorting: `heap_sort`, `median` and `sort_order` against an independent insertion sort on
!> random vectors with many equal values and signed zeros (the heap sort places equal values
!> in its own order, so the values are compared, not their bits).
module test_sorting_mod
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check
    use greenconv_core_kinds, only: dp
    use greenconv_core_sorting, only: heap_sort, median, sort_order
    use greenconv_core_text, only: int_text
    implicit none
    private

    public :: collect_sorting

    !> Vectors tried by each test.
    integer, parameter :: n_trials = 400

contains

    !> Tests of greenconv_core_sorting.
    subroutine collect_sorting(testsuite)
        !> The suite's tests.
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('heap_sort gives the insertion sort''s values, ties and signed zeros', test_heap), &
                     new_unittest('median is the middle of the insertion-sorted values', test_median), &
                     new_unittest('sort_order is a permutation that sorts the integer keys', test_order)]
    end subroutine collect_sorting

    subroutine test_heap(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), allocatable :: a(:), b(:)
        integer :: trial

        do trial = 1, n_trials
            call values(trial, a)
            b = insertion_sorted(a)
            call heap_sort(a)
            call check(error, all(a == b), 'trial '//int_text(trial)//': heap_sort differs from the insertion sort')
            if (allocated(error)) return
        end do
    end subroutine test_heap

    subroutine test_median(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), allocatable :: a(:), b(:)
        real(dp) :: expected
        integer :: trial, n

        do trial = 1, n_trials
            call values(trial, a)
            if (size(a) == 0) cycle
            b = insertion_sorted(a)
            n = size(b)
            if (mod(n, 2) == 1) then
                expected = b((n + 1)/2)
            else
                expected = 0.5_dp*(b(n/2) + b(n/2 + 1))
            end if
            call check(error, median(a) == expected, 'trial '//int_text(trial)//': median differs')
            if (allocated(error)) return
        end do
    end subroutine test_median

    subroutine test_order(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), allocatable :: a(:)
        integer, allocatable :: keys(:), order(:), seen(:)
        integer :: trial, i

        do trial = 1, n_trials
            call values(trial, a)
            keys = nint(a*1.0e3_dp)
            order = sort_order(keys)
            allocate (seen(size(keys)), source=0)
            do i = 1, size(order)
                if (order(i) >= 1 .and. order(i) <= size(keys)) seen(order(i)) = seen(order(i)) + 1
            end do
            call check(error, all(seen == 1), 'trial '//int_text(trial)//': sort_order is not a permutation')
            if (.not. allocated(error)) &
                call check(error, all(keys(order) == nint(insertion_sorted(real(keys, dp)))), &
                           'trial '//int_text(trial)//': keys(sort_order(keys)) is not ascending')
            if (allocated(error)) return
            deallocate (seen)
        end do
    end subroutine test_order

    !> Trial `trial`'s vector: 0 to 60 values, in turn all distinct, from seven levels, or with
    !> signed zeros among them.
    subroutine values(trial, a)
        integer, intent(in) :: trial
        real(dp), allocatable, intent(out) :: a(:)

        integer :: i

        allocate (a(mod(trial*7, 61)))
        call random_number(a)
        select case (mod(trial, 3))
        case (1)
            a = anint(7.0_dp*a) - 3.0_dp
        case (2)
            a = anint(3.0_dp*a) - 1.0_dp
            do i = 1, size(a), 4
                a(i) = -0.0_dp
            end do
        end select
    end subroutine values

    !> The values in ascending order by insertion.
    pure function insertion_sorted(a) result(b)
        real(dp), intent(in) :: a(:)
        real(dp) :: b(size(a))

        real(dp) :: t
        integer :: i, j

        b = a
        do i = 2, size(b)
            t = b(i)
            j = i - 1
            do while (j >= 1)
                if (.not. (b(j) > t)) exit
                b(j + 1) = b(j)
                j = j - 1
            end do
            b(j + 1) = t
        end do
    end function insertion_sorted

end module test_sorting_mod
