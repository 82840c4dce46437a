!> Sorting of real vectors: an in-place ascending heap sort (O(n log n) whatever the order of
!> the input, with a work array of n indices) and the median that rests on it. Used by the identification's
!> noise estimate and outlier screening; generic over any real(dp) data. `sort_order` gives
!> the order that sorts integer keys (node labels). Both are one heap sort on indices.
module greenconv_core_sorting
    use greenconv_core_kinds, only: dp
    implicit none
    private

    public :: heap_sort, median, sort_order

contains

    !> Median of a vector (the mean of the two middle values of a sorted copy when the size
    !> is even), in the units of x.
    pure real(dp) function median(x)
        !> The values (at least one).
        real(dp), intent(in) :: x(:)

        real(dp) :: s(size(x))
        integer :: n

        s = x
        call heap_sort(s)
        n = size(s)
        median = 0.5_dp*(s((n + 1)/2) + s(n/2 + 1))
    end function median

    !> Ascending heap sort in place: the values moved by the permutation `order_by` finds, so
    !> each one lands where the heap sort of the values themselves puts it.
    pure subroutine heap_sort(a)
        !> The values, sorted ascending on return (any units).
        real(dp), intent(inout) :: a(:)

        a(:) = a(order_by(a))
    end subroutine heap_sort

    !> The permutation that sorts integer keys ascending: keys(order) is ascending (equal keys
    !> in any order). O(n log n).
    pure function sort_order(keys) result(order)
        !> The keys (e.g. node labels).
        integer, intent(in) :: keys(:)
        integer :: order(size(keys))

        ! Every default integer is a double exactly, so the comparisons are those of the integers.
        order = order_by(real(keys, dp))
    end function sort_order

    !> The heap sort on indices: keys(order) is ascending, the order of equal keys that of the
    !> heap sort. O(n log n), no work array but the order.
    pure function order_by(keys) result(order)
        !> The keys (any units).
        real(dp), intent(in) :: keys(:)
        integer :: order(size(keys))

        integer :: n, i, last, t

        n = size(keys)
        order = [(i, i=1, n)]
        do i = n/2, 1, -1
            call sift_order(i, n)
        end do
        do last = n, 2, -1
            t = order(1)
            order(1) = order(last)
            order(last) = t
            call sift_order(1, last - 1)
        end do

    contains

        !> Move order(start) down the heap order(1:m) of keys until both its children are no larger.
        pure subroutine sift_order(start, m)
            !> Position to sift down from, and the heap's size.
            integer, intent(in) :: start, m

            integer :: root, child, swap

            root = start
            do while (2*root <= m)
                child = 2*root
                if (child < m) then
                    if (keys(order(child + 1)) > keys(order(child))) child = child + 1
                end if
                if (keys(order(root)) >= keys(order(child))) return
                swap = order(root)
                order(root) = order(child)
                order(child) = swap
                root = child
            end do
        end subroutine sift_order
    end function order_by

end module greenconv_core_sorting
