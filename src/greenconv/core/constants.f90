!> Mathematical constants shared by the layers above, each written once.
module greenconv_core_constants
    use greenconv_core_kinds, only: dp
    implicit none
    private

    !> pi, correctly rounded to double precision.
    real(dp), parameter, public :: pi = 3.141592653589793238462643383279_dp
    !> 2*pi [rad per cycle], for omega = 2*pi*f (exact: doubling is exact in binary).
    real(dp), parameter, public :: two_pi = 2.0_dp*pi
    !> The imaginary unit i.
    complex(dp), parameter, public :: i_unit = (0.0_dp, 1.0_dp)

end module greenconv_core_constants
