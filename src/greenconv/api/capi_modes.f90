!> The C doors of a multi-point convolver on a universal file of normal modes, and of the
!> accuracy a host asks of a multi-point convolver (include/greenconv.h, multi-point section):
!>
!> - `gc_multi_new_modes_file`: the file's nodes the contact points, its modes up to a band
!>   stepped, as a scene's `&structure model = 'modes_file'`, then stepped from the
!>   host's loop with the other `gc_multi_*` functions;
!> - `gc_multi_estimate`, `gc_convolver_estimate` (one body, `greenconv_estimate_door`, behind
!>   their aliases in capi_aliases.c): the method's own estimate of its relative error, the
!>   contact run's time-step and band terms included (greenconv_api_budget);
!> - `gc_multi_set_accuracy`, `gc_convolver_set_accuracy` (`greenconv_accuracy_door`): the
!>   accuracy the host asks; beyond it, the calls that run contact return GC_ACCURACY (4, "ran,
!>   but outside the accuracy asked");
!> - `gc_identify_ml_file`: the modes of a receptance file by maximum likelihood, with their
!>   standard deviations and whether the data determine each.
!>
!> Conventions are those of greenconv_capi_multi (status 0, 2, 3 or 4, a message in `errmsg`,
!> NULL checked); the handle is the one `convolver_box` behind every handle.
module greenconv_capi_modes
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_size_t, c_ptr, c_f_pointer, c_associated
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_ident_mlfit, only: ml_result
    use greenconv_api_handle, only: identify_file_ml
    use greenconv_api_multi_handle, only: modes_file_box, check_box
    use greenconv_api_budget, only: set_box_accuracy
    use greenconv_api_doors, only: finish, from_c, put_if, start_door, need_pointer, need_pointers, need_capacity, &
                                   modes_to_c
    use greenconv_api_handle, only: convolver_box, box_at
    use greenconv_capi_multi, only: made, request_of, null_handle
    use greenconv_capi, only: point_null_handle
    implicit none
    private

    public :: gc_multi_new_modes_file, gc_identify_ml_file, greenconv_estimate_door, greenconv_accuracy_door

contains

    !> int gc_multi_new_modes_file(const char *path, int direction, double damping_ratio,
    !> double f_band, const char *method, double dt, int n_steps, const gc_build_options *options,
    !> gc_multi_convolver **conv, char *errmsg, size_t errmsg_len): a convolver on a universal
    !> file of normal modes (datasets 15/2411 and 55), every node a contact point.
    function gc_multi_new_modes_file(path, direction, damping_ratio, f_band, method, dt, n_steps, options, conv, &
                                     errmsg, errmsg_len) bind(c, name='gc_multi_new_modes_file') result(status)
        !> Path of the universal file (NUL-terminated).
        type(c_ptr), value, intent(in) :: path
        !> Direction of the shapes at the contact: 1, 2, 3 for X, Y, Z, negative for the opposite sense.
        integer(c_int), value, intent(in) :: direction
        !> Viscous damping ratio of the modes the file gives none, in [0, 1).
        real(c_double), value, intent(in) :: damping_ratio
        !> Highest natural frequency stepped [Hz], or 0 for the Nyquist frequency 1/(2*dt).
        real(c_double), value, intent(in) :: f_band
        !> Method: "modal" (= "recursive"), "exact", "direct" or "fft".
        type(c_ptr), value, intent(in) :: method
        !> Time step dt [s], > 0.
        real(c_double), value, intent(in) :: dt
        !> Number of steps N_t of the run, >= 1.
        integer(c_int), value, intent(in) :: n_steps
        !> Build options (truncation_tol; accuracy is not used), or NULL for the defaults.
        type(c_ptr), value, intent(in) :: options
        !> Where the new convolver goes (NULL there on failure).
        type(c_ptr), value, intent(in) :: conv
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        character(len=*), parameter :: caller = 'gc_multi_new_modes_file'
        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box

        box => null()
        call start_door(caller, conv, 'gc_multi_convolver', method, error)
        call need_pointer(caller, path, 'path', 'pass the name of a universal file of normal modes', error)
        if (.not. allocated(error)) then
            call modes_file_box(caller, from_c(path), int(direction), damping_ratio, f_band, &
                                request_of(method, dt, n_steps, options), box, error)
        end if
        status = made(box, conv, error, errmsg, errmsg_len)
    end function gc_multi_new_modes_file

    !> int greenconv_estimate_door(int single, const gc_multi_convolver *conv, double *estimate,
    !> char *errmsg, size_t errmsg_len): gc_multi_estimate (single = 0) and gc_convolver_estimate
    !> (single not 0) of capi_aliases.c, the method's own estimate of the relative error of its
    !> contact forces (the model's terms, plus the time-step and band terms of the contact run
    !> going on or last run) into *estimate, the messages naming the door. Not in the header.
    function greenconv_estimate_door(single, conv, estimate, errmsg, errmsg_len) &
        bind(c, name='greenconv_estimate_door') result(status)
        !> Not 0 for the single-point door.
        integer(c_int), value, intent(in) :: single
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> Where the estimate goes [-].
        type(c_ptr), value, intent(in) :: estimate
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        real(c_double), pointer :: value_out

        box => checked_box(single, 'gc_multi_estimate', 'gc_convolver_estimate', conv, error)
        call need_pointer(door(single, 'gc_multi_estimate', 'gc_convolver_estimate'), estimate, 'estimate', &
                          'pass the address of a double', error)
        if (.not. allocated(error)) then
            call c_f_pointer(estimate, value_out)
            value_out = box%estimate + box%run_terms
        end if
        status = finish(error, errmsg, errmsg_len)
    end function greenconv_estimate_door

    !> int greenconv_accuracy_door(int single, gc_multi_convolver *conv, double accuracy,
    !> char *errmsg, size_t errmsg_len): gc_multi_set_accuracy (single = 0) and
    !> gc_convolver_set_accuracy (single not 0) of capi_aliases.c, the relative accuracy the host
    !> asks (0: none) kept, GC_ACCURACY at once when the method's own estimate exceeds it and
    !> from the doors that run contact afterwards, the messages naming the door. Not in the header.
    function greenconv_accuracy_door(single, conv, accuracy, errmsg, errmsg_len) &
        bind(c, name='greenconv_accuracy_door') result(status)
        !> Not 0 for the single-point door.
        integer(c_int), value, intent(in) :: single
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> Relative accuracy asked (the largest error estimate accepted), > 0, or 0 for none.
        real(c_double), value, intent(in) :: accuracy
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box

        box => checked_box(single, 'gc_multi_set_accuracy', 'gc_convolver_set_accuracy', conv, error)
        if (.not. allocated(error)) then
            call set_box_accuracy(door(single, 'gc_multi_set_accuracy', 'gc_convolver_set_accuracy'), box, &
                                  accuracy, error)
        end if
        status = finish(error, errmsg, errmsg_len)
    end function greenconv_accuracy_door

    !> The door's name: its multi-point one, or its single-point one when `single` is not 0.
    pure function door(single, multi_name, point_name) result(name)
        integer(c_int), intent(in) :: single
        character(len=*), intent(in) :: multi_name, point_name
        character(len=merge(len(point_name), len(multi_name), single /= 0)) :: name

        if (single /= 0) then
            name = point_name
        else
            name = multi_name
        end if
    end function door

    !> The box behind a handle, refused (status 2) when NULL with the words of the door's family.
    function checked_box(single, multi_name, point_name, conv, error) result(box)
        integer(c_int), intent(in) :: single
        character(len=*), intent(in) :: multi_name, point_name
        type(c_ptr), intent(in) :: conv
        type(error_type), allocatable, intent(out) :: error
        type(convolver_box), pointer :: box

        box => box_at(conv)
        if (single /= 0) then
            call check_box(point_name, point_null_handle, box, error=error)
        else
            call check_box(multi_name, null_handle, box, error=error)
        end if
    end function checked_box

    !> int gc_identify_ml_file(const char *path, const char *noise_model, int max_order, int capacity,
    !> int *n_modes, int *n_determined, double *pole_re, double *pole_im, double *residue_re,
    !> double *residue_im, double *sigma_f, double *sigma_xi, int *determined, char *errmsg,
    !> size_t errmsg_len): the modes of a receptance file by maximum likelihood (order by MDL,
    !> noise model "auto" from the data), lowest natural frequency first, each with its standard
    !> deviations and determined[k] = 1 when the data determine it, 0 for a pole of the fitted
    !> receptance they do not (as the column `determined` of a scene's modes file).
    function gc_identify_ml_file(path, noise_model, max_order, capacity, n_modes, n_determined, pole_re, pole_im, &
                                 residue_re, residue_im, sigma_f, sigma_xi, determined, errmsg, errmsg_len) &
        bind(c, name='gc_identify_ml_file') result(status)
        !> Path of the receptance file (columns or a universal file), NUL-terminated.
        type(c_ptr), value, intent(in) :: path
        !> "auto", "relative", "absolute", "floor" or "band", NUL-terminated; NULL for "auto".
        type(c_ptr), value, intent(in) :: noise_model
        !> Highest order of the stabilisation diagram (modes), 1 to 200 (30 is usual).
        integer(c_int), value, intent(in) :: max_order
        !> Capacity of the seven output arrays, >= 0.
        integer(c_int), value, intent(in) :: capacity
        !> Where the number of modes found goes (an int; set also when it exceeds capacity).
        type(c_ptr), value, intent(in) :: n_modes
        !> Where the number of modes the data determine goes (an int).
        type(c_ptr), value, intent(in) :: n_determined
        !> Where the real parts of the poles [rad/s] go (capacity values).
        type(c_ptr), value, intent(in) :: pole_re
        !> Where the imaginary parts of the poles [rad/s] go.
        type(c_ptr), value, intent(in) :: pole_im
        !> Where the real parts of the residues [m/(N*s)] go.
        type(c_ptr), value, intent(in) :: residue_re
        !> Where the imaginary parts of the residues [m/(N*s)] go.
        type(c_ptr), value, intent(in) :: residue_im
        !> Where the standard deviations of the natural frequencies [Hz] go.
        type(c_ptr), value, intent(in) :: sigma_f
        !> Where the standard deviations of the damping ratios go.
        type(c_ptr), value, intent(in) :: sigma_xi
        !> Where the flags go (ints): 1 determined by the data, 0 not.
        type(c_ptr), value, intent(in) :: determined
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        character(len=*), parameter :: caller = 'gc_identify_ml_file'
        type(error_type), allocatable :: error
        type(ml_result) :: result
        character(len=:), allocatable :: model

        call need_pointer(caller, path, 'path', 'pass the name of a receptance file', error)
        call need_pointers(caller, [n_modes, n_determined, pole_re, pole_im, residue_re, residue_im, sigma_f, &
                                    sigma_xi, determined], 'n_modes, n_determined, pole_re, pole_im, residue_re, ' &
                           //'residue_im, sigma_f, sigma_xi and determined', 'pass where they should go', error)
        call need_capacity(caller, int(capacity), error)
        if (allocated(error)) then
            status = finish(error, errmsg, errmsg_len)
            return
        end if
        call put_if(n_modes, 0)
        call put_if(n_determined, 0)
        model = 'auto'
        if (c_associated(noise_model)) model = from_c(noise_model)
        call identify_file_ml(from_c(path), model, int(max_order), result, error)
        if (.not. allocated(error)) then
            call put_if(n_modes, result%modes%n_modes())
            call put_if(n_determined, count(result%determined_modes()))
            call modes_to_c(caller, result%modes, int(capacity), pole_re, pole_im, residue_re, residue_im, error)
            if (.not. allocated(error)) then
                call put_if(sigma_f, result%sigma_frequency)
                call put_if(sigma_xi, result%sigma_damping)
                call put_if(determined, merge(1, 0, result%determined_modes()))
            end if
        end if
        status = finish(error, errmsg, errmsg_len)
    end function gc_identify_ml_file

end module greenconv_capi_modes
