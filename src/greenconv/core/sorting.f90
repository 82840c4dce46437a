!> Sorting of real vectors: an in-place ascending heap sort (O(n log n) whatever the order of
!> the input, no work array) and the median that rests on it. Used by the identification's
!> noise estimate and outlier screening; generic over any real(dp) data. `sort_order` gives
!> the order that sorts integer keys (node labels), by the same heap sort on indices.
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

    !> Ascending heap sort in place.
    pure subroutine heap_sort(a)
        !> The values, sorted ascending on return (any units).
        real(dp), intent(inout) :: a(:)

        integer :: n, i, last
        real(dp) :: t

        n = size(a)
        do i = n/2, 1, -1
            call sift(a, i, n)
        end do
        do last = n, 2, -1
            t = a(1)
            a(1) = a(last)
            a(last) = t
            call sift(a, 1, last - 1)
        end do
    end subroutine heap_sort

    !> Move a(start) down the heap a(1:n) until both its children are no larger.
    pure subroutine sift(a, start, n)
        real(dp), intent(inout) :: a(:)
        integer, intent(in) :: start, n

        integer :: root, child
        real(dp) :: t

        root = start
        do while (2*root <= n)
            child = 2*root
            if (child < n) then
                if (a(child + 1) > a(child)) child = child + 1
            end if
            if (a(root) >= a(child)) return
            t = a(root)
            a(root) = a(child)
            a(child) = t
            root = child
        end do
    end subroutine sift

    !> The permutation that sorts integer keys ascending: keys(order) is ascending (equal keys
    !> in any order). O(n log n).
    pure function sort_order(keys) result(order)
        !> The keys (e.g. node labels).
        integer, intent(in) :: keys(:)
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

        !> Move order(start) down the heap order(1:m) of keys.
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
    end function sort_order

end module greenconv_core_sorting
