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
!>
!> What single-point and multi-point convolvers (greenconv_conv_multipoint) have in common sits
!> in `convolver_core`: an engine implements `history`, `push` (which advances `step`) and
!> `clear` (its memory of the forces; `reset` clears and returns the step to 0), and its
!> constructor names it, with its time step and model size, by `set_model`.
!>
!> A sampled kernel cut at the length of the run it was made for (g not yet below the
!> truncation level there) is wrong for any later step: such a convolver, one point or N_c,
!> knows its `valid_steps`; its history past them is NaN, never a silently short sum, and
!> every door (the contact loops, the C and F77 handles) refuses those steps first with
!> `check_validity`'s message.
module greenconv_conv_convolver
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error, stat_input
    use greenconv_core_text, only: int_text
    implicit none
    private

    public :: convolver_core, convolver, free_convolver, capped_step

    !> What every convolver holds and does, for one contact point (`convolver`) or for N_c
    !> (greenconv_conv_multipoint's `multipoint_convolver`): its name, time step, step
    !> counter and model size; `reset`, `model_size` and `release`.
    type, abstract :: convolver_core
        !> Short name of the method, as written in a scene's `methods` list.
        character(len=:), allocatable :: name
        !> Time step dt [s].
        real(dp) :: dt = 0.0_dp
        !> Number of forces pushed so far (the index n of the next step); 64 bits, so that a
        !> convolver may be stepped past 2^31 - 1 pushes.
        integer(int64) :: step = 0
        !> Size of the model: N_g kernel samples or N_m modes (set by `set_model`).
        integer :: model_count = 0
        !> What `model_count` counts: `N_g` or `N_m`.
        character(len=:), allocatable :: model_label
        !> Steps n whose history the model covers, n < valid_steps: the n_steps a sampled
        !> kernel was cut at (g not decayed by then); huge (any run length) otherwise.
        integer(int64) :: valid_steps = huge(0_int64)
    contains
        !> Forget all forces pushed and return to step 0: `clear`, then the step counter.
        procedure, non_overridable :: reset
        !> Forget the forces pushed: the engine's own memory of them (by `reset`).
        procedure(clear_interface), deferred :: clear
        !> Size of the model: N_g kernel samples or N_m modes, with its label.
        procedure :: model_size
        !> Set the name, time step and model size (by the constructors).
        procedure :: set_model
        !> Refuse steps past `valid_steps` (status 2), before they are taken.
        procedure :: check_validity
        !> Give back what the convolver holds outside Fortran's memory (FFTW plans); it makes
        !> them again if stepped further. Nothing to give back by default.
        procedure :: release => release_nothing
    end type convolver_core

    !> A causal convolver of one contact point, stepped once per time step.
    type, abstract, extends(convolver_core) :: convolver
        !> Displacement per newton [m/N] of the current step's own force, w0; fixed when the
        !> convolver is built, the same at every step.
        real(dp) :: weight0 = 0.0_dp
    contains
        !> Displacement u_h(n) [m] at t_n from the forces pushed so far.
        procedure(history_interface), deferred :: history
        !> Record the force q(t_n) [N] of the current step and advance to the next.
        procedure(push_interface), deferred :: push
        !> Displacement per newton [m/N] of the current step's own force.
        procedure :: instant_weight
    end type convolver

    abstract interface
        !> Forget the forces pushed so far (the step counter is `reset`'s).
        subroutine clear_interface(self)
            import :: convolver_core
            implicit none
            class(convolver_core), intent(inout) :: self
        end subroutine clear_interface

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

    !> Forget all forces pushed and return to step 0.
    !>
    !> Recursive: a convolver that holds another (the 1 x 1 point_matrix around a single-point
    !> engine, the modal Green's matrix around its recursion) resets the one it holds from its
    !> own `clear`, so this routine runs inside itself.
    recursive subroutine reset(self)
        !> The convolver.
        class(convolver_core), intent(inout) :: self

        call self%clear()
        self%step = 0
    end subroutine reset

    !> Size of the model and its label (`N_g` or `N_m`).
    subroutine model_size(self, n, label)
        !> The convolver.
        class(convolver_core), intent(in) :: self
        !> Number of kernel samples N_g or of modes N_m.
        integer, intent(out) :: n
        !> `N_g` or `N_m`.
        character(len=:), allocatable, intent(out) :: label

        n = self%model_count
        label = ''
        if (allocated(self%model_label)) label = self%model_label
    end subroutine model_size

    !> Name a new convolver and give it its time step and model size.
    pure subroutine set_model(self, name, dt, n, label)
        !> The convolver.
        class(convolver_core), intent(inout) :: self
        !> Short name of the method.
        character(len=*), intent(in) :: name
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Number of kernel samples N_g or of modes N_m.
        integer, intent(in) :: n
        !> `N_g` or `N_m`.
        character(len=*), intent(in) :: label

        self%name = name
        self%dt = dt
        self%model_count = n
        self%model_label = label
    end subroutine set_model

    !> Refuse (`stat_input`) `steps` more steps from the current one when one of them lies
    !> at or past `valid_steps`: "step 10 is past the direct kernel, cut at the 10 steps the
    !> convolver was made for (...)".
    subroutine check_validity(self, steps, error)
        !> The convolver.
        class(convolver_core), intent(in) :: self
        !> Steps about to be taken from the current one (a history or push of this step: 1).
        integer(int64), intent(in) :: steps
        !> Set when a step lies past the kernel's validity.
        type(error_type), allocatable, intent(out) :: error

        if (self%step + steps <= self%valid_steps) return
        call fatal_error(error, 'step '//int_text(max(self%step, self%valid_steps))//' is past the '//self%name &
                         //' kernel, cut at the '//int_text(self%valid_steps)//' steps the convolver was made for ' &
                         //'(g has not decayed by then): make it with n_steps >= the steps you run, or use a ' &
                         //'modal method', stat_input)
    end subroutine check_validity

    !> Default `release`: a convolver made of Fortran arrays only holds nothing else.
    subroutine release_nothing(self)
        !> The convolver.
        class(convolver_core), intent(inout) :: self

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
