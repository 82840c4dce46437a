!> The seam between the contact loop and every convolution method.
!>
!> A convolver computes the causal discrete convolution of eq. (20),
!>
!>     u(t_n) = u_h(n) + w0*q(t_n),   u_h(n) = sum_{m < n} w(n - m)*q(t_m),   t_n = n*dt,
!>
!> one step at a time. The contact loop asks `history()` for u_h(n), the displacement
!> from the forces pushed so far, decides this step's force q(t_n), and hands it over
!> with `push(q)`, which advances to step n + 1. `instant_weight()` is w0, the
!> displacement per newton of the current step's own force (zero for the paper's scheme).
!> The loop never knows whether a direct sum, an FFT or modes answer.
module greenconv_conv_convolver
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    implicit none
    private

    public :: convolver, free_convolver, capped_step

    !> A causal convolver stepped once per time step.
    type, abstract :: convolver
        !> Short name of the method, as written in a scene's `methods` list.
        character(len=:), allocatable :: name
        !> Time step dt [s].
        real(dp) :: dt = 0.0_dp
        !> Number of forces pushed so far (the index n of the next step); 64 bits, so that a
        !> convolver may be stepped past 2^31 - 1 pushes.
        integer(int64) :: step = 0
        !> Displacement per newton [m/N] of the current step's own force, w0; fixed when the
        !> convolver is built, the same at every step.
        real(dp) :: weight0 = 0.0_dp
    contains
        !> Displacement u_h(n) [m] at t_n from the forces pushed so far.
        procedure(history_interface), deferred :: history
        !> Record the force q(t_n) [N] of the current step and advance to the next.
        procedure(push_interface), deferred :: push
        !> Forget all forces pushed and return to step 0.
        procedure(reset_interface), deferred :: reset
        !> Size of the model: N_g kernel samples or N_m modes, with its label.
        procedure(size_interface), deferred :: model_size
        !> Displacement per newton [m/N] of the current step's own force.
        procedure :: instant_weight
        !> Give back what the convolver holds outside Fortran's memory (FFTW plans); it makes
        !> them again if stepped further. Nothing to give back by default.
        procedure :: release => release_nothing
    end type convolver

    abstract interface
        !> Displacement u_h(n) [m] at t_n from the forces pushed so far.
        function history_interface(self) result(u)
            import :: convolver, dp
            implicit none
            class(convolver), intent(in) :: self
            real(dp) :: u
        end function history_interface

        !> Record the force of the current step and advance.
        subroutine push_interface(self, force)
            import :: convolver, dp
            implicit none
            class(convolver), intent(inout) :: self
            real(dp), intent(in) :: force
        end subroutine push_interface

        !> Return to step 0 with no force history.
        subroutine reset_interface(self)
            import :: convolver
            implicit none
            class(convolver), intent(inout) :: self
        end subroutine reset_interface

        !> Size of the model and its label (`N_g` or `N_m`).
        subroutine size_interface(self, n, label)
            import :: convolver
            implicit none
            class(convolver), intent(in) :: self
            integer, intent(out) :: n
            character(len=:), allocatable, intent(out) :: label
        end subroutine size_interface
    end interface

contains

    !> Displacement per newton [m/N] of the current step's own force, w0.
    pure function instant_weight(self) result(w0)
        !> The convolver.
        class(convolver), intent(in) :: self
        real(dp) :: w0

        w0 = self%weight0
    end function instant_weight

    !> min(step, limit) as a default integer: how many of `limit` kernel taps or ring slots
    !> the forces pushed so far fill (a step counter may exceed the default integer range).
    elemental integer function capped_step(step, limit)
        !> Number of forces pushed so far.
        integer(int64), intent(in) :: step
        !> The cap (a kernel length), >= 0.
        integer, intent(in) :: limit

        capped_step = limit
        if (step < limit) capped_step = int(step)
    end function capped_step

    !> Default `release`: a convolver made of Fortran arrays only holds nothing else.
    subroutine release_nothing(self)
        !> The convolver.
        class(convolver), intent(inout) :: self

        associate (unused => self%step)
        end associate
    end subroutine release_nothing

    !> Release what a convolver holds outside Fortran's memory (an `fft` convolver's FFTW
    !> plans) and deallocate it. Call it before dropping a convolver. Safe on an
    !> unallocated convolver.
    subroutine free_convolver(conv)
        !> The convolver; unallocated on return.
        class(convolver), allocatable, intent(inout) :: conv

        if (.not. allocated(conv)) return
        call conv%release()
        deallocate (conv)
    end subroutine free_convolver

end module greenconv_conv_convolver
