!> The one place a method of the registry (greenconv_conv_methods) is turned into the engine
!> that steps it: `engine_of` gives a method's constructors and what the builder must know of
!> it, and nobody else tells the methods apart. The builder (greenconv_conv_builder) and the
!> Green's-file builder (greenconv_conv_green_file) call what it gives.
!>
!> Each method names how it is built: on the sampled g, its kind `on_sampled_g` (the direct sum
!> or the partitioned FFT), which `on_kernel` (one point) and `on_table` (a table g_ij, several
!> points) turn into an engine; on modes, `recursion` (a decaying recursion, which also steps
!> the modal Green's matrix of several points) or the paper's own recursion
!> (`paper_recursion`), which `on_modes` and `on_point_modes` build for one or several points.
!> The registry's `check_method` refuses a kind of contact a method does not serve before any
!> constructor is called. Adding an engine: its module, its row in the registry, and its
!> `case` in `engine_of` (for a decaying modal recursion, its constructor; for one more kind of
!> convolution with the sampled g, its kind and its branch in `on_kernel` and `on_table`).
module greenconv_conv_engines
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_model_modal_set, only: modal_set
    use greenconv_model_point_modes, only: point_modes
    use greenconv_conv_methods, only: method_scheme, scheme_direct, scheme_fft, scheme_paper, scheme_rectangle, &
                                      scheme_first_order, scheme_backward, scheme_auto
    use greenconv_conv_convolver, only: convolver
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_direct, only: new_direct_convolver
    use greenconv_conv_fft, only: new_fft_convolver
    use greenconv_conv_paper, only: new_paper_convolver
    use greenconv_conv_recursive, only: recursive_convolver, new_recursive_convolver, new_exact_convolver, &
                                        new_backward_convolver
    use greenconv_conv_green_modal, only: modal_green_matrix, modal_green_matrix_on
    use greenconv_conv_green_sampled, only: sampled_green_matrix, new_sampled_green_matrix
    use greenconv_conv_green_fft, only: fft_green_matrix, new_fft_green_matrix
    implicit none
    private

    public :: engine_constructors, engine_of
    public :: recursion_constructor
    public :: kernel_none, kernel_direct, kernel_partitioned

    !> How a method convolves with a sampled g: it does not (a modal method).
    integer, parameter :: kernel_none = 0
    !> ... by the direct sum of eq. (5) (`direct`).
    integer, parameter :: kernel_direct = 1
    !> ... by the partitioned FFT (`fft`).
    integer, parameter :: kernel_partitioned = 2

    abstract interface
        !> A decaying modal recursion (greenconv_conv_recursive), the single-point engine that a
        !> multi-point one on the same modes holds.
        function recursion_constructor(modes, dt) result(conv)
            import :: dp, modal_set, recursive_convolver
            !> The Green's function as modes (Re lambda_k <= 0).
            type(modal_set), intent(in) :: modes
            !> Time step [s].
            real(dp), intent(in) :: dt
            !> The recursion, at step 0.
            type(recursive_convolver) :: conv
        end function recursion_constructor
    end interface

    !> What builds a method, and what its builder must know of it.
    type :: engine_constructors
        !> How the method convolves with the sampled g (`kernel_direct` for `direct`,
        !> `kernel_partitioned` for `fft`), `kernel_none` when it runs on modes.
        integer :: on_sampled_g = kernel_none
        !> Whether the method is the paper's own recursion of eqs. (15)-(17) on modes (`paper`),
        !> single-point only, which is no decaying recursion.
        logical :: paper_recursion = .false.
        !> The decaying recursion (`recursive`, `exact`, `backward`): single-point on modes, and
        !> the engine of the multi-point one on modes and shapes; else unassociated.
        procedure(recursion_constructor), pointer, nopass :: recursion => null()
        !> Whether the method picks another one instead of stepping (`auto`).
        logical :: chooses = .false.
        !> Whether its multi-point step has an instantaneous part W0 /= 0 (the first-order
        !> hold, stepped implicitly by Newton on the active set).
        logical :: instant_part = .false.
    contains
        !> Whether the method runs on the sampled g (one point) or on a table g_ij (several).
        procedure :: samples_g
        !> Build the single-point engine on a sampled kernel.
        procedure :: on_kernel
        !> Build the multi-point engine on a table g_ij.
        procedure :: on_table
        !> Build the single-point engine on modes.
        procedure :: on_modes
        !> Build the multi-point engine on modes and mode shapes.
        procedure :: on_point_modes
    end type engine_constructors

contains

    !> The constructors of a method of the registry (aliases resolved); none for `auto`
    !> (`chooses`) and for an unknown name.
    function engine_of(method) result(engine)
        !> A method name.
        character(len=*), intent(in) :: method
        type(engine_constructors) :: engine

        select case (method_scheme(method))
        case (scheme_direct)
            engine%on_sampled_g = kernel_direct
        case (scheme_fft)
            engine%on_sampled_g = kernel_partitioned
        case (scheme_paper)
            engine%paper_recursion = .true.
        case (scheme_rectangle)
            engine%recursion => new_recursive_convolver
        case (scheme_first_order)
            engine%recursion => new_exact_convolver
            engine%instant_part = .true.
        case (scheme_backward)
            engine%recursion => new_backward_convolver
        case (scheme_auto)
            engine%chooses = .true.
        end select
    end function engine_of

    !> Whether the method runs on the sampled g (`direct`, `fft`), not on modes.
    elemental logical function samples_g(self)
        !> The method's constructors.
        class(engine_constructors), intent(in) :: self

        samples_g = self%on_sampled_g /= kernel_none
    end function samples_g

    !> The single-point engine of a method on the sampled g (`direct` or `fft`).
    subroutine on_kernel(self, kernel, dt, valid, conv)
        !> The method's constructors (`samples_g`).
        class(engine_constructors), intent(in) :: self
        !> The kernel w_j = g(t_j) [m/(N*s)], j = 0..N_g.
        real(dp), intent(in) :: kernel(0:)
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Number of steps the kernel is valid for (huge when it holds the whole of g).
        integer(int64), intent(in) :: valid
        !> The convolver, at step 0.
        class(convolver), allocatable, intent(out) :: conv

        if (self%on_sampled_g == kernel_partitioned) then
            conv = new_fft_convolver(kernel, dt, valid_steps=valid)
        else
            conv = new_direct_convolver(kernel, dt, valid)
        end if
    end subroutine on_kernel

    !> The multi-point engine of a method on a table kernel(m, i, j) = g_ij(m*dt) [m/(N*s)]:
    !> the sampled table (`direct`) or the table by partitioned FFT (`fft`).
    subroutine on_table(self, kernel, dt, conv, error)
        !> The method's constructors (`samples_g`).
        class(engine_constructors), intent(in) :: self
        !> The table g_ij(t_m) [m/(N*s)].
        real(dp), intent(in) :: kernel(0:, :, :)
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> The convolver, at step 0.
        class(multipoint_convolver), allocatable, intent(out) :: conv
        !> Set when the table does not make a convolver.
        type(error_type), allocatable, intent(out) :: error

        type(sampled_green_matrix) :: sampled
        type(fft_green_matrix) :: partitioned

        if (self%on_sampled_g == kernel_partitioned) then
            call new_fft_green_matrix(kernel, dt, partitioned, error)
            if (.not. allocated(error)) allocate (conv, source=partitioned)
        else
            call new_sampled_green_matrix(kernel, dt, sampled, error)
            if (.not. allocated(error)) allocate (conv, source=sampled)
        end if
    end subroutine on_table

    !> The single-point engine of a modal method: its recursion, or its own constructor (`paper`).
    subroutine on_modes(self, modes, dt, conv)
        !> The method's constructors (a modal method's).
        class(engine_constructors), intent(in) :: self
        !> The Green's function as modes.
        type(modal_set), intent(in) :: modes
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> The convolver, at step 0.
        class(convolver), allocatable, intent(out) :: conv

        if (associated(self%recursion)) then
            conv = self%recursion(modes, dt)
        else
            conv = new_paper_convolver(modes, dt)
        end if
    end subroutine on_modes

    !> The multi-point engine of a decaying recursion: the modal Green's matrix
    !> (greenconv_conv_green_modal) holding the recursion over the same modes.
    subroutine on_point_modes(self, modes, dt, conv, error)
        !> The method's constructors (a decaying recursion's).
        class(engine_constructors), intent(in) :: self
        !> Modes and mode shapes at the points.
        type(point_modes), intent(in) :: modes
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> The convolver, at step 0.
        class(multipoint_convolver), allocatable, intent(out) :: conv
        !> Set when the mode shapes do not match the modes.
        type(error_type), allocatable, intent(out) :: error

        type(modal_green_matrix) :: modal

        call modal_green_matrix_on(modes, dt, self%recursion(modes%modes, dt), modal, error)
        if (.not. allocated(error)) allocate (conv, source=modal)
    end subroutine on_point_modes

end module greenconv_conv_engines
