!> A structure known by the Green's matrix between its N_c contact points, read from a
!> universal file, made ready for the multi-point convolvers:
!>
!> - **Receptances** G_ij(f) (datasets 58 of function type 4, greenconv_model_green_matrix_file):
!>   the poles are identified once for the whole matrix with a residue matrix per pole
!>   (greenconv_ident_shared_poles: maximum likelihood on the summed driving points, the order
!>   chosen by the noise, then refined over all receptances), and turned into modes with real
!>   shapes at the points for the modal recursions (`shared_point_modes`). The residual terms
!>   U and L of the fit have no place in a recursion (greenconv_conv_green_file adds U to the
!>   instant matrix of `exact`), so E of eq. (7) is reported for the fit, for the modes alone
!>   (`e_modes`) and for the modes with U (`e_upper`). For
!>   `direct` and `fft`, `sampled_kernel` gives g_ij(t_m) by the inverse FFT of the file's G_ij
!>   when the time step suits the grid (see there).
!> - **Impulse responses** g_ij(t) (datasets 58 of function type 1, time response, in
!>   m/(N*s): displacement at i per unit impulse at j, sampled evenly from t = 0): no
!>   identification; `sampled_kernel` gives them at a time step that is a whole multiple of
!>   the file's, for `direct` and `fft` only.
!>
!> The points are the nodes given both as response and as reference, in label order, at the
!> node coordinates of the file (x along the travel, y across).
module greenconv_ident_green_structure
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_io_uff, only: uff_file, read_uff
    use greenconv_model_frf, only: frf_type
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_plate, only: patch_receptance
    use greenconv_model_green_matrix_file, only: green_matrix, check_green_matrix
    use greenconv_ident_lsce, only: impulse_from_frf, error_e
    use greenconv_ident_mlfit, only: ml_options, ml_result
    use greenconv_ident_shared_poles, only: shared_fit, identify_shared, shared_point_modes, shared_receptance
    use greenconv_ident_cost, only: green_cost, green_cost_bound, measured_rate, cost_text
    implicit none
    private

    public :: green_options, green_structure, read_green_structure, read_green_layout, identify_green, sampled_kernel
    public :: summary_text, cost_bound_text

    real(dp), parameter :: two_pi = 6.283185307179586476925286766559_dp
    !> Relative tolerance on a time step that must fit a grid (record 7 of a universal file
    !> holds the abscissa step to six digits).
    real(dp), parameter :: step_tolerance = 1.0e-5_dp
    !> Fraction of the kept half period over which the wrap-around of g from G is measured.
    real(dp), parameter :: wrap_fraction = 0.1_dp

    !> Settings of `read_green_structure`.
    type :: green_options
        !> The pole fit of the summed driving points (greenconv_ident_mlfit): largest order of
        !> its stabilisation diagram, noise model, residual terms.
        type(ml_options) :: fit
        !> Terms of a residue matrix's eigen-split below this fraction of the pole's largest
        !> are dropped (greenconv_ident_shared_poles's `shared_point_modes`).
        real(dp) :: term_tol = 1.0e-10_dp
        !> Take the poles from all receptances by the poly-reference fit (greenconv_ident_polyref,
        !> for modally dense structures) instead of the summed driving points.
        logical :: poly_reference = .false.
        !> Fit both (the summed driving points and poly-reference) and keep the one of smaller
        !> worst E of eq. (7) over the receptances (`poly_reference` is then ignored).
        logical :: choose_poles = .false.
    end type green_options

    !> A Green's matrix from a universal file, identified when it holds receptances.
    type :: green_structure
        !> The file read.
        character(len=:), allocatable :: path
        !> The matrix: points (node labels, x_i, y_i [m]), grid and data, reciprocity.
        type(green_matrix) :: matrix
        !> Whether the file held receptances, identified with shared poles (else impulse responses).
        logical :: identified = .false.
        !> The shared-pole identification (receptances only).
        type(shared_fit) :: fit
        !> The modes the modal methods run on: poles, residues and real shapes at the points.
        type(point_modes) :: modes
        !> E of eq. (7) of the modes alone (no residual terms) per receptance, e_modes(i, j).
        real(dp), allocatable :: e_modes(:, :)
        !> E of eq. (7) of the modes with the fit's upper residual U (the modes alone when the fit
        !> has none) per receptance, e_upper(i, j).
        real(dp), allocatable :: e_upper(:, :)
        !> Worst relative standard deviation of a pole's natural frequency, sigma_f/f, and of
        !> its damping ratio, sigma_xi/xi, from the pole fit.
        real(dp) :: worst_sigma_f = 0.0_dp, worst_sigma_xi = 0.0_dp
        !> CPU time of the identification [s].
        real(dp) :: cpu_time = 0.0_dp
        !> The bound of the identification's cost, computed before it starts (greenconv_ident_cost).
        type(green_cost) :: cost
        !> The bound in words, with its seconds at the rate measured before the identification.
        character(len=:), allocatable :: cost_summary
        !> With `choose_poles`: the worst E of the fit not kept (-1 when only one was fitted).
        real(dp) :: e_other = -1.0_dp
    contains
        !> Number of contact points N_c.
        procedure :: n_points => structure_n_points
        !> The lines a summary prints ("# ..."), joined by line ends.
        procedure :: summary => structure_summary
    end type green_structure

