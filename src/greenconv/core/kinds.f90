!> Real kind used throughout greenconv.
module greenconv_core_kinds
    use, intrinsic :: iso_fortran_env, only: real64
    implicit none
    private

    public :: dp

    !> Double precision (IEEE binary64), the only real kind greenconv computes in.
    integer, parameter :: dp = real64

end module greenconv_core_kinds
