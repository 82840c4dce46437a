!> The C interface of multi-point contact: `bind(c)` functions `gc_multi_*` declared in the
!> multi-point section of include/greenconv.h, on the shared layer greenconv_api_multi_handle.
!>
!> A `gc_multi_convolver *` is the C address of the one `convolver_box` (greenconv_api_handle)
!> behind every handle. Conventions are those of
!> greenconv_capi: every function returns 0, 2 (bad input, NULL pointer) or 3 (numerical
!> failure) and writes its message into `errmsg` (`errmsg_len` bytes as a `size_t`, clamped,
!> always NUL-terminated, "" on success). Arrays are C arrays laid out as Fortran stores them
!> (the first index fastest): shape[k*n_points + i] = phi_ik, g[(j*n_points + i)*n_samples + m]
!> = g_ij(m*dt), road[i*n_steps + n] = u_r,i(t_n), W0[j*n_points + i] = W0_ij. SI units.
!>
!> Here too, for both handle types (the same box behind them):
!> - `gc_multi_new_modes_file`: the nodes of a universal file of normal modes the contact
!>   points, its modes up to a band stepped, as a scene's `&structure model = 'modes_file'`;
!> - `gc_multi_estimate` and `gc_convolver_estimate` (one body, `greenconv_estimate_door`,
!>   behind their aliases in capi_aliases.c): the method's own estimate of the relative error
!>   of the contact forces, the contact run's time-step and band terms included
!>   (greenconv_api_budget);
!> - `gc_multi_set_accuracy` and `gc_convolver_set_accuracy` (`greenconv_accuracy_door`): the
!>   accuracy the host asks; beyond it, the calls that run contact return GC_ACCURACY (4, "ran,
!>   but outside the accuracy asked").
module greenconv_capi_multi
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_size_t, c_ptr, c_associated, &
                                           c_f_pointer, c_loc
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text
    use greenconv_model_point_modes, only: point_modes
    use greenconv_contact_laws, only: contact_law
    use greenconv_capi_law, only: laws_at
    use greenconv_api_library, only: default_truncation_tol
    use greenconv_api_multi_handle, only: modes_multi_box, samples_multi_box, patch_modes, &
                                          check_box, set_multi_options, start_multi_box, advance_multi_box, &
                                          run_multi_box, file_multi_box, method_multi_box, check_file_box, &
                                          file_e_modes, box_points, file_summary, run_request, modes_file_box
    use greenconv_api_budget, only: set_box_accuracy
    use greenconv_capi, only: gc_build_options, point_null_handle
    use greenconv_api_doors, only: finish, from_c, to_c, put_if, start_door, need_pointer, need_pointers, need_count
    use greenconv_api_handle, only: convolver_box, box_at, reset_box, describe_box, check_steps
    implicit none
    private

    public :: gc_multi_new_modes, gc_multi_new_samples, gc_multi_plate_patch
    public :: gc_multi_n_points, gc_multi_history, gc_multi_push, gc_multi_instant_matrix, gc_multi_reset
    public :: gc_multi_describe, gc_multi_set_newton, gc_multi_contact_step
    public :: gc_multi_new_file, gc_multi_new_method, gc_multi_points, gc_multi_file_summary
    public :: gc_multi_contact_start_law, gc_multi_run_contact_law, greenconv_multi_check_for_door
    public :: gc_multi_new_modes_file, greenconv_estimate_door, greenconv_accuracy_door
    public :: made, request_of, null_handle

    !> What a NULL handle's message says.
    character(len=*), parameter :: null_handle = 'conv is NULL: make a convolver with gc_multi_new_modes, ' &
                                                 //'gc_multi_new_samples, gc_multi_new_file or gc_multi_new_modes_file'

contains

    !> int gc_multi_new_modes(int n_points, int n_modes, const double *pole_re,
    !> const double *pole_im, const double *residue_re, const double *residue_im,
    !> const double *shape, double dt, const char *method, int n_steps,
    !> const gc_build_options *options, gc_multi_convolver **conv, char *errmsg, size_t errmsg_len)
    function gc_multi_new_modes(n_points, n_modes, pole_re, pole_im, residue_re, residue_im, shape, dt, method, &
                                n_steps, options, conv, errmsg, errmsg_len) bind(c, name='gc_multi_new_modes') &
        result(status)
        !> Number of contact points N_c, >= 1.
        integer(c_int), value, intent(in) :: n_points
        !> Number of modes N_m, >= 1.
        integer(c_int), value, intent(in) :: n_modes
        !> Real parts of the poles lambda_k [rad/s], < 0 (n_modes values).
        type(c_ptr), value, intent(in) :: pole_re
        !> Imaginary parts of the poles [rad/s], > 0 (n_modes values).
        type(c_ptr), value, intent(in) :: pole_im
        !> Real parts of the modal residues r_k (n_modes values).
        type(c_ptr), value, intent(in) :: residue_re
        !> Imaginary parts of the modal residues (n_modes values).
        type(c_ptr), value, intent(in) :: residue_im
        !> Mode shapes shape[k*n_points + i] = phi_ik (n_points*n_modes values).
        type(c_ptr), value, intent(in) :: shape
        !> Time step dt [s], > 0.
        real(c_double), value, intent(in) :: dt
        !> Method: "modal" (= "recursive"), "exact", "direct" or "fft".
        type(c_ptr), value, intent(in) :: method
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

        character(len=*), parameter :: caller = 'gc_multi_new_modes'
        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        real(c_double), pointer :: p_re(:), p_im(:), r_re(:), r_im(:), phi(:, :)

        box => null()
        call start_door(caller, conv, 'gc_multi_convolver', method, error)
        call need_count(caller, 'n_points', int(n_points), 1, 'point', error)
        call need_count(caller, 'n_modes', int(n_modes), 1, 'mode', error)
        call need_pointers(caller, [pole_re, pole_im, residue_re, residue_im, shape], &
                           'pole_re, pole_im, residue_re, residue_im and shape', &
                           'pass arrays of n_modes (shape: n_points*n_modes) values', error)
        if (.not. allocated(error)) then
            call c_f_pointer(pole_re, p_re, [n_modes])
            call c_f_pointer(pole_im, p_im, [n_modes])
            call c_f_pointer(residue_re, r_re, [n_modes])
            call c_f_pointer(residue_im, r_im, [n_modes])
            call c_f_pointer(shape, phi, [n_points, n_modes])
            call modes_multi_box(caller, p_re, p_im, r_re, r_im, phi, request_of(method, dt, n_steps, options), box, &
                                 error)
        end if
        status = made(box, conv, error, errmsg, errmsg_len)
    end function gc_multi_new_modes

    !> int gc_multi_new_samples(int n_points, int n_samples, const double *g, double dt,
    !> const char *method, int n_steps, const gc_build_options *options,
    !> gc_multi_convolver **conv, char *errmsg, size_t errmsg_len)
    function gc_multi_new_samples(n_points, n_samples, g, dt, method, n_steps, options, conv, errmsg, errmsg_len) &
        bind(c, name='gc_multi_new_samples') result(status)
        !> Number of contact points N_c, >= 1.
        integer(c_int), value, intent(in) :: n_points
        !> Number of samples of each g_ij, >= 2.
        integer(c_int), value, intent(in) :: n_samples
        !> Samples g[(j*n_points + i)*n_samples + m] = g_ij(m*dt) [m/(N*s)].
        type(c_ptr), value, intent(in) :: g
        !> Time step dt [s] of the samples and of the run, > 0.
        real(c_double), value, intent(in) :: dt
        !> Method: "direct" or "fft".
        type(c_ptr), value, intent(in) :: method
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

        character(len=*), parameter :: caller = 'gc_multi_new_samples'
        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        real(c_double), pointer :: samples(:, :, :)

        box => null()
        call start_door(caller, conv, 'gc_multi_convolver', method, error)
        call need_count(caller, 'n_points', int(n_points), 1, 'point', error)
        call need_count(caller, 'n_samples', int(n_samples), 2, 'samples of every g_ij', error)
        call need_pointer(caller, g, 'g', 'pass n_points*n_points*n_samples samples', error)
        if (.not. allocated(error)) then
            call c_f_pointer(g, samples, [n_samples, n_points, n_points])
            call samples_multi_box(caller, samples, request_of(method, dt, n_steps, options), box, error)
        end if
        status = made(box, conv, error, errmsg, errmsg_len)
    end function gc_multi_new_samples

    !> int gc_multi_plate_patch(int n_x, int n_y, double length, double width, double f_max,
    !> int capacity, int *n_modes, double *pole_re, double *pole_im, double *residue_re,
    !> double *residue_im, double *shape, double *x, double *y, char *errmsg, size_t errmsg_len)
    function gc_multi_plate_patch(n_x, n_y, length, width, f_max, capacity, n_modes, pole_re, pole_im, residue_re, &
                                  residue_im, shape, x, y, errmsg, errmsg_len) bind(c, name='gc_multi_plate_patch') &
        result(status)
        !> Points along x (the direction of travel), >= 1.
        integer(c_int), value, intent(in) :: n_x
        !> Points across, >= 1.
        integer(c_int), value, intent(in) :: n_y
        !> Length of the patch along x [m].
        real(c_double), value, intent(in) :: length
        !> Width of the patch across [m].
        real(c_double), value, intent(in) :: width
        !> Highest natural frequency kept [Hz].
        real(c_double), value, intent(in) :: f_max
        !> Room in the arrays: modes (shape: n_x*n_y*capacity values).
        integer(c_int), value, intent(in) :: capacity
        !> Where the number of modes N_m goes.
        type(c_ptr), value, intent(in) :: n_modes
        !> Real parts of the poles [rad/s] (capacity values).
        type(c_ptr), value, intent(in) :: pole_re
        !> Imaginary parts of the poles [rad/s] (capacity values).
        type(c_ptr), value, intent(in) :: pole_im
        !> Real parts of the modal residues (capacity values).
        type(c_ptr), value, intent(in) :: residue_re
        !> Imaginary parts of the modal residues (capacity values).
        type(c_ptr), value, intent(in) :: residue_im
        !> Mode shapes shape[k*n_x*n_y + i] = phi_ik [1/sqrt(kg)].
        type(c_ptr), value, intent(in) :: shape
        !> x_i [m] of the n_x*n_y points (x fastest), or NULL.
        type(c_ptr), value, intent(in) :: x
        !> y_i [m] of the points, or NULL.
        type(c_ptr), value, intent(in) :: y
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        character(len=*), parameter :: caller = 'gc_multi_plate_patch'
        type(error_type), allocatable :: error
        type(point_modes) :: modes
        real(dp), allocatable :: x_points(:), y_points(:)
        real(c_double), pointer :: p_re(:), p_im(:), r_re(:), r_im(:), phi(:, :)
        integer :: n_m, n_c

        call need_pointers(caller, [n_modes, pole_re, pole_im, residue_re, residue_im, shape], &
                           'n_modes, pole_re, pole_im, residue_re, residue_im and shape', '', error)
        if (.not. allocated(error)) then
            call patch_modes(caller, 'f_max', int(n_x), int(n_y), [real(length, dp), real(width, dp)], f_max, modes, &
                             x_points, y_points, error)
        end if
        if (.not. allocated(error)) then
            n_m = modes%modes%n_modes()
            n_c = modes%n_points()
            call put_if(n_modes, n_m)
            if (n_m > capacity) then
                call fatal_error(error, caller//': capacity = '//int_text(int(capacity))//': the plate has ' &
                                 //int_text(n_m)//' modes below f_max: give arrays of that many modes')
            else
                call c_f_pointer(pole_re, p_re, [n_m])
                call c_f_pointer(pole_im, p_im, [n_m])
                call c_f_pointer(residue_re, r_re, [n_m])
                call c_f_pointer(residue_im, r_im, [n_m])
                call c_f_pointer(shape, phi, [n_c, n_m])
                p_re(:) = modes%modes%pole%re
                p_im(:) = modes%modes%pole%im
                r_re(:) = modes%modes%residue%re
                r_im(:) = modes%modes%residue%im
                phi(:, :) = modes%shape
                call put_if(x, x_points)
                call put_if(y, y_points)
            end if
        end if
        status = finish(error, errmsg, errmsg_len)
    end function gc_multi_plate_patch

    !> int gc_multi_new_file(const char *path, const char *method, double dt, int n_steps,
    !> const gc_build_options *options, int max_order, gc_multi_convolver **conv, char *errmsg,
    !> size_t errmsg_len): a convolver on a universal file of a Green's matrix, its receptances
    !> identified with shared poles (greenconv_conv_green_file).
    function gc_multi_new_file(path, method, dt, n_steps, options, max_order, conv, errmsg, errmsg_len) &
        bind(c, name='gc_multi_new_file') result(status)
        !> Path of the universal file (NUL-terminated).
        type(c_ptr), value, intent(in) :: path
        !> Method: "modal" (= "recursive"), "exact", "direct" or "fft".
        type(c_ptr), value, intent(in) :: method
        !> Time step dt [s], > 0.
        real(c_double), value, intent(in) :: dt
        !> Number of steps N_t of the run, >= 1.
        integer(c_int), value, intent(in) :: n_steps
        !> Build options (truncation_tol; accuracy is not used), or NULL for the defaults.
        type(c_ptr), value, intent(in) :: options
        !> Largest order of the pole fit's stabilisation diagram, or 0 for the library's default (30).
        integer(c_int), value, intent(in) :: max_order
        !> Where the new convolver goes (NULL there on failure).
        type(c_ptr), value, intent(in) :: conv
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        character(len=*), parameter :: caller = 'gc_multi_new_file'
        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box

        box => null()
        call start_door(caller, conv, 'gc_multi_convolver', method, error)
        call need_pointer(caller, path, 'path', 'pass the name of a universal file', error)
        if (.not. allocated(error)) then
            call file_multi_box(caller, from_c(path), request_of(method, dt, n_steps, options), int(max_order), box, &
                                error)
        end if
        status = made(box, conv, error, errmsg, errmsg_len)
    end function gc_multi_new_file

    !> int gc_multi_new_method(const gc_multi_convolver *source, const char *method, double dt,
    !> int n_steps, const gc_build_options *options, gc_multi_convolver **conv, char *errmsg,
    !> size_t errmsg_len): another method (or time step) on the file gc_multi_new_file read
    !> into source, without identifying it again.
    function gc_multi_new_method(source, method, dt, n_steps, options, conv, errmsg, errmsg_len) &
        bind(c, name='gc_multi_new_method') result(status)
        !> A convolver made by gc_multi_new_file (or by this function).
        type(c_ptr), value, intent(in) :: source
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

        character(len=*), parameter :: caller = 'gc_multi_new_method'
        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box, from

        box => null()
        call start_door(caller, conv, 'gc_multi_convolver', method, error)
        if (.not. allocated(error)) then
            from => box_at(source)
            call check_box(caller, 'source is NULL: pass a convolver made by gc_multi_new_file', from, error=error)
            if (.not. allocated(error)) call method_multi_box(caller, from, request_of(method, dt, n_steps, options), &
                                                              box, error)
        end if
        status = made(box, conv, error, errmsg, errmsg_len)
    end function gc_multi_new_method

    !> int gc_multi_points(const gc_multi_convolver *conv, int n_points, int *node, double *x,
    !> double *y, char *errmsg, size_t errmsg_len): the node labels and positions of the points
    !> of a convolver made from a file (a Green's matrix or a modes file), in the convolver's
    !> order (any output may be NULL).
    function gc_multi_points(conv, n_points, node, x, y, errmsg, errmsg_len) bind(c, name='gc_multi_points') &
        result(status)
        !> A convolver made by gc_multi_new_file or gc_multi_new_method.
        type(c_ptr), value, intent(in) :: conv
        !> Number of points (the convolver's N_c).
        integer(c_int), value, intent(in) :: n_points
        !> Where the node labels go (n_points values), or NULL.
        type(c_ptr), value, intent(in) :: node
        !> Where x_i [m] (along the travel) goes (n_points values), or NULL.
        type(c_ptr), value, intent(in) :: x
        !> Where y_i [m] (across) goes (n_points values), or NULL.
        type(c_ptr), value, intent(in) :: y
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        integer, allocatable :: nodes(:)
        real(dp), allocatable :: x_points(:), y_points(:)

        box => box_at(conv)
        call check_box('gc_multi_points', null_handle, box, int(n_points), error)
        if (.not. allocated(error)) call box_points('gc_multi_points', box, nodes, x_points, y_points, error)
        if (.not. allocated(error)) then
            call put_if(node, nodes)
            call put_if(x, x_points)
            call put_if(y, y_points)
        end if
        status = finish(error, errmsg, errmsg_len)
    end function gc_multi_points

    !> int gc_multi_file_summary(const gc_multi_convolver *conv, double *e_worst, double *e_mean,
    !> int *n_poles, char *text, size_t text_len): what gc_multi_new_file found in its file: E of
    !> eq. (7) of the identified modes alone, worst and mean over the receptances, the number of
    !> shared poles (all 0 for a file of impulse responses), and the summary in "# " lines
    !> (the file, its points, the identification, the modes) into text (the message on failure).
    function gc_multi_file_summary(conv, e_worst, e_mean, n_poles, text, text_len) &
        bind(c, name='gc_multi_file_summary') result(status)
        !> A convolver made by gc_multi_new_file or gc_multi_new_method.
        type(c_ptr), value, intent(in) :: conv
        !> Where the worst E goes, or NULL.
        type(c_ptr), value, intent(in) :: e_worst
        !> Where the mean E goes, or NULL.
        type(c_ptr), value, intent(in) :: e_mean
        !> Where the number of shared poles goes, or NULL.
        type(c_ptr), value, intent(in) :: n_poles
        !> Buffer for the summary, or NULL.
        type(c_ptr), value, intent(in) :: text
        !> Size of the buffer [bytes].
        integer(c_size_t), value, intent(in) :: text_len
        integer(c_int) :: status

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        character(len=:), allocatable :: summary
        real(dp) :: worst, mean
        integer :: poles

        box => box_at(conv)
        call check_box('gc_multi_file_summary', null_handle, box, error=error)
        if (.not. allocated(error)) call check_file_box('gc_multi_file_summary', box, error)
        status = finish(error, text, text_len)
        if (allocated(error)) return
        call file_e_modes(box%green, worst, mean, poles)
        call put_if(e_worst, worst)
        call put_if(e_mean, mean)
        call put_if(n_poles, poles)
        call file_summary(box, summary)
        call to_c(summary, text, text_len)
    end function gc_multi_file_summary

    !> int gc_multi_n_points(const gc_multi_convolver *conv, int *n_points, char *errmsg, size_t errmsg_len)
    function gc_multi_n_points(conv, n_points, errmsg, errmsg_len) bind(c, name='gc_multi_n_points') result(status)
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> Where N_c goes.
        type(c_ptr), value, intent(in) :: n_points
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box

        box => box_at(conv)
        call check_box('gc_multi_n_points', null_handle, box, error=error)
        call need_pointer('gc_multi_n_points', n_points, 'n_points', 'pass the address of an int', error)
        if (.not. allocated(error)) call put_if(n_points, box%conv%n_points())
        status = finish(error, errmsg, errmsg_len)
    end function gc_multi_n_points

    !> int gc_multi_history(const gc_multi_convolver *conv, int n_points, double *displacement,
    !> char *errmsg, size_t errmsg_len): u_h(n) [m] at every point.
    function gc_multi_history(conv, n_points, displacement, errmsg, errmsg_len) bind(c, name='gc_multi_history') &
        result(status)
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> Number of points the array holds (the convolver's N_c).
        integer(c_int), value, intent(in) :: n_points
        !> Where the history displacements u_h,i(n) [m] go (n_points values).
        type(c_ptr), value, intent(in) :: displacement
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        real(c_double), pointer :: u(:)

        box => checked('gc_multi_history', conv, n_points, [displacement], 'displacement', error)
        if (.not. allocated(error)) call check_steps(box, 'gc_multi_history', 1_int64, error)
        if (.not. allocated(error)) then
            call c_f_pointer(displacement, u, [n_points])
            call box%conv%history(u)
        end if
        status = finish(error, errmsg, errmsg_len)
    end function gc_multi_history

    !> int gc_multi_push(gc_multi_convolver *conv, int n_points, const double *force,
    !> char *errmsg, size_t errmsg_len): the forces q_i(t_n) [N] of this step; on to the next.
    function gc_multi_push(conv, n_points, force, errmsg, errmsg_len) bind(c, name='gc_multi_push') result(status)
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> Number of points the array holds (the convolver's N_c).
        integer(c_int), value, intent(in) :: n_points
        !> Forces q_i(t_n) [N] (n_points values).
        type(c_ptr), value, intent(in) :: force
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        real(c_double), pointer :: q(:)

        box => checked('gc_multi_push', conv, n_points, [force], 'force', error)
        if (.not. allocated(error)) call check_steps(box, 'gc_multi_push', 1_int64, error)
        if (.not. allocated(error)) then
            call c_f_pointer(force, q, [n_points])
            call box%conv%push(q)
        end if
        status = finish(error, errmsg, errmsg_len)
    end function gc_multi_push

    !> int gc_multi_instant_matrix(const gc_multi_convolver *conv, int n_points, double *w0,
    !> char *errmsg, size_t errmsg_len): W0[j*n_points + i] = W0_ij [m/N] (0: explicit scheme).
    function gc_multi_instant_matrix(conv, n_points, w0, errmsg, errmsg_len) &
        bind(c, name='gc_multi_instant_matrix') result(status)
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> Number of points (the convolver's N_c).
        integer(c_int), value, intent(in) :: n_points
        !> Where W0 goes (n_points*n_points values).
        type(c_ptr), value, intent(in) :: w0
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        real(c_double), pointer :: matrix(:, :)

        box => checked('gc_multi_instant_matrix', conv, n_points, [w0], 'w0', error)
        if (.not. allocated(error)) then
            call c_f_pointer(w0, matrix, [n_points, n_points])
            matrix(:, :) = box%conv%weight0
        end if
        status = finish(error, errmsg, errmsg_len)
    end function gc_multi_instant_matrix

    !> int gc_multi_reset(gc_multi_convolver *conv, char *errmsg, size_t errmsg_len): back to
    !> step 0 with no force history; ends a stepped contact run.
    function gc_multi_reset(conv, errmsg, errmsg_len) bind(c, name='gc_multi_reset') result(status)
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box

        box => box_at(conv)
        call check_box('gc_multi_reset', null_handle, box, error=error)
        if (.not. allocated(error)) then
            call reset_box(box)
        end if
        status = finish(error, errmsg, errmsg_len)
    end function gc_multi_reset

    !> int gc_multi_describe(const gc_multi_convolver *conv, int *model_size, char *text,
    !> size_t text_len): "method: what the model neglects" into text (the message on failure),
    !> N_g samples or N_m modes into *model_size (when not NULL).
    function gc_multi_describe(conv, model_size, text, text_len) bind(c, name='gc_multi_describe') result(status)
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> Where the model size goes, or NULL.
        type(c_ptr), value, intent(in) :: model_size
        !> Buffer for the description, or NULL.
        type(c_ptr), value, intent(in) :: text
        !> Size of the buffer [bytes].
        integer(c_size_t), value, intent(in) :: text_len
        integer(c_int) :: status

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        character(len=:), allocatable :: description
        integer :: n

        box => box_at(conv)
        call check_box('gc_multi_describe', null_handle, box, error=error)
        status = finish(error, text, text_len)
        if (allocated(error)) return
        call describe_box(box, description, n)
        call to_c(description, text, text_len)
        call put_if(model_size, n)
    end function gc_multi_describe

    !> int gc_multi_set_newton(gc_multi_convolver *conv, double tolerance, int max_iterations,
    !> double divergence_bound, char *errmsg, size_t errmsg_len): settings of the next runs.
    function gc_multi_set_newton(conv, tolerance, max_iterations, divergence_bound, errmsg, errmsg_len) &
        bind(c, name='gc_multi_set_newton') result(status)
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> Relative tolerance of a step's residual, > 0 (default 1e-12).
        real(c_double), value, intent(in) :: tolerance
        !> Most Newton iterations per step, >= 1 (default 50).
        integer(c_int), value, intent(in) :: max_iterations
        !> Largest |u_i| [m] accepted, > 0 (default 1 m).
        real(c_double), value, intent(in) :: divergence_bound
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box

        box => box_at(conv)
        call check_box('gc_multi_set_newton', null_handle, box, error=error)
        if (.not. allocated(error)) call set_multi_options('gc_multi_set_newton', box, tolerance, &
                                                           int(max_iterations), divergence_bound, error)
        status = finish(error, errmsg, errmsg_len)
    end function gc_multi_set_newton

    !> int gc_multi_contact_step(gc_multi_convolver *conv, int n_points, const double *road,
    !> double *displacement, double *force, double *compression, char *errmsg, size_t errmsg_len):
    !> the next step of the run gc_multi_contact_start began, all forces solved together.
    function gc_multi_contact_step(conv, n_points, road, displacement, force, compression, errmsg, errmsg_len) &
        bind(c, name='gc_multi_contact_step') result(status)
        !> The convolver, advanced by one step.
        type(c_ptr), value, intent(in) :: conv
        !> Number of points (the convolver's N_c).
        integer(c_int), value, intent(in) :: n_points
        !> Road heights u_r,i(t_n) [m] under the points.
        type(c_ptr), value, intent(in) :: road
        !> Where the displacements u_i(t_n) [m] go (0 on a fault).
        type(c_ptr), value, intent(in) :: displacement
        !> Where the forces F_i(t_n) [N] go (0 on a fault).
        type(c_ptr), value, intent(in) :: force
        !> Where the compressions delta_i(t_n) [m] go (0 on a fault), or NULL.
        type(c_ptr), value, intent(in) :: compression
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        real(c_double), pointer :: heights(:), u(:), f(:)
        real(dp), allocatable :: delta(:)

        box => checked('gc_multi_contact_step', conv, n_points, [road, displacement, force], &
                       'road, displacement and force', error)
        if (.not. allocated(error)) then
            allocate (delta(n_points))
            call c_f_pointer(road, heights, [n_points])
            call c_f_pointer(displacement, u, [n_points])
            call c_f_pointer(force, f, [n_points])
            call advance_multi_box('gc_multi_contact_step', box, heights, u, f, delta, error)
            call put_if(compression, delta)
        end if
        status = finish(error, errmsg, errmsg_len)
    end function gc_multi_contact_step

    !> int gc_multi_contact_start_law(gc_multi_convolver *conv, int n_points,
    !> const gc_law *const *laws, const double *preload, char *errmsg, size_t errmsg_len): reset
    !> the convolver and start a run stepped by gc_multi_contact_step, laws[i] the law of point i
    !> (one law for every point, its parameters free per point; a handle may repeat).
    function gc_multi_contact_start_law(conv, n_points, laws, preload, errmsg, errmsg_len) &
        bind(c, name='gc_multi_contact_start_law') result(status)
        !> The convolver; reset here.
        type(c_ptr), value, intent(in) :: conv
        !> Number of points (the convolver's N_c).
        integer(c_int), value, intent(in) :: n_points
        !> The law of each point, n_points `gc_law *` (gc_law_new).
        type(c_ptr), value, intent(in) :: laws
        !> Static preload F0_i [N] of each point, >= 0.
        type(c_ptr), value, intent(in) :: preload
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        character(len=*), parameter :: caller = 'gc_multi_contact_start_law'
        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        class(contact_law), allocatable :: springs(:)
        character(len=:), allocatable :: door
        real(c_double), pointer :: load(:)

        box => checked(caller, conv, n_points, [laws, preload], 'laws and preload', error)
        if (.not. allocated(error)) call laws_at(caller, laws, int(n_points), springs, door, error)
        if (.not. allocated(error)) then
            call c_f_pointer(preload, load, [n_points])
            call start_multi_box(door, box, springs, load, error)
        else if (associated(box)) then
            box%stepping = .false.
        end if
        status = finish(error, errmsg, errmsg_len)
    end function gc_multi_contact_start_law

    !> int gc_multi_run_contact_law(gc_multi_convolver *conv, int n_points, int n_steps,
    !> const gc_law *const *laws, const double *preload, const double *road, double *displacement,
    !> double *force, double *compression, char *errmsg, size_t errmsg_len): a whole run (the
    !> convolver reset first), laws as gc_multi_contact_start_law takes them; arrays
    !> road[i*n_steps + n].
    function gc_multi_run_contact_law(conv, n_points, n_steps, laws, preload, road, displacement, force, &
                                      compression, errmsg, errmsg_len) bind(c, name='gc_multi_run_contact_law') &
        result(status)
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> Number of points (the convolver's N_c).
        integer(c_int), value, intent(in) :: n_points
        !> Number of steps N_t, >= 1.
        integer(c_int), value, intent(in) :: n_steps
        !> The law of each point, n_points `gc_law *` (gc_law_new).
        type(c_ptr), value, intent(in) :: laws
        !> Static preload F0_i [N] of each point, >= 0.
        type(c_ptr), value, intent(in) :: preload
        !> Road heights road[i*n_steps + n] = u_r,i(t_n) [m].
        type(c_ptr), value, intent(in) :: road
        !> Displacements u_i(t_n) [m], same layout (0 from a fault on).
        type(c_ptr), value, intent(in) :: displacement
        !> Forces F_i(t_n) [N], same layout (0 from a fault on).
        type(c_ptr), value, intent(in) :: force
        !> Compressions delta_i(t_n) [m], same layout (0 from a fault on), or NULL.
        type(c_ptr), value, intent(in) :: compression
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        character(len=*), parameter :: caller = 'gc_multi_run_contact_law'
        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        class(contact_law), allocatable :: springs(:)
        character(len=:), allocatable :: door
        real(c_double), pointer :: load(:), heights(:, :), u(:, :), f(:, :)
        real(dp), allocatable :: delta(:, :)

        box => checked(caller, conv, n_points, [laws, preload, road, displacement, force], &
                       'laws, preload, road, displacement and force', error)
        call need_count(caller, 'n_steps', int(n_steps), 1, 'step', error)
        if (.not. allocated(error)) call laws_at(caller, laws, int(n_points), springs, door, error)
        if (.not. allocated(error)) then
            allocate (delta(n_steps, n_points))
            call c_f_pointer(preload, load, [n_points])
            call c_f_pointer(road, heights, [n_steps, n_points])
            call c_f_pointer(displacement, u, [n_steps, n_points])
            call c_f_pointer(force, f, [n_steps, n_points])
            call run_multi_box(door, box, springs, load, heights, u, f, delta, error)
            call put_if(compression, delta)
        end if
        status = finish(error, errmsg, errmsg_len)
    end function gc_multi_run_contact_law

    !> int greenconv_multi_check_for_door(const char *door, gc_multi_convolver *conv,
    !> int n_points, int n_steps, int n_arrays, const void *const *arrays, const char *names,
    !> int starts, char *errmsg, size_t errmsg_len): the checks a multi-point (k_c, p) door of
    !> capi_aliases.c makes before it reads k_c[i] and p[i] (the handle, n_points against its
    !> points, its arrays not NULL, n_steps >= 1), its messages naming `door`; a failed check
    !> of a door that starts a stepped run (`starts` not 0) ends the run going on. Not in the header.
    function greenconv_multi_check_for_door(door, conv, n_points, n_steps, n_arrays, arrays, names, starts, &
                                            errmsg, errmsg_len) bind(c, name='greenconv_multi_check_for_door') &
        result(status)
        !> The (k_c, p) door's name, NUL-terminated.
        type(c_ptr), value, intent(in) :: door
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> Number of points (the convolver's N_c).
        integer(c_int), value, intent(in) :: n_points
        !> Number of steps N_t, >= 1 (1 for a door that starts a stepped run).
        integer(c_int), value, intent(in) :: n_steps
        !> Number of arrays.
        integer(c_int), value, intent(in) :: n_arrays
        !> The door's arrays, n_arrays addresses.
        type(c_ptr), value, intent(in) :: arrays
        !> Their names as the message lists them, NUL-terminated.
        type(c_ptr), value, intent(in) :: names
        !> Not 0 for a door that starts a stepped run.
        integer(c_int), value, intent(in) :: starts
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        type(c_ptr), pointer :: addresses(:)

        call c_f_pointer(arrays, addresses, [n_arrays])
        box => checked(from_c(door), conv, n_points, addresses, from_c(names), error)
        call need_count(from_c(door), 'n_steps', int(n_steps), 1, 'step', error)
        if (allocated(error) .and. associated(box) .and. starts /= 0) box%stepping = .false.
        status = finish(error, errmsg, errmsg_len)
    end function greenconv_multi_check_for_door

    ! ---- conversions -------------------------------------------------------------------------


    !> The box behind a handle, checked with its count of points and the arrays it needs.
    function checked(caller, conv, n_points, arrays, names, error) result(box)
        character(len=*), intent(in) :: caller, names
        type(c_ptr), intent(in) :: conv, arrays(:)
        integer(c_int), intent(in) :: n_points
        type(error_type), allocatable, intent(out) :: error
        type(convolver_box), pointer :: box

        box => box_at(conv)
        call check_box(caller, null_handle, box, int(n_points), error)
        call need_pointers(caller, arrays, names, 'pass arrays of n_points values', error)
    end function checked

    !> What a multi-point constructor door builds: its method, time step and run length, and the
    !> truncation fraction of its C build options (the library's default for NULL).
    function request_of(method, dt, n_steps, options) result(request)
        !> The method's name, a NUL-terminated string (checked not NULL by the door).
        type(c_ptr), intent(in) :: method
        !> Time step dt [s].
        real(c_double), intent(in) :: dt
        !> Number of steps N_t of the run.
        integer(c_int), intent(in) :: n_steps
        !> A `const gc_build_options *`, or NULL.
        type(c_ptr), intent(in) :: options
        !> The request, unchecked.
        type(run_request) :: request

        type(gc_build_options), pointer :: settings

        request%method = from_c(method)
        request%dt = dt
        request%n_steps = int(n_steps)
        request%truncation_tol = default_truncation_tol
        if (.not. c_associated(options)) return
        call c_f_pointer(options, settings)
        request%truncation_tol = settings%truncation_tol
    end function request_of

    !> Store a new box at *conv (when made) and return the status with the message.
    function made(box, conv, error, errmsg, errmsg_len) result(status)
        !> The new box, or null.
        type(convolver_box), pointer, intent(in) :: box
        !> The caller's `gc_multi_convolver **`, and its message buffer (or NULL).
        type(c_ptr), intent(in) :: conv, errmsg
        !> The constructor's failure, if any.
        type(error_type), allocatable, intent(in) :: error
        !> Size of the message buffer [bytes].
        integer(c_size_t), intent(in) :: errmsg_len
        !> 0, or the failure's status.
        integer(c_int) :: status

        type(c_ptr), pointer :: handle

        if (.not. allocated(error) .and. associated(box)) then
            call c_f_pointer(conv, handle)
            handle = c_loc(box)
        end if
        status = finish(error, errmsg, errmsg_len)
    end function made

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

end module greenconv_capi_multi