contains

    !> Number of contact points N_c.
    elemental integer function structure_n_points(self)
        !> The structure.
        class(green_structure), intent(in) :: self

        structure_n_points = self%matrix%n_points()
    end function structure_n_points

    !> Read a universal file of a Green's matrix (receptances, or impulse responses when it has
    !> no receptance) and identify the receptances with shared poles (see the module description).
    subroutine read_green_structure(path, options, structure, error)
        !> The universal file.
        character(len=*), intent(in) :: path
        !> Settings of the identification.
        type(green_options), intent(in) :: options
        !> The structure.
        type(green_structure), intent(out) :: structure
        !> Set (status 2) for a file that holds no complete Green's matrix, or when the
        !> identification fails, the message naming the file.
        type(error_type), allocatable, intent(out) :: error

        structure%path = path
        call read_green_layout(path, structure%matrix, error)
        if (.not. allocated(error)) call identify_green(options, structure, error)
    end subroutine read_green_structure

    !> Identify the receptances of a structure whose `path` and `matrix` are set (by
    !> `read_green_layout`) with shared poles; nothing to do for impulse responses.
    subroutine identify_green(options, structure, error)
        !> Settings of the identification.
        type(green_options), intent(in) :: options
        !> The structure: its matrix read, its identification and modes set here.
        type(green_structure), intent(inout) :: structure
        !> Set when the identification fails, the message naming the file.
        type(error_type), allocatable, intent(out) :: error

        type(shared_fit) :: other
        type(error_type), allocatable :: other_error
        real(dp) :: start, finish

        if (structure%matrix%function_type /= 4) return
        call cost_bound_text(structure%matrix, options, structure%cost_summary, structure%cost)
        call cpu_time(start)
        call identify_shared(structure%matrix%frequency, structure%matrix%g, structure%matrix%reciprocal, &
                             options%fit, structure%fit, error, options%poly_reference .and. .not. options%choose_poles)
        if (options%choose_poles) then
            ! the poly-reference fit may fail or fit worse (a structure with more modes than its
            ! matrix orders resolve): the summed driving points' fit is kept unless E says otherwise
            call identify_shared(structure%matrix%frequency, structure%matrix%g, structure%matrix%reciprocal, &
                                 options%fit, other, other_error, .true.)
            if (.not. allocated(other_error)) then
                if (allocated(error)) then
                    structure%fit = other
                    deallocate (error)
                else if (other%e_worst < structure%fit%e_worst) then
                    structure%e_other = structure%fit%e_worst
                    structure%fit = other
                else
                    structure%e_other = other%e_worst
                end if
            end if
        end if
        if (allocated(error)) then
            error%message = structure%path//': '//error%message
            return
        end if
        call shared_point_modes(structure%fit, options%term_tol, structure%modes)
        call cpu_time(finish)
        structure%cpu_time = finish - start
        structure%identified = .true.
        if (structure%fit%poly_reference) then
            associate (fit => structure%fit)
                structure%worst_sigma_f = maxval(fit%sigma_f/(abs(fit%pole)/two_pi))
                structure%worst_sigma_xi = maxval(fit%sigma_xi*abs(fit%pole)/max(-real(fit%pole, dp), tiny(1.0_dp)))
            end associate
        else
            structure%worst_sigma_f = structure%fit%pole_fit%worst_frequency_spread()
            structure%worst_sigma_xi = structure%fit%pole_fit%worst_damping_spread()
        end if
        call modes_error(structure)
    end subroutine identify_green

    !> The bound of the cost of identifying a matrix of receptances (greenconv_ident_cost), in
    !> words, with its seconds at the rate of the fits' Gram product measured here (0.05 s of CPU).
    subroutine cost_bound_text(matrix, options, text, cost)
        !> The matrix (its points, lines and reciprocity).
        type(green_matrix), intent(in) :: matrix
        !> Settings of the identification.
        type(green_options), intent(in) :: options
        !> The bound in words ('' for impulse responses, which are not identified).
        character(len=:), allocatable, intent(out) :: text
        !> The bound [flop].
        type(green_cost), intent(out), optional :: cost

        type(green_cost) :: bound

        text = ''
        if (matrix%function_type /= 4) return
        bound = green_cost_bound(matrix%n_points(), size(matrix%frequency), matrix%reciprocal, options%fit, &
                                 options%choose_poles .or. .not. options%poly_reference, &
                                 options%choose_poles .or. options%poly_reference)
        call cost_text(bound, measured_rate(0.05_dp), text)
        if (present(cost)) cost = bound
    end subroutine cost_bound_text

    !> Read the Green's matrix of a universal file without identifying it: its receptances, or
    !> its impulse responses (`matrix%function_type` 1) when it has no receptance, checked.
    subroutine read_green_layout(path, matrix, error)
        !> The universal file.
        character(len=*), intent(in) :: path
        !> The matrix, its points and their layout.
        type(green_matrix), intent(out) :: matrix
        !> Set (status 2) for a file that holds no complete Green's matrix.
        type(error_type), allocatable, intent(out) :: error

        type(uff_file) :: file

        call read_uff(path, file, error)
        if (allocated(error)) return
        if (any(file%functions%function_type == 4) .or. .not. any(file%functions%function_type == 1)) then
            call check_green_matrix(file, matrix, error)
        else
            call check_green_matrix(file, matrix, error, function_type=1)
            if (.not. allocated(error)) call check_time_grid(file, matrix, error)
        end if
    end subroutine read_green_layout

    !> Impulse responses must be sampled evenly from t = 0.
    subroutine check_time_grid(file, matrix, error)
        type(uff_file), intent(in) :: file
        type(green_matrix), intent(in) :: matrix
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: step
        integer :: l, n

        n = size(matrix%frequency)
        if (n < 2) then
            call fatal_error(error, file%path//': expected impulse responses of at least 2 samples, found ' &
                             //int_text(n))
            return
        end if
        step = matrix%frequency(2) - matrix%frequency(1)
        if (.not. (step > 0.0_dp) .or. abs(matrix%frequency(1)) > step_tolerance*step .or. &
            any([(abs(matrix%frequency(l) - matrix%frequency(1) - (l - 1)*step), l=1, n)] > step_tolerance*step)) then
            call fatal_error(error, file%path//': expected impulse responses g_ij(t) sampled evenly from t = 0 s, ' &
                             //'found times from '//sci_text(matrix%frequency(1))//' s by '//sci_text(step)//' s' &
                             //' (or uneven)')
        end if
    end subroutine check_time_grid

    !> E of eq. (7) of the modes alone, and of the modes with the upper residual U, against
    !> every receptance of the file.
    subroutine modes_error(structure)
        type(green_structure), intent(inout) :: structure

        complex(dp), allocatable :: model(:, :, :)
        integer :: i, j, l, n_c

        n_c = structure%n_points()
        allocate (model(n_c, n_c, size(structure%matrix%frequency)), structure%e_modes(n_c, n_c), &
                  structure%e_upper(n_c, n_c))
        do l = 1, size(structure%matrix%frequency)
            model(:, :, l) = patch_receptance(structure%modes, two_pi*structure%matrix%frequency(l))
        end do
        do j = 1, n_c
            do i = 1, n_c
                structure%e_modes(i, j) = error_e(structure%matrix%g(i, j, :), model(i, j, :))
                structure%e_upper(i, j) = error_e(structure%matrix%g(i, j, :), &
                                                  model(i, j, :) + structure%fit%upper(i, j))
            end do
        end do
    end subroutine modes_error

    !> g_ij(m*dt) [m/(N*s)], m = 0..N - 1, from the file itself:
    !>
    !> - impulse responses: every (dt/step)-th sample of the file, dt a whole multiple of its
    !>   step (else an error, status 2);
    !> - receptances: the inverse real FFT of each G_ij (greenconv_ident_lsce's `impulse_from_frf`),
    !>   the band-limited g_ij periodised with the period T = 1/df of the grid. dt must divide T
    !>   into an even number n >= 4 of samples: n = 2*(n_f - 1) gives the FFT's own step 1/(2*f_max); a larger even n
    !>   pads G with zeros above f_max (g band-limited, interpolated between the FFT's samples);
    !>   a smaller n dividing 2*(n_f - 1) keeps every (2*(n_f - 1)/n)-th sample. Only the first
    !>   half period is kept (the second holds g's wrapped end). When dt does not fit, no kernel
    !>   is returned and `source` says why (the caller may sample the modes instead).
    !>
    !> `source` says in words where g came from and, for receptances, how much of it is left at
    !> the end of the kept half period (the wrap-around: g not decayed within T/2). `fitted`
    !> gives the identified model's g_ij (modes and residual terms) by the same inverse FFT, so
    !> that the two differ by the fit's misfit alone, not by the band limit.
    subroutine sampled_kernel(structure, dt, kernel, source, error, fitted)
        !> The structure.
        type(green_structure), intent(in) :: structure
        !> Time step [s], > 0.
        real(dp), intent(in) :: dt
        !> kernel(m, i, j) = g_ij(m*dt), m = 0..N - 1; not allocated when dt does not fit G's grid.
        real(dp), allocatable, intent(out) :: kernel(:, :, :)
        !> Where g comes from, or why there is none.
        character(len=:), allocatable, intent(out) :: source
        !> Set (status 2) when dt does not fit the file's impulse responses.
        type(error_type), allocatable, intent(out) :: error
        !> The identified model's g_ij(m*dt) by the same inverse FFT as `kernel` (receptances only).
        real(dp), allocatable, intent(out), optional :: fitted(:, :, :)

        complex(dp), allocatable :: model(:, :, :)
        character(len=:), allocatable :: ignored

        if (.not. structure%identified) then
            call kernel_from_impulses(structure%matrix, dt, kernel, source, error)
            return
        end if
        call kernel_from_receptances(structure%matrix%frequency, structure%matrix%g, dt, kernel, source, error)
        if (allocated(error) .or. .not. allocated(kernel) .or. .not. present(fitted)) return
        call shared_receptance(structure%fit, structure%matrix%frequency, model)
        call kernel_from_receptances(structure%matrix%frequency, model, dt, fitted, ignored, error)
    end subroutine sampled_kernel

    !> The file's impulse responses at every stride-th sample.
    subroutine kernel_from_impulses(matrix, dt, kernel, source, error)
        type(green_matrix), intent(in) :: matrix
        real(dp), intent(in) :: dt
        real(dp), allocatable, intent(out) :: kernel(:, :, :)
        character(len=:), allocatable, intent(out) :: source
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: step
        integer :: stride, i, j, n

        step = matrix%frequency(2) - matrix%frequency(1)
        stride = nint(dt/step)
        if (stride < 1 .or. abs(stride*step - dt) > step_tolerance*dt) then
            call fatal_error(error, 'time step dt: expected '//sci_text(step)//' s or a whole multiple of it ' &
                             //'(the step of the file''s g_ij(t)), found '//sci_text(dt)//' s')
            source = ''
            return
        end if
        n = (size(matrix%frequency) - 1)/stride + 1
        allocate (kernel(0:n - 1, matrix%n_points(), matrix%n_points()))
        do j = 1, matrix%n_points()
            do i = 1, matrix%n_points()
                kernel(:, i, j) = real(matrix%g(i, j, 1::stride), dp)
            end do
        end do
        source = 'g_ij(t) of the file ('//int_text(n)//' samples'
        if (stride > 1) source = source//', every '//int_text(stride)//'th'
        source = source//')'
    end subroutine kernel_from_impulses

    !> g_ij at dt by the inverse FFT of receptances g(i, j, l) on a grid from 0 Hz (see `sampled_kernel`).
    subroutine kernel_from_receptances(frequency, receptance, dt, kernel, source, error)
        real(dp), intent(in) :: frequency(:)
        complex(dp), intent(in) :: receptance(:, :, :)
        real(dp), intent(in) :: dt
        real(dp), allocatable, intent(out) :: kernel(:, :, :)
        character(len=:), allocatable, intent(out) :: source
        type(error_type), allocatable, intent(out) :: error

        type(frf_type) :: frf
        real(dp), allocatable :: g(:)
        real(dp) :: df, samples, step, peak, tail
        integer :: n, n_fft, n_lines, stride, i, j, l, n_f, n_c, first_tail

        n_f = size(frequency)
        n_c = size(receptance, 1)
        df = frequency(2) - frequency(1)
        samples = 1.0_dp/(df*dt)
        n = nint(samples)
        n_fft = 2*(n_f - 1)
        source = ''
        if (n < 4 .or. abs(samples - n) > step_tolerance*samples) then
            source = 'dt = '//sci_text(dt)//' s does not divide the period 1/df = '//sci_text(1.0_dp/df) &
                     //' s of G''s grid'
        else if (mod(n, 2) /= 0) then
            source = 'dt = '//sci_text(dt)//' s divides 1/df into an odd number of samples ('//int_text(n)//')'
        else if (n < n_fft .and. mod(n_fft, n) /= 0) then
            source = 'dt = '//sci_text(dt)//' s is not a whole multiple of the FFT step ' &
                     //sci_text(1.0_dp/(2.0_dp*frequency(n_f)))//' s (1/(2*f) at G''s last line f)'
        end if
        if (len(source) > 0) return
        n_lines = max(n_f, n/2 + 1)
        stride = max(1, n_fft/n)
        frf%frequency = [(l*df, l=0, n_lines - 1)]
        allocate (frf%receptance(n_lines), kernel(0:n/2 - 1, n_c, n_c))
        frf%receptance(:) = (0.0_dp, 0.0_dp)
        do j = 1, n_c
            do i = 1, n_c
                frf%receptance(1:n_f) = receptance(i, j, :)
                call impulse_from_frf(frf, g, step, error)
                if (allocated(error)) return
                kernel(:, i, j) = g(1:size(g)/2:stride)
            end do
        end do
        peak = max(maxval(abs(kernel)), tiny(1.0_dp))
        first_tail = int((1.0_dp - wrap_fraction)*(n/2))
        tail = maxval(abs(kernel(first_tail:, :, :)))/peak
        source = 'g_ij by inverse FFT of G (band 0 to '//sci_text(frequency(n_f))//' Hz'
        if (n > n_fft) source = source//', zero above'
        source = source//', half period '//sci_text(0.5_dp/df)//' s; its last tenth reaches '//sci_text(tail) &
                 //' of max|g|)'
    end subroutine kernel_from_receptances

    !> The summary of the structure in "# " lines, joined by line ends: the file and its points,
    !> the identification (order, noise, worst uncertainty, E per receptance and per point) and
    !> the modes the modal methods run on, the reciprocity warning.
    function structure_summary(self) result(text)
        !> The structure.
        class(green_structure), intent(in) :: self
        character(len=:), allocatable :: text

        call summary_text(self, text)
    end function structure_summary

    !> The summary of `structure_summary` into an intent(out) text: a caller that two threads
    !> may run at once takes it so, without the static length a deferred-length result keeps.
    subroutine summary_text(self, text)
        !> The structure.
        class(green_structure), intent(in) :: self
        !> Its summary in "# " lines, joined by line ends.
        character(len=:), allocatable, intent(out) :: text

        character(len=*), parameter :: nl = new_line('a')
        integer :: worst

        associate (matrix => self%matrix)
            text = '# Green''s matrix: '//self%path//': '//int_text(matrix%n_points())//' points (nodes ' &
                   //int_text(minval(matrix%node))//' to '//int_text(maxval(matrix%node))//'), x from ' &
                   //sci_text(minval(matrix%x))//' to '//sci_text(maxval(matrix%x))//' m, y from ' &
                   //sci_text(minval(matrix%y))//' to '//sci_text(maxval(matrix%y))//' m, '
            if (.not. self%identified) then
                text = text//int_text(size(matrix%frequency))//' samples of g_ij(t) by ' &
                       //sci_text(matrix%frequency(2) - matrix%frequency(1))//' s (no identification: direct and ' &
                       //'fft only)'
            else
                text = text//int_text(size(matrix%frequency))//' lines of G_ij to ' &
                       //sci_text(maxval(matrix%frequency)) &
                       //' Hz, reciprocity ratio '//sci_text(matrix%reciprocity)//' (about 1 for noise alone)'
            end if
        end associate
        if (.not. self%identified) return
        if (allocated(self%cost_summary)) text = text//nl//'# '//self%cost_summary//'; measured CPU ' &
                                                 //sci_text(self%cpu_time)//' s'
        associate (fit => self%fit, ml => self%fit%pole_fit)
            worst = maxloc(fit%e_point, 1)
            if (fit%poly_reference) then
                text = text//nl//'# identification: shared poles, '//int_text(size(fit%pole))//' poles ' &
                       //'(poly-reference fit of all receptances, '//trim(merge('matrix order      ', &
                       'common denominator', fit%order > 0))//' '//int_text(abs(fit%order))//' by MDL'
                if (self%e_other >= 0.0_dp) text = text//'; chosen over the summed driving points, E worst ' &
                                                  //sci_text(self%e_other)
                text = text//'), noise '
            else
                text = text//nl//'# identification: shared poles, '//int_text(size(fit%pole))//' poles (maximum ' &
                       //'likelihood on the summed driving points, order by MDL, diagram to N = ' &
                       //int_text(maxval([0, ml%diagram_order]))//', refined over all receptances), noise '
            end if
            text = text &
                   //sci_text(fit%noise_level)//' of |G|, worst sigma_f/f = '//sci_text(self%worst_sigma_f) &
                   //', worst sigma_xi/xi = '//sci_text(self%worst_sigma_xi)//'; E (eq. 7) per receptance worst ' &
                   //sci_text(fit%e_worst)//', mean '//sci_text(fit%e_mean)//'; per point worst ' &
                   //sci_text(fit%e_point(worst))//' (node '//int_text(self%matrix%node(worst))//'), mean ' &
                   //sci_text(sum(fit%e_point)/size(fit%e_point))//'; CPU '//sci_text(self%cpu_time)//' s'
            text = text//nl//'# modes: '//int_text(self%modes%modes%n_modes())//' terms with real shapes from the ' &
                   //int_text(size(fit%pole))//' residue matrices (largest distance from rank one ' &
                   //sci_text(maxval([0.0_dp, fit%rank_one]))//')'
            if (ml%has_upper .or. ml%has_lower) text = text//'; the fit''s residual terms (' &
                //trim(merge('U   ', '    ', ml%has_upper))//trim(merge(' L', '  ', ml%has_lower)) &
                //') are left out of the modes'
            text = text//'; the modes alone: E worst '//sci_text(maxval(self%e_modes))//', mean ' &
                   //sci_text(sum(self%e_modes)/size(self%e_modes))
        end associate
        if (allocated(self%matrix%warning)) then
            if (len(self%matrix%warning) > 0) text = text//nl//'# warning: '//self%matrix%warning
        end if
    end subroutine summary_text

end module greenconv_ident_green_structure
