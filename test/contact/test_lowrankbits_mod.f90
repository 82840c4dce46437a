!> The products by the low-rank factors of W0 (greenconv_contact_lowrank_solve's
!> `apply_compliance`: z = V^T*x, then y = U*z, each entry an ordered sum vectorised over the
!> entries) against plain loops written here in the order the module documents: each z_k and
!> y_i summed from zero in the order of the points (for z) and of the factors' columns (for
!> y). Tolerance 0 (bit for bit): the vectorised products must keep each sum's order, which is
!> what lets the driver's outputs stay byte-identical. Shapes whose column counts are not
!> multiples of four (the products take four columns a pass) and a single column are included,
!> and a point count not a multiple of the row blocks. A second check, with a tolerance: U*V^T
!> equals W0 to 1e-13 of max|W0| (the elimination stops at 1e-14), so the factors compared
!> are those of a real elimination.
module test_lowrankbits_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check
    use greenconv_core_random, only: random_stream
    use greenconv_contact_lowrank_solve, only: lowrank_compliance, factor_compliance, apply_compliance
    implicit none
    private

    public :: collect_lowrankbits

contains

    !> Tests of the low-rank products' bits.
    subroutine collect_lowrankbits(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('W0*x by the factors, rank 23 of 301 points: bit for bit plain loops', test_rank_23), &
                     new_unittest('W0*x by the factors, rank 8 of 640 points: bit for bit plain loops', test_rank_8), &
                     new_unittest('W0*x by the factors, rank 1 of 7 points: bit for bit plain loops', test_rank_1)]
    end subroutine collect_lowrankbits

    subroutine test_rank_23(error)
        type(test_error), allocatable, intent(out) :: error

        call product_case(301, 23, 11_8, error)
    end subroutine test_rank_23

    subroutine test_rank_8(error)
        type(test_error), allocatable, intent(out) :: error

        call product_case(640, 8, 12_8, error)
    end subroutine test_rank_8

    subroutine test_rank_1(error)
        type(test_error), allocatable, intent(out) :: error

        call product_case(7, 1, 13_8, error)
    end subroutine test_rank_1

    !> W0 = A*diag(w)*A^T of rank `rank` on `n_c` points (random A, w > 0, as a modal W0),
    !> factored; W0*x of random loads by `apply_compliance` against plain loops on the factors.
    subroutine product_case(n_c, rank, seed, error)
        integer, intent(in) :: n_c, rank
        integer(8), intent(in) :: seed
        type(test_error), allocatable, intent(out) :: error

        type(random_stream) :: stream
        type(lowrank_compliance) :: compliance
        real(dp), allocatable :: weight0(:, :)
        real(dp) :: a(n_c, rank), w(rank), x(n_c), z(rank), expected(n_c), found(n_c)
        real(dp) :: largest
        integer :: i, j, k, trial

        stream = random_stream(seed)
        do k = 1, rank
            w(k) = stream%between(0.5_dp, 2.0_dp)*1.0e-6_dp
            do i = 1, n_c
                a(i, k) = stream%between(-1.0_dp, 1.0_dp)
            end do
        end do
        allocate (weight0(n_c, n_c))
        do j = 1, n_c
            do i = 1, n_c
                weight0(i, j) = sum(a(i, :)*w*a(j, :))
            end do
        end do
        call factor_compliance(weight0, compliance)
        call check(error, compliance%low_rank .and. compliance%rank == rank, 'factored at rank '// &
                   trim(text(compliance%rank))//', expected '//trim(text(rank)))
        if (allocated(error)) return
        largest = maxval(abs(weight0 - matmul(compliance%left, transpose(compliance%right))))
        call check(error, largest <= 1.0e-13_dp*maxval(abs(weight0)), 'max|W0 - U V^T| too large')
        if (allocated(error)) return
        do trial = 1, 3
            do i = 1, n_c
                x(i) = stream%between(-1.0e3_dp, 1.0e3_dp)
            end do
            do k = 1, rank
                z(k) = 0.0_dp
                do i = 1, n_c
                    z(k) = z(k) + compliance%right(i, k)*x(i)
                end do
            end do
            do i = 1, n_c
                expected(i) = 0.0_dp
                do k = 1, rank
                    expected(i) = expected(i) + compliance%left(i, k)*z(k)
                end do
            end do
            found = apply_compliance(compliance, weight0, x)
            call check(error, all(found == expected), 'W0*x differs from the plain loops by up to '// &
                       trim(text_real(maxval(abs(found - expected))))//' m')
            if (allocated(error)) return
        end do
    end subroutine product_case

    function text(n) result(s)
        integer, intent(in) :: n
        character(len=12) :: s

        write (s, '(i0)') n
    end function text

    function text_real(x) result(s)
        real(dp), intent(in) :: x
        character(len=24) :: s

        write (s, '(es10.3)') x
    end function text_real

end module test_lowrankbits_mod
