!> The C doors of a multi-point convolver on a universal file of normal modes, and of the
!> accuracy a host asks of a multi-point convolver (include/greenconv.h, multi-point section):
!>
!> - `gc_multi_new_modes_file`: the file's nodes the contact points, its modes up to a band
!>   stepped, as a scene's `&structure model = 'modes_file'` (issue 25), then stepped from the
!>   host's loop with the other `gc_multi_*` functions;
!> - `gc_multi_estimate`: the method's own estimate of its relative error;
!> - `gc_multi_set_accuracy`: the accuracy the host asks; beyond it, the calls that run contact
!>   return GC_ACCURACY (4, "ran, but outside the accuracy asked", issue 23).
!>
!> Conventions are those of greenconv_capi_multi (status 0, 2, 3 or 4, a message in `errmsg`,
!> NULL checked); the handle is the one `convolver_box` behind every handle.
module greenconv_capi_modes
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_size_t, c_ptr, c_f_pointer
    use greenconv_core_error, only: error_type
    use greenconv_api_multi_handle, only: modes_file_box, check_box, set_box_accuracy
    use greenconv_api_doors, only: finish, from_c, start_door, need_pointer
    use greenconv_api_handle, only: convolver_box, box_at
    use greenconv_capi_multi, only: made, tolerance_of, null_handle
    implicit none
    private

    public :: gc_multi_new_modes_file, gc_multi_estimate, gc_multi_set_accuracy

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
            call modes_file_box(caller, from_c(path), int(direction), damping_ratio, f_band, from_c(method), dt, &
                                tolerance_of(options), int(n_steps), box, error)
        end if
        status = made(box, conv, error, errmsg, errmsg_len)
    end function gc_multi_new_modes_file

    !> int gc_multi_estimate(const gc_multi_convolver *conv, double *estimate, char *errmsg,
    !> size_t errmsg_len): the method's own estimate of its relative error (0 for modes given
    !> exactly; E of eq. (7) of an identified model; what a sampled kernel leaves out).
    function gc_multi_estimate(conv, estimate, errmsg, errmsg_len) bind(c, name='gc_multi_estimate') result(status)
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> Where the estimate goes (dimensionless, relative to the largest |g_ij|).
        type(c_ptr), value, intent(in) :: estimate
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        real(c_double), pointer :: value_out

        box => box_at(conv)
        call check_box('gc_multi_estimate', null_handle, box, error=error)
        call need_pointer('gc_multi_estimate', estimate, 'estimate', 'pass the address of a double', error)
        if (.not. allocated(error)) then
            call c_f_pointer(estimate, value_out)
            value_out = box%estimate
        end if
        status = finish(error, errmsg, errmsg_len)
    end function gc_multi_estimate

    !> int gc_multi_set_accuracy(gc_multi_convolver *conv, double accuracy, char *errmsg,
    !> size_t errmsg_len): the relative accuracy the host asks (0: none); GC_ACCURACY at once
    !> when the method's own estimate exceeds it, and from gc_multi_contact_start and
    !> gc_multi_run_contact afterwards.
    function gc_multi_set_accuracy(conv, accuracy, errmsg, errmsg_len) bind(c, name='gc_multi_set_accuracy') &
        result(status)
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

        box => box_at(conv)
        call check_box('gc_multi_set_accuracy', null_handle, box, error=error)
        if (.not. allocated(error)) call set_box_accuracy('gc_multi_set_accuracy', box, accuracy, error)
        status = finish(error, errmsg, errmsg_len)
    end function gc_multi_set_accuracy

end module greenconv_capi_modes
