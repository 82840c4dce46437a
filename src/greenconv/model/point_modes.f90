!> Modes shared by the N_c points of a contact patch, the modal description of a Green's
!> matrix:
!>
!>     g_ij(t) = sum_k phi_ik*phi_jk*h_k(t),   h_k(t) = 2*Re(r_k*exp(lambda_k*t)),
!>
!> h_k the unit modal impulse response in pole-residue form (greenconv_model_modal_set); for
!> a mode of unit modal mass, r_k = 1/(2i*omega_k^d) [1/(kg*s)] and phi_ik is in 1/sqrt(kg).
!>
!> **Separable shapes.** When every mode shape is a product of a function of x and a function
!> of y (a plate's c_m*cos(k_m*x)*sin(q_n*y)) and the points sit on the cells of a grid of
!> n_col distinct x (columns) by n_row distinct y (rows), the description may also carry the
!> factors (`separable_shapes`): phi_ik = X_f(k)(x_col(i))*Y_n(k)(y_row(i)), N_x functions of x
!> at the columns and N_y functions of y at the rows. The two products a modal convolver needs
!> each step then cost O(n_col*(N_m + n_row*N_y)) instead of O(N_c*N_m):
!>
!>     u_i = sum_k phi_ik*a_k:   B(c, n) = sum_{k: n(k) = n} X_f(k)(c)*a_k,
!>                               u_i = sum_n B(col(i), n)*Y_n(row(i)),
!>     Q_k = sum_i phi_ik*q_i:   H(c, n) = sum_{i in column c} q_i*Y_n(row(i)),
!>                               Q_k = sum_c X_f(k)(c)*H(c, n(k)),
!>
!> every sum taken in a fixed order, so that the result does not depend on the threads that
!> share the columns or the modes. The dense `shape` stays the reference: its columns are the
!> products of the factors.
module greenconv_model_point_modes
    !$ use omp_lib, only: omp_get_max_threads
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: real_text
    use greenconv_model_modal_set, only: modal_set
    use, intrinsic :: iso_c_binding, only: c_int, c_double
    implicit none
    private

    interface
        !> u = Phi*a on one thread, each sum in the order of `separable_displacements`'s loops
        !> (separable_kernel.c); by_column and grid are work space.
        pure subroutine displacements_kernel(n_col, n_y, n_row, n_m, n_c, along, mode_along, mode_across, across, &
                                             amplitudes, column, row, by_column, grid, u) &
            bind(c, name='greenconv_model_separable_displacements')
            import :: c_int, c_double
            !> Columns, y functions, rows, modes and points.
            integer(c_int), value :: n_col, n_y, n_row, n_m, n_c
            !> X_f(x_c) (n_col x N_x) and Y_n(y_r) (n_row x N_y).
            real(c_double), intent(in) :: along(n_col, *), across(n_row, n_y)
            !> f(k) and n(k) of each mode (N_m), col(i) and row(i) of each point (N_c).
            integer(c_int), intent(in) :: mode_along(n_m), mode_across(n_m), column(n_c), row(n_c)
            !> Modal amplitudes a_k (N_m).
            real(c_double), intent(in) :: amplitudes(n_m)
            !> Work space: B (n_col x N_y) and the grid's displacements (n_col x n_row).
            real(c_double), intent(out) :: by_column(n_col, n_y), grid(n_col, n_row)
            !> u_i (N_c).
            real(c_double), intent(out) :: u(n_c)
        end subroutine displacements_kernel

        !> Q = Phi^T*q on one thread, each sum in the order of `modal_forces_serial`'s loops
        !> (separable_kernel.c); by_point is work space.
        pure subroutine forces_kernel(n_col, n_y, n_x, n_m, n_c, along_t, mode_along, mode_across, across_t, loads, &
                                      column, row, by_point, modal) bind(c, name='greenconv_model_separable_forces')
            import :: c_int, c_double
            !> Columns, y functions, x functions, modes and points.
            integer(c_int), value :: n_col, n_y, n_x, n_m, n_c
            !> X_f(x_c) transposed (N_x x n_col) and Y_n(y_r) transposed (N_y x n_row).
            real(c_double), intent(in) :: along_t(n_x, n_col), across_t(n_y, *)
            !> f(k) and n(k) of each mode (N_m), col(i) and row(i) of each point (N_c).
            integer(c_int), intent(in) :: mode_along(n_m), mode_across(n_m), column(n_c), row(n_c)
            !> Loads q_i (N_c).
            real(c_double), intent(in) :: loads(n_c)
            !> Work space: H transposed (N_y x n_col).
            real(c_double), intent(out) :: by_point(n_y, n_col)
            !> Q_k (N_m).
            real(c_double), intent(out) :: modal(n_m)
        end subroutine forces_kernel
    end interface

    public :: point_modes, separable_shapes, check_on_belt
    public :: separable_displacements, separable_modal_forces, separable_work

    !> Shapes of the form phi_ik = X_f(k)(x_col(i))*Y_n(k)(y_row(i)) on a grid of points.
    type :: separable_shapes
        !> Functions of x at the grid's columns, along(c, f) = X_f(x_c) [1/sqrt(kg)] (n_col x N_x).
        real(dp), allocatable :: along(:, :)
        !> Functions of y at the grid's rows, across(r, n) = Y_n(y_r) (n_row x N_y), dimensionless.
        real(dp), allocatable :: across(:, :)
        !> The function of x of each mode, f(k) in 1..N_x (N_m).
        integer, allocatable :: mode_along(:)
        !> The function of y of each mode, n(k) in 1..N_y (N_m).
        integer, allocatable :: mode_across(:)
        !> The column of each point, col(i) in 1..n_col (N_c).
        integer, allocatable :: column(:)
        !> The row of each point, row(i) in 1..n_row (N_c).
        integer, allocatable :: row(:)
    end type separable_shapes

    !> Modes shared by N_c points: g_ij(t) = sum_k phi_ik*phi_jk*2*Re(r_k*exp(lambda_k*t)).
    type :: point_modes
        !> Poles lambda_k [rad/s] and residues r_k of the modal impulse responses h_k.
        type(modal_set) :: modes
        !> Mode shapes at the points, shape(i, k) = phi_ik (N_c x N_m), in units such that
        !> phi_ik*phi_jk*r_k is in m/(N*s) (1/sqrt(kg) for unit-modal-mass modes).
        real(dp), allocatable :: shape(:, :)
        !> The same shapes as factors over a grid of points, when the model's shapes separate
        !> and the points form a grid (unallocated otherwise): shape(i, k) =
        !> along(column(i), mode_along(k))*across(row(i), mode_across(k)).
        type(separable_shapes), allocatable :: separable
    contains
        !> Number of points N_c.
        procedure :: n_points => modes_n_points
        !> Green's function g_ij(t) [m/(N*s)] between two points.
        procedure :: green => modes_green
    end type point_modes

contains

    !> Number of points N_c of a modal description.
    elemental integer function modes_n_points(self)
        !> The modal description.
        class(point_modes), intent(in) :: self

        modes_n_points = 0
        if (allocated(self%shape)) modes_n_points = size(self%shape, 1)
    end function modes_n_points

    !> g_ij(t) = sum_k phi_ik*phi_jk*2*Re(r_k*exp(lambda_k*t)) [m/(N*s)]; zero for t < 0.
    elemental real(dp) function modes_green(self, i, j, t)
        !> The modal description.
        class(point_modes), intent(in) :: self
        !> Point where the displacement is taken, 1..N_c.
        integer, intent(in) :: i
        !> Point where the impulse acts, 1..N_c.
        integer, intent(in) :: j
        !> Time [s].
        real(dp), intent(in) :: t

        modes_green = 0.0_dp
        if (t < 0.0_dp) return
        modes_green = 2.0_dp*sum(self%shape(i, :)*self%shape(j, :) &
                                 *real(self%modes%residue*exp(self%modes%pole*t), kind=dp))
    end function modes_green

    !> Multiplications of one product by the factors, n_col*(N_m + n_row*N_y): what a caller
    !> compares with N_c*N_m to choose a path or to share the work among threads.
    pure integer function separable_work(factors)
        !> The factors.
        type(separable_shapes), intent(in) :: factors

        separable_work = size(factors%along, 1)*(size(factors%mode_along) &
                                                 + size(factors%across, 1)*size(factors%across, 2))
    end function separable_work

    !> u_i = sum_k phi_ik*a_k from the factors: B(:, n) = sum_k X_f(k)*a_k over the modes of
    !> each n in the order of k, then the grid's displacements sum_n B(:, n)*Y_n(y_r) in the
    !> order of n, read at each point's cell. The y functions, then the rows, then the points
    !> are shared among threads when `threaded` (each sum is the serial one). On one thread B
    !> is made in one pass over the modes, each column B(:, n) still summed in the order of k:
    !> the same sums, without a scan of the modes for each n.
    subroutine separable_displacements(factors, amplitudes, u, threaded)
        !> The factors.
        type(separable_shapes), intent(in) :: factors
        !> Modal amplitudes a_k (N_m), in the units that make phi_ik*a_k a displacement [m].
        real(dp), intent(in) :: amplitudes(:)
        !> Displacements u_i at the points (N_c) [m].
        real(dp), intent(out) :: u(:)
        !> Whether to share the work among the threads of a parallel region.
        logical, intent(in) :: threaded

        real(dp) :: by_column(size(factors%along, 1), size(factors%across, 2)), &
                    grid(size(factors%along, 1), size(factors%across, 1))
        integer :: i, k, n, r
        logical :: spread

        spread = shared_out(threaded)
        if (.not. spread) then
            ! the amplitudes and displacements side by side for the kernel (either may be a
            ! section of the caller's array)
            block
                real(dp) :: packed(size(amplitudes)), points(size(u))

                packed(:) = amplitudes
                call displacements_kernel(size(factors%along, 1, c_int), size(factors%across, 2, c_int), &
                                          size(factors%across, 1, c_int), size(amplitudes, kind=c_int), &
                                          size(u, kind=c_int), factors%along, factors%mode_along, &
                                          factors%mode_across, factors%across, packed, factors%column, factors%row, &
                                          by_column, grid, points)
                u(:) = points
            end block
            return
        end if
        !$omp parallel default(none) shared(factors, amplitudes, u, by_column, grid) private(i, k, n, r)
        !$omp do schedule(static)
        do n = 1, size(factors%across, 2)
            by_column(:, n) = 0.0_dp
            do k = 1, size(factors%mode_along)
                if (factors%mode_across(k) == n) then
                    by_column(:, n) = by_column(:, n) + factors%along(:, factors%mode_along(k))*amplitudes(k)
                end if
            end do
        end do
        !$omp end do
        !$omp do schedule(static)
        do r = 1, size(factors%across, 1)
            grid(:, r) = 0.0_dp
            do n = 1, size(factors%across, 2)
                grid(:, r) = grid(:, r) + by_column(:, n)*factors%across(r, n)
            end do
        end do
        !$omp end do
        !$omp do schedule(static)
        do i = 1, size(u)
            u(i) = grid(factors%column(i), factors%row(i))
        end do
        !$omp end do
        !$omp end parallel
    end subroutine separable_displacements

    !> Q_k = sum_i phi_ik*q_i from the factors: H(c, n) = sum_i q_i*Y_n(y_row(i)) over the points
    !> of column c in the order of i, then Q_k = sum_c X_f(k)(x_c)*H(c, n(k)) in the order of c.
    !> The y functions, then the modes, are shared among threads when `threaded`. On one thread
    !> H is made in one pass over the points (its transpose, the N_y values of a point
    !> contiguous) and the Q_k are summed over c for all modes at once (the sums of the N_m
    !> modes side by side instead of one after the other): each sum in the same order.
    subroutine separable_modal_forces(factors, loads, modal, threaded)
        !> The factors.
        type(separable_shapes), intent(in) :: factors
        !> Loads q_i at the points (N_c) [N].
        real(dp), intent(in) :: loads(:)
        !> Modal loads Q_k = sum_i phi_ik*q_i (N_m) [N/sqrt(kg) for shapes in 1/sqrt(kg)].
        real(dp), intent(out) :: modal(:)
        !> Whether to share the work among the threads of a parallel region.
        logical, intent(in) :: threaded

        real(dp) :: by_column(size(factors%along, 1), size(factors%across, 2))
        integer :: c, i, k, n

        if (.not. shared_out(threaded)) then
            call modal_forces_serial(factors, loads, modal)
            return
        end if
        !$omp parallel default(none) shared(factors, loads, modal, by_column) private(c, i, k, n)
        !$omp do schedule(static)
        do n = 1, size(factors%across, 2)
            by_column(:, n) = 0.0_dp
            do i = 1, size(loads)
                by_column(factors%column(i), n) = by_column(factors%column(i), n) &
                                                  + loads(i)*factors%across(factors%row(i), n)
            end do
        end do
        !$omp end do
        !$omp do schedule(static)
        do k = 1, size(modal)
            modal(k) = 0.0_dp
            do c = 1, size(factors%along, 1)
                modal(k) = modal(k) + factors%along(c, factors%mode_along(k))*by_column(c, factors%mode_across(k))
            end do
        end do
        !$omp end do
        !$omp end parallel
    end subroutine separable_modal_forces

    !> Whether a product asked to share its work among threads gets more than one: one thread
    !> takes the serial loops, whose sums are the same.
    logical function shared_out(threaded)
        logical, intent(in) :: threaded

        shared_out = .false.
        !$ shared_out = threaded .and. omp_get_max_threads() > 1
    end function shared_out

    !> `separable_modal_forces` on the calling thread: H^T (N_y x n_col) by points, then the
    !> Q_k by columns c, every sum in the order of the threaded loops (separable_kernel.c).
    pure subroutine modal_forces_serial(factors, loads, modal)
        type(separable_shapes), intent(in) :: factors
        real(dp), intent(in) :: loads(:)
        real(dp), intent(out) :: modal(:)

        real(dp) :: across_t(size(factors%across, 2), size(factors%across, 1)), &
                    by_point(size(factors%across, 2), size(factors%along, 1)), &
                    along_t(size(factors%along, 2), size(factors%along, 1)), packed(size(loads)), &
                    sums(size(modal))

        across_t(:, :) = transpose(factors%across)
        along_t(:, :) = transpose(factors%along)
        ! the loads and modal loads side by side for the kernel (sections of the caller's arrays)
        packed(:) = loads
        call forces_kernel(size(factors%along, 1, c_int), size(factors%across, 2, c_int), &
                           size(factors%along, 2, c_int), size(modal, kind=c_int), size(loads, kind=c_int), along_t, &
                           factors%mode_along, factors%mode_across, across_t, packed, factors%column, factors%row, &
                           by_point, sums)
        modal(:) = sums
    end subroutine modal_forces_serial

    !> An error unless every contact point lies on the belt of an analytic model in one
    !> coordinate, 0 <= value <= extent; the message names the model, the coordinate and
    !> the symbol of the extent (`tyre`, `x`, `L`).
    pure subroutine check_on_belt(model, coordinate, symbol, values, extent, error)
        !> Name of the model (`tyre`, `plate`).
        character(len=*), intent(in) :: model
        !> Name of the coordinate (`x`, `y`).
        character(len=*), intent(in) :: coordinate
        !> Symbol of the belt's extent in that coordinate (`L`, `b`).
        character(len=*), intent(in) :: symbol
        !> The coordinate of every contact point [m].
        real(dp), intent(in) :: values(:)
        !> The belt's extent in that coordinate [m].
        real(dp), intent(in) :: extent
        !> Set (status 2) when a point lies off the belt.
        type(error_type), allocatable, intent(out) :: error

        if (any(values < 0.0_dp .or. values > extent)) then
            call fatal_error(error, model//' model: contact points must lie on the belt, 0 <= '//coordinate//' <= ' &
                             //symbol//' = '//real_text(extent)//' m')
        end if
    end subroutine check_on_belt

end module greenconv_model_point_modes
