!> The C interface of greenconv: `bind(c)` functions declared in include/greenconv.h, usable
!> from C and C++. Each is a thin layer over the plain subroutines of `greenconv_legacy`:
!> it turns C strings into Fortran ones, opaque `gc_convolver *` handles into the legacy
!> `INTEGER*8` handles (the same address), and Fortran messages into NUL-terminated text in
!> a buffer the caller provides. No function keeps state between calls.
!>
!> Conventions (see the header): functions return a status, 0 (`GC_OK`), 2
!> (`GC_ERROR_INPUT`) or 3 (`GC_ERROR_NUMERICAL`), the codes of greenconv_core_error; `errmsg` may be
!> NULL, otherwise it receives at most `errmsg_len` bytes, NUL included. SI units throughout.
module greenconv_capi
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_size_t, c_ptr, c_null_ptr, &
                                           c_null_char, c_associated, c_f_pointer, c_intptr_t
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_legacy, only: gcsdof, gcmode, gcsamp, gcfrf, gcfree, gchist, gcpush, gcw0, gcrset, gcsize, &
                                gcdesc, gcstep, gccont, gcid, gcscen
    implicit none
    private

    public :: gc_convolver_new_sdof, gc_convolver_new_modes, gc_convolver_new_samples, gc_convolver_new_frf_file
    public :: gc_convolver_free, gc_convolver_history, gc_convolver_push, gc_convolver_instant_weight
    public :: gc_convolver_reset, gc_convolver_model_size, gc_convolver_describe
    public :: gc_contact_step, gc_run_contact, gc_identify_frf_file, gc_run_scene

    !> Length of the Fortran message buffers (messages are one line).
    integer, parameter :: message_length = 1024

    interface
        !> size_t strlen(const char *s)
        pure function c_strlen(text) bind(c, name='strlen') result(length)
            import :: c_ptr, c_size_t
            implicit none
            type(c_ptr), value, intent(in) :: text
            integer(c_size_t) :: length
        end function c_strlen
    end interface

