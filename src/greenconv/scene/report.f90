!> What an identification reports: a summary on the terminal (order, E of eq. 7, poles
!> dropped, warnings) and column files of the modes and of G against its fit.
module greenconv_scene_report
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_model_modal_set, only: modal_set
    use greenconv_ident_lsce, only: paper_form
    use greenconv_io_files, only: write_columns
    use greenconv_scene_input, only: scene_type
    use greenconv_ident_structure, only: structure_model
    implicit none
    private

    public :: identification_summary, write_identification

    !> 2*pi
    real(dp), parameter :: two_pi = 2.0_dp*acos(-1.0_dp)

contains

    !> Print the identification in a few `#` lines: order, E, dropped poles, warnings.
    subroutine identification_summary(structure, unit)
        !> The identified structure.
        type(structure_model), intent(in) :: structure
        !> Unit to print on.
        integer, intent(in) :: unit

        associate (fit => structure%fit)
            write (unit, '(a,i0,a,i0,a,i0,a,es9.2,a,l1)') '# identification: LSCE order 2N = ', 2*fit%order_modes, &
                ' (N = ', fit%order_modes, '), ', fit%modes%n_modes(), ' modes, E = ', fit%e, &
                ' (eq. 7), target met: ', fit%tolerance_met
            write (unit, '(a,i0,a,i0,a,i0,a)') '# poles dropped: ', fit%n_unstable, ' unstable (Re lambda >= 0), ', &
                fit%n_real, ' real, ', fit%n_not_stable, ' not stable across orders'
            if (allocated(fit%warning)) then
                if (len(fit%warning) > 0) write (unit, '(a)') '# warning: '//fit%warning
            end if
        end associate
    end subroutine identification_summary

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
        call write_modes(stem//'_modes.dat', 'modes identified by LSCE', structure%model, error)
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

    !> G and the fitted model on the identified grid: real and imaginary parts, magnitude
    !> and phase, for Fig. 4.
    subroutine write_fit(path, structure, error)
        character(len=*), intent(in) :: path
        type(structure_model), intent(in) :: structure
        type(error_type), allocatable, intent(out) :: error

        complex(dp), allocatable :: fitted(:)
        character(len=100) :: comments(4)
        real(dp), parameter :: degrees = 180.0_dp/acos(-1.0_dp)

        allocate (fitted(structure%frf%n_freq()))
        associate (f => structure%frf%frequency, g => structure%frf%receptance)
            fitted(:) = structure%fit%receptance(two_pi*f)
            write (comments(1), '(a,es9.2,a)') 'greenconv: receptance G and its LSCE fit, E = ', structure%fit%e, &
                ' (eq. 7)'
            comments(2) = 'phase in degrees, in (-180, 180]'
            comments(3) = 'units: Hz m/N m/N m/N deg m/N m/N m/N deg'
            comments(4) = 'f re_g im_g abs_g phase_g re_fit im_fit abs_fit phase_fit'
            call write_columns(path, comments, reshape([f, real(g, dp), aimag(g), abs(g), &
                                                        degrees*atan2(aimag(g), real(g, dp)), real(fitted, dp), &
                                                        aimag(fitted), abs(fitted), &
                                                        degrees*atan2(aimag(fitted), real(fitted, dp))], &
                                                       [size(f), 9]), error)
        end associate
    end subroutine write_fit

end module greenconv_scene_report
