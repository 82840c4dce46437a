!> The dense linear algebra of the identification fits (greenconv_ident_dense, the global order search's
!> speed): the Gram matrix by upper-triangle blocks against the sums written out, on sizes
!> below, at and across the block size; the Cholesky solve and inverse against the matrix they
!> invert; a matrix that is not positive definite, or holds a NaN, reported rather than solved;
!> the fit's information with the residual carried by the caller (Levenberg-Marquardt keeps the
!> accepted step's) the same bits as computed afresh, its gradient against central differences.
module test_identdense_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_ident_dense, only: gram, dot, spd_solve, spd_inverse, identity, svd_solve, product_of, quadratic_form
    use greenconv_ext_lapack, only: least_squares
    use greenconv_core_error, only: error_type
    use greenconv_ident_lm_fit, only: model_type, data_type, information, evaluate, chi_square
    implicit none
    private

    public :: collect_identdense

contains

    !> Tests of greenconv_ident_dense.
    subroutine collect_identdense(testsuite)
        !> The suite's tests.
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('gram: scale*A^T A and scale*A^T b against the sums, 1 to 48 columns', test_gram), &
                     new_unittest('gram: the bits of the sums in row order and of dot, 4,099 rows, 1 to 37 columns', &
                                  test_gram_order), &
                     new_unittest('spd: solve and inverse against A, to round-off', test_spd), &
                     new_unittest('spd: indefinite and NaN matrices reported, not solved', test_not_spd), &
                     new_unittest('information: carried residual, same bits; gradient by differences', test_carried), &
                     new_unittest('svd_solve: against LAPACK dgelsd, full rank and rank-deficient, tall and square', &
                                  test_svd), &
                     new_unittest('product_of, quadratic_form: against the sums written out', test_products)]
    end subroutine collect_identdense

    !> svd_solve (Householder reduction, then one-sided Jacobi) against LAPACK's dgelsd through
    !> greenconv_ext_lapack's least_squares, an independent SVD: tall (301 x n) and square
    !> matrices of full rank, and with two columns repeated (rank n - 2), where both must give
    !> the minimum-norm solution. Tolerance 1e-10 relative to |x| (conditions below 1e4).
    subroutine test_svd(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: sizes(4) = [1, 6, 17, 40]
        real(dp), allocatable :: a(:, :), b(:), x(:), y(:)
        type(error_type), allocatable :: failure
        real(dp) :: worst
        integer :: s, n, m, l, shape_kind

        worst = 0.0_dp
        do shape_kind = 1, 3
            do s = 1, size(sizes)
                n = sizes(s)
                m = merge(n, 301, shape_kind == 2)
                a = sample_matrix(m, n)
                if (shape_kind == 3 .and. n >= 3) then
                    a(:, n) = a(:, 1)
                    a(:, n - 1) = 2.0_dp*a(:, 2)
                end if
                b = [(cos(0.3_dp*l) + 0.2_dp*sin(1.1_dp*l*l), l=1, m)]
                if (allocated(x)) deallocate (x, y)
                allocate (x(n), y(n))
                call svd_solve(a, b, x, 1.0e-13_dp)
                call least_squares(a, b, y, failure, rcond=1.0e-13_dp)
                call check(error, .not. allocated(failure), 'dgelsd failed')
                if (allocated(error)) return
                worst = max(worst, maxval(abs(x - y))/max(maxval(abs(y)), tiny(1.0_dp)))
            end do
        end do
        call note('svd_solve: worst |x - x_dgelsd|/|x_dgelsd|', worst)
        call check(error, worst < 1.0e-10_dp, 'svd_solve differs from dgelsd by more than 1e-10')
    end subroutine test_svd

    !> product_of and quadratic_form against the sums written out in the same order as a
    !> reference loop, to 1e-14 of the sums' magnitude.
    subroutine test_products(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), allocatable :: a(:, :), b(:, :), c(:, :), x(:)
        real(dp) :: worst, reference, magnitude
        integer :: i, j, k

        a = sample_matrix(7, 13)
        b = transpose(sample_matrix(9, 13))
        c = product_of(a, b)
        worst = 0.0_dp
        do j = 1, size(b, 2)
            do i = 1, size(a, 1)
                reference = 0.0_dp
                magnitude = 0.0_dp
                do k = 1, size(a, 2)
                    reference = reference + a(i, k)*b(k, j)
                    magnitude = magnitude + abs(a(i, k)*b(k, j))
                end do
                worst = max(worst, abs(c(i, j) - reference)/magnitude)
            end do
        end do
        x = [(0.1_dp*k - 0.5_dp, k=1, 13)]
        a = sample_matrix(13, 13)
        reference = 0.0_dp
        magnitude = 0.0_dp
        do j = 1, 13
            do i = 1, 13
                reference = reference + x(i)*a(i, j)*x(j)
                magnitude = magnitude + abs(x(i)*a(i, j)*x(j))
            end do
        end do
        worst = max(worst, abs(quadratic_form(a, x) - reference)/magnitude)
        call note('product_of, quadratic_form: worst relative error', worst)
        call check(error, worst < 1.0e-14_dp, 'product_of or quadratic_form differs from the written-out sums')
    end subroutine test_products

    !> A deterministic m x n matrix with entries in (-1, 1) of no pattern the blocks could share.
    pure function sample_matrix(m, n) result(a)
        integer, intent(in) :: m, n
        real(dp) :: a(m, n)

        integer :: i, j

        do j = 1, n
            do i = 1, m
                a(i, j) = sin(1.7_dp*i + 0.37_dp*j*j) + 0.1_dp*cos(3.1_dp*i*j)
            end do
        end do
    end function sample_matrix

    subroutine test_gram(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: sizes(6) = [1, 5, 16, 17, 33, 48]
        real(dp), allocatable :: a(:, :), b(:), product(:, :), projection(:)
        real(dp) :: worst, sum_ij
        integer :: s, n, i, j, l

        worst = 0.0_dp
        do s = 1, size(sizes)
            n = sizes(s)
            a = sample_matrix(301, n)
            b = [(cos(0.3_dp*l), l=1, 301)]
            if (allocated(product)) deallocate (product, projection)
            allocate (product(n, n), projection(n))
            call gram(a, 2.0_dp, product, b, projection)
            do j = 1, n
                do i = 1, n
                    sum_ij = 0.0_dp
                    do l = 1, size(a, 1)
                        sum_ij = sum_ij + a(l, i)*a(l, j)
                    end do
                    worst = max(worst, abs(product(i, j) - 2.0_dp*sum_ij)/(2.0_dp*size(a, 1)))
                end do
                worst = max(worst, abs(projection(j) - 2.0_dp*dot_product(a(:, j), b))/(2.0_dp*size(a, 1)))
            end do
        end do
        call note('gram: worst |error|/(2 m)', worst)
        call check(error, worst < 1.0e-14_dp, 'A^T A and A^T b to round-off on every size')
    end subroutine test_gram

    !> The kernel takes the rows in chunks and the columns in blocks of 4, 8 or 16 (by the CPU):
    !> each element must still be the sum over the rows in order from 0, bit for bit, and A^T b
    !> the bits of `dot`. 4,099 rows: three chunks, the last partial, and a tail after the
    !> last multiple of four; widths across every block edge.
    subroutine test_gram_order(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: sizes(7) = [1, 3, 8, 9, 16, 17, 37]
        real(dp), allocatable :: a(:, :), b(:), product(:, :), projection(:)
        real(dp) :: sum_ij
        integer :: s, n, i, j, l, differ

        differ = 0
        do s = 1, size(sizes)
            n = sizes(s)
            a = sample_matrix(4099, n)
            ! Magnitudes over 24 decades: a sum in another order would round otherwise.
            do j = 1, n
                a(:, j) = a(:, j)*[(10.0_dp**(mod(7*l + j, 25) - 12), l=1, 4099)]
            end do
            b = [(cos(0.3_dp*l)*10.0_dp**mod(l, 9), l=1, 4099)]
            if (allocated(product)) deallocate (product, projection)
            allocate (product(n, n), projection(n))
            call gram(a, 2.0_dp, product, b, projection)
            do j = 1, n
                do i = 1, j
                    sum_ij = 0.0_dp
                    do l = 1, size(a, 1)
                        sum_ij = sum_ij + a(l, i)*a(l, j)
                    end do
                    if (product(i, j) /= 2.0_dp*sum_ij .or. product(j, i) /= product(i, j)) differ = differ + 1
                end do
                if (projection(j) /= 2.0_dp*dot(a(:, j), b)) differ = differ + 1
            end do
        end do
        call note('gram: elements not bit for bit the in-order sums', real(differ, dp))
        call check(error, differ == 0, 'every element of A^T A the sum in row order, A^T b the bits of dot')
    end subroutine test_gram_order

    subroutine test_spd(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n = 40
        real(dp) :: a(n, n), inverse(n, n), b(n), residual, off_identity
        real(dp), allocatable :: x(:), unused(:)
        logical :: ok
        integer :: i

        ! A = B^T B + I, condition about 1e3: positive definite.
        allocate (unused(n))
        call gram(sample_matrix(60, n), 1.0_dp, a, [(0.0_dp, i=1, 60)], unused)
        do i = 1, n
            a(i, i) = a(i, i) + 1.0_dp
        end do
        b = [(real(i, dp), i=1, n)]
        call spd_solve(a, b, x, ok)
        call check(error, ok, 'A = B^T B + I is positive definite')
        if (allocated(error)) return
        residual = maxval(abs(matmul(a, x) - b))/maxval(abs(b))
        inverse = a
        call spd_inverse(inverse, ok)
        call check(error, ok, 'its inverse exists')
        if (allocated(error)) return
        off_identity = maxval(abs(matmul(inverse, a) - identity(n)))
        call note('spd_solve: max|A x - b|/max|b|', residual)
        call note('spd_inverse: max|inv(A) A - I|', off_identity)
        call check(error, residual < 1.0e-12_dp, 'A x = b to round-off')
        if (allocated(error)) return
        call check(error, off_identity < 1.0e-11_dp, 'inv(A) A = I to round-off')
        if (allocated(error)) return
        call check(error, maxval(abs(inverse - transpose(inverse))) == 0.0_dp, 'both triangles of the inverse')
    end subroutine test_spd

    subroutine test_not_spd(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp) :: a(3, 3)
        real(dp), allocatable :: x(:)
        logical :: ok

        a = reshape([2.0_dp, 3.0_dp, 0.0_dp, 3.0_dp, 2.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [3, 3])
        call spd_solve(a, [1.0_dp, 1.0_dp, 1.0_dp], x, ok)
        call check(error, .not. ok, 'an indefinite matrix (eigenvalues 5, -1, 1) is reported')
        if (allocated(error)) return
        call spd_inverse(a, ok)
        call check(error, .not. ok, 'and has no inverse here')
        if (allocated(error)) return
        a = identity(3)
        a(2, 2) = ieee_value(1.0_dp, ieee_quiet_nan)
        call spd_solve(a, [1.0_dp, 1.0_dp, 1.0_dp], x, ok)
        call check(error, .not. ok, 'a NaN pivot is reported')
    end subroutine test_not_spd

    !> Two modes and both residual terms on 400 lines to 50 Hz, the data a perturbed model's
    !> receptance: the information with the residual given equals that computed afresh, bit for
    !> bit, and its gradient of -chi2/2 matches central differences of chi_square (relative step
    !> 1e-6: the differences of chi2 lose about seven digits to cancellation, 2e-7 found).
    subroutine test_carried(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: two_pi = 2.0_dp*3.141592653589793_dp
        type(model_type) :: model, moved
        type(data_type) :: data
        real(dp), allocatable :: fisher(:, :), gradient(:), fisher_given(:, :), gradient_given(:), jac(:, :)
        real(dp) :: h, worst, difference
        integer :: l, k

        data%omega = [(two_pi*0.125_dp*l, l=1, 400)]
        data%weight = [(1.0e4_dp*(1.0_dp + 0.3_dp*sin(0.1_dp*l)), l=1, 400)]
        model%pole = [cmplx(-0.02_dp*two_pi*12.0_dp, two_pi*12.0_dp, dp), cmplx(-0.05_dp*two_pi*31.0_dp, two_pi*31.0_dp, dp)]
        model%residue = [cmplx(1.0e-4_dp, -2.0e-3_dp, dp), cmplx(-3.0e-4_dp, 1.5e-3_dp, dp)]
        model%upper = .true.
        model%lower = .true.
        model%r_u = 2.0e-6_dp
        model%r_l = 1.0e-3_dp
        moved = model
        moved%pole = moved%pole*cmplx(1.001_dp, 0.0005_dp, dp)
        moved%residue = moved%residue*1.01_dp
        data%g = evaluate(moved, data%omega)
        call information(data, model, fisher, gradient, jac)
        call information(data, model, fisher_given, gradient_given, jac, &
                         data%weight*(data%g - evaluate(model, data%omega)))
        call check(error, all(fisher_given == fisher) .and. all(gradient_given == gradient), &
                   'the information from a given residual is the same bits')
        if (allocated(error)) return
        ! d(-chi2/2)/d(Re lambda_k), d(-chi2/2)/d(Im r_k) by central differences.
        worst = 0.0_dp
        do k = 1, 2
            h = 1.0e-6_dp*abs(model%pole(k))
            moved = model
            moved%pole(k) = model%pole(k) + h
            difference = -chi_square(data, moved)
            moved%pole(k) = model%pole(k) - h
            difference = (difference + chi_square(data, moved))/(4.0_dp*h)
            worst = max(worst, abs(difference - gradient(4*k - 3))/abs(gradient(4*k - 3)))
            h = 1.0e-6_dp*abs(model%residue(k))
            moved = model
            moved%residue(k) = model%residue(k) + cmplx(0.0_dp, h, dp)
            difference = -chi_square(data, moved)
            moved%residue(k) = model%residue(k) - cmplx(0.0_dp, h, dp)
            difference = (difference + chi_square(data, moved))/(4.0_dp*h)
            worst = max(worst, abs(difference - gradient(4*k))/abs(gradient(4*k)))
        end do
        call note('information: worst relative gradient error against central differences', worst)
        call check(error, worst < 1.0e-6_dp, 'the gradient of -chi2/2 to 1e-6 of central differences')
    end subroutine test_carried

end module test_identdense_mod
