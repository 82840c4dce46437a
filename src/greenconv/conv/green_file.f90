!> Multi-point convolvers from a universal file of a Green's matrix: the library
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
!>     Lines above the file's f_max that dt asks for (up to 1/(2*dt)) hold the identified model
!>     rather than zero (`extend_band`): the response above the band is the model's.
!>     When dt does not fit the receptances' grid, or the grid is not the uniform grid from
!>     0 Hz the inverse FFT needs (a file whose lines start above 0 Hz, or uneven lines: the
!>     FFT would put line l at l*df), g_ij is sampled from the identified modes instead, the
!>     fit's upper residual U added to W0, and the accuracy says so, why, and on which band the
!>     modes were fitted.
module greenconv_conv_green_file
    use greenconv_core_kinds, only: dp
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_conv_methods, only: check_method, default_truncation_tol
    use greenconv_conv_engines, only: engine_constructors, engine_of
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_builder, only: make_multipoint_convolver, table_convolver
    use greenconv_conv_kernel, only: period_end_level
    use greenconv_model_frf, only: frf_type
    use greenconv_ident_green_structure, only: green_options, green_structure, read_green_structure, sampled_kernel, &
                                               summary_text
    use greenconv_ident_shared_poles, only: shared_receptance
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
        call summary_text(structure, report%summary)
        call conv%model_size(report%model_size, report%size_label)
        if (structure%identified) then
            report%e_worst = maxval(structure%e_modes)
            report%e_mean = mean_e(structure%e_modes)
        end if
    end subroutine new_green_file_convolver

    !> Build one method on a Green's matrix read by `read_green_structure` (see the module
    !> description); `accuracy` says in words what the model neglects.
    subroutine green_file_convolver(structure, method, dt, truncation_tol, n_steps, conv, accuracy, error, estimate)
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
        !> The method's own estimate of its relative error, to compare with an accuracy asked:
        !> for the modes (`modal`, `exact`, and `direct`/`fft` sampled from them) the mean E of
        !> eq. (7) over the receptances of the model they run on (with U when it is in W0); for
        !> g_ij by the inverse FFT of the file, the larger of what is left at the end of its
        !> period (wrap-around, `period_end_level`) and what the band leaves out (`extend_band`);
        !> 0 for a file of impulse responses (their truncation is the one asked).
        real(dp), intent(out), optional :: estimate

        type(engine_constructors) :: engine
        real(dp), allocatable :: kernel(:, :, :), fitted(:, :, :), row_max(:)
        character(len=:), allocatable :: source, text, band
        type(green_structure) :: extended
        real(dp) :: own, outside
        integer :: m
        logical :: with_upper

        accuracy = ''
        own = 0.0_dp
        outside = 0.0_dp
        if (present(estimate)) estimate = 0.0_dp
        call check_method(method, .true., .true., structure%identified, error)
        if (allocated(error)) return
        engine = engine_of(method)
        if (engine%samples_g()) then
            call grid_problem(structure, source)
            if (len(source) == 0) then
                call extend_band(structure, dt, extended, band, outside)
                call sampled_kernel(extended, dt, kernel, source, error, fitted)
                if (allocated(kernel)) source = source//band
            end if
            if (allocated(error)) return
            if (allocated(kernel)) then
                call table_convolver(method, kernel, dt, truncation_tol, n_steps, conv, text, error, fitted)
                if (allocated(error)) return
                accuracy = source//'; '//text
                if (structure%identified) then
                    row_max = [(maxval(abs(kernel(m, :, :))), m=lbound(kernel, 1), ubound(kernel, 1))]
                    own = max(period_end_level(row_max), outside)
                end if
                if (present(estimate)) estimate = own
                return
            end if
        end if
        call make_multipoint_convolver(method, structure%modes, dt, truncation_tol, n_steps, conv, text, error)
        if (allocated(error)) return
        ! The fit's upper residual U is an impulse U*delta(t) in g_ij: the first-order hold puts
        ! all of it in the current step's displacement, W0 (g_ij sampled from the modes too).
        with_upper = structure%fit%pole_fit%has_upper .and. (engine%samples_g() .or. engine%instant_part)
        if (with_upper) call conv%set_instant_matrix(conv%weight0 + structure%fit%upper)
        if (engine%samples_g() .and. with_upper) then
            accuracy = 'g_ij sampled from the identified modes, U in W0 ('//source//'); '//text//'; '
        else if (engine%samples_g()) then
            accuracy = 'g_ij sampled from the identified modes ('//source//'); '//text//'; '
        else if (with_upper) then
            accuracy = text//', the fit''s upper residual U added to W0; '
        else
            accuracy = text//'; '
        end if
        call modes_accuracy(structure, with_upper, text)
        accuracy = accuracy//text
        own = mean_e(structure%e_modes)
        if (with_upper) own = mean_e(structure%e_upper)
        if (present(estimate)) estimate = own
    end subroutine green_file_convolver

    !> Mean of the E (eq. 7) of the receptances (0 when there are none: not identified).
    pure real(dp) function mean_e(e)
        real(dp), allocatable, intent(in) :: e(:, :)

        mean_e = 0.0_dp
        if (.not. allocated(e)) return
        if (size(e) > 0) mean_e = sum(e)/size(e)
    end function mean_e

    !> What the file's band leaves out, from the identified model: the inverse FFT of G on the
    !> file's lines, zero above f_max up to the Nyquist frequency 1/(2*dt), gives g_ij
    !> band-limited to the file's band, so a force's response above f_max (the tails of the
    !> modes in band and the quasi-static compliance U of those above it) would be lost. The
    !> copy `extended` holds the file's lines and, above f_max up to 1/(2*dt) on the same step,
    !> the identified model (shared poles and U), so that the same inverse FFT gives g_ij whose
    !> spectrum is the data in band and the model above it. Not extended (and `note` says why or
    !> is '') when dt needs no line above f_max, or the fit has a lower residual (-L/omega^2,
    !> fitted to the band alone) or the grid is not the uniform grid from 0 Hz.
    !>
    !> `outside` estimates what the band leaves out, relative to g_ij: the share of the model's
    !> spectrum above f_max in the whole, s = sqrt(sum_above |G_model|^2 / (sum_file |G|^2 +
    !> sum_above |G_model|^2)) over all i, j (Parseval: the share of g_ij's energy from above the
    !> band); when the model fills the band above f_max, its error there, s times the mean E
    !> (eq. 7) of the model in the band (with U when the fit has it); when G stays zero above,
    !> s itself. 0 when dt needs no line above f_max.
    subroutine extend_band(structure, dt, extended, note, outside)
        type(green_structure), intent(in) :: structure
        real(dp), intent(in) :: dt
        type(green_structure), intent(out) :: extended
        character(len=:), allocatable, intent(out) :: note
        real(dp), intent(out) :: outside

        complex(dp), allocatable :: model(:, :, :)
        real(dp), allocatable :: above(:)
        real(dp) :: df, f_max, share
        integer :: n_f, n_lines, l

        extended = structure
        note = ''
        outside = 0.0_dp
        if (.not. structure%identified) return
        n_f = size(structure%matrix%frequency)
        df = structure%matrix%frequency(2) - structure%matrix%frequency(1)
        f_max = structure%matrix%frequency(n_f)
        n_lines = nint(1.0_dp/(df*dt))/2 + 1
        if (n_lines <= n_f) return
        above = [(l*df, l=n_f, n_lines - 1)]
        call shared_receptance(structure%fit, above, model)
        share = sum(abs(model)**2)
        if (share > 0.0_dp) share = sqrt(share/(share + sum(abs(structure%matrix%g)**2)))
        if (structure%fit%pole_fit%has_lower) then
            note = '; G zero above the band (the fit has a lower residual), which leaves out about ' &
                   //sci_text(share)//' of g_ij'
            outside = share
            return
        end if
        outside = share*mean_e(structure%e_modes)
        if (structure%fit%pole_fit%has_upper) outside = share*mean_e(structure%e_upper)
        extended%matrix%frequency = [structure%matrix%frequency, above]
        deallocate (extended%matrix%g)
        allocate (extended%matrix%g(size(model, 1), size(model, 2), n_lines))
        extended%matrix%g(:, :, 1:n_f) = structure%matrix%g
        extended%matrix%g(:, :, n_f + 1:) = model
        note = '; G from '//sci_text(f_max)//' Hz (the file''s last line) to '//sci_text(above(size(above))) &
               //' Hz from the identified poles'//trim(merge(' and U', '      ', structure%fit%pole_fit%has_upper))
    end subroutine extend_band

    !> Why the inverse FFT of the file's receptances cannot give g_ij: their lines are not the
    !> uniform grid from 0 Hz (a band starting above 0 Hz, or uneven lines), on which the FFT
    !> would put line l at l*df and so at a frequency it does not have; '' when they are (or
    !> for a file of impulse responses). The text names the band the modes were fitted on.
    subroutine grid_problem(structure, text)
        type(green_structure), intent(in) :: structure
        character(len=:), allocatable, intent(out) :: text

        type(frf_type) :: grid

        text = ''
        if (.not. structure%identified) return
        grid%frequency = structure%matrix%frequency
        text = grid%fft_grid_problem()
        if (len(text) == 0) return
        text = 'not from the inverse FFT of G: '//text//'; the modes are fitted on the file''s band ' &
               //sci_text(grid%frequency(1))//' to '//sci_text(grid%f_max())//' Hz ('//int_text(grid%n_freq()) &
               //' lines), g_ij outside it is the modes'' extrapolation'
    end subroutine grid_problem

    !> "N terms of K shared poles, E of the modes alone worst ..., mean ... (eq. 7)", or of the
    !> modes with the upper residual.
    subroutine modes_accuracy(structure, with_upper, text)
        type(green_structure), intent(in) :: structure
        logical, intent(in) :: with_upper
        character(len=:), allocatable, intent(out) :: text

        text = int_text(structure%modes%modes%n_modes())//' terms of '//int_text(size(structure%fit%pole)) &
               //' shared poles, E of the modes alone worst '//sci_text(maxval(structure%e_modes))//', mean ' &
               //sci_text(mean_e(structure%e_modes))//' (eq. 7)'
        if (with_upper .and. structure%fit%pole_fit%has_upper) &
            text = int_text(structure%modes%modes%n_modes())//' terms of '//int_text(size(structure%fit%pole)) &
                   //' shared poles and U, E worst '//sci_text(maxval(structure%e_upper))//', mean ' &
                   //sci_text(mean_e(structure%e_upper))//' (eq. 7)'
    end subroutine modes_accuracy

end module greenconv_conv_green_file