contains

    !> int gc_convolver_new_sdof(double mass, double stiffness, double damping_ratio, double dt,
    !> const char *method, int n_steps, gc_convolver **conv, char *errmsg, size_t errmsg_len)
    function gc_convolver_new_sdof(mass, stiffness, damping_ratio, dt, method, n_steps, conv, errmsg, errmsg_len) &
        bind(c, name='gc_convolver_new_sdof') result(status)
        !> Mass M [kg], > 0.
        real(c_double), value, intent(in) :: mass
        !> Stiffness K [N/m], > 0.
        real(c_double), value, intent(in) :: stiffness
        !> Damping ratio xi, 0 <= xi < 1.
        real(c_double), value, intent(in) :: damping_ratio
        !> Time step dt [s], > 0.
        real(c_double), value, intent(in) :: dt
        !> Method name, a NUL-terminated string.
        type(c_ptr), value, intent(in) :: method
        !> Number of steps N_t of the run, >= 1.
        integer(c_int), value, intent(in) :: n_steps
        !> The new convolver (NULL on failure).
        type(c_ptr), intent(out) :: conv
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        integer(int64) :: handle
        integer :: ierr
        character(len=message_length) :: message

        call gcsdof(mass, stiffness, damping_ratio, dt, int(n_steps), from_c(method), handle, ierr, message)
        conv = pointer_of(handle)
        status = finish(ierr, message, errmsg, errmsg_len)
    end function gc_convolver_new_sdof

    !> int gc_convolver_new_modes(int n_modes, const double *pole_re, const double *pole_im,
    !> const double *residue_re, const double *residue_im, double dt, const char *method,
    !> int n_steps, gc_convolver **conv, char *errmsg, size_t errmsg_len)
    function gc_convolver_new_modes(n_modes, pole_re, pole_im, residue_re, residue_im, dt, method, n_steps, conv, &
                                    errmsg, errmsg_len) bind(c, name='gc_convolver_new_modes') result(status)
        !> Number of modes (conjugate pairs), >= 1.
        integer(c_int), value, intent(in) :: n_modes
        !> Real parts of the poles lambda_k [rad/s], < 0.
        real(c_double), intent(in) :: pole_re(*)
        !> Imaginary parts of the poles [rad/s], > 0.
        real(c_double), intent(in) :: pole_im(*)
        !> Real parts of the residues r_k [m/(N*s)].
        real(c_double), intent(in) :: residue_re(*)
        !> Imaginary parts of the residues [m/(N*s)].
        real(c_double), intent(in) :: residue_im(*)
        !> Time step dt [s], > 0.
        real(c_double), value, intent(in) :: dt
        !> Method name, a NUL-terminated string.
        type(c_ptr), value, intent(in) :: method
        !> Number of steps N_t of the run, >= 1.
        integer(c_int), value, intent(in) :: n_steps
        !> The new convolver (NULL on failure).
        type(c_ptr), intent(out) :: conv
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        integer(int64) :: handle
        integer :: ierr, n
        character(len=message_length) :: message

        n = max(int(n_modes), 0)
        call gcmode(int(n_modes), pole_re(1:n), pole_im(1:n), residue_re(1:n), residue_im(1:n), dt, int(n_steps), &
                    from_c(method), handle, ierr, message)
        conv = pointer_of(handle)
        status = finish(ierr, message, errmsg, errmsg_len)
    end function gc_convolver_new_modes

    !> int gc_convolver_new_samples(int n_samples, const double *g, double dt, const char *method,
    !> int n_steps, gc_convolver **conv, char *errmsg, size_t errmsg_len)
    function gc_convolver_new_samples(n_samples, g, dt, method, n_steps, conv, errmsg, errmsg_len) &
        bind(c, name='gc_convolver_new_samples') result(status)
        !> Number of samples, >= 2.
        integer(c_int), value, intent(in) :: n_samples
        !> Samples g(n*dt), n = 0..n_samples-1 [m/(N*s)].
        real(c_double), intent(in) :: g(*)
        !> Time step dt [s] of the samples and of the run, > 0.
        real(c_double), value, intent(in) :: dt
        !> Method name, "direct" or "fft".
        type(c_ptr), value, intent(in) :: method
        !> Number of steps N_t of the run, >= 1.
        integer(c_int), value, intent(in) :: n_steps
        !> The new convolver (NULL on failure).
        type(c_ptr), intent(out) :: conv
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        integer(int64) :: handle
        integer :: ierr
        character(len=message_length) :: message

        call gcsamp(int(n_samples), g(1:max(int(n_samples), 0)), dt, int(n_steps), from_c(method), handle, ierr, &
                    message)
        conv = pointer_of(handle)
        status = finish(ierr, message, errmsg, errmsg_len)
    end function gc_convolver_new_samples

    !> int gc_convolver_new_frf_file(const char *path, double dt, const char *method, int n_steps,
    !> double tol_e, int max_modes, gc_convolver **conv, char *errmsg, size_t errmsg_len)
    function gc_convolver_new_frf_file(path, dt, method, n_steps, tol_e, max_modes, conv, errmsg, errmsg_len) &
        bind(c, name='gc_convolver_new_frf_file') result(status)
        !> Path of the receptance file (f [Hz], Re G, Im G [m/N]), NUL-terminated.
        type(c_ptr), value, intent(in) :: path
        !> Time step dt [s], > 0.
        real(c_double), value, intent(in) :: dt
        !> Method name, a NUL-terminated string.
        type(c_ptr), value, intent(in) :: method
        !> Number of steps N_t of the run, >= 1.
        integer(c_int), value, intent(in) :: n_steps
        !> Target of the identification error E of eq. (7), > 0.
        real(c_double), value, intent(in) :: tol_e
        !> Largest number of modes the LSCE scan tries, >= 1.
        integer(c_int), value, intent(in) :: max_modes
        !> The new convolver (NULL on failure).
        type(c_ptr), intent(out) :: conv
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        integer(int64) :: handle
        integer :: ierr
        character(len=message_length) :: message

        call gcfrf(from_c(path), dt, int(n_steps), from_c(method), tol_e, int(max_modes), handle, ierr, message)
        conv = pointer_of(handle)
        status = finish(ierr, message, errmsg, errmsg_len)
    end function gc_convolver_new_frf_file

    !> void gc_convolver_free(gc_convolver *conv): free a convolver (NULL: nothing).
    subroutine gc_convolver_free(conv) bind(c, name='gc_convolver_free')
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv

        integer(int64) :: handle

        handle = handle_of(conv)
        call gcfree(handle)
    end subroutine gc_convolver_free

    !> int gc_convolver_history(const gc_convolver *conv, double *displacement)
    function gc_convolver_history(conv, displacement) bind(c, name='gc_convolver_history') result(status)
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> History displacement u_h(n) [m] from the forces pushed so far.
        real(c_double), intent(out) :: displacement
        integer(c_int) :: status

        integer :: ierr

        call gchist(handle_of(conv), displacement, ierr)
        status = int(ierr, c_int)
    end function gc_convolver_history

    !> int gc_convolver_push(gc_convolver *conv, double force)
    function gc_convolver_push(conv, force) bind(c, name='gc_convolver_push') result(status)
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> Force q(t_n) [N] of the current step.
        real(c_double), value, intent(in) :: force
        integer(c_int) :: status

        integer :: ierr

        call gcpush(handle_of(conv), force, ierr)
        status = int(ierr, c_int)
    end function gc_convolver_push

    !> int gc_convolver_instant_weight(const gc_convolver *conv, double *weight)
    function gc_convolver_instant_weight(conv, weight) bind(c, name='gc_convolver_instant_weight') result(status)
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> Instantaneous weight w0 [m/N] of the current step's own force.
        real(c_double), intent(out) :: weight
        integer(c_int) :: status

        integer :: ierr

        call gcw0(handle_of(conv), weight, ierr)
        status = int(ierr, c_int)
    end function gc_convolver_instant_weight

    !> int gc_convolver_reset(gc_convolver *conv)
    function gc_convolver_reset(conv) bind(c, name='gc_convolver_reset') result(status)
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        integer(c_int) :: status

        integer :: ierr

        call gcrset(handle_of(conv), ierr)
        status = int(ierr, c_int)
    end function gc_convolver_reset

    !> int gc_convolver_model_size(const gc_convolver *conv, int *size)
    function gc_convolver_model_size(conv, size) bind(c, name='gc_convolver_model_size') result(status)
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> N_g kernel samples ("direct", "fft") or N_m modes.
        integer(c_int), intent(out) :: size
        integer(c_int) :: status

        integer :: ierr, n

        call gcsize(handle_of(conv), n, ierr)
        size = int(n, c_int)
        status = int(ierr, c_int)
    end function gc_convolver_model_size

    !> int gc_convolver_describe(const gc_convolver *conv, char *text, size_t text_len)
    function gc_convolver_describe(conv, text, text_len) bind(c, name='gc_convolver_describe') result(status)
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> Buffer for "method: what the model neglects", or NULL.
        type(c_ptr), value, intent(in) :: text
        !> Size of the buffer [bytes].
        integer(c_size_t), value, intent(in) :: text_len
        integer(c_int) :: status

        integer :: ierr
        character(len=message_length) :: description

        call gcdesc(handle_of(conv), description, ierr)
        call to_c(description, text, text_len)
        status = int(ierr, c_int)
    end function gc_convolver_describe

    !> int gc_contact_step(gc_convolver *conv, double k_c, double p, double preload, double road,
    !> double *displacement, double *force, double *compression)
    function gc_contact_step(conv, k_c, p, preload, road, displacement, force, compression) &
        bind(c, name='gc_contact_step') result(status)
        !> The convolver, advanced by one step.
        type(c_ptr), value, intent(in) :: conv
        !> Contact stiffness k_c [N/m^p], > 0.
        real(c_double), value, intent(in) :: k_c
        !> Contact exponent p, > 0.
        real(c_double), value, intent(in) :: p
        !> Static preload F0 [N], >= 0.
        real(c_double), value, intent(in) :: preload
        !> Road height u_r(t_n) [m].
        real(c_double), value, intent(in) :: road
        !> Body displacement u(t_n) [m].
        real(c_double), intent(out) :: displacement
        !> Contact force F(t_n) [N].
        real(c_double), intent(out) :: force
        !> Compression delta(t_n) [m], or NULL.
        type(c_ptr), value, intent(in) :: compression
        integer(c_int) :: status

        real(c_double), pointer :: delta_out
        real(c_double) :: delta
        integer :: ierr

        call gcstep(handle_of(conv), k_c, p, preload, road, displacement, force, delta, ierr)
        if (c_associated(compression)) then
            call c_f_pointer(compression, delta_out)
            delta_out = delta
        end if
        status = int(ierr, c_int)
    end function gc_contact_step

    !> int gc_run_contact(gc_convolver *conv, double k_c, double p, double preload, int n_steps,
    !> const double *road, double *displacement, double *force, double *compression,
    !> char *errmsg, size_t errmsg_len)
    function gc_run_contact(conv, k_c, p, preload, n_steps, road, displacement, force, compression, errmsg, &
                            errmsg_len) bind(c, name='gc_run_contact') result(status)
        !> The convolver (reset first).
        type(c_ptr), value, intent(in) :: conv
        !> Contact stiffness k_c [N/m^p], > 0.
        real(c_double), value, intent(in) :: k_c
        !> Contact exponent p, > 0.
        real(c_double), value, intent(in) :: p
        !> Static preload F0 [N], >= 0.
        real(c_double), value, intent(in) :: preload
        !> Number of steps N_t, >= 1.
        integer(c_int), value, intent(in) :: n_steps
        !> Road heights u_r(t_n) [m], n_steps values.
        real(c_double), intent(in) :: road(*)
        !> Body displacements u(t_n) [m], n_steps values.
        real(c_double), intent(out) :: displacement(*)
        !> Contact forces F(t_n) [N], n_steps values.
        real(c_double), intent(out) :: force(*)
        !> Compressions delta(t_n) [m], n_steps values, or NULL.
        type(c_ptr), value, intent(in) :: compression
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        real(c_double), pointer :: delta_out(:)
        real(c_double), allocatable :: delta(:)
        integer :: ierr, n
        character(len=message_length) :: message

        n = max(int(n_steps), 0)
        allocate (delta(n))
        call gccont(handle_of(conv), k_c, p, preload, int(n_steps), road(1:n), displacement(1:n), force(1:n), delta, &
                    ierr, message)
        if (ierr == 0 .and. c_associated(compression)) then
            call c_f_pointer(compression, delta_out, [n])
            delta_out(:) = delta
        end if
        status = finish(ierr, message, errmsg, errmsg_len)
    end function gc_run_contact

    !> int gc_identify_frf_file(const char *path, double tol_e, int max_modes, int capacity,
    !> int *n_modes, double *pole_re, double *pole_im, double *residue_re, double *residue_im,
    !> double *error_e, char *errmsg, size_t errmsg_len)
    function gc_identify_frf_file(path, tol_e, max_modes, capacity, n_modes, pole_re, pole_im, residue_re, &
                                  residue_im, error_e, errmsg, errmsg_len) &
        bind(c, name='gc_identify_frf_file') result(status)
        !> Path of the receptance file, NUL-terminated.
        type(c_ptr), value, intent(in) :: path
        !> Target of the identification error E of eq. (7), > 0.
        real(c_double), value, intent(in) :: tol_e
        !> Largest number of modes the LSCE scan tries, >= 1.
        integer(c_int), value, intent(in) :: max_modes
        !> Capacity of the four output arrays.
        integer(c_int), value, intent(in) :: capacity
        !> Number of modes found.
        integer(c_int), intent(out) :: n_modes
        !> Real parts of the poles [rad/s].
        real(c_double), intent(out) :: pole_re(*)
        !> Imaginary parts of the poles [rad/s].
        real(c_double), intent(out) :: pole_im(*)
        !> Real parts of the residues [m/(N*s)].
        real(c_double), intent(out) :: residue_re(*)
        !> Imaginary parts of the residues [m/(N*s)].
        real(c_double), intent(out) :: residue_im(*)
        !> Error E of eq. (7) of the model.
        real(c_double), intent(out) :: error_e
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        integer :: ierr, n, cap
        character(len=message_length) :: message

        cap = max(int(capacity), 0)
        call gcid(from_c(path), tol_e, int(max_modes), cap, n, pole_re(1:cap), pole_im(1:cap), residue_re(1:cap), &
                  residue_im(1:cap), error_e, ierr, message)
        n_modes = int(n, c_int)
        status = finish(ierr, message, errmsg, errmsg_len)
    end function gc_identify_frf_file

    !> int gc_run_scene(const char *path, char *errmsg, size_t errmsg_len)
    function gc_run_scene(path, errmsg, errmsg_len) bind(c, name='gc_run_scene') result(status)
        !> Path of the namelist scene file, NUL-terminated.
        type(c_ptr), value, intent(in) :: path
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        integer :: ierr
        character(len=message_length) :: message

        call gcscen(from_c(path), ierr, message)
        status = finish(ierr, message, errmsg, errmsg_len)
    end function gc_run_scene

    !> The status as a C int, the message copied to the caller's buffer.
    function finish(ierr, message, errmsg, errmsg_len) result(status)
        integer, intent(in) :: ierr
        character(len=*), intent(in) :: message
        type(c_ptr), intent(in) :: errmsg
        integer(c_size_t), intent(in) :: errmsg_len
        integer(c_int) :: status

        call to_c(message, errmsg, errmsg_len)
        status = int(ierr, c_int)
    end function finish

    !> A NUL-terminated C string as Fortran text (empty for NULL).
    function from_c(text) result(fortran_text)
        type(c_ptr), intent(in) :: text
        character(len=:), allocatable :: fortran_text

        character(kind=c_char), pointer :: chars(:)
        integer :: i, n

        n = 0
        if (c_associated(text)) n = int(c_strlen(text))
        allocate (character(len=n) :: fortran_text)
        if (n == 0) return
        call c_f_pointer(text, chars, [n])
        do i = 1, n
            fortran_text(i:i) = chars(i)
        end do
    end function from_c

    !> Copy trimmed text into a C buffer of `length` bytes, truncated, NUL-terminated.
    subroutine to_c(text, buffer, length)
        character(len=*), intent(in) :: text
        type(c_ptr), intent(in) :: buffer
        integer(c_size_t), intent(in) :: length

        character(kind=c_char), pointer :: chars(:)
        integer :: i, n

        if (.not. c_associated(buffer) .or. length < 1) return
        call c_f_pointer(buffer, chars, [length])
        n = min(len_trim(text), int(length) - 1)
        do i = 1, n
            chars(i) = text(i:i)
        end do
        chars(n + 1) = c_null_char
    end subroutine to_c

    !> The C pointer of a legacy handle.
    function pointer_of(handle) result(pointer)
        integer(int64), intent(in) :: handle
        type(c_ptr) :: pointer

        pointer = c_null_ptr
        if (handle /= 0_int64) pointer = transfer(int(handle, c_intptr_t), c_null_ptr)
    end function pointer_of

    !> The legacy handle of a C pointer.
    function handle_of(pointer) result(handle)
        type(c_ptr), intent(in) :: pointer
        integer(int64) :: handle

        handle = 0_int64
        if (c_associated(pointer)) handle = int(transfer(pointer, 0_c_intptr_t), int64)
    end function handle_of

end module greenconv_capi
