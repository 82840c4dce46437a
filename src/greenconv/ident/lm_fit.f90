!> Levenberg-Marquardt fit of a modal model to a weighted receptance (step 4 of
!> greenconv_ident_mlfit's description): the model and the weighted data, the receptance of a
!> model, chi2 and the MDL criterion, the residues by weighted linear least squares, the
!> analytic Jacobian, the Fisher information and the covariance, and the damped Gauss-Newton
!> iteration that keeps every pole physical (Re < 0 < Im, no narrower than narrow_band of a line).
module greenconv_ident_lm_fit
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_double_complex
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_ident_dense, only: gram, spd_factor, spd_solve, spd_inverse, svd_solve, identity, product_of
    use greenconv_ident_lsce, only: stack, add_parameter_step
    implicit none
    private

    public :: model_type, data_type, narrow_band, final_tolerance
    public :: evaluate, chi_square, n_parameters, criterion, fit, refine, reweight, information, covariance
    public :: widened, narrowest, leave_out, within_range

    interface
        !> g_l += sum_k r_k/(i*omega_l - lambda_k) + conj(r_k)/(i*omega_l - conj(lambda_k)), the
        !> poles in order, with the bits of `evaluate`'s loop written in Fortran (modal_sum.c).
        pure subroutine modal_terms(n_lines, n_poles, omega, pole, residue, g) &
            bind(c, name='greenconv_ident_modal_terms')
            import :: c_int, c_double, c_double_complex
            !> Number of lines.
            integer(c_int), value :: n_lines
            !> Number of poles.
            integer(c_int), value :: n_poles
            !> Angular frequencies [rad/s].
            real(c_double), intent(in) :: omega(n_lines)
            !> Poles [rad/s].
            complex(c_double_complex), intent(in) :: pole(n_poles)
            !> Residues [m/(N*s)].
            complex(c_double_complex), intent(in) :: residue(n_poles)
            !> Receptance [m/N], the terms added.
            complex(c_double_complex), intent(inout) :: g(n_lines)
        end subroutine modal_terms

        !> The first 2*n_poles columns of `linear_matrix`, with the bits of its Fortran loop (modal_sum.c).
        pure subroutine modal_linear(n_lines, n_poles, omega, weight, pole, a) &
            bind(c, name='greenconv_ident_modal_linear')
            import :: c_int, c_double, c_double_complex
            !> Number of lines.
            integer(c_int), value :: n_lines
            !> Number of poles.
            integer(c_int), value :: n_poles
            !> Angular frequencies [rad/s].
            real(c_double), intent(in) :: omega(n_lines)
            !> Weights 1/sigma [N/m].
            real(c_double), intent(in) :: weight(n_lines)
            !> Poles [rad/s].
            complex(c_double_complex), intent(in) :: pole(n_poles)
            !> The columns, [Re; Im] stacked (units of the weight times s).
            real(c_double), intent(inout) :: a(2*n_lines, 2*n_poles)
        end subroutine modal_linear

        !> The first 4*n_poles columns of `jacobian`, with the bits of its Fortran loop (modal_sum.c).
        pure subroutine modal_jacobian(n_lines, n_poles, omega, weight, pole, residue, jac) &
            bind(c, name='greenconv_ident_modal_jacobian')
            import :: c_int, c_double, c_double_complex
            !> Number of lines.
            integer(c_int), value :: n_lines
            !> Number of poles.
            integer(c_int), value :: n_poles
            !> Angular frequencies [rad/s].
            real(c_double), intent(in) :: omega(n_lines)
            !> Weights 1/sigma [N/m].
            real(c_double), intent(in) :: weight(n_lines)
            !> Poles [rad/s].
            complex(c_double_complex), intent(in) :: pole(n_poles)
            !> Residues [m/(N*s)].
            complex(c_double_complex), intent(in) :: residue(n_poles)
            !> The columns, [Re; Im] stacked (units of the weight times the model per parameter).
            real(c_double), intent(inout) :: jac(2*n_lines, 4*n_poles)
        end subroutine modal_jacobian
    end interface

    !> Narrowest half-power band 2*xi*f of a pole, as a fraction of the line spacing df: a
    !> narrower pole acts on a single line only (its peak), which is what a spike of noise or
    !> an outlier line does; no sampled FRF can show such a mode. The fit keeps every pole at
    !> least this wide, and a pole it pushes below twice this is dropped first.
    real(dp), parameter :: narrow_band = 1.0e-3_dp
    !> Fall of chi2 in one iteration below which the fit of the final model stops: a parameter
    !> change of a few hundredths of its standard deviation.
    real(dp), parameter :: final_tolerance = 1.0e-3_dp
    !> Smallest sigma_l of a noise model that follows |G| (relative, floor, band), as a fraction
    !> of the largest (80 dB), in the order search and in the final refinement alike: the data's
    !> own level floors the weights. Without it the weights of an FRF rolling off as omega^-10
    !> (sdypy-EMA's far transfers, 11 decades from the peak to 1700 Hz) span 1e22: the fit is
    !> ruled by the lines of the tail, where the five mode terms cancel to 1e-7 of each, and
    !> resonances 100 dB above them were thrown out as outliers at 1e13 sigma or merged (chi2/nu
    !> 3e11, 600-800 LM iterations, the 50 Hz mode lost). The final refinement's weights
    !> rho*|G_model| were not capped before: on sdypy's accelerance H_51 the search's model
    !> (chi2/nu 0.54) went to chi2/nu 5e7 under weights spanning 1e10 to 1e21 [N/m], where the
    !> Levenberg-Marquardt steps no longer moved, and the clean-up that followed ended at
    !> chi2/nu 2e12 under some BLAS kernels and at the five modes under others. Where the noise
    !> spans less than 80 dB nothing changes.
    real(dp), parameter :: dynamic_range = 1.0e-4_dp

    !> A model under fit: G(omega) = sum_k [r_k/(i*omega - lambda_k) + conj(r_k)/(i*omega -
    !> conj(lambda_k))] + R_u - R_l/omega^2.
    type :: model_type
        !> Poles lambda_k [rad/s] (Re < 0 < Im).
        complex(dp), allocatable :: pole(:)
        !> Residues r_k [m/(N*s)], one per pole.
        complex(dp), allocatable :: residue(:)
        !> Whether the upper residual R_u is part of the model.
        logical :: upper = .false.
        !> Whether the lower residual R_l is part of the model.
        logical :: lower = .false.
        !> Upper residual R_u [m/N].
        real(dp) :: r_u = 0.0_dp
        !> Lower residual R_l [1/kg] of the term -R_l/omega^2.
        real(dp) :: r_l = 0.0_dp
    end type model_type

    !> The weighted data: lines used, G and 1/sigma on them; for the relative noise model the
    !> level rho and the floor of sigma, to take the weights from a model's |G|.
    type :: data_type
        !> Angular frequency of each line used [rad/s].
        real(dp), allocatable :: omega(:)
        !> Weight 1/sigma_l of each line used [N/m].
        real(dp), allocatable :: weight(:)
        !> Smallest sigma_l of each line used [m/N] (noise_floor*|G_l|).
        real(dp), allocatable :: floor(:)
        !> Receptance of each line used [m/N].
        complex(dp), allocatable :: g(:)
        !> Index of each used line in the FRF.
        integer, allocatable :: line(:)
        !> MDL price of one real parameter, ln(2L) for L lines.
        real(dp) :: penalty = 0.0_dp
        !> Highest frequency of the FRF [Hz].
        real(dp) :: f_max = 0.0_dp
        !> Noise level rho of the relative noise model (sigma_l = rho*|G_l|).
        real(dp) :: level = 0.0_dp
        !> Smallest -Re(lambda) [1/s] of a pole: pi*narrow_band*df (a half-power band of narrow_band lines).
        real(dp) :: min_decay = 0.0_dp
        !> Line spacing of the FRF [Hz].
        real(dp) :: df = 0.0_dp
        !> Whether the weights follow the relative noise model (estimated level times |G|).
        logical :: relative = .false.
        !> Noise floor s [m/N] of the 'floor' model: sigma_l^2 = (level*|G_l|)^2 + s^2 (0: none).
        real(dp) :: absolute_floor = 0.0_dp
        !> Level rho_b of each line used, for the 'band' noise model (not allocated otherwise).
        real(dp), allocatable :: line_level(:)
        !> Most Levenberg-Marquardt iterations of a fit.
        integer :: max_iterations = 60
        !> Most modes of a model in the order search.
        integer :: max_modes = 0
        !> Outlier threshold on |e_l|/sigma_l (0: no detection).
        real(dp) :: outlier_sigma = 0.0_dp
        !> A Levenberg-Marquardt fit stops when chi2 falls by less than this (plus 1e-10*chi2) in an iteration.
        real(dp) :: tolerance = final_tolerance
        !> Whether `refine` projects out the residues (variable projection; the global order search).
        logical :: projection = .false.
    end type data_type

contains

    !> Receptance of a model on omega [rad/s].
    pure function evaluate(model, omega) result(g)
        !> The model.
        type(model_type), intent(in) :: model
        !> Angular frequencies [rad/s].
        real(dp), intent(in) :: omega(:)
        !> Receptance [m/N] at each.
        complex(dp) :: g(size(omega))

        g = model%r_u
        ! For each pole in turn, every line: g(l) = g(l) + r/(i*omega(l) - pole) +
        ! conjg(r)/(i*omega(l) - conjg(pole)), each reciprocal by one real division, in C over the
        ! lines side by side (modal_sum.c; one line at a time took a tenth of a fit's time).
        if (size(model%pole) > 0 .and. size(omega) > 0) &
            call modal_terms(int(size(omega), c_int), int(size(model%pole), c_int), omega, model%pole, &
                             model%residue, g)
        if (model%lower) g = g - model%r_l/omega**2
    end function evaluate

    !> chi2 = sum 2*|w*(G - G_model)|^2.
    pure real(dp) function chi_square(data, model)
        !> The weighted data.
        type(data_type), intent(in) :: data
        !> The model.
        type(model_type), intent(in) :: model

        chi_square = 2.0_dp*sum(abs(weighted_residual(data, model))**2)
    end function chi_square

    !> Weighted residual w*(G - G_model) of each line used (dimensionless, complex).
    pure function weighted_residual(data, model) result(e)
        !> The weighted data.
        type(data_type), intent(in) :: data
        !> The model.
        type(model_type), intent(in) :: model
        !> w_l*(G_l - G_model(omega_l)).
        complex(dp) :: e(size(data%g))

        e = data%weight*(data%g - evaluate(model, data%omega))
    end function weighted_residual

    !> Number of real parameters of a model.
    elemental integer function n_parameters(model)
        !> The model.
        type(model_type), intent(in) :: model

        n_parameters = 4*size(model%pole) + merge(1, 0, model%upper) + merge(1, 0, model%lower)
    end function n_parameters

    !> MDL criterion chi2 + P*ln(2L).
    pure real(dp) function criterion(data, model, chi)
        !> The weighted data (its penalty ln(2L)).
        type(data_type), intent(in) :: data
        !> The model (its number of parameters P).
        type(model_type), intent(in) :: model
        !> chi2 of the model on the data.
        real(dp), intent(in) :: chi

        criterion = chi + data%penalty*n_parameters(model)
    end function criterion

    !> Weighted linear least squares for the residues and residual terms of the model's poles.
    subroutine fit_linear(data, model, error)
        type(data_type), intent(in) :: data
        type(model_type), intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: a(:, :), b(:), x(:), norms(:), normal(:, :), low(:, :), projection(:)
        real(dp) :: total
        integer :: k, n, col, r
        logical :: ok

        n = size(model%pole)
        allocate (a(2*size(data%g), 2*n + merge(1, 0, model%upper) + merge(1, 0, model%lower)))
        if (size(a, 2) == 0) then
            if (allocated(model%residue)) deallocate (model%residue)
            allocate (model%residue(0))
            return
        end if
        call linear_matrix(data, model, a)
        ! Each column to unit norm (its squares summed in row order).
        allocate (norms(size(a, 2)))
        do col = 1, size(a, 2)
            total = 0.0_dp
            do r = 1, size(a, 1)
                total = total + a(r, col)**2
            end do
            norms(col) = sqrt(total)
            if (.not. (norms(col) > 0.0_dp)) norms(col) = 1.0_dp
            a(:, col) = a(:, col)/norms(col)
        end do
        ! allocated before the assignment: gfortran's reallocation of an unallocated local
        ! reads its unset bounds first (UBSan's signed overflow, harmless but not clean)
        allocate (b(2*size(data%g)))
        b(:) = stack(data%weight*data%g)
        ! Normal equations of the unit-norm columns by Cholesky (a tenth of the SVD's time);
        ! the SVD when a pivot shows a condition beyond 1e8 (near-duplicate poles).
        allocate (normal(size(a, 2), size(a, 2)), projection(size(a, 2)))
        call gram(a, 1.0_dp, normal, b, projection)
        low = normal
        call spd_factor(low, ok)
        if (ok) ok = minval([(low(col, col), col=1, size(low, 1))])**2 > 1.0e-8_dp
        if (ok) call spd_solve(normal, projection, x, ok)
        if (.not. ok) then
            if (allocated(x)) deallocate (x)
            allocate (x(size(a, 2)))
            call svd_solve(a, b, x, 1.0e-13_dp)
        end if
        x = x/norms
        model%residue = [(cmplx(x(2*k - 1), x(2*k), dp), k=1, n)]
        col = 2*n
        if (model%upper) then
            col = col + 1
            model%r_u = x(col)
        end if
        if (model%lower) model%r_l = x(col + 1)
    end subroutine fit_linear

    !> Weighted columns of the linear part, real parts in rows 1..L and imaginary parts below
    !> (as `jacobian`): per pole the responses to r = 1 and r = i, then R_u and R_l. Written
    !> in place, one pass per pole (the complex columns and their stacked copy it replaced took
    !> a third of the least squares' time).
    pure subroutine linear_matrix(data, model, a)
        type(data_type), intent(in) :: data
        type(model_type), intent(in) :: model
        real(dp), intent(out) :: a(:, :)

        integer :: n

        n = size(data%omega)
        ! Per pole and line, with direct = 1/(i*omega - pole), mirror = 1/(i*omega - conjg(pole))
        ! and w the weight: w*(direct + mirror), then w*i*(direct - mirror) =
        ! w*(-Im(.), Re(.)); in C over the lines side by side, the same bits.
        if (size(model%pole) > 0 .and. n > 0) &
            call modal_linear(int(n, c_int), int(size(model%pole), c_int), data%omega, data%weight, model%pole, &
                              a(:, 1:2*size(model%pole)))
        call residual_columns(data, model, a, 2*size(model%pole))
    end subroutine linear_matrix

    !> Weighted Jacobian of G_model, columns per mode (Re lambda, Im lambda, Re r, Im r), then
    !> R_u, R_l; real parts in rows 1..L, imaginary parts below.
    pure subroutine jacobian(data, model, jac)
        type(data_type), intent(in) :: data
        type(model_type), intent(in) :: model
        real(dp), intent(inout) :: jac(:, :)

        integer :: n

        n = size(data%omega)
        ! Per pole and line, with direct and mirror the reciprocals at the pole and its
        ! conjugate, w the weight, slope = w*r*direct**2 and image = w*conjg(r)*mirror**2:
        ! columns slope + image, i*(slope - image), w*direct + w*mirror, i*(w*direct - w*mirror);
        ! in C over the lines side by side (modal_sum.c), the same bits.
        if (size(model%pole) > 0 .and. n > 0) &
            call modal_jacobian(int(n, c_int), int(size(model%pole), c_int), data%omega, data%weight, model%pole, &
                                model%residue, jac(:, 1:4*size(model%pole)))
        call residual_columns(data, model, jac, 4*size(model%pole))
    end subroutine jacobian

    !> The columns of the residuals after column `last` of a stacked matrix laid out as in
    !> `linear_matrix` and `jacobian`, each when the model has it: R_u's w, then R_l's
    !> -w/omega^2, in rows 1..L, and zero imaginary parts below.
    pure subroutine residual_columns(data, model, a, last)
        type(data_type), intent(in) :: data
        type(model_type), intent(in) :: model
        real(dp), intent(inout) :: a(:, :)
        integer, intent(in) :: last

        integer :: col, n

        n = size(data%omega)
        col = last
        if (model%upper) then
            col = col + 1
            a(1:n, col) = data%weight
            a(n + 1:, col) = 0.0_dp
        end if
        if (model%lower) then
            a(1:n, col + 1) = -data%weight/data%omega**2
            a(n + 1:, col + 1) = 0.0_dp
        end if
    end subroutine residual_columns

    !> A model plus a parameter step laid out as in `jacobian`.
    pure function stepped(model, step) result(trial)
        type(model_type), intent(in) :: model
        real(dp), intent(in) :: step(:)
        type(model_type) :: trial

        trial = model
        call add_parameter_step(step, model%upper, model%lower, trial%pole, trial%residue, trial%r_u, trial%r_l)
    end function stepped

    !> Fisher information 2*Re(J^H W J) and the gradient 2*Re(J^H W e) of -chi2/2.
    subroutine information(data, model, fisher, gradient, jac, residual)
        !> The weighted data.
        type(data_type), intent(in) :: data
        !> The model.
        type(model_type), intent(in) :: model
        !> Fisher information, P x P, parameters laid out as in `jacobian` (units of 1/parameter^2).
        real(dp), allocatable, intent(out) :: fisher(:, :)
        !> Gradient of -chi2/2 with respect to each parameter (units of 1/parameter).
        real(dp), allocatable, intent(out) :: gradient(:)
        !> Work array for the Jacobian, kept between calls of one fit (its fresh allocation at
        !> every iteration cost 15 % of the time in page faults).
        real(dp), allocatable, intent(inout) :: jac(:, :)
        !> The model's weighted residual w*(G - G_model) when the caller has it (computed when absent).
        complex(dp), intent(in), optional :: residual(:)

        real(dp), allocatable :: stacked_residual(:)
        integer :: m, p

        m = 2*size(data%g)
        p = n_parameters(model)
        if (allocated(jac)) then
            if (size(jac, 1) /= m .or. size(jac, 2) /= p) deallocate (jac)
        end if
        if (.not. allocated(jac)) allocate (jac(m, p))
        call jacobian(data, model, jac)
        if (present(residual)) then
            stacked_residual = stack(residual)
        else
            stacked_residual = stack(weighted_residual(data, model))
        end if
        allocate (fisher(p, p), gradient(p))
        call gram(jac, 2.0_dp, fisher, stacked_residual, gradient)
    end subroutine information

    !> Residues for the model's poles, then Levenberg-Marquardt (at most `iterations`).
    subroutine fit(data, model, lm_iterations, error, iterations)
        !> The weighted data.
        type(data_type), intent(in) :: data
        !> In: the poles (and residues to start from); out: the fitted model.
        type(model_type), intent(inout) :: model
        !> Count of Levenberg-Marquardt iterations, increased by those of this fit.
        integer, intent(inout) :: lm_iterations
        !> Set when the linear least squares fail.
        type(error_type), allocatable, intent(out) :: error
        !> Most iterations (data%max_iterations when absent).
        integer, intent(in), optional :: iterations

        call fit_linear(data, model, error)
        if (allocated(error)) return
        call refine(data, model, lm_iterations, iterations)
    end subroutine fit

    !> The final refinement: for the relative noise model with the weights 1/max(rho*|G_model|,
    !> floor) from the model rather than from the noisy |G|, each sigma at least dynamic_range
    !> of the largest (`within_range`).
    subroutine reweight(data, model, lm_iterations)
        !> The weighted data (its weights replaced for the relative noise model).
        type(data_type), intent(inout) :: data
        !> The model, refined.
        type(model_type), intent(inout) :: model
        !> Count of Levenberg-Marquardt iterations, increased by those of this refinement.
        integer, intent(inout) :: lm_iterations

        if (data%relative .and. data%absolute_floor > 0.0_dp) then
            data%weight = 1.0_dp/max(within_range(hypot(data%level*abs(evaluate(model, data%omega)), &
                                                        data%absolute_floor)), data%floor)
        else if (data%relative .and. allocated(data%line_level)) then
            data%weight = 1.0_dp/max(within_range(data%line_level*abs(evaluate(model, data%omega))), data%floor)
        else if (data%relative) then
            data%weight = 1.0_dp/max(within_range(data%level*abs(evaluate(model, data%omega))), data%floor)
        end if
        call refine(data, model, lm_iterations)
    end subroutine reweight

    !> Standard deviations of a noise model that follows |G|, each raised to at least
    !> dynamic_range of the largest [m/N].
    pure function within_range(sigma) result(capped)
        !> sigma_l of each line [m/N].
        real(dp), intent(in) :: sigma(:)
        !> max(sigma_l, dynamic_range*max_l sigma_l) [m/N].
        real(dp) :: capped(size(sigma))

        capped = sigma
        if (size(sigma) > 0) capped = max(sigma, dynamic_range*maxval(sigma))
    end function within_range

    !> Levenberg-Marquardt on all parameters (the step of every parameter from the information,
    !> scaled to unit diagonal, damped by mu*I, by Cholesky), or, when data%projection (the
    !> global order search), with variable projection: the poles are the only
    !> nonlinear parameters; at every trial the residues and residual terms are the weighted
    !> linear least squares for the trial poles (`fit_linear`), and the poles' step solves the
    !> Gauss-Newton system of the projected problem (`projected`: Kaufman's J^T J, the Schur
    !> complement of the information), scaled to unit diagonal, damped by mu*I, by Cholesky.
    !> A step is kept when chi2 falls and every pole stays physical (Re < 0 < Im). Stops when
    !> mu grows past 1e12 or chi2 falls by less than data%tolerance + 1e-10*chi2 in an
    !> iteration (search_tolerance during the order search, final_tolerance for the final
    !> model). Against the step in all parameters it replaced, a cluster of overlapping modes
    !> converges in a few iterations instead of stalling (three modes at 400-455 Hz, xi up to
    !> 0.09, 3 % noise: 61 iterations left 10 sigma_CRB off, now 2), and the 50-mode bench fit
    !> takes 158-168 iterations instead of 262. The residual of the kept model is carried from
    !> the step that made it to the next iteration's gradient.
    subroutine refine(data, model, lm_iterations, iterations)
        !> The weighted data.
        type(data_type), intent(in) :: data
        !> The model, refined in place.
        type(model_type), intent(inout) :: model
        !> Count of Levenberg-Marquardt iterations, increased by those of this refinement.
        integer, intent(inout) :: lm_iterations
        !> Most iterations (data%max_iterations when absent).
        integer, intent(in), optional :: iterations

        type(model_type) :: trial
        type(error_type), allocatable :: failure
        real(dp), allocatable :: fisher(:, :), gradient(:), scale(:), a(:, :), y(:), jac(:, :)
        real(dp), allocatable :: reduced(:, :), pull(:), step(:)
        complex(dp), allocatable :: residual(:), residual_trial(:)
        integer, allocatable :: nonlinear(:)
        real(dp) :: chi, chi_trial, mu
        integer :: iteration, p, small, i, last, q
        logical :: ok

        if (n_parameters(model) == 0) return
        residual = weighted_residual(data, model)
        chi = 2.0_dp*sum(abs(residual)**2)
        residual_trial = residual
        mu = 1.0e-4_dp
        small = 0
        last = data%max_iterations
        if (present(iterations)) last = iterations
        p = n_parameters(model)
        nonlinear = [(4*((i - 1)/2) + 1 + mod(i - 1, 2), i=1, 2*size(model%pole))]
        q = size(nonlinear)
        allocate (step(p), scale(q))
        do iteration = 1, last
            call information(data, model, fisher, gradient, jac, residual)
            lm_iterations = lm_iterations + 1
            if (data%projection) then
                call projected(fisher, gradient, nonlinear, reduced, pull, ok)
                if (.not. ok) return
            else
                reduced = fisher
                pull = gradient
            end if
            q = size(pull)
            if (size(scale) /= q) then
                deallocate (scale)
                allocate (scale(q))
            end if
            do i = 1, q
                scale(i) = sqrt(reduced(i, i))
            end do
            where (.not. (scale > 0.0_dp)) scale = 1.0_dp
            do
                a = reduced/spread(scale, 1, q)/spread(scale, 2, q)
                a = a + mu*identity(q)
                call spd_solve(a, pull/scale, y, ok)
                chi_trial = huge(1.0_dp)
                if (ok) then
                    if (data%projection) then
                        step = 0.0_dp
                        step(nonlinear) = y/scale
                    else
                        step = y/scale
                    end if
                    trial = stepped(model, step)
                    if (physical(trial, data%min_decay)) then
                        if (data%projection) call fit_linear(data, trial, failure)
                        if (.not. allocated(failure)) then
                            residual_trial = weighted_residual(data, trial)
                            chi_trial = 2.0_dp*sum(abs(residual_trial)**2)
                        end if
                        if (allocated(failure)) deallocate (failure)
                    end if
                end if
                if (chi_trial < chi) exit
                mu = 10.0_dp*mu
                if (mu > 1.0e12_dp) return
            end do
            small = merge(1, 0, chi - chi_trial <= data%tolerance + 1.0e-10_dp*chi)
            model = trial
            residual = residual_trial
            chi = chi_trial
            mu = max(0.1_dp*mu, 1.0e-12_dp)
            if (small >= 1) exit
        end do
    end subroutine refine

    !> Variable projection (Golub-Pereyra with Kaufman's Jacobian) from the information of all
    !> parameters: the linear ones (residues, residual terms) eliminated, the Gauss-Newton
    !> system of the poles alone is the Schur complement F_pp - F_pl inv(F_ll) F_lp (Kaufman's
    !> J^T J of the projected pole columns) and its right side g_p - F_pl inv(F_ll) g_l.
    pure subroutine projected(fisher, gradient, nonlinear, reduced, pull, ok)
        !> Information of all parameters, laid out as in `jacobian`.
        real(dp), intent(in) :: fisher(:, :)
        !> Gradient of all parameters.
        real(dp), intent(in) :: gradient(:)
        !> Indices of the nonlinear parameters (Re, Im of each pole).
        integer, intent(in) :: nonlinear(:)
        !> Reduced information of the nonlinear parameters.
        real(dp), allocatable, intent(out) :: reduced(:, :)
        !> Reduced gradient of the nonlinear parameters.
        real(dp), allocatable, intent(out) :: pull(:)
        !> False when the information of the linear parameters is singular.
        logical, intent(out) :: ok

        real(dp), allocatable :: inverse(:, :), coupling(:, :)
        logical :: linear(size(gradient))
        integer, allocatable :: other(:)
        integer :: i

        linear = .true.
        linear(nonlinear) = .false.
        other = pack([(i, i=1, size(gradient))], linear)
        reduced = fisher(nonlinear, nonlinear)
        pull = gradient(nonlinear)
        ok = .true.
        if (size(other) == 0) return
        call covariance(fisher(other, other), inverse, ok)
        if (.not. ok) return
        coupling = product_of(fisher(nonlinear, other), inverse)
        reduced = reduced - product_of(coupling, fisher(other, nonlinear))
        pull = pull - reshape(product_of(coupling, reshape(gradient(other), [size(other), 1])), [size(nonlinear)])
    end subroutine projected

    !> Every pole with Re <= -min_decay < 0 < Im.
    pure logical function physical(model, min_decay)
        type(model_type), intent(in) :: model
        !> Smallest -Re(lambda) [1/s] (> 0).
        real(dp), intent(in) :: min_decay

        physical = all(real(model%pole, dp) <= -min_decay .and. aimag(model%pole) > 0.0_dp)
    end function physical

    !> Poles moved, when needed, to the narrowest band allowed: Re(lambda) <= -min_decay.
    elemental complex(dp) function widened(pole, min_decay)
        !> Pole [rad/s].
        complex(dp), intent(in) :: pole
        !> Smallest -Re(lambda) [1/s] (> 0).
        real(dp), intent(in) :: min_decay

        widened = cmplx(min(real(pole, dp), -min_decay), aimag(pole), dp)
    end function widened

    !> Whether a pole sits within a factor 2 of the narrowest band allowed.
    elemental logical function narrowest(pole, min_decay)
        !> Pole [rad/s].
        complex(dp), intent(in) :: pole
        !> Smallest -Re(lambda) [1/s] (> 0).
        real(dp), intent(in) :: min_decay

        narrowest = -real(pole, dp) < 2.0_dp*min_decay
    end function narrowest

    !> Covariance inv(F) of a symmetric positive definite F (scaled to unit diagonal first).
    pure subroutine covariance(fisher, cov, ok)
        !> Fisher information (units of 1/parameter^2).
        real(dp), intent(in) :: fisher(:, :)
        !> Its inverse, the covariance of the parameters (units of parameter^2; 0 when n = 0).
        real(dp), allocatable, intent(out) :: cov(:, :)
        !> False when F is not positive definite (cov then incomplete).
        logical, intent(out) :: ok

        real(dp) :: scale(size(fisher, 1))
        integer :: j, n

        n = size(fisher, 1)
        allocate (cov(n, n))
        cov = 0.0_dp
        ok = .true.
        if (n == 0) return
        scale = [(sqrt(max(fisher(j, j), tiny(1.0_dp))), j=1, n)]
        cov = fisher/spread(scale, 1, n)/spread(scale, 2, n)
        call spd_inverse(cov, ok)
        if (.not. ok) return
        cov = cov/spread(scale, 1, n)/spread(scale, 2, n)
    end subroutine covariance

    !> Remove one line (index in data) from the data.
    pure subroutine leave_out(data, line)
        !> The weighted data, without the line on return (its penalty ln(2L) updated).
        type(data_type), intent(inout) :: data
        !> Index of the line in data.
        integer, intent(in) :: line

        logical :: keep(size(data%g))

        keep = .true.
        keep(line) = .false.
        data%line = pack(data%line, keep)
        data%omega = pack(data%omega, keep)
        data%g = pack(data%g, keep)
        data%weight = pack(data%weight, keep)
        data%floor = pack(data%floor, keep)
        if (allocated(data%line_level)) data%line_level = pack(data%line_level, keep)
        data%penalty = log(2.0_dp*size(data%g))
    end subroutine leave_out

end module greenconv_ident_lm_fit
