!> Standard causal convolution with a sampled Green's function, eqs. (4), (5) and (20).
!>
!> The kernel is w_j = dt*g(t_j), j = 0..N_g, truncated by the paper's rule (section 2.1;
!> see greenconv_conv_kernel). Past forces sit in a doubled ring buffer, newest first, so
!> that the history is one contiguous dot product of length min(n, N_g) per step, summed by
!> `lane_dot` (greenconv_conv_kernel) in eight interleaved partial sums.
!>
!> A kernel cut at the length of the run it was made for (g not yet below the truncation
!> level there) is wrong for any later step: such a convolver knows its `valid_steps`
!> (greenconv_conv_convolver), and its history past them is NaN, never a silently short sum.
module greenconv_conv_direct
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use greenconv_core_kinds, only: dp
    use greenconv_conv_convolver, only: convolver, capped_step
    use greenconv_conv_kernel, only: lane_dot
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

        integer :: m

        if (self%step >= self%valid_steps) then
            u = ieee_value(u, ieee_quiet_nan)
            return
        end if
        m = capped_step(self%step, size(self%weight))
        u = lane_dot(m, self%weight, self%past(self%head:))
    end function direct_history

    !> Store the force of the current step in both halves of the ring and advance.
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
    end subroutine direct_push

    !> Clear the force history.
    subroutine direct_clear(self)
        class(direct_convolver), intent(inout) :: self

        self%past = 0.0_dp
        self%head = 1
    end subroutine direct_clear

end module greenconv_conv_direct
