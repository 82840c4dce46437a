!> What the C and Fortran 77 front doors share for multi-point contact: the checks of the
!> constructors' plain arrays, and contact runs into caller-sized arrays, on the one object
!> behind every handle, greenconv_api_handle's `convolver_box`.
!>
!> A multi-point box holds a convolver (greenconv_conv_multipoint) built from one of
!>
!> - modes shared by the N_c points in the form of greenconv_model_point_modes: poles lambda_k
!>   [rad/s], residues r_k of the unit modal impulse responses and mode shapes phi_ik, so that
!>   g_ij(t) = sum_k phi_ik*phi_jk*2*Re(r_k*exp(lambda_k*t)) (a rank-one residue matrix
!>   r_k*phi_k*phi_k^T per mode; no engine takes a general residue matrix), for every method
!>   of the registry that serves multi-point contact;
!> - samples g_ij(m*dt) [m/(N*s)], for `direct` and `fft`, truncated by the paper's rule;
!> - a universal file of a Green's matrix (greenconv_conv_green_file: its receptances
!>   identified with shared poles, or its impulse responses), kept read and identified in the
!>   box, so that another method or time step on the same file costs no second identification;
!> - a universal file of normal modes from an FE model (datasets 15/2411 and 55,
!>   greenconv_model_modes_file), its nodes the points and its modes up to a band stepped,
!>   those above as their static compliance in W0, as a scene's `&structure model =
!>   'modes_file'` takes them (all of the file's nodes);
!>
!> with what its model neglects, the Newton and divergence settings of its contact runs and
!> the state of a run stepped one call at a time. Each box keeps its method's own estimate
!> of its relative error; when the host asks an accuracy (`set_box_accuracy`), a box whose
!> estimate exceeds it makes the calls that run contact end with status 4 (`stat_accuracy`,
!> "ran, but outside the accuracy asked"), as a scene's runner does. The arrays the doors pass are laid out as
!> Fortran stores them: shape(i, k) = phi_ik, g(m, i, j) = g_ij(m*dt), road(n, i) = u_r,i(t_n).
!> There is no module state.
module greenconv_api_multi_handle
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error, stat_accuracy
    use greenconv_core_text, only: lower_text, sci_text, int_text
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_plate, only: tyre_plate, plate_modes, patch_points
    use greenconv_model_modes_file, only: file_modes, read_file_modes, split_band, band_bytes
    use greenconv_api_doors, only: need_method, need_count
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_builder, only: make_multipoint_convolver, table_convolver, check_kernel_values
    use greenconv_conv_green_file, only: green_file_convolver
    use greenconv_conv_engines, only: engine_constructors, engine_of
    use greenconv_ident_green_structure, only: green_options, green_structure, read_green_structure, summary_text
    use greenconv_contact_law, only: contact_law
    use greenconv_contact_multi, only: newton_options, multi_contact_response, &
                                       start_multi_contact, multi_contact_block, run_multi_contact
    use greenconv_scene_facade, only: max_lsce_modes, max_contact_points
    use greenconv_api_library, only: check_contact_law
    use greenconv_api_handle, only: convolver_box, free_box
    use greenconv_api_budget, only: start_budget, feed_budget, stop_budget, outside_accuracy
    implicit none
    private

    public :: modes_multi_box, samples_multi_box, patch_modes, file_multi_box
    public :: method_multi_box, check_file_box, file_e_modes, modes_file_box, box_points
    public :: file_summary
    public :: check_box, set_multi_options, start_multi_box, advance_multi_box, run_multi_box
    public :: run_request

    !> What every multi-point constructor builds its convolver for, as a door gives it: the
    !> method, the time step, the truncation and the run length, checked by name in the box's
    !> constructor and kept in the box for the error budget's companions.
    type :: run_request
        !> Method: `modal` (= `recursive`), `exact`, `direct` or `fft`, any case (the constructor
        !> of samples takes `direct` and `fft` alone).
        character(len=:), allocatable :: method
        !> Time step dt [s], > 0.
        real(dp) :: dt = 0.0_dp
        !> Truncation fraction of max |g_ij| for `direct` and `fft`, in [0, 1) (0 keeps the whole run).
        real(dp) :: truncation_tol = 0.0_dp
        !> Number of steps N_t of the run, >= 1.
        integer :: n_steps = 0
    end type run_request

contains

    !> A new box for modes shared by the points (poles, residues, mode shapes), the arrays
    !> checked by name; null on failure.
    subroutine modes_multi_box(caller, pole_re, pole_im, residue_re, residue_im, shape, request, box, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> Real parts of the poles lambda_k [rad/s], < 0 (N_m).
        real(dp), intent(in) :: pole_re(:)
        !> Imaginary parts of the poles [rad/s], > 0 (N_m).
        real(dp), intent(in) :: pole_im(:)
        !> Real parts of the residues r_k of the modal impulse responses (N_m).
        real(dp), intent(in) :: residue_re(:)
        !> Imaginary parts of the residues (N_m).
        real(dp), intent(in) :: residue_im(:)
        !> Mode shapes shape(i, k) = phi_ik at the points (N_c x N_m), phi_ik*phi_jk*r_k in m/(N*s).
        real(dp), intent(in) :: shape(:, :)
        !> Method (`modal` (= `recursive`), `exact`, `direct` or `fft`), dt, truncation and N_t.
        type(run_request), intent(in) :: request
        !> The new box; null when `error` is set.
        type(convolver_box), pointer, intent(out) :: box
        !> Set (`stat_input`) naming the argument out of range.
        type(error_type), allocatable, intent(out) :: error

        type(point_modes) :: description

        box => null()
        call need_count(caller, 'n_modes', size(pole_re), 1, 'mode', error)
        call need_count(caller, 'n_points', size(shape, 1), 1, 'point', error)
        if (allocated(error)) then
            return
        else if (.not. all(pole_re < 0.0_dp .and. pole_im > 0.0_dp .and. ieee_is_finite(pole_re) &
                           .and. ieee_is_finite(pole_im))) then
            call fatal_error(error, caller//': pole_re, pole_im: give every pole a finite real part < 0 and ' &
                             //'imaginary part > 0 rad/s (a damped mode)')
        else if (.not. all(ieee_is_finite(residue_re) .and. ieee_is_finite(residue_im))) then
            call fatal_error(error, caller//': residue_re, residue_im: give finite residues')
        else if (.not. all(ieee_is_finite(shape))) then
            call fatal_error(error, caller//': shape: give finite mode shapes phi_ik')
        else
            call check_run(caller, request, error)
        end if
        if (allocated(error)) return
        description%modes%pole = cmplx(pole_re, pole_im, dp)
        description%modes%residue = cmplx(residue_re, residue_im, dp)
        description%shape = shape
        call modes_box(caller, description, request, box, error)
    end subroutine modes_multi_box

    !> A new box for checked modes at the points: the kernel's size checked against the cap,
    !> the convolver and its own error estimate made; null on failure.
    subroutine modes_box(caller, description, request, box, error, residual)
        character(len=*), intent(in) :: caller
        type(point_modes), intent(in) :: description
        type(run_request), intent(in) :: request
        type(convolver_box), pointer, intent(out) :: box
        type(error_type), allocatable, intent(out) :: error
        !> Static compliance [m/N] of modes left out of `description` (a modes file's above its
        !> band; unallocated when none are).
        real(dp), allocatable, intent(in), optional :: residual(:, :)

        box => null()
        if (description%modes%n_modes() > 0) call check_kernel_values(lower_text(request%method), &
            description%modes%slowest_decay(), request%dt, request%truncation_tol, request%n_steps, &
            description%n_points(), error)
        if (allocated(error)) then
            error%message = caller//': '//error%message
            return
        end if
        allocate (box)
        call make_multipoint_convolver(lower_text(request%method), description, request%dt, request%truncation_tol, &
                                       request%n_steps, box%conv, box%description, error, box%estimate, residual)
        call keep_or_drop(caller, box, error)
        if (.not. associated(box)) return
        call keep_recipe(box, request)
        box%source_modes = description
        if (present(residual)) then
            if (allocated(residual)) box%source_residual = residual
        end if
    end subroutine modes_box

    !> Keep what the error budget's companions of a box's whole runs are built with.
    subroutine keep_recipe(box, request)
        type(convolver_box), intent(inout) :: box
        type(run_request), intent(in) :: request

        box%method = lower_text(request%method)
        box%dt = request%dt
        box%truncation_tol = request%truncation_tol
        box%n_steps = request%n_steps
    end subroutine keep_recipe

    !> A new box on a universal file of normal modes (greenconv_model_modes_file): every node of
    !> the file a point (in the file's order), the modes up to `f_band` stepped by `method`,
    !> those above it kept as their static compliance R (greenconv_model_modes_file's
    !> `split_band`, added to W0 by greenconv_conv_builder) and reported in the description as
    !> a scene's summary reports them: the same convolver as a scene with `&structure model =
    !> 'modes_file'` makes on those nodes. Null on failure.
    subroutine modes_file_box(caller, path, direction, damping_ratio, f_band, request, box, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The universal file (nodes in dataset 15 or 2411, one dataset 55 per mode).
        character(len=*), intent(in) :: path
        !> Direction of the shapes at the contact: +-1, +-2, +-3 for +-X, +-Y, +-Z.
        integer, intent(in) :: direction
        !> Viscous damping ratio of the modes the file gives none, in [0, 1).
        real(dp), intent(in) :: damping_ratio
        !> Highest natural frequency stepped [Hz], > 0; 0 for the Nyquist frequency 1/(2*dt).
        real(dp), intent(in) :: f_band
        !> Method (`modal` (= `recursive`), `exact`, `direct` or `fft`), dt, truncation and N_t.
        type(run_request), intent(in) :: request
        !> The new box; null when `error` is set.
        type(convolver_box), pointer, intent(out) :: box
        !> Set (`stat_input`) for a bad argument or file, with the reader's message.
        type(error_type), allocatable, intent(out) :: error

        type(file_modes) :: modes
        type(point_modes) :: description
        real(dp), allocatable :: residual(:, :)
        character(len=:), allocatable :: summary
        type(engine_constructors) :: engine
        real(dp) :: band, share
        integer :: i

        box => null()
        call check_run(caller, request, error)
        if (allocated(error)) return
        if (all(abs(direction) /= [1, 2, 3])) then
            call fatal_error(error, caller//': direction = '//int_text(direction)//': give 1, 2 or 3 (X, Y, Z), ' &
                             //'negative for the opposite sense')
        else if (.not. (damping_ratio >= 0.0_dp .and. damping_ratio < 1.0_dp)) then
            call fatal_error(error, caller//': damping_ratio = '//sci_text(damping_ratio)//': give a ratio in [0, 1)')
        else if (.not. (f_band >= 0.0_dp .and. ieee_is_finite(f_band))) then
            call fatal_error(error, caller//': f_band = '//sci_text(f_band)//' Hz: give a finite band >= 0 Hz ' &
                             //'(0: the Nyquist frequency 1/(2*dt))')
        end if
        call need_method(caller, request%method, .true., .true., error)
        if (allocated(error)) return
        band = f_band
        if (band <= 0.0_dp) band = 0.5_dp/request%dt
        call read_file_modes(path, direction, damping_ratio, modes, error)
        ! every node is a point: sized before the N_c x N_c matrices are made (nested: Fortran's
        ! .and. may look at both sides, and modes is unset after a failed read)
        if (.not. allocated(error)) then
            if (size(modes%x) > max_contact_points) call fatal_error(error, path &
                //': expected at most '//int_text(max_contact_points)//' nodes (each node is a contact point), found ' &
                //int_text(size(modes%x))//', whose N_c x N_c static compliance alone would take ' &
                //sci_text(band_bytes(size(modes%x), size(modes%frequency))/1.0e9_dp)//' GB: give a file of ' &
                //'the patch''s nodes')
        end if
        if (.not. allocated(error)) call split_band(modes, band, [(i, i=1, size(modes%x))], damping_ratio, description, &
                                                    residual, summary, error, share)
        if (allocated(error)) then
            error%message = caller//': '//error%message
            return
        end if
        call modes_box(caller, description, request, box, error, residual)
        if (allocated(error)) return
        box%node = modes%label
        box%node_x = modes%x
        box%node_y = modes%y
        if (allocated(residual)) then
            box%source_file = modes
            box%band = band
            ! Before a run: the static flexibility the band leaves out, for a method that does
            ! not hold it in W0 (an upper bound of the static share of the forces' error); a
            ! run's band companion then measures the band's whole term.
            engine = engine_of(lower_text(request%method))
            if (.not. (engine%samples_g() .or. engine%instant_part)) box%prior_terms = share
            box%run_terms = box%prior_terms
        end if
        box%description = box%description//'; modes of '//path//', '//summary
    end subroutine modes_file_box

    !> A new box convolving with samples g(m, i, j) = g_ij(m*dt) (`direct` or `fft`), the
    !> table truncated by the paper's rule over max_ij |g_ij(t_m)| and never beyond the run;
    !> null on failure.
    subroutine samples_multi_box(caller, g, request, box, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> Samples g(m, i, j) = g_ij(m*dt) [m/(N*s)], m = 0..N_s-1 (N_s >= 2), N_c x N_c.
        real(dp), intent(in) :: g(0:, :, :)
        !> Method (`direct` or `fft`), the time step dt of the samples and of the run, truncation and N_t.
        type(run_request), intent(in) :: request
        !> The new box; null when `error` is set.
        type(convolver_box), pointer, intent(out) :: box
        !> Set (`stat_input`) naming the argument out of range.
        type(error_type), allocatable, intent(out) :: error

        box => null()
        call need_count(caller, 'n_points', size(g, 2), 1, 'point', error)
        call need_count(caller, 'n_samples', size(g, 1), 2, 'samples of every g_ij', error)
        if (allocated(error)) then
            return
        else if (.not. all(ieee_is_finite(g))) then
            call fatal_error(error, caller//': g: give finite samples [m/(N*s)]')
        else
            call check_run(caller, request, error)
        end if
        call need_method(caller, request%method, .true., .false., error)
        if (allocated(error)) return
        allocate (box)
        call table_convolver(lower_text(request%method), g, request%dt, request%truncation_tol, request%n_steps, &
                             box%conv, box%description, error)
        call keep_or_drop(caller, box, error)
        if (.not. associated(box)) return
        call keep_recipe(box, request)
        box%source_g = g
    end subroutine samples_multi_box

    !> A new box on a universal file of a Green's matrix (greenconv_conv_green_file): the file
    !> read, its receptances identified with shared poles (up to `max_order` modes in the
    !> stabilisation diagram), and `method` built on it; null on failure.
    subroutine file_multi_box(caller, path, request, max_order, box, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The universal file (nodes in dataset 15 or 2411, datasets 58 of receptances or impulse responses).
        character(len=*), intent(in) :: path
        !> Method (`modal` (= `recursive`), `exact`, `direct` or `fft`), dt, truncation and N_t.
        type(run_request), intent(in) :: request
        !> Largest order of the pole fit's stabilisation diagram, >= 1, or 0 for the library's default.
        integer, intent(in) :: max_order
        !> The new box; null when `error` is set.
        type(convolver_box), pointer, intent(out) :: box
        !> Set (`stat_input`) for a bad argument or file, naming it; (`stat_numerical`) when the
        !> identification fails.
        type(error_type), allocatable, intent(out) :: error

        type(green_options) :: options

        box => null()
        call check_run(caller, request, error)
        if (.not. allocated(error) .and. (max_order < 0 .or. max_order > max_lsce_modes)) then
            call fatal_error(error, caller//': max_order = '//int_text(max_order) &
                             //': give the largest order of the pole fit (1 to '//int_text(max_lsce_modes) &
                             //'), or 0 for the default')
        end if
        if (allocated(error)) return
        ! A method no file serves is refused before the identification, which takes seconds.
        call need_method(caller, request%method, .true., .true., error)
        if (allocated(error)) return
        if (max_order > 0) options%fit%max_order = max_order
        allocate (box)
        allocate (box%green)
        call read_green_structure(path, options, box%green, error)
        call build_on_file(caller, request, box, error)
    end subroutine file_multi_box

    !> A new box for another method, time step or run length on the file a box made by
    !> `file_multi_box` read and identified (no second identification); null on failure.
    subroutine method_multi_box(caller, source, request, box, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> A box made by `file_multi_box`.
        type(convolver_box), intent(in) :: source
        !> Method (`modal` (= `recursive`), `exact`, `direct` or `fft`), dt, truncation and N_t.
        type(run_request), intent(in) :: request
        !> The new box; null when `error` is set.
        type(convolver_box), pointer, intent(out) :: box
        !> Set (`stat_input`) for a bad argument or a source not made from a file.
        type(error_type), allocatable, intent(out) :: error

        box => null()
        call check_run(caller, request, error)
        if (allocated(error)) return
        if (.not. allocated(source%green)) then
            call fatal_error(error, caller//': the source convolver was not made from a file: make it with ' &
                             //'gc_multi_new_file (GCMFIL)')
            return
        end if
        allocate (box)
        allocate (box%green, source=source%green)
        call build_on_file(caller, request, box, error)
    end subroutine method_multi_box

    !> Check that a box was made from a file (after `check_box`).
    subroutine check_file_box(caller, box, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The box (checked by `check_box`).
        type(convolver_box), intent(in) :: box
        !> Set (`stat_input`) when the box holds no file.
        type(error_type), allocatable, intent(out) :: error

        if (.not. allocated(box%green)) call fatal_error(error, caller//': the convolver was not made from a ' &
                                                         //'file (gc_multi_new_file, GCMFIL): it has no nodes ' &
                                                         //'and no identification')
    end subroutine check_file_box

    !> The node labels and positions x_i, y_i [m] of the points of a box made from a file (a
    !> Green's matrix or a modes file), in the convolver's order.
    subroutine box_points(caller, box, node, x, y, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The box (checked by `check_box`).
        type(convolver_box), intent(in) :: box
        !> Node labels.
        integer, allocatable, intent(out) :: node(:)
        !> x_i [m], along the travel.
        real(dp), allocatable, intent(out) :: x(:)
        !> y_i [m], across.
        real(dp), allocatable, intent(out) :: y(:)
        !> Set (`stat_input`) when the box was made from no file.
        type(error_type), allocatable, intent(out) :: error

        if (allocated(box%node)) then
            node = box%node
            x = box%node_x
            y = box%node_y
            return
        end if
        call check_file_box(caller, box, error)
        if (allocated(error)) return
        node = box%green%matrix%node
        x = box%green%matrix%x
        y = box%green%matrix%y
    end subroutine box_points

    !> The summary in "# " lines of the file a box was made from (greenconv_ident_green_structure's
    !> `summary_text`), into an intent(out) text.
    subroutine file_summary(box, text)
        !> The box, made from a Green's matrix file.
        type(convolver_box), intent(in) :: box
        !> The summary, lines joined by line ends.
        character(len=:), allocatable, intent(out) :: text

        call summary_text(box%green, text)
    end subroutine file_summary

    !> E of eq. (7) of the identified modes alone against the file's receptances, worst and
    !> mean over the receptances, and the number of shared poles (all 0 for impulse responses).
    subroutine file_e_modes(green, e_worst, e_mean, n_poles)
        !> The file read (and identified when it held receptances).
        type(green_structure), intent(in) :: green
        !> Worst E over the receptances.
        real(dp), intent(out) :: e_worst
        !> Mean E over the receptances.
        real(dp), intent(out) :: e_mean
        !> Number of shared poles.
        integer, intent(out) :: n_poles

        e_worst = 0.0_dp
        e_mean = 0.0_dp
        n_poles = 0
        if (.not. green%identified) return
        e_worst = maxval(green%e_modes)
        e_mean = sum(green%e_modes)/size(green%e_modes)
        n_poles = size(green%fit%pole)
    end subroutine file_e_modes

    !> The convolver of a box whose file is read (unless `error` is set), and its description;
    !> the box freed on failure.
    subroutine build_on_file(caller, request, box, error)
        character(len=*), intent(in) :: caller
        type(run_request), intent(in) :: request
        type(convolver_box), pointer, intent(inout) :: box
        type(error_type), allocatable, intent(inout) :: error

        if (.not. allocated(error)) then
            call green_file_convolver(box%green, lower_text(request%method), request%dt, request%truncation_tol, &
                                      request%n_steps, box%conv, box%description, error, box%estimate)
        end if
        call keep_recipe(box, request)
        call keep_or_drop(caller, box, error)
    end subroutine build_on_file

    !> The modes of the library's tyre belt (greenconv_model_plate's default `tyre_plate`) up
    !> to f_max at an n_x by n_y patch centred on the belt (`patch_points`, x fastest), in the
    !> order of `plate_modes`.
    subroutine patch_modes(caller, band_name, n_x, n_y, extent, f_max, modes, x, y, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The door's name for f_max (`f_max`, `FMAX`), for the messages.
        character(len=*), intent(in) :: band_name
        !> Points along x (the direction of travel), >= 1.
        integer, intent(in) :: n_x
        !> Points across, >= 1.
        integer, intent(in) :: n_y
        !> Length along x and width along y of the patch [m], each in (0, the belt's size).
        real(dp), intent(in) :: extent(2)
        !> Highest natural frequency kept [Hz], > 0.
        real(dp), intent(in) :: f_max
        !> The modes and shapes at the points.
        type(point_modes), intent(out) :: modes
        !> x_i [m] of the points.
        real(dp), allocatable, intent(out) :: x(:)
        !> y_i [m] of the points.
        real(dp), allocatable, intent(out) :: y(:)
        !> Set (`stat_input`) naming the argument out of range.
        type(error_type), allocatable, intent(out) :: error

        type(tyre_plate) :: plate

        if (n_x < 1 .or. n_y < 1) then
            call fatal_error(error, caller//': n_x = '//int_text(n_x)//', n_y = '//int_text(n_y) &
                             //': give at least 1 point each way')
        else if (.not. (extent(1) > 0.0_dp .and. extent(1) < plate%length .and. extent(2) > 0.0_dp &
                        .and. extent(2) < plate%width)) then
            call fatal_error(error, caller//': extent = ('//sci_text(extent(1))//', '//sci_text(extent(2)) &
                             //') m: give a patch within the belt, '//sci_text(plate%length)//' m by ' &
                             //sci_text(plate%width)//' m')
        else if (.not. (f_max > 0.0_dp .and. ieee_is_finite(f_max))) then
            call fatal_error(error, caller//': '//band_name//' = '//sci_text(f_max)//' Hz: give a finite ' &
                             //band_name//' > 0 Hz')
        end if
        if (allocated(error)) return
        allocate (x(n_x*n_y), y(n_x*n_y))
        call patch_points([plate%length/2, plate%width/2], extent, n_x, n_y, x, y)
        call plate_modes(plate, x, y, f_max, modes, error, band_name)
        if (allocated(error)) error%message = caller//': '//error%message
    end subroutine patch_modes

    !> Check a door's handle and, when n_points >= 0, that its count of points agrees with
    !> the convolver's.
    subroutine check_box(caller, missing, box, n_points, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> What to say of a null handle, e.g. "conv is NULL: make one with gc_multi_new_modes".
        character(len=*), intent(in) :: missing
        !> The box, or null.
        type(convolver_box), pointer, intent(in) :: box
        !> Number of points the caller's arrays hold; absent: not checked (a negative count is refused).
        integer, intent(in), optional :: n_points
        !> Set (`stat_input`) for a null handle or a count that differs.
        type(error_type), allocatable, intent(out) :: error

        if (.not. associated(box)) then
            call fatal_error(error, caller//': '//missing)
        else if (.not. present(n_points)) then
            return
        else if (n_points /= box%conv%n_points()) then
            call fatal_error(error, caller//': n_points = '//int_text(n_points)//': the convolver has ' &
                             //int_text(box%conv%n_points())//' points: pass arrays of that many values')
        end if
    end subroutine check_box

    !> Set the Newton and divergence settings of the box's next contact runs.
    subroutine set_multi_options(caller, box, tolerance, max_iterations, divergence_bound, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The box.
        type(convolver_box), intent(inout) :: box
        !> Relative tolerance of the step's residual (dimensionless), > 0.
        real(dp), intent(in) :: tolerance
        !> Most Newton iterations per step, >= 1.
        integer, intent(in) :: max_iterations
        !> Largest |u_i| [m] accepted, > 0.
        real(dp), intent(in) :: divergence_bound
        !> Set (`stat_input`) naming the setting out of range.
        type(error_type), allocatable, intent(out) :: error

        if (.not. (tolerance > 0.0_dp .and. ieee_is_finite(tolerance))) then
            call fatal_error(error, caller//': tolerance = '//sci_text(tolerance)//': give a finite tolerance > 0')
        else if (max_iterations < 1) then
            call fatal_error(error, caller//': max_iterations = '//int_text(max_iterations)//': give at least 1')
        else if (.not. (divergence_bound > 0.0_dp)) then
            call fatal_error(error, caller//': divergence_bound = '//sci_text(divergence_bound) &
                             //' m: give a bound > 0 m')
        else
            box%settings = newton_options(tolerance, max_iterations, divergence_bound)
        end if
    end subroutine set_multi_options

    !> Start a contact run stepped one call at a time (`advance_multi_box`): laws and preloads
    !> checked point by point, the convolver reset.
    subroutine start_multi_box(caller, box, laws, preload, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The box: its convolver reset, its stepped run and the run's budget started.
        type(convolver_box), intent(inout) :: box
        !> Contact law of each point (N_c, of one dynamic type), checked here.
        class(contact_law), intent(in) :: laws(:)
        !> Static preload F0_i [N] of each point, >= 0.
        real(dp), intent(in) :: preload(:)
        !> Set (`stat_input`) naming the point whose law is out of range; (`stat_accuracy`) when
        !> the run started but the method is outside the accuracy asked.
        type(error_type), allocatable, intent(out) :: error

        box%stepping = .false.
        call check_laws(caller, laws, preload, error)
        if (allocated(error)) return
        call start_multi_contact(box%conv, laws, preload, box%contact, error, box%settings)
        if (allocated(error)) error%message = caller//': '//error%message
        box%stepping = .not. allocated(error)
        if (.not. box%stepping) return
        call start_budget(box, laws, preload, box%n_steps)
        call outside_accuracy(caller, box, error)
    end subroutine start_multi_box

    !> The next step of the run `start_multi_box` began, exactly as `run_multi_contact` takes
    !> it: the outputs are zero after a fault, which ends the run and names step and point.
    subroutine advance_multi_box(caller, box, road, displacement, force, compression, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The box.
        type(convolver_box), intent(inout) :: box
        !> Road heights u_r,i(t_n) [m] under the points.
        real(dp), intent(in) :: road(:)
        !> Displacements u_i(t_n) [m].
        real(dp), intent(out) :: displacement(:)
        !> Contact forces F_i(t_n) [N].
        real(dp), intent(out) :: force(:)
        !> Compressions delta_i(t_n) [m].
        real(dp), intent(out) :: compression(:)
        !> Set when no run is going on (`stat_input`) or the step fails (`stat_numerical`).
        type(error_type), allocatable, intent(out) :: error

        type(multi_contact_response) :: response

        displacement(:) = 0.0_dp
        force(:) = 0.0_dp
        compression(:) = 0.0_dp
        if (.not. box%stepping) then
            call fatal_error(error, caller//': no contact run is going on with this convolver: start one first ' &
                             //'(a fault or a reset ends a run)')
            return
        end if
        call multi_contact_block(box%conv, box%contact, reshape(road, [1, size(road)]), response, error)
        if (allocated(error)) then
            box%stepping = .false.
            call stop_budget(box)
            error%message = caller//': '//error%message
            return
        end if
        displacement(:) = response%displacement(0, :)
        force(:) = response%force(0, :)
        compression(:) = response%compression(0, :)
        call feed_budget(box, reshape(road, [1, size(road)]), response%force)
    end subroutine advance_multi_box

    !> A whole contact run (`run_multi_contact`, the convolver reset first) into arrays
    !> road-shaped (0:N_t-1, N_c): the steps done, then zero after a fault, which `error`
    !> names (step, time, point).
    subroutine run_multi_box(caller, box, laws, preload, road, displacement, force, compression, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The box: its convolver reset and run over the whole road, the run's budget taken.
        type(convolver_box), intent(inout) :: box
        !> Contact law of each point (N_c, of one dynamic type), checked here.
        class(contact_law), intent(in) :: laws(:)
        !> Static preload F0_i [N] of each point, >= 0.
        real(dp), intent(in) :: preload(:)
        !> Road heights road(n, i) = u_r,i(t_n) [m].
        real(dp), intent(in) :: road(0:, :)
        !> Displacements u_i(t_n) [m]; zero after a fault.
        real(dp), intent(out) :: displacement(0:, :)
        !> Contact forces F_i(t_n) [N]; zero after a fault.
        real(dp), intent(out) :: force(0:, :)
        !> Compressions delta_i(t_n) [m]; zero after a fault.
        real(dp), intent(out) :: compression(0:, :)
        !> Set on bad input (`stat_input`) or a fault of the run (`stat_numerical`); (`stat_accuracy`)
        !> when the run is whole but the method outside the accuracy asked.
        type(error_type), allocatable, intent(out) :: error

        type(multi_contact_response) :: response
        integer :: n_done

        box%stepping = .false.
        displacement(:, :) = 0.0_dp
        force(:, :) = 0.0_dp
        compression(:, :) = 0.0_dp
        call check_laws(caller, laws, preload, error)
        if (allocated(error)) return
        call run_multi_contact(box%conv, laws, road, preload, response, error, &
                               box%settings)
        if (allocated(error)) error%message = caller//': '//error%message
        if (.not. allocated(response%force)) return
        n_done = size(response%force, 1)
        displacement(0:n_done - 1, :) = response%displacement
        force(0:n_done - 1, :) = response%force
        compression(0:n_done - 1, :) = response%compression
        if (allocated(error)) return
        call start_budget(box, laws, preload, size(response%force, 1), road, response%force)
        call outside_accuracy(caller, box, error)
    end subroutine run_multi_box

    !> Every point's law checked, the message naming the point.
    subroutine check_laws(caller, laws, preload, error)
        character(len=*), intent(in) :: caller
        class(contact_law), intent(in) :: laws(:)
        real(dp), intent(in) :: preload(:)
        type(error_type), allocatable, intent(out) :: error

        integer :: i

        do i = 1, size(laws)
            call check_contact_law(laws(i), preload(i), error)
            if (allocated(error)) then
                error%message = caller//': point '//int_text(i)//': '//error%message
                return
            end if
        end do
    end subroutine check_laws

    !> A request's time step, truncation and run length checked by name.
    subroutine check_run(caller, request, error)
        character(len=*), intent(in) :: caller
        type(run_request), intent(in) :: request
        type(error_type), allocatable, intent(out) :: error

        if (.not. (request%dt > 0.0_dp .and. ieee_is_finite(request%dt))) then
            call fatal_error(error, caller//': dt = '//sci_text(request%dt)//' s: give a finite time step > 0 s')
        else if (.not. (request%truncation_tol >= 0.0_dp .and. request%truncation_tol < 1.0_dp)) then
            call fatal_error(error, caller//': truncation_tol = '//sci_text(request%truncation_tol) &
                             //': give a fraction of max|g_ij| in [0, 1)')
        end if
        call need_count(caller, 'n_steps', request%n_steps, 1, 'step', error)
    end subroutine check_run

    !> Keep a box whose convolver was made; otherwise free it and put the caller's name in front.
    subroutine keep_or_drop(caller, box, error)
        character(len=*), intent(in) :: caller
        type(convolver_box), pointer, intent(inout) :: box
        type(error_type), allocatable, intent(inout) :: error

        if (.not. allocated(error)) return
        error%message = caller//': '//error%message
        call free_box(box)
    end subroutine keep_or_drop

end module greenconv_api_multi_handle
