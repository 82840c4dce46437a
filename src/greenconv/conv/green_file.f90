!> Multi-point convolvers from a universal file of a Green's matrix (issue 14): the library
!> entry the scene (`&structure model = 'green_file'`) and the front doors build on.
!>
!> - `new_green_file_convolver`: one call, file in, convolver and report out: read the file,
!>   identify its receptances with shared poles (greenconv_ident_green_structure), build the
!>   method asked and say what it neglects. For several methods on one file, read it once
!>   with `read_green_structure` and call `green_file_convolver` per method.
!> - `green_file_convolver`: one method on a structure already read:
!>   - `modal`/`recursive` (the rectangle rule, explicit: W0 = 0) runs on the identified modes
!>     alone (greenconv_conv_builder's `make_multipoint_convolver`); its accuracy is E of
!>     eq. (7) of the modes alone against the file's receptances, worst and mean;
!>   - `exact` (first-order hold, implicit) runs on the same modes and adds the fit's upper
!>     residual U to its instant matrix W0: U, constant in frequency, is an impulse U*delta(t)
!>     in g_ij, all of it in the current step's displacement. Its accuracy is E of the modes
!>     with U. (A lower residual -L/omega^2 has no place in either and is left out.)
!>   - `direct` and `fft` run on g_ij(t_m) from the file itself when the time step allows it
!>     (the inverse FFT of the receptances, or the file's impulse responses: `sampled_kernel`),
!>     truncated by the paper's rule; their accuracy says where g came from, the neglected tail,
!>     and how far the identified model's g_ij by the same inverse FFT is from it (max
!>     |difference|/max |g_ij| over the table: the fit's misfit, the band limit being the same).
!>     When dt does not fit the receptances' grid, g_ij is sampled from the identified modes
!>     instead, and the accuracy says so and why.
module greenconv_conv_green_file
    use greenconv_core_kinds, only: dp
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_conv_methods, only: check_method, default_truncation_tol
    use greenconv_conv_engines, only: engine_constructors, engine_of
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_builder, only: make_multipoint_convolver, table_convolver
    use greenconv_ident_green_structure, only: green_options, green_structure, read_green_structure, sampled_kernel
    implicit none
    private

    public :: green_file_options, green_file_report, new_green_file_convolver, green_file_convolver

    !> Settings of `new_green_file_convolver`.
    type :: green_file_options
        !> The identification of the receptances (pole fit settings, e.g. `identification%fit%max_order`).
        type(green_options) :: identification
        !> Truncation fraction of max |g_ij| for `direct` and `fft`, in (0, 1).
        real(dp) :: truncation_tol = default_truncation_tol
    end type green_file_options

    !> What `new_green_file_convolver` built, for the caller and its user.
    type :: green_file_report
        !> Node label of each contact point, in the order of the convolver's points.
        integer, allocatable :: node(:)
        !> Position of each point along the travel x_i [m] (from the file's coordinates).
        real(dp), allocatable :: x(:)
        !> Position of each point across y_i [m].
        real(dp), allocatable :: y(:)
        !> The file, its points, the identification (E per receptance and point, worst
        !> uncertainty) and the modes, in "# " lines joined by line ends.
        character(len=:), allocatable :: summary
        !> What the convolver's model neglects, in one line.
        character(len=:), allocatable :: accuracy
        !> Model size of the convolver (N_m modes or N_g samples) and its label.
        integer :: model_size = 0
        !> `N_m` or `N_g`.
        character(len=:), allocatable :: size_label
        !> E of eq. (7) of the identified modes alone against the file, worst and mean over the
        !> receptances (0 for a file of impulse responses).
        real(dp) :: e_worst = 0.0_dp, e_mean = 0.0_dp
    end type green_file_report

contains

    !> Build a multi-point convolver from a universal file of a Green's matrix: receptances
    !> G_ij(f) (identified with shared poles) or impulse responses g_ij(t) (`direct`, `fft`
    !> only). See the module description for what each method runs on.
    subroutine new_green_file_convolver(path, method, dt, n_steps, conv, report, error, options)
        !> The universal file (nodes in dataset 15 or 2411, datasets 58 of function type 4 or 1).
        character(len=*), intent(in) :: path
        !> Method, one of greenconv_conv_methods's `method_list(multi_point=.true.)`.
        character(len=*), intent(in) :: method
        !> Time step dt [s], > 0.
        real(dp), intent(in) :: dt
        !> Number of steps N_t of the run, >= 1 (caps the table of `direct` and `fft`).
        integer, intent(in) :: n_steps
        !> The convolver at step 0; release it with its `release` before dropping it.
        class(multipoint_convolver), allocatable, intent(out) :: conv
        !> The points, the identification and the model, in words and numbers.
        type(green_file_report), intent(out) :: report
        !> Set (status 2) for a bad file or request, status 3 when the identification fails.
        type(error_type), allocatable, intent(out) :: error
        !> Settings; defaults when absent.
        type(green_file_options), intent(in), optional :: options

        type(green_file_options) :: settings
        type(green_structure) :: structure

        if (present(options)) settings = options
        if (.not. (dt > 0.0_dp .and. dt < huge(dt))) then
            call fatal_error(error, 'new_green_file_convolver: the time step dt must be finite and > 0 s')
        else if (n_steps < 1) then
            call fatal_error(error, 'new_green_file_convolver: the number of steps must be >= 1')
        else if (.not. (settings%truncation_tol > 0.0_dp .and. settings%truncation_tol < 1.0_dp)) then
            call fatal_error(error, 'new_green_file_convolver: truncation_tol must be in (0, 1)')
        end if
        if (allocated(error)) return
        call check_method(method, .true., .true., .true., error)
        if (allocated(error)) return
        call read_green_structure(path, settings%identification, structure, error)
        if (allocated(error)) return
        call green_file_convolver(structure, method, dt, settings%truncation_tol, n_steps, conv, report%accuracy, &
                                  error)
        if (allocated(error)) return
        report%node = structure%matrix%node
        report%x = structure%matrix%x
        report%y = structure%matrix%y
        report%summary = structure%summary()
        call conv%model_size(report%model_size, report%size_label)
        if (structure%identified) then
            report%e_worst = maxval(structure%e_modes)
            report%e_mean = sum(structure%e_modes)/size(structure%e_modes)
        end if
    end subroutine new_green_file_convolver

    !> Build one method on a Green's matrix read by `read_green_structure` (see the module
    !> description); `accuracy` says in words what the model neglects.
    subroutine green_file_convolver(structure, method, dt, truncation_tol, n_steps, conv, accuracy, error)
        !> The structure.
        type(green_structure), intent(in) :: structure
        !> Method, one of greenconv_conv_methods's `method_list(multi_point=.true.)`.
        character(len=*), intent(in) :: method
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Truncation fraction of max |g_ij| for `direct` and `fft`.
        real(dp), intent(in) :: truncation_tol
        !> Number of steps of the run.
        integer, intent(in) :: n_steps
        !> The convolver, at step 0.
        class(multipoint_convolver), allocatable, intent(out) :: conv
        !> What the model neglects, in words.
        character(len=:), allocatable, intent(out) :: accuracy
        !> Set for a method that does not serve multi-point contact or this structure, or a dt
        !> that does not fit the file's impulse responses.
        type(error_type), allocatable, intent(out) :: error

        type(engine_constructors) :: engine
        real(dp), allocatable :: kernel(:, :, :), fitted(:, :, :)
        character(len=:), allocatable :: source, text

        accuracy = ''
        call check_method(method, .true., .true., structure%identified, error)
        if (allocated(error)) return
        engine = engine_of(method)
        if (engine%samples_g()) then
            call sampled_kernel(structure, dt, kernel, source, error, fitted)
            if (allocated(error)) return
            if (allocated(kernel)) then
                call table_convolver(method, kernel, dt, truncation_tol, n_steps, conv, text, error, fitted)
                if (allocated(error)) return
                accuracy = source//'; '//text
                return
            end if
            call make_multipoint_convolver(method, structure%modes, dt, truncation_tol, n_steps, conv, text, error)
            if (allocated(error)) return
            accuracy = 'g_ij sampled from the identified modes ('//source//'); '//text//'; ' &
                       //modes_accuracy(structure, .false.)
            return
        end if
        call make_multipoint_convolver(method, structure%modes, dt, truncation_tol, n_steps, conv, text, error)
        if (allocated(error)) return
        accuracy = text//'; '//modes_accuracy(structure, .false.)
        ! The fit's upper residual U is an impulse U*delta(t) in g_ij: the first-order hold puts
        ! all of it in the current step's displacement, W0.
        if (engine%instant_part .and. structure%fit%pole_fit%has_upper) then
            call conv%set_instant_matrix(conv%weight0 + structure%fit%upper)
            accuracy = text//', the fit''s upper residual U added to W0; '//modes_accuracy(structure, .true.)
        end if
    end subroutine green_file_convolver

    !> `modes_accuracy` built into an allocatable (see greenconv_core_text on static string lengths).
    pure subroutine modes_accuracy_build(structure, with_upper, text)
        type(green_structure), intent(in) :: structure
        logical, intent(in) :: with_upper
        character(len=:), allocatable, intent(out) :: text

        text = int_text(structure%modes%modes%n_modes())//' terms of '//int_text(size(structure%fit%pole)) &
               //' shared poles, E of the modes alone worst '//sci_text(maxval(structure%e_modes))//', mean ' &
               //sci_text(sum(structure%e_modes)/size(structure%e_modes))//' (eq. 7)'
        if (with_upper .and. structure%fit%pole_fit%has_upper) &
            text = int_text(structure%modes%modes%n_modes())//' terms of '//int_text(size(structure%fit%pole)) &
                   //' shared poles and U, E worst '//sci_text(maxval(structure%e_upper))//', mean ' &
                   //sci_text(sum(structure%e_upper)/size(structure%e_upper))//' (eq. 7)'
    end subroutine modes_accuracy_build

    !> Length of the text `modes_accuracy` gives.
    pure integer function modes_accuracy_length(structure, with_upper)
        type(green_structure), intent(in) :: structure
        logical, intent(in) :: with_upper

        character(len=:), allocatable :: built

        call modes_accuracy_build(structure, with_upper, built)
        modes_accuracy_length = len(built)
    end function modes_accuracy_length

    !> "N terms of K shared poles, E of the modes alone worst ..., mean ... (eq. 7)", or of the
    !> modes with the upper residual.
    pure function modes_accuracy(structure, with_upper) result(text)
        type(green_structure), intent(in) :: structure
        logical, intent(in) :: with_upper
        character(len=modes_accuracy_length(structure, with_upper)) :: text

        character(len=:), allocatable :: built

        call modes_accuracy_build(structure, with_upper, built)
        text = built
    end function modes_accuracy

end module greenconv_conv_green_file
