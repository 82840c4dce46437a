!> Standard causal convolution with a sampled Green's function, eqs. (4), (5) and (20).
!>
!> The kernel is w_j = dt*g(t_j), j = 0..N_g, truncated by the paper's rule (section 2.1;
!> see greenconv_conv_kernel). Past forces sit in a doubled ring buffer, newest first, so
!> that any stretch of the last N_g forces is contiguous.
!>
!> The steps go in blocks of B = `block_size` (greenconv_conv_kernel). When a block starts at
!> step n0, the part of its B histories that comes from the forces already known,
!>
!>     older(i) = sum_{j=i+1..N_g} w_j*q(t_{n0+i-j}),   i = 0..B-1,
!>
!> is one small Toeplitz matrix-vector product (`block_sums`: each force loaded once for the B
!> sums, so that the sum is bound by arithmetic and not by the memory traffic of a dot product
!> per step). Within the block the history of step n0 + i adds only the i forces pushed since:
!>
!>     u_h(n0 + i) = older(i) + sum_{j=1..min(i,N_g)} w_j*q(t_{n0+i-j}).
!>
!> This is the same sum as eq. (20), term for term, in another order of addition: equal to
!> round-off. The seam does not change: `history` reads, `push` advances (and, at the end of a
!> block, sums the next one's `older`), `reset` returns to the start of a block.
!>
!> A kernel cut at the length of the run it was made for (g not yet below the truncation
!> level there) is wrong for any later step: such a convolver knows its `valid_steps`
!> (greenconv_conv_convolver), and its history past them is NaN, never a silently short sum.
module greenconv_conv_direct
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use greenconv_core_kinds, only: dp
    use greenconv_conv_convolver, only: convolver, capped_step
    use greenconv_conv_kernel, only: block_sums, block_size
    implicit none
    private

    public :: direct_convolver, new_direct_convolver

    !> Direct sum over N_g past forces (cost per step proportional to N_g).
    type, extends(convolver) :: direct_convolver
        !> Kernel weights w_j = dt*g(t_j) [m/N], j = 1..N_g.
        real(dp), allocatable :: weight(:)
        !> Past forces [N], each stored twice (positions i and i + N_g), newest at `head`.
        real(dp), allocatable :: past(:)
        !> Position of the newest force in `past`.
        integer :: head = 1
        !> Steps taken since the current block started, 0..block_size - 1.
        integer :: offset = 0
        !> Part of the block's histories [m] from the forces older than the block: entry i
        !> belongs to the block's step i.
        real(dp) :: older(0:block_size - 1) = 0.0_dp
    contains
        procedure :: history => direct_history
        procedure :: push => direct_push
        procedure :: clear => direct_clear
    end type direct_convolver

contains

    !> A direct convolver from kernel samples g(t_j) [m/(N*s)], j = 0..N_g (N_g >= 1), step dt [s].
    function new_direct_convolver(kernel, dt, valid_steps) result(conv)
        !> Samples g(j*dt), j = 0..N_g, of the impulse response [m/(N*s)].
        real(dp), intent(in) :: kernel(0:)
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Number of steps the kernel is valid for, when it was cut at a run's length (default:
        !> any number).
        integer(int64), intent(in), optional :: valid_steps
        type(direct_convolver) :: conv

        integer :: n_g

        n_g = ubound(kernel, 1)
        call conv%set_model('direct', dt, n_g, 'N_g')
        conv%weight0 = dt*kernel(0)
        conv%weight = dt*kernel(1:n_g)
        allocate (conv%past(2*n_g))
        if (present(valid_steps)) conv%valid_steps = valid_steps
        call conv%reset()
    end function new_direct_convolver

    !> Displacement from past forces: sum_{j=1..min(n,N_g)} w_j*q(t_{n-j}); NaN from step
    !> `valid_steps` on.
    function direct_history(self) result(u)
        class(direct_convolver), intent(in) :: self
        real(dp) :: u

        integer :: j

        if (self%step >= self%valid_steps) then
            u = ieee_value(u, ieee_quiet_nan)
            return
        end if
        u = self%older(self%offset)
        do j = 1, min(self%offset, size(self%weight))
            u = u + self%weight(j)*self%past(self%head + j - 1)
        end do
    end function direct_history

    !> Store the force of the current step in both halves of the ring and advance; at the end
    !> of a block, sum the next block's `older`.
    subroutine direct_push(self, force)
        class(direct_convolver), intent(inout) :: self
        real(dp), intent(in) :: force

        integer :: n_g

        n_g = size(self%weight)
        self%head = self%head - 1
        if (self%head < 1) self%head = n_g
        self%past(self%head) = force
        self%past(self%head + n_g) = force
        self%step = self%step + 1
        self%offset = self%offset + 1
        if (self%offset == block_size) call start_block(self)
    end subroutine direct_push

    !> Start a block at the current step n0: older(i) = sum_{m=1..min(L,N_g-i)} w_{m+i}*p_m,
    !> with p_m = q(t_{n0-m}) the L = min(n0, N_g) forces known, newest first.
    subroutine start_block(self)
        class(direct_convolver), intent(inout) :: self

        integer :: n_g, known, n, i, m

        n_g = size(self%weight)
        known = capped_step(self%step, n_g)
        ! The terms every sum has (m + block_size - 1 <= N_g), an even number, by block_sums.
        n = max(0, min(known, n_g - block_size + 1))
        n = n - mod(n, 2)
        if (n > 0) then
            call block_sums(n, self%weight(1:n + block_size - 1), self%past(self%head:self%head + n - 1), &
                            self%older)
        else
            self%older = 0.0_dp
        end if
        do i = 0, block_size - 1
            do m = n + 1, min(known, n_g - i)
                self%older(i) = self%older(i) + self%weight(m + i)*self%past(self%head + m - 1)
            end do
        end do
        self%offset = 0
    end subroutine start_block

    !> Clear the force history and start a block.
    subroutine direct_clear(self)
        class(direct_convolver), intent(inout) :: self

        self%past = 0.0_dp
        self%head = 1
        self%offset = 0
        self%older = 0.0_dp
    end subroutine direct_clear

end module greenconv_conv_direct
