!> One contact point as the 1 x 1 case of a Green's matrix: a single-point `convolver`
!> (greenconv_conv_convolver) seen as a `multipoint_convolver` (greenconv_conv_multipoint).
!>
!> The wrapped engine does all the arithmetic: `history` hands on its u_h(n), `push` its
!> force, and W0 is the 1 x 1 matrix of its w0. So a front door or a loop written for N_c
!> points serves a single-point structure unchanged, with the single-point engine's numbers to
!> the last bit. The engine stays reachable (`point`) for what only single-point contact does
!> (its scalar implicit step, the explicit step with w0 > 0 of the paper's scheme). A
!> `point_matrix` owns its engine; a `lent_point` borrows the caller's for one call.
module greenconv_conv_point_matrix
    use greenconv_core_kinds, only: dp
    use greenconv_conv_convolver, only: convolver
    use greenconv_conv_multipoint, only: multipoint_convolver
    implicit none
    private

    public :: point_matrix, wrap_point, lent_point, lend_point

    !> A single-point convolver as a 1 x 1 Green's matrix.
    type, extends(multipoint_convolver) :: point_matrix
        !> The single-point engine.
        class(convolver), allocatable :: point
    contains
        procedure :: history => point_history
        procedure :: push => point_push
        procedure :: clear => point_clear
        procedure :: release => point_release
    end type point_matrix

    !> A single-point convolver lent as a 1 x 1 Green's matrix for the length of a call (a
    !> single-point contact run on the multi-point loop): a `point_matrix` that borrows its
    !> engine where `point_matrix` owns it, the same arithmetic on it.
    type, extends(multipoint_convolver) :: lent_point
        !> The caller's engine.
        class(convolver), pointer :: point => null()
    contains
        procedure :: history => lent_history
        procedure :: push => lent_push
        procedure :: clear => lent_clear
    end type lent_point

contains

    !> Wrap a single-point convolver (moved in, unallocated on return) as a 1 x 1 matrix
    !> with its name, step, dt, valid steps and W0 = [w0].
    subroutine wrap_point(point, matrix)
        !> The single-point convolver; moved into `matrix`.
        class(convolver), allocatable, intent(inout) :: point
        !> The 1 x 1 convolver.
        type(point_matrix), intent(out) :: matrix

        call take_model(point, matrix)
        call move_alloc(point, matrix%point)
    end subroutine wrap_point

    !> Lend a single-point convolver (it must outlive `matrix`) as a 1 x 1 matrix with its
    !> name, step, dt, valid steps and W0 = [w0].
    subroutine lend_point(point, matrix)
        !> The single-point convolver; `matrix` points to it.
        class(convolver), intent(in), target :: point
        !> The 1 x 1 convolver on it.
        type(lent_point), intent(out) :: matrix

        call take_model(point, matrix)
        matrix%point => point
    end subroutine lend_point

    !> Give a 1 x 1 matrix the engine's name, step, dt, valid steps and W0 = [w0].
    subroutine take_model(point, matrix)
        class(convolver), intent(in) :: point
        class(multipoint_convolver), intent(inout) :: matrix

        character(len=:), allocatable :: label
        integer :: n

        call point%model_size(n, label)
        call matrix%set_model(point%name, point%dt, n, label)
        matrix%step = point%step
        matrix%valid_steps = point%valid_steps
        call matrix%set_instant_matrix(reshape([point%instant_weight()], [1, 1]))
    end subroutine take_model

    !> Push the force [N] of the one point to the engine (halved at step 0) and take its step.
    subroutine push_point(matrix, point, forces)
        class(multipoint_convolver), intent(inout) :: matrix
        class(convolver), intent(inout) :: point
        real(dp), intent(in) :: forces(:)

        real(dp) :: load(1)

        load = matrix%recorded_load(forces(1:1))
        call point%push(load(1))
        matrix%step = point%step
    end subroutine push_point

    !> u_h(n) [m] of the engine, at the one point.
    subroutine point_history(self, u)
        class(point_matrix), intent(in) :: self
        real(dp), intent(out) :: u(:)

        u(1) = self%point%history()
    end subroutine point_history

    !> Push the force [N] of the one point and advance.
    subroutine point_push(self, forces)
        class(point_matrix), intent(inout) :: self
        real(dp), intent(in) :: forces(:)

        call push_point(self, self%point, forces)
    end subroutine point_push

    !> The engine back to step 0.
    subroutine point_clear(self)
        class(point_matrix), intent(inout) :: self

        call self%point%reset()
    end subroutine point_clear

    !> Release what the engine holds outside Fortran (FFTW plans).
    subroutine point_release(self)
        class(point_matrix), intent(inout) :: self

        if (allocated(self%point)) call self%point%release()
    end subroutine point_release

    !> u_h(n) [m] of the lent engine, at the one point.
    subroutine lent_history(self, u)
        class(lent_point), intent(in) :: self
        real(dp), intent(out) :: u(:)

        u(1) = self%point%history()
    end subroutine lent_history

    !> Push the force [N] of the one point to the lent engine and advance.
    subroutine lent_push(self, forces)
        class(lent_point), intent(inout) :: self
        real(dp), intent(in) :: forces(:)

        call push_point(self, self%point, forces)
    end subroutine lent_push

    !> The lent engine back to step 0.
    subroutine lent_clear(self)
        class(lent_point), intent(inout) :: self

        call self%point%reset()
    end subroutine lent_clear

end module greenconv_conv_point_matrix
