!> The Green's matrix of shared modes as decaying modal recursions, cost O(N_c*N_m) per step.
!>
!> With g_ij(t) = sum_k phi_ik*phi_jk*h_k(t) (greenconv_conv_multipoint), the history at every point
!> is a combination of N_m modal histories, each driven by the modal force
!> Q_k(t_n) = sum_j phi_jk*q_j(t_n):
!>
!>     u_h,i(n) = sum_k phi_ik*Re(p_k(n)),   p_k(n + 1) = z_k*p_k(n) + c_k*Q_k(t_n),
!>     u_i(t_n) = u_h,i(n) + sum_j W0_ij*q_j(t_n),   W0_ij = sum_k phi_ik*phi_jk*w0_k.
!>
!> z_k = exp(lambda_k*dt) and c_k are those of the single-point engines of
!> greenconv_conv_recursive, which this type holds (one `recursive_convolver` over the N_m modes,
!> whose states are the p_k): `recursive`, the paper's rectangle rule (c_k = 2*r_k*dt*z_k,
!> w0_k = 0, explicit), or `exact`, the first-order hold (c_k = 2*r_k*dt*phi1^2,
!> w0_k = 2*Re(r_k*dt*phi2(lambda_k*dt)), with phi1, phi2 from `hold_functions`), or
!> `backward`, the backward zero-order hold (c_k = 2*r_k*dt*phi1*z_k, w0_k = 2*Re(r_k*dt*phi1)).
!> A step costs
!> N_c*N_m multiplications for the modal forces, 4*N_m for the states and N_c*N_m for the
!> displacements: O(N_c*N_m) instead of the O(N_c^2*N_g) of the sampled table.
!>
!> Threads (a build with OpenMP, `-fopenmp`: the Makefile's): the modal forces, each with its
!> mode's recursion, are shared out over the modes, the history displacements over the points
!> and W0 (once) over its columns, as many threads as OMP_NUM_THREADS says. Each Q_k and each u_h,i is summed by one thread in the order of the
!> serial loop, so the results are those of one thread bit for bit. The loops stay serial when
!> the step is called from inside a parallel region of a host (`omp_in_parallel`: each host
!> thread then steps its own convolvers alone) and when N_c*N_m is below `threads_from` (a
!> region costs a few microseconds).
!>
!> Separable shapes (a plate's modes on a grid of points, `separable_shapes` of
!> greenconv_model_point_modes): the convolver then holds the factors instead of the dense
!> shapes, and the history, the modal forces and W0's columns (W0*e_j = Phi*(w o Phi^T*e_j))
!> cost n_col*(N_m + n_row*N_y) multiplications each instead of N_c*N_m: for 100 x 50 points
!> and 441 modes 25 times fewer, with factors that stay in the caches. Each sum is
!> taken in a fixed order there too, so one and two threads give the same bits.
module greenconv_conv_green_modal
    !$ use omp_lib, only: omp_in_parallel
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_model_point_modes, only: point_modes, separable_shapes, separable_displacements, &
                                           separable_modal_forces, separable_work
    use greenconv_conv_recursive, only: recursive_convolver, new_modal_engine
    use greenconv_conv_methods, only: method_scheme, is_modal_recursion, method_list
    implicit none
    private

    public :: modal_green_matrix, new_modal_green_matrix, modal_green_matrix_on

    !> The smallest N_c*N_m (multiplications per modal-force pass) shared out over threads.
    integer, parameter :: threads_from = 20000
    !> Points per block of the history displacements (one thread's share at a time).
    integer, parameter :: history_block = 256

    !> Shared modes stepped by one decaying recursion per mode (`recursive` or `exact`).
    type, extends(multipoint_convolver) :: modal_green_matrix
        !> The modal engine: decay factors z_k, input coefficients c_k and states p_k.
        type(recursive_convolver) :: engine
        !> Mode shapes at the points, shape(i, k) = phi_ik (N_c x N_m); unallocated when the
        !> factors below are held instead.
        real(dp), allocatable :: shape(:, :)
        !> The shapes' factors over a grid of points, when the description has them and they
        !> cost fewer multiplications a product than the dense shapes.
        type(separable_shapes), allocatable :: separable
        !> Modal forces Q_k [N] of the last push (work space).
        real(dp), allocatable :: modal_force(:)
        !> The loads x [N] (N_c) of the last `apply_instant_kept` on the separable factors and
        !> their modal loads Phi^T*x (N_m), for a push of the same loads (allocated at the first
        !> such product and kept; `kept` says whether they are current).
        real(dp), allocatable :: kept_load(:), kept_modal(:)
        !> Whether `kept_load` and `kept_modal` are those of the last product, not yet pushed.
        logical :: kept = .false.
    contains
        procedure :: history => modal_history
        procedure :: push => modal_push
        procedure :: clear => modal_clear
        procedure :: fast_instant => separable_instant
        procedure :: apply_instant_kept => modal_instant_kept
        procedure :: instant_modes => separable_instant_modes
    end type modal_green_matrix

contains

    !> A modal multi-point convolver with the scheme `recursive` (explicit, W0 = 0), `exact`
    !> (first-order hold, W0 /= 0) or `backward` (backward zero-order hold, W0 /= 0), at time
    !> step dt [s]: any method of the registry (greenconv_conv_methods) that the decaying
    !> recursion steps, aliases included (`modal` is `recursive`).
    subroutine new_modal_green_matrix(description, dt, scheme, conv, error)
        !> Modes and mode shapes at the points.
        type(point_modes), intent(in) :: description
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> A method of greenconv_conv_methods's `method_list(engine='recursive')`.
        character(len=*), intent(in) :: scheme
        !> The convolver.
        type(modal_green_matrix), intent(out) :: conv
        !> Set for an unknown scheme or mode shapes that do not match the modes.
        type(error_type), allocatable, intent(out) :: error

        call check_shapes(description, error)
        if (allocated(error)) return
        if (.not. is_modal_recursion(scheme)) then
            call fatal_error(error, 'modal Green''s matrix: unknown scheme '''//scheme//''': expected ' &
                             //method_list(engine='recursive'))
            return
        end if
        call set_up_matrix(description, dt, new_modal_engine(method_scheme(scheme), description%modes, dt), conv)
    end subroutine new_modal_green_matrix

    !> A modal multi-point convolver on a single-point decaying recursion already built on the
    !> same modes at the same step (greenconv_conv_recursive's `new_recursive_convolver`,
    !> `new_exact_convolver`, `new_backward_convolver`): its states are the p_k, and its
    !> per-mode shares of w0 weigh the mode shapes into W0.
    subroutine modal_green_matrix_on(description, dt, engine, conv, error)
        !> Modes and mode shapes at the points.
        type(point_modes), intent(in) :: description
        !> Time step [s], the engine's.
        real(dp), intent(in) :: dt
        !> The single-point recursion on `description%modes`.
        type(recursive_convolver), intent(in) :: engine
        !> The convolver.
        type(modal_green_matrix), intent(out) :: conv
        !> Set for mode shapes that do not match the modes.
        type(error_type), allocatable, intent(out) :: error

        call check_shapes(description, error)
        if (allocated(error)) return
        call set_up_matrix(description, dt, engine, conv)
    end subroutine modal_green_matrix_on

    !> Refuse mode shapes for no point, or with a column count other than the number of modes.
    subroutine check_shapes(description, error)
        type(point_modes), intent(in) :: description
        type(error_type), allocatable, intent(out) :: error

        if (description%n_points() < 1 .or. size(description%shape, 2) /= description%modes%n_modes()) then
            call fatal_error(error, 'modal Green''s matrix: expected mode shapes for at least one point and ' &
                             //'one column per mode')
        end if
    end subroutine check_shapes

    !> Hold the engine and the mode shapes, weigh W0 from the engine's per-mode shares, and reset.
    subroutine set_up_matrix(description, dt, engine, conv)
        type(point_modes), intent(in) :: description
        real(dp), intent(in) :: dt
        type(recursive_convolver), intent(in) :: engine
        type(modal_green_matrix), intent(inout) :: conv

        real(dp), allocatable :: weight0(:, :)
        integer :: n_c, n_m, j, k
        logical :: share

        n_c = description%n_points()
        n_m = description%modes%n_modes()
        conv%engine = engine
        call conv%set_model(conv%engine%name, dt, n_m, 'N_m')
        allocate (conv%modal_force(n_m), weight0(n_c, n_c))
        if (allocated(description%separable)) then
            if (real(separable_work(description%separable), dp) < real(n_c, dp)*n_m) &
                conv%separable = description%separable
        end if
        if (allocated(conv%separable)) then
            call separable_weight0(conv%separable, conv%engine%mode_weight, weight0)
            call conv%set_instant_matrix(weight0)
            call conv%reset()
            return
        end if
        allocate (conv%shape(n_c, n_m))
        conv%shape(:, :) = description%shape
        ! W0_ij = sum_k (w_k*phi_ik)*phi_jk in the order of k, column by column (N_c^2*N_m
        ! multiply-adds once, without temporaries; columns shared among threads).
        share = size(conv%shape) >= threads_from
        !$ share = share .and. .not. omp_in_parallel()
        !$omp parallel do if (share) default(none) shared(conv, weight0, n_c, n_m) private(k) schedule(static)
        do j = 1, n_c
            weight0(:, j) = 0.0_dp
            do k = 1, n_m
                weight0(:, j) = weight0(:, j) + conv%engine%mode_weight(k)*conv%shape(:, k)*conv%shape(j, k)
            end do
        end do
        !$omp end parallel do
        call conv%set_instant_matrix(weight0)
        call conv%reset()
    end subroutine set_up_matrix

    !> W0 = Phi*diag(w)*Phi^T from the shapes' factors, column by column: W0*e_j = Phi*(w o phi_j.),
    !> phi_jk = X_f(k)(x_col(j))*Y_n(k)(y_row(j)); columns shared among threads. Zero when every
    !> w_k is (the explicit scheme).
    subroutine separable_weight0(factors, weight, weight0)
        type(separable_shapes), intent(in) :: factors
        real(dp), intent(in) :: weight(:)
        real(dp), intent(out) :: weight0(:, :)

        real(dp) :: scaled(size(weight))
        integer :: j
        logical :: share

        if (maxval(abs(weight)) <= 0.0_dp) then
            weight0(:, :) = 0.0_dp
            return
        end if
        share = real(separable_work(factors), dp)*size(weight0, 2) >= threads_from
        !$ share = share .and. .not. omp_in_parallel()
        !$omp parallel do if (share) default(none) shared(factors, weight, weight0) private(scaled) schedule(static)
        do j = 1, size(weight0, 2)
            scaled(:) = weight*factors%along(factors%column(j), factors%mode_along) &
                        *factors%across(factors%row(j), factors%mode_across)
            call separable_displacements(factors, scaled, weight0(:, j), .false.)
        end do
        !$omp end parallel do
    end subroutine separable_weight0

    !> Whether W0*x is made on the separable factors (`modal_instant_kept`): 2*n_col*(N_m + n_row*N_y)
    !> multiplications on factors that stay in the caches, against 2*N_c*r streamed for a
    !> product by W0's low-rank factors U*V^T (r about N_m).
    pure logical function separable_instant(self)
        !> The convolver.
        class(modal_green_matrix), intent(in) :: self

        separable_instant = allocated(self%separable) .and. .not. self%explicit
    end function separable_instant

    !> y = W0*x [m] for loads x [N]: Phi*(w o (Phi^T*x)) on the separable factors, the form
    !> W0's columns are made in (`separable_weight0`), its modal loads Phi^T*x kept with x: the
    !> next push, when its recorded loads equal x bit for bit (the implicit step's last residual
    !> is of the forces it pushes), takes them instead of making them again, the same numbers.
    !> Its sums are taken in a fixed order, so one and two threads give the same bits. Without
    !> the factors, the dense product (`apply_instant`), keeping nothing.
    subroutine modal_instant_kept(self, x, y)
        !> The convolver.
        class(modal_green_matrix), intent(inout) :: self
        !> Loads [N] at the points (N_c).
        real(dp), intent(in) :: x(:)
        !> W0*x [m] (N_c).
        real(dp), intent(out) :: y(:)

        real(dp) :: modal(size(self%engine%mode_weight)), weighted(size(self%engine%mode_weight))
        logical :: share

        if (.not. allocated(self%separable)) then
            call self%apply_instant(x, y)
            return
        end if
        share = separable_work(self%separable) >= threads_from
        !$ share = share .and. .not. omp_in_parallel()
        call separable_modal_forces(self%separable, x, modal, share)
        weighted(:) = self%engine%mode_weight*modal
        call separable_displacements(self%separable, weighted, y, share)
        if (allocated(self%kept_load)) then
            if (size(self%kept_load) /= size(x)) deallocate (self%kept_load, self%kept_modal)
        end if
        if (.not. allocated(self%kept_load)) allocate (self%kept_load(size(x)), self%kept_modal(size(modal)))
        self%kept_load(:) = x
        self%kept_modal(:) = modal
        self%kept = .true.
    end subroutine modal_instant_kept

    !> W0 = Phi*diag(w)*Phi^T on the separable factors, when the convolver holds them and W0 /= 0:
    !> the factors and the engine's per-mode shares w_k of W0.
    subroutine separable_instant_modes(self, shapes, weight, offered)
        !> The convolver.
        class(modal_green_matrix), intent(in) :: self
        !> The mode shapes' factors over the grid of points, when offered.
        type(separable_shapes), allocatable, intent(out) :: shapes
        !> w_k (N_m), when offered: W0_ij = sum_k phi_ik*w_k*phi_jk [m/N].
        real(dp), allocatable, intent(out) :: weight(:)
        !> Whether W0 = Phi*diag(w)*Phi^T is offered.
        logical, intent(out) :: offered

        offered = self%fast_instant()
        if (.not. offered) return
        shapes = self%separable
        weight = self%engine%mode_weight
    end subroutine separable_instant_modes

    !> u_h,i(n) = sum_k phi_ik*Re(p_k(n)) [m].
    subroutine modal_history(self, u)
        class(modal_green_matrix), intent(in) :: self
        real(dp), intent(out) :: u(:)

        integer :: block, first, last, k
        logical :: share

        if (allocated(self%separable)) then
            share = separable_work(self%separable) >= threads_from
            !$ share = share .and. .not. omp_in_parallel()
            call separable_displacements(self%separable, self%engine%state_re, u, share)
            return
        end if
        share = size(self%shape) >= threads_from
        !$ share = share .and. .not. omp_in_parallel()
        ! Blocks of points, each summed over the modes column by column (contiguous in shape):
        ! every u_i is the serial loop's sum, in its order.
        !$omp parallel do if (share) default(none) shared(self, u) private(first, last, k) schedule(static)
        do block = 1, (size(u) + history_block - 1)/history_block
            first = (block - 1)*history_block + 1
            last = min(block*history_block, size(u))
            u(first:last) = 0.0_dp
            do k = 1, size(self%shape, 2)
                u(first:last) = u(first:last) + self%shape(first:last, k)*self%engine%state_re(k)
            end do
        end do
        !$omp end parallel do
    end subroutine modal_history

    !> Q_k = sum_j phi_jk*q_j, then p_k <- z_k*p_k + c_k*Q_k, and advance. Both by modes in one
    !> loop: the thread that sums Q_k steps p_k, with no barrier between.
    subroutine modal_push(self, forces)
        class(modal_green_matrix), intent(inout) :: self
        real(dp), intent(in) :: forces(:)

        real(dp) :: load(size(forces))
        integer :: k
        logical :: share

        load(:) = self%recorded_load(forces)
        if (allocated(self%separable)) then
            share = separable_work(self%separable) >= threads_from
            !$ share = share .and. .not. omp_in_parallel()
            if (kept_for(self, load)) then
                self%modal_force(:) = self%kept_modal
            else
                call separable_modal_forces(self%separable, load, self%modal_force, share)
            end if
            self%kept = .false.
            do k = 1, size(self%modal_force)
                call step_mode(self%engine, k, self%modal_force(k))
            end do
            self%step = self%step + 1
            return
        end if
        share = size(self%shape) >= threads_from
        !$ share = share .and. .not. omp_in_parallel()
        !$omp parallel do if (share) default(none) shared(self, load) schedule(static)
        do k = 1, size(self%shape, 2)
            self%modal_force(k) = dot_product(self%shape(:, k), load)
            call step_mode(self%engine, k, self%modal_force(k))
        end do
        !$omp end parallel do
        self%step = self%step + 1
    end subroutine modal_push

    !> Whether the modal loads kept by the last `modal_instant_kept` are those of `load`: the
    !> same values bit for bit (a NaN never matches, so it is projected again).
    pure logical function kept_for(self, load)
        class(modal_green_matrix), intent(in) :: self
        real(dp), intent(in) :: load(:)

        kept_for = .false.
        if (.not. self%kept) return
        if (size(self%kept_load) /= size(load)) return
        kept_for = all(self%kept_load == load)
    end function kept_for

    !> p_k <- z_k*p_k + c_k*Q_k for one mode k, Q_k [N] its modal force.
    pure subroutine step_mode(engine, k, force)
        type(recursive_convolver), intent(inout) :: engine
        integer, intent(in) :: k
        real(dp), intent(in) :: force

        real(dp) :: old_re

        old_re = engine%state_re(k)
        engine%state_re(k) = engine%decay_re(k)*old_re - engine%decay_im(k)*engine%state_im(k) &
                             + engine%input_re(k)*force
        engine%state_im(k) = engine%decay_re(k)*engine%state_im(k) + engine%decay_im(k)*old_re &
                             + engine%input_im(k)*force
    end subroutine step_mode

    !> Clear the modal states.
    subroutine modal_clear(self)
        class(modal_green_matrix), intent(inout) :: self

        call self%engine%reset()
        self%modal_force(:) = 0.0_dp
        self%kept = .false.
    end subroutine modal_clear

end module greenconv_conv_green_modal
