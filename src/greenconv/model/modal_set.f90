!> A Green's function as a sum of damped modes, in pole-residue form.
!>
!> Each mode k has a pole lambda_k = -xi_k*omega_k + i*omega_k*sqrt(1 - xi_k^2) [rad/s]
!> (Re < 0, Im > 0) and a complex residue r_k [m/(N*s)]. With its conjugate pair:
!>
!>     G(omega) = sum_k  r_k/(i*omega - lambda_k) + conj(r_k)/(i*omega - conj(lambda_k))   [m/N]
!>     g(t)     = sum_k  2*Re(r_k*exp(lambda_k*t))   for t >= 0, zero before          [m/(N*s)]
!>
!> The paper's form, eq. (6), A_k/(omega_k^2 - omega^2 + 2i*xi_k*omega*omega_k) with real
!> A_k [1/kg], is the special case r_k = A_k/(2i*omega_k^d), omega_k^d = omega_k*sqrt(1 - xi_k^2),
!> for which g(t) is eq. (8): (A_k/omega_k^d)*exp(-xi_k*omega_k*t)*sin(omega_k^d*t).
module greenconv_model_modal_set
    use greenconv_core_kinds, only: dp
    use greenconv_core_random, only: random_stream
    implicit none
    private

    public :: modal_set, modes_from_paper, random_modes, sorted_by_frequency, sorted_order

    !> A set of modes in pole-residue form (see the module description for the convention).
    type :: modal_set
        !> Poles lambda_k [rad/s], one per conjugate pair, Re < 0 and Im > 0.
        complex(dp), allocatable :: pole(:)
        !> Residues r_k [m/(N*s)] matching `pole`.
        complex(dp), allocatable :: residue(:)
    contains
        !> Number of modes (conjugate pairs).
        procedure :: n_modes
        !> Receptance G(omega) [m/N] at angular frequency omega [rad/s].
        procedure :: receptance
        !> Impulse response g(t) [m/(N*s)] at time t [s].
        procedure :: impulse
        !> Upper bound of |g(t)| [m/(N*s)] from the decay of each mode.
        procedure :: envelope
        !> Slowest decay rate sigma = min(-Re lambda_k) [1/s] (0 for no mode or an undamped one).
        procedure :: slowest_decay
    end type modal_set

