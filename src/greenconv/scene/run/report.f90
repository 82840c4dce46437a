!> What an identification reports: a summary on the terminal (order, noise, uncertainty,
!> E of eq. 7, CPU time, poles dropped, warnings) and column files of the modes (with their
!> standard deviations for the maximum-likelihood fit), of G against its fit and residual,
!> and of the stabilisation diagram.
module greenconv_scene_run_report
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_model_modal_set, only: modal_set
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_ident_lsce, only: paper_form
    use greenconv_ident_mlfit, only: ml_result, dropped_by_criterion, dropped_left_band, dropped_degenerate, &
                                     dropped_boundary
    use greenconv_io_files, only: write_columns
    use greenconv_scene_read_facade, only: scene_type
    use greenconv_ident_structure, only: structure_model
    use greenconv_ident_methods, only: ident_ml
    implicit none
    private

    public :: identification_summary, write_identification

    !> 2*pi
    real(dp), parameter :: two_pi = 2.0_dp*acos(-1.0_dp)

contains

    !> The identification in a few `#` lines (separated by new_line('a')), for the caller to
    !> print: where G came from (a universal file), the order, noise, worst uncertainty, E and
    !> CPU time, dropped poles, warnings.
    pure subroutine identification_summary(structure, text)
        !> The identified structure.
        type(structure_model), intent(in) :: structure
        !> The lines.
        character(len=:), allocatable, intent(out) :: text

        character(len=400) :: buffer

        text = ''
        if (allocated(structure%frf%source)) then
            if (len(structure%frf%source) > 0) call add_line(text, '# receptance: '//structure%frf%source)
        end if
        if (structure%method == ident_ml) then
            call ml_summary(structure, text)
            return
        end if
        associate (fit => structure%fit)
            write (buffer, '(a,i0,a,i0,a,i0,a,es9.2,a,l1)') '# identification: LSCE order 2N = ', 2*fit%order_modes, &
                ' (N = ', fit%order_modes, '), ', fit%modes%n_modes(), ' modes, E = ', fit%e, &
                ' (eq. 7), target met: ', fit%tolerance_met
            call add_line(text, trim(buffer))
            write (buffer, '(a,i0,a,i0,a,i0,a)') '# poles dropped: ', fit%n_unstable, ' unstable (Re lambda >= 0), ', &
                fit%n_real, ' real, ', fit%n_not_stable, ' not stable across orders'
            call add_line(text, trim(buffer))
            if (allocated(fit%warning)) then
                if (len(fit%warning) > 0) call add_line(text, '# warning: '//fit%warning)
            end if
        end associate
    end subroutine identification_summary

    !> Append a line to a text of lines.
    pure subroutine add_line(text, line)
        character(len=:), allocatable, intent(inout) :: text
        character(len=*), intent(in) :: line

        if (len(text) > 0) text = text//new_line('a')
        text = text//line
    end subroutine add_line

    !> The maximum-likelihood fit in two to four lines, e.g.
    !>
    !>     # identification: maximum likelihood, 12 modes (order by MDL), noise 1.01E-02 of |G| (estimated
    !>     #   from the data), worst sigma_f/f = 1.26E-04, worst sigma_xi/xi = 1.75E-02, diagram to N = 30,
    !>     #   E = 8.95E-03 (eq. 7), CPU 9.70E-01 s
    pure subroutine ml_summary(structure, text)
        type(structure_model), intent(in) :: structure
        character(len=:), allocatable, intent(inout) :: text

        character(len=:), allocatable :: line
        integer :: k

        associate (ml => structure%ml)
            call ml%brief(line)
            call add_line(text, '# identification: maximum likelihood, '//line//', diagram to N = ' &
                //int_text(maxval([0, ml%diagram_order]))//', E = '//sci_text(ml%e)//' (eq. 7), CPU ' &
                //sci_text(structure%cpu_time)//' s')
            call add_line(text, '# residual: chi2/nu = '//sci_text(ml%chi_square/max(ml%dof, 1))//' ('// &
                trim(merge('explained by the noise    ', 'larger than the noise asks', ml%explained))//'), ' &
                //int_text(ml%n_start)//' start poles from the stabilisation diagram, '//int_text(ml%n_wandering) &
                //' wandering, '//int_text(ml%iterations)//' Levenberg-Marquardt iterations' &
                //trim(merge(', upper residual kept', '                     ', ml%has_upper)) &
                //trim(merge(', lower residual kept', '                     ', ml%has_lower)))
            if (size(ml%dropped_pole) > 0) then
                line = '# dropped:'
                do k = 1, size(ml%dropped_pole)
                    if (k > 1) line = line//';'
                    line = line//' '//sci_text(abs(ml%dropped_pole(k))/two_pi)//' Hz ('
                    call add_reason(line, ml%dropped_reason(k))
                    line = line//')'
                end do
                call add_line(text, line)
            end if
            if (allocated(ml%warning)) then
                if (len(ml%warning) > 0) call add_line(text, '# warning: '//ml%warning)
            end if
        end associate
    contains
        !> Append why a pole was dropped to `text`.
        pure subroutine add_reason(text, code)
            character(len=:), allocatable, intent(inout) :: text
            integer, intent(in) :: code

            select case (code)
            case (dropped_by_criterion)
                text = text//'its removal lowered MDL'
            case (dropped_left_band)
                text = text//'moved out of the band'
            case (dropped_degenerate)
                text = text//'singular information, merged'
            case (dropped_boundary)
                text = text//'narrowed to a single line, a spike'
            case default
                text = text//'code '//int_text(code)
            end select
        end subroutine add_reason
    end subroutine ml_summary

    !> Write `<name>_modes.dat` (identified), `<name>_modes_true.dat` (when the exact modes are
    !> known) and `<name>_frf.dat` (G and its fit on the identified grid).
    subroutine write_identification(scene, structure, error)
        !> The scene (output directory and name).
        type(scene_type), intent(in) :: scene
        !> The identified structure.
        type(structure_model), intent(in) :: structure
        !> Set when a file cannot be written.
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: stem

        stem = scene%output_dir//'/'//scene%name
        if (structure%method == ident_ml) then
            call write_ml_modes(stem//'_modes.dat', structure, error)
            if (allocated(error)) return
            call write_diagram(stem//'_diagram.dat', structure, error)
        else
            call write_modes(stem//'_modes.dat', 'modes identified by LSCE', structure%model, error)
        end if
        if (allocated(error)) return
        if (structure%has_exact) then
            call write_modes(stem//'_modes_true.dat', 'the structure''s own modes', structure%exact, error)
            if (allocated(error)) return
        end if
        call write_fit(stem//'_frf.dat', structure, error)
    end subroutine write_identification

    !> One row per mode: f [Hz], omega [rad/s], xi, Re r, Im r [m/(N*s)], A [1/kg], lost.
    subroutine write_modes(path, title, modes, error)
        character(len=*), intent(in) :: path, title
        type(modal_set), intent(in) :: modes
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: amplitude(:), omega(:), damping(:), lost(:)
        character(len=100) :: comments(6)

        call paper_form(modes, amplitude, omega, damping, lost)
        comments(1) = 'greenconv: '//title
        comments(2) = 'G(w) = sum_k r_k/(iw - l_k) + conj(r_k)/(iw - conj(l_k)), l_k = -xi_k w_k + i w_k sqrt(1-xi_k^2)'
        comments(3) = 'paper form, eq. (6): A_k/(w_k^2 - w^2 + 2i xi_k w w_k), A_k = -2 Im(l_k) Im(r_k)'
        comments(4) = 'lost = |Re r_k|/|r_k|, the part of r_k the paper form drops'
        comments(5) = 'units: Hz rad/s 1 m/(N*s) m/(N*s) 1/kg 1'
        comments(6) = 'f omega xi re_r im_r a_paper lost'
        call write_columns(path, comments, reshape([omega/two_pi, omega, damping, real(modes%residue, dp), &
                                                    aimag(modes%residue), amplitude, lost], &
                                                   [modes%n_modes(), 7]), error)
    end subroutine write_modes

    !> The maximum-likelihood modes: the columns of `write_modes` and the standard deviations
    !> sigma_f [Hz], sigma_xi and sigma_r [m/(N*s)] from the Fisher information.
    subroutine write_ml_modes(path, structure, error)
        character(len=*), intent(in) :: path
        type(structure_model), intent(in) :: structure
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: amplitude(:), omega(:), damping(:), lost(:), determined(:)
        character(len=:), allocatable :: comments(:), noise
        character(len=110) :: buffer
        integer :: width

        associate (ml => structure%ml, modes => structure%ml%modes)
            call paper_form(modes, amplitude, omega, damping, lost)
            determined = merge(1.0_dp, 0.0_dp, structure%ml%determined_modes())
            write (buffer, '(a,es10.3,a,es10.3,a)') 'noise level ', ml%noise_level_fit, ', upper residual ', &
                ml%upper_residual, ' m/N'
            call noise_line(ml, noise)
            width = max(110, len(noise))
            allocate (character(len=width) :: comments(10))
            comments(1) = 'greenconv: modes identified by maximum likelihood (order by MDL), with their standard ' &
                          //'deviations'
            comments(2) = 'G(w) = sum_k r_k/(iw - l_k) + conj(r_k)/(iw - conj(l_k)), l_k = -xi_k w_k + i w_k ' &
                          //'sqrt(1-xi_k^2)'
            comments(3) = 'paper form, eq. (6): A_k/(w_k^2 - w^2 + 2i xi_k w w_k), A_k = -2 Im(l_k) Im(r_k); ' &
                          //'lost = |Re r_k|/|r_k|'
            comments(4) = 'sigma_f, sigma_xi, sigma_r = sqrt(var Re r + var Im r): Fisher information at the optimum'
            comments(5) = 'determined: 1 when the data determine the mode, 0 for a pole of the fitted receptance ' &
                          //'they do not'
            comments(6) = int_text(count(determined > 0.0_dp))//' of '//int_text(modes%n_modes()) &
                          //' poles determined by the data'
            comments(7) = noise
            comments(8) = buffer
            comments(9) = 'units: Hz rad/s 1 m/(N*s) m/(N*s) 1/kg 1 Hz 1 m/(N*s) 1'
            comments(10) = 'f omega xi re_r im_r a_paper lost sigma_f sigma_xi sigma_r determined'
            call write_columns(path, comments, reshape([omega/two_pi, omega, damping, real(modes%residue, dp), &
                                                        aimag(modes%residue), amplitude, lost, ml%sigma_frequency, &
                                                        ml%sigma_damping, ml%sigma_residue, determined], &
                                                       [modes%n_modes(), 11]), error)
        end associate
    end subroutine write_ml_modes

    !> The noise model of the fit and why it was taken, for the modes file's header.
    pure subroutine noise_line(ml, line)
        type(ml_result), intent(in) :: ml
        character(len=:), allocatable, intent(out) :: line

        line = 'noise model '//trim(ml%noise_model)//' (as set, not chosen from the data)'
        if (allocated(ml%noise_choice)) then
            if (len(ml%noise_choice) > 0) line = 'noise model '//trim(ml%noise_model)//': '//ml%noise_choice
        end if
    end subroutine noise_line

    !> The stabilisation diagram: one row per pole of every order N, and the chosen modes as
    !> rows of order 0 with flag 3 (so one file draws both).
    subroutine write_diagram(path, structure, error)
        character(len=*), intent(in) :: path
        type(structure_model), intent(in) :: structure
        type(error_type), allocatable, intent(out) :: error

        character(len=110) :: comments(5)
        real(dp), allocatable :: table(:, :)
        integer :: n, m

        associate (ml => structure%ml)
            n = size(ml%diagram_order)
            m = ml%modes%n_modes()
            comments(1) = 'greenconv: stabilisation diagram of the linear LSCE step, N = 1..max_order modes'
            comments(2) = 'flag 2: f and xi stable against order N - 1, 1: f only, 0: neither; order 0: the ' &
                          //'fit''s poles, flag 3 determined, 4 not'
            comments(3) = 'chosen modes (order by MDL): '//int_text(count(structure%ml%determined_modes())) &
                          //' determined of '//int_text(m)
            comments(4) = 'units: 1 Hz 1 1'
            comments(5) = 'order f xi flag'
            allocate (table(n + m, 4))
            table(:n, 1) = ml%diagram_order
            table(:n, 2) = ml%diagram_frequency
            table(:n, 3) = ml%diagram_damping
            table(:n, 4) = ml%diagram_flag
            table(n + 1:, 1) = 0.0_dp
            table(n + 1:, 2) = abs(ml%modes%pole)/two_pi
            table(n + 1:, 3) = -real(ml%modes%pole, dp)/abs(ml%modes%pole)
            table(n + 1:, 4) = merge(3.0_dp, 4.0_dp, structure%ml%determined_modes())
            call write_columns(path, comments, table, error)
        end associate
    end subroutine write_diagram

    !> G and the fitted model on the identified grid: real and imaginary parts, magnitude
    !> and phase, for Fig. 4.
    subroutine write_fit(path, structure, error)
        character(len=*), intent(in) :: path
        type(structure_model), intent(in) :: structure
        type(error_type), allocatable, intent(out) :: error

        complex(dp), allocatable :: fitted(:)
        character(len=100) :: comments(4)

        allocate (fitted(structure%frf%n_freq()))
        associate (f => structure%frf%frequency, g => structure%frf%receptance)
            fitted(:) = structure%fitted(two_pi*f)
            if (structure%method == ident_ml) then
                call write_ml_fit(path, structure, fitted, error)
                return
            end if
            write (comments(1), '(a,es9.2,a)') 'greenconv: receptance G and its LSCE fit, E = ', structure%fit%e, &
                ' (eq. 7)'
            comments(2) = 'phase in degrees, in (-180, 180]'
            comments(3) = 'units: Hz m/N m/N m/N deg m/N m/N m/N deg'
            comments(4) = 'f re_g im_g abs_g phase_g re_fit im_fit abs_fit phase_fit'
            call write_columns(path, comments, fit_columns(f, g, fitted), error)
        end associate
    end subroutine write_fit

    !> G, the maximum-likelihood model, the residual |G - model| and the noise standard
    !> deviation of each line (the level times |model| for the relative noise model); the 0 Hz
    !> line is left out when the model has a lower residual term (infinite there).
    subroutine write_ml_fit(path, structure, fitted, error)
        character(len=*), intent(in) :: path
        type(structure_model), intent(in) :: structure
        complex(dp), intent(in) :: fitted(:)
        type(error_type), allocatable, intent(out) :: error

        character(len=120) :: comments(4)
        integer :: first

        first = merge(2, 1, structure%ml%has_lower)
        associate (f => structure%frf%frequency(first:), g => structure%frf%receptance(first:), &
                   model => fitted(first:), ml => structure%ml)
            write (comments(1), '(a,es9.2,a,es9.2,a)') 'greenconv: G, its maximum-likelihood fit (E = ', ml%e, &
                ', eq. 7), the residual and the noise (level ', ml%noise_level_fit, ')'
            comments(2) = 'phase in degrees, in (-180, 180]; sigma: noise standard deviation of the line'
            comments(3) = 'units: Hz m/N m/N m/N deg m/N m/N m/N deg m/N m/N'
            comments(4) = 'f re_g im_g abs_g phase_g re_fit im_fit abs_fit phase_fit abs_residual sigma'
            call write_columns(path, comments, reshape([fit_columns(f, g, model), abs(g - model), &
                                                        ml%noise_level_fit*abs(model)], [size(f), 11]), error)
        end associate
    end subroutine write_ml_fit

    !> The columns f, Re G, Im G, |G|, phase of G [deg], then the same four of a model of G,
    !> one row per frequency line.
    pure function fit_columns(f, g, model) result(table)
        real(dp), intent(in) :: f(:)
        complex(dp), intent(in) :: g(:), model(:)
        real(dp), allocatable :: table(:, :)

        real(dp), parameter :: degrees = 180.0_dp/acos(-1.0_dp)

        table = reshape([f, real(g, dp), aimag(g), abs(g), degrees*atan2(aimag(g), real(g, dp)), real(model, dp), &
                         aimag(model), abs(model), degrees*atan2(aimag(model), real(model, dp))], [size(f), 9])
    end function fit_columns

end module greenconv_scene_run_report
