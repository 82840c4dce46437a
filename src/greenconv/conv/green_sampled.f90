!> The Green's matrix as a table of samples g_ij(t_m), convolved by direct truncated sums.
!>
!> The matrix form of eq. (20) with weights W_ij(m) = dt*g_ij(t_m), m = 1..N_g:
!>
!>     u_h,i(n) = sum_j sum_{m=1..min(n,N_g)} W_ij(m)*q_j(t_{n-m}),   W0_ij = dt*g_ij(0),
!>
!> N_c^2 dot products of length N_g per step: cost O(N_c^2*N_g). The table may come from
!> measurements, a finite-element model or `sample_green_matrix` (greenconv_conv_multipoint). As in
!> greenconv_conv_direct, past forces sit in a doubled ring buffer, newest first, one column per
!> point, so that every dot product is contiguous.
module greenconv_conv_green_sampled
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_conv_multipoint, only: multipoint_convolver, check_green_table
    use greenconv_conv_kernel, only: lane_dot
    use greenconv_conv_convolver, only: capped_step
    implicit none
    private

    public :: sampled_green_matrix, new_sampled_green_matrix

    !> Direct sums over a sampled Green's matrix (cost per step O(N_c^2*N_g)).
    type, extends(multipoint_convolver) :: sampled_green_matrix
        !> Weights weight(m, i, j) = dt*g_ij(t_m) [m/N], m = 1..N_g.
        real(dp), allocatable :: weight(:, :, :)
        !> Past forces past(:, j) [N] at point j, each stored twice (rows r and r + N_g),
        !> newest at row `head`.
        real(dp), allocatable :: past(:, :)
        !> Row of the newest force in `past`.
        integer :: head = 1
    contains
        procedure :: history => sampled_history
        procedure :: push => sampled_push
        procedure :: clear => sampled_clear
    end type sampled_green_matrix

contains

    !> A sampled multi-point convolver from kernel(m, i, j) = g_ij(m*dt) [m/(N*s)],
    !> m = 0..N_g (N_g >= 1), at time step dt [s].
    subroutine new_sampled_green_matrix(kernel, dt, conv, error)
        !> Samples g_ij(m*dt), first index m = 0..N_g, then i and j (N_c x N_c).
        real(dp), intent(in) :: kernel(0:, :, :)
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> The convolver.
        type(sampled_green_matrix), intent(out) :: conv
        !> Set when the table is not square in (i, j) or has no sample after t = 0.
        type(error_type), allocatable, intent(out) :: error

        integer :: n_g, n_c

        call check_green_table(kernel, error)
        if (allocated(error)) return
        n_g = ubound(kernel, 1)
        n_c = size(kernel, 2)
        call conv%set_model('direct', dt, n_g, 'N_g')
        allocate (conv%weight(n_g, n_c, n_c), conv%past(2*n_g, n_c))
        call conv%set_instant_matrix(dt*kernel(0, :, :))
        conv%weight(:, :, :) = dt*kernel(1:n_g, :, :)
        call conv%reset()
    end subroutine new_sampled_green_matrix

    !> u_h,i = sum_j sum_{m=1..min(n,N_g)} W_ij(m)*q_j(t_{n-m}) [m]; NaN from step
    !> `valid_steps` on.
    subroutine sampled_history(self, u)
        class(sampled_green_matrix), intent(in) :: self
        real(dp), intent(out) :: u(:)

        integer :: i, j, m, first, last

        if (self%step >= self%valid_steps) then
            u(:) = ieee_value(1.0_dp, ieee_quiet_nan)
            return
        end if
        m = capped_step(self%step, size(self%weight, 1))
        first = self%head
        last = self%head + m - 1
        u(:) = 0.0_dp
        do j = 1, size(self%past, 2)
            do i = 1, size(u)
                u(i) = u(i) + lane_dot(m, self%weight(1:m, i, j), self%past(first:last, j))
            end do
        end do
    end subroutine sampled_history

    !> Store the forces of the current step in both halves of the ring and advance.
    subroutine sampled_push(self, forces)
        class(sampled_green_matrix), intent(inout) :: self
        real(dp), intent(in) :: forces(:)

        integer :: n_g

        n_g = size(self%weight, 1)
        self%head = self%head - 1
        if (self%head < 1) self%head = n_g
        self%past(self%head, :) = self%recorded_load(forces)
        self%past(self%head + n_g, :) = self%past(self%head, :)
        self%step = self%step + 1
    end subroutine sampled_push

    !> Clear the force history.
    subroutine sampled_clear(self)
        class(sampled_green_matrix), intent(inout) :: self

        self%past(:, :) = 0.0_dp
        self%head = 1
    end subroutine sampled_clear

end module greenconv_conv_green_sampled
