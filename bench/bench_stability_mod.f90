!> Where the paper's recursion fails, measured: a map over the natural frequency f and the
!> damping ratio xi of a single mode of the time at which `paper` (eqs. 15-17, growth factors
!> e^{+xi*omega*t}) first returns a non-finite displacement, against the prediction
!> t = ln(huge)/(xi*omega) = 709.78/(xi*omega); and whether `recursive` and `exact` stay
!> finite and on their step responses in closed form at the end of the same runs.
module bench_stability_mod
    use greenconv_core_kinds, only: dp
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use greenconv_core_error, only: error_type
    use greenconv_conv_convolver, only: convolver
    use greenconv_model_modal_set, only: modal_set
    use greenconv_model_sdof, only: sdof_modes
    use greenconv_conv_paper, only: new_paper_convolver
    use greenconv_conv_recursive, only: new_recursive_convolver, new_exact_convolver
    use greenconv_io_files, only: write_columns
    implicit none
    private

    public :: overflow_map

    real(dp), parameter :: pi = acos(-1.0_dp)

contains

    !> Write the map to `path` (columns f [Hz], xi, measured and predicted failure time of
    !> `paper` [s] (-1: finite over the whole run), and the deviation of `recursive` and
    !> `exact` from their closed-form step responses at the end, relative to the static
    !> displacement) and summarise it on `unit`.
    subroutine overflow_map(unit, path, error)
        !> Unit of the summary.
        integer, intent(in) :: unit
        !> Output file.
        character(len=*), intent(in) :: path
        !> Set when the file cannot be written.
        type(error_type), allocatable, intent(out) :: error

        real(dp), parameter :: frequency(6) = [100.0_dp, 200.0_dp, 500.0_dp, 1000.0_dp, 2000.0_dp, 5000.0_dp]
        real(dp), parameter :: damping(6) = [0.005_dp, 0.01_dp, 0.02_dp, 0.05_dp, 0.1_dp, 0.2_dp]
        real(dp), parameter :: dt = 2.0e-5_dp, duration = 2.0_dp
        real(dp) :: table(size(frequency)*size(damping), 6)
        integer :: i, j, row, failures, predicted

        row = 0
        do i = 1, size(frequency)
            do j = 1, size(damping)
                row = row + 1
                table(row, 1) = frequency(i)
                table(row, 2) = damping(j)
                call run_cell(frequency(i), damping(j), dt, nint(duration/dt), table(row, 3:6))
            end do
        end do
        call write_columns(path, [character(len=100) :: &
            'Where the paper''s recursion overflows: one mode, unit step load, dt = 20 us, 2 s', &
            't_fail: first non-finite paper history (-1: none); predicted 709.78/(xi*omega)', &
            'dev_recursive, dev_exact: |u - u_closed_form|/u_static at the end (exact: with what remains of', &
            'its first step''s ramp from rest, which decays with the mode)', &
            'units: Hz 1 s s 1 1', 'f xi t_fail t_predicted dev_recursive dev_exact'], table, error)
        if (allocated(error)) return
        failures = count(table(:, 3) > 0.0_dp)
        predicted = count(table(:, 4) < duration)
        write (unit, '(a)') '# Stability: where paper overflows (one mode, unit step load, dt 20 us, ' &
            //'2 s of simulated time)'
        write (unit, '(a,i0,a,i0,a,i0,a)') '#   paper failed in ', failures, ' of ', size(table, 1), &
            ' cells (', predicted, ' predicted by xi*omega*t > 709.78)'
        write (unit, '(a,es9.2)') '#   largest |t_fail/t_predicted - 1| where it failed: ', &
            maxval(abs(table(:, 3)/table(:, 4) - 1.0_dp), mask=table(:, 3) > 0.0_dp)
        write (unit, '(a,l1,a,2es9.2)') '#   recursive, exact all finite: ', all(table(:, 5:6) < 1.0_dp), &
            '; largest deviation from their closed forms /(F/K): ', maxval(table(:, 5)), maxval(table(:, 6))
        write (unit, '(a)') ''
    end subroutine overflow_map

    !> One cell: failure time of paper (measured, predicted) and the end deviations of
    !> recursive from its discrete sum in closed form, dt*sum_{j=1..n} 2*Re(r*z^j), and of
    !> exact from the continuous step response (the hold is exact for a constant force).
    subroutine run_cell(frequency, damping, dt, n_steps, values)
        real(dp), intent(in) :: frequency, damping, dt
        integer, intent(in) :: n_steps
        real(dp), intent(out) :: values(4)

        class(convolver), allocatable :: paper, recursive, exact
        type(modal_set) :: modes
        complex(dp) :: z
        real(dp) :: omega, stiffness, t_fail, discrete_sum, decay, omega_d, t_end, step_response
        integer :: n

        omega = 2.0_dp*pi*frequency
        stiffness = omega**2
        modes = sdof_modes(1.0_dp, stiffness, damping)
        paper = new_paper_convolver(modes, dt)
        recursive = new_recursive_convolver(modes, dt)
        exact = new_exact_convolver(modes, dt)
        t_fail = -1.0_dp
        do n = 0, n_steps - 1
            if (t_fail < 0.0_dp) then
                if (.not. ieee_is_finite(paper%history())) t_fail = n*dt
                call paper%push(1.0_dp)
            end if
            call recursive%push(1.0_dp)
            call exact%push(1.0_dp)
        end do
        z = exp(modes%pole(1)*dt)
        discrete_sum = dt*2.0_dp*real(modes%residue(1)*z*(1.0_dp - z**n_steps)/(1.0_dp - z), kind=dp)
        decay = damping*omega
        omega_d = omega*sqrt(1.0_dp - damping**2)
        t_end = n_steps*dt
        step_response = (1.0_dp - exp(-decay*t_end)*(cos(omega_d*t_end) + decay/omega_d*sin(omega_d*t_end)))/stiffness
        values(1) = t_fail
        values(2) = log(huge(1.0_dp))/decay
        values(3) = abs(recursive%history() - discrete_sum)*stiffness
        values(4) = abs(exact%history() + exact%instant_weight() - step_response)*stiffness
    end subroutine run_cell

end module bench_stability_mod
