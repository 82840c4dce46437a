!> Convolution by modal decomposition: the recursion of eqs. (11)-(17) and (24).
!>
!> For each mode (pole lambda_k = -a_k + i*omega_k^d, residue r_k) the force history is
!> accumulated in the integrals of eqs. (12)-(13), advanced by the rectangle rule of
!> eqs. (16)-(17):
!>
!>     alpha_k(n+1) = alpha_k(n) + exp(a_k*t_n)*cos(omega_k^d*t_n)*q(t_n)*dt
!>     beta_k(n+1)  = beta_k(n)  + exp(a_k*t_n)*sin(omega_k^d*t_n)*q(t_n)*dt
!>
!> and the history displacement of eq. (15)/(24) at t_n is
!>
!>     u_h(n) = sum_k 2*Re( r_k*exp(-a_k*t_n)*exp(i*omega_k^d*t_n)*(alpha_k(n) - i*beta_k(n)) ),
!>
!> which for the paper's real A_k (r_k = A_k/(2i*omega_k^d)) is eq. (15) term by term.
!> alpha_k(n) holds the forces of steps 0..n-1: this is how eq. (24)'s alpha((n-1)*dt) is read
!> here, and it makes u_h(n) equal to the direct sum of eq. (20) with the untruncated kernel,
!> up to round-off. Cost per step is proportional to the number of modes.
!>
!> The factors exp(+a_k*t_n) grow without bound, as in the paper. Kept as written, as the
!> reference the other recursions are checked against, it fails for long runs:
!> - exp(+a_k*t_n) overflows to +Inf once a_k*t_n > log(huge) = 709.78, and u_h becomes
!>   Inf or NaN from then on; a_k = xi_k*omega_k, so a 2 kHz mode with xi = 0.05
!>   (a_k = 628 1/s) fails after 1.13 s of simulated time, whatever dt. The integrals
!>   alpha_k, beta_k, of the order of exp(a_k*t_n)*max|q|/a_k [N*s], overflow a little
!>   earlier when max|q|/a_k exceeds 1 N*s;
!> - a little before, exp(-a_k*t_n) in the history is subnormal (a_k*t_n > 708.4) and the
!>   history loses digits;
!> - short of that, the argument omega_k^d*t_n of cos and sin grows with t_n, so the
!>   rounding of the phase (about 1e-16*omega_k^d*t_n) is the limit of its accuracy.
!> greenconv_conv_recursive gives the same numbers with factors of modulus below 1 (`recursive`).
module greenconv_conv_paper
    use greenconv_core_kinds, only: dp
    use greenconv_conv_convolver, only: convolver
    use greenconv_model_modal_set, only: modal_set
    implicit none
    private

    public :: paper_convolver, new_paper_convolver

    !> The paper's modal recursion, eqs. (15)-(17).
    type, extends(convolver) :: paper_convolver
        !> Decay rates a_k = xi_k*omega_k [1/s].
        real(dp), allocatable :: decay(:)
        !> Damped angular frequencies omega_k^d [rad/s].
        real(dp), allocatable :: omega_d(:)
        !> Residues r_k [m/(N*s)].
        complex(dp), allocatable :: residue(:)
        !> Accumulated integrals alpha_k of eq. (12) [N*s].
        real(dp), allocatable :: alpha(:)
        !> Accumulated integrals beta_k of eq. (13) [N*s].
        real(dp), allocatable :: beta(:)
    contains
        procedure :: history => modal_history
        procedure :: push => modal_push
        procedure :: clear => modal_clear
    end type paper_convolver

contains

    !> The paper's recursion, eqs. (15)-(17), for the modes of `modes` at time step dt [s].
    function new_paper_convolver(modes, dt) result(conv)
        !> The Green's function as modes.
        type(modal_set), intent(in) :: modes
        !> Time step [s].
        real(dp), intent(in) :: dt
        type(paper_convolver) :: conv

        call conv%set_model('paper', dt, modes%n_modes(), 'N_m')
        conv%decay = -real(modes%pole, kind=dp)
        conv%omega_d = aimag(modes%pole)
        conv%residue = modes%residue
        allocate (conv%alpha(modes%n_modes()), conv%beta(modes%n_modes()))
        call conv%reset()
    end function new_paper_convolver

    !> Clear the accumulated integrals.
    subroutine modal_clear(self)
        class(paper_convolver), intent(inout) :: self

        self%alpha = 0.0_dp
        self%beta = 0.0_dp
    end subroutine modal_clear

    !> History displacement of eq. (15) at t_n from alpha_k(n), beta_k(n).
    function modal_history(self) result(u)
        class(paper_convolver), intent(in) :: self
        real(dp) :: u

        real(dp) :: t
        complex(dp) :: rotated(size(self%decay))

        t = self%step*self%dt
        rotated = exp(-self%decay*t)*cmplx(cos(self%omega_d*t), sin(self%omega_d*t), kind=dp) &
                  *cmplx(self%alpha, -self%beta, kind=dp)
        u = 2.0_dp*sum(real(self%residue*rotated, kind=dp))
    end function modal_history

    !> Accumulate the force of step n by eqs. (16)-(17) and advance.
    subroutine modal_push(self, force)
        class(paper_convolver), intent(inout) :: self
        real(dp), intent(in) :: force

        real(dp) :: t
        real(dp) :: growth(size(self%decay))

        t = self%step*self%dt
        growth = exp(self%decay*t)*(force*self%dt)
        self%alpha = self%alpha + growth*cos(self%omega_d*t)
        self%beta = self%beta + growth*sin(self%omega_d*t)
        self%step = self%step + 1
    end subroutine modal_push

end module greenconv_conv_paper