contains

    !> Modes from the paper's parameters of eq. (6): amplitudes A_k [1/kg],
    !> natural angular frequencies omega_k [rad/s] and damping ratios xi_k in [0, 1).
    pure function modes_from_paper(amplitude, omega, damping_ratio) result(modes)
        !> Modal amplitudes A_k [1/kg] (for one mass M on a spring, A = 1/M).
        real(dp), intent(in) :: amplitude(:)
        !> Undamped natural angular frequencies omega_k [rad/s].
        real(dp), intent(in) :: omega(:)
        !> Damping ratios xi_k, 0 <= xi_k < 1.
        real(dp), intent(in) :: damping_ratio(:)
        type(modal_set) :: modes

        real(dp) :: omega_d(size(omega))

        omega_d = omega*sqrt(1.0_dp - damping_ratio**2)
        allocate (modes%pole(size(omega)), modes%residue(size(omega)))
        modes%pole = cmplx(-damping_ratio*omega, omega_d, kind=dp)
        modes%residue = cmplx(0.0_dp, -amplitude/(2.0_dp*omega_d), kind=dp)
    end function modes_from_paper

    !> A random modal system in the paper's form (section 3.2): for each mode, drawn in this
    !> order from `seed` (SplitMix64, the same on every compiler), a natural frequency
    !> uniform in [f_low, f_high) Hz, a damping ratio uniform in [xi_low, xi_high) and an
    !> amplitude A_k uniform in [a_low, a_high) 1/kg; modes sorted by frequency.
    function random_modes(seed, n_modes, f_low, f_high, xi_low, xi_high, a_low, a_high) result(modes)
        !> Seed of the draws.
        integer, intent(in) :: seed
        !> Number of modes.
        integer, intent(in) :: n_modes
        !> Range of natural frequencies [Hz].
        real(dp), intent(in) :: f_low, f_high
        !> Range of damping ratios, within [0, 1).
        real(dp), intent(in) :: xi_low, xi_high
        !> Range of amplitudes A_k [1/kg].
        real(dp), intent(in) :: a_low, a_high
        type(modal_set) :: modes

        type(random_stream) :: stream
        real(dp) :: frequency(n_modes), ratio(n_modes), amplitude(n_modes)
        integer :: k, order(n_modes)

        stream = random_stream(seed)
        do k = 1, n_modes
            frequency(k) = stream%between(f_low, f_high)
            ratio(k) = stream%between(xi_low, xi_high)
            amplitude(k) = stream%between(a_low, a_high)
        end do
        order = sorted_order(frequency)
        modes = modes_from_paper(amplitude(order), 2.0_dp*acos(-1.0_dp)*frequency(order), ratio(order))
    end function random_modes

    !> The same modes ordered by natural frequency |lambda_k|, lowest first.
    function sorted_by_frequency(modes) result(sorted)
        !> The modes.
        type(modal_set), intent(in) :: modes
        type(modal_set) :: sorted

        integer :: order(modes%n_modes())

        allocate (sorted%pole(size(order)), sorted%residue(size(order)))
        if (size(order) == 0) return
        order = sorted_order(abs(modes%pole))
        sorted%pole = modes%pole(order)
        sorted%residue = modes%residue(order)
    end function sorted_by_frequency

    !> Indices that sort `values` ascending, equal values in their order (a stable insertion
    !> sort: the sets are small).
    pure function sorted_order(values) result(order)
        !> The values to sort (any unit).
        real(dp), intent(in) :: values(:)
        !> values(order) is ascending.
        integer :: order(size(values))

        integer :: i, j, item

        order = [(i, i=1, size(values))]
        do i = 2, size(values)
            item = order(i)
            j = i - 1
            do while (j >= 1)
                if (values(order(j)) <= values(item)) exit
                order(j + 1) = order(j)
                j = j - 1
            end do
            order(j + 1) = item
        end do
    end function sorted_order

    !> Number of modes (conjugate pairs) in the set.
    elemental integer function n_modes(self)
        !> The modal set.
        class(modal_set), intent(in) :: self

        n_modes = 0
        if (allocated(self%pole)) n_modes = size(self%pole)
    end function n_modes

    !> Receptance G(omega) [m/N] at angular frequency omega [rad/s].
    elemental complex(dp) function receptance(self, omega)
        !> The modal set.
        class(modal_set), intent(in) :: self
        !> Angular frequency [rad/s].
        real(dp), intent(in) :: omega

        complex(dp) :: s

        s = cmplx(0.0_dp, omega, kind=dp)
        receptance = sum(self%residue/(s - self%pole) + conjg(self%residue)/(s - conjg(self%pole)))
    end function receptance

    !> Impulse response g(t) [m/(N*s)] at time t [s]; zero for t < 0, g(0+) at t = 0.
    elemental real(dp) function impulse(self, t)
        !> The modal set.
        class(modal_set), intent(in) :: self
        !> Time [s].
        real(dp), intent(in) :: t

        impulse = 0.0_dp
        if (t < 0.0_dp) return
        impulse = 2.0_dp*sum(real(self%residue*exp(self%pole*t), kind=dp))
    end function impulse

    !> Upper bound of |g(t)| [m/(N*s)]: sum of 2*|r_k|*exp(Re(lambda_k)*t).
    elemental real(dp) function envelope(self, t)
        !> The modal set.
        class(modal_set), intent(in) :: self
        !> Time [s], t >= 0.
        real(dp), intent(in) :: t

        envelope = 2.0_dp*sum(abs(self%residue)*exp(real(self%pole, kind=dp)*t))
    end function envelope

    pure real(dp) function slowest_decay(self)
        !> The modal set.
        class(modal_set), intent(in) :: self

        slowest_decay = 0.0_dp
        if (self%n_modes() > 0) slowest_decay = max(minval(-real(self%pole, dp)), 0.0_dp)
    end function slowest_decay

end module greenconv_model_modal_set
