!> A small, portable pseudo-random generator, so that a scene's seed gives the same road
!> and the same modes with every compiler (the intrinsic `random_number` does not).
!>
!> SplitMix64 (G. Steele, D. Lea, C. Flood, "Fast splittable pseudorandom number
!> generators", OOPSLA 2014): a 64-bit state advanced by a fixed odd increment and mixed
!> by two multiply-xorshift rounds. Arithmetic wraps modulo 2^64 (two's complement).
module greenconv_core_random
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    implicit none
    private

    public :: random_stream

    !> Golden-ratio increment 0x9E3779B97F4A7C15 as a signed 64-bit integer.
    integer(int64), parameter :: increment = -7046029254386353131_int64
    !> First mixing multiplier 0xBF58476D1CE4E5B9.
    integer(int64), parameter :: mix1 = -4658895280553007687_int64
    !> Second mixing multiplier 0x94D049BB133111EB.
    integer(int64), parameter :: mix2 = -7723592293110705685_int64

    !> A stream of pseudo-random numbers from a seed.
    type :: random_stream
        !> Generator state.
        integer(int64) :: state = 0_int64
    contains
        !> Next uniform number in [0, 1).
        procedure :: uniform
        !> Next uniform number in [low, high).
        procedure :: between
    end type random_stream

    !> `random_stream(seed)`: a new stream started from an integer seed.
    interface random_stream
        module procedure new_stream
    end interface random_stream

contains

    !> A stream started from `seed`.
    pure function new_stream(seed) result(stream)
        !> Any integer; equal seeds give equal streams.
        integer, intent(in) :: seed
        type(random_stream) :: stream

        stream%state = int(seed, int64)
    end function new_stream

    !> Next 64-bit output of SplitMix64.
    integer(int64) function next_bits(self)
        class(random_stream), intent(inout) :: self

        integer(int64) :: z

        self%state = wrapping_add(self%state, increment)
        z = self%state
        z = wrapping_mul(ieor(z, shiftr(z, 30)), mix1)
        z = wrapping_mul(ieor(z, shiftr(z, 27)), mix2)
        next_bits = ieor(z, shiftr(z, 31))
    end function next_bits

    !> Next uniform number in [0, 1), from the top 53 bits.
    real(dp) function uniform(self)
        !> The stream.
        class(random_stream), intent(inout) :: self

        uniform = real(shiftr(next_bits(self), 11), dp)*2.0_dp**(-53)
    end function uniform

    !> Next uniform number in [low, high).
    real(dp) function between(self, low, high)
        !> The stream.
        class(random_stream), intent(inout) :: self
        !> Lower bound.
        real(dp), intent(in) :: low
        !> Upper bound.
        real(dp), intent(in) :: high

        between = low + (high - low)*self%uniform()
    end function between

    !> a + b modulo 2^64, without signed overflow: the sum of the two 32-bit halves.
    pure integer(int64) function wrapping_add(a, b)
        integer(int64), intent(in) :: a, b

        integer(int64), parameter :: low_mask = 4294967295_int64
        integer(int64) :: low, high

        low = iand(a, low_mask) + iand(b, low_mask)
        high = shiftr(a, 32) + shiftr(b, 32) + shiftr(low, 32)
        wrapping_add = ior(shiftl(high, 32), iand(low, low_mask))
    end function wrapping_add

    !> a*b modulo 2^64, without signed overflow: schoolbook product of 32-bit halves.
    pure integer(int64) function wrapping_mul(a, b)
        integer(int64), intent(in) :: a, b

        integer(int64), parameter :: low_mask = 4294967295_int64
        integer(int64) :: a_low, a_high, b_low, b_high, low_product, cross

        a_low = iand(a, low_mask)
        a_high = shiftr(a, 32)
        b_low = iand(b, low_mask)
        b_high = shiftr(b, 32)
        low_product = product_low(a_low, b_low)
        cross = iand(wrapping_add(product_low(a_low, b_high), product_low(a_high, b_low)), low_mask)
        wrapping_mul = wrapping_add(low_product, shiftl(cross, 32))
    end function wrapping_mul

    !> The low 64 bits of the product of two numbers below 2^32.
    pure integer(int64) function product_low(a, b)
        integer(int64), intent(in) :: a, b

        integer(int64), parameter :: mask16 = 65535_int64
        integer(int64) :: a1, a0, b1, b0, middle

        ! a = a1*2^16 + a0 (a1 < 2^16), b = b1*2^16 + b0: every partial product fits in 2^48.
        a1 = shiftr(a, 16)
        a0 = iand(a, mask16)
        b1 = shiftr(b, 16)
        b0 = iand(b, mask16)
        middle = a1*b0 + a0*b1
        product_low = wrapping_add(wrapping_add(shiftl(a1*b1, 32), shiftl(middle, 16)), a0*b0)
    end function product_low

end module greenconv_core_random
