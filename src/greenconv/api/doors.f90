!> What the foreign front doors share, whatever the object behind their handles: C strings
!> and values for the C API (greenconv_capi, greenconv_capi_multi), status and message for
!> the Fortran 77 layer (greenconv_legacy, greenconv_legacy_multi), and the `INTEGER*8`
!> handle of the Fortran 77 layer as the C address it stands for; and the checks of their
!> arguments (a pointer given, a count large enough, a method the registry serves, a new
!> handle cleared), so that every door refuses a bad argument with the same logic and words.
!> Each check keeps the first failure: it does nothing when `error` is already set, so a door
!> chains them and reports the first argument out of place. No module state.
module greenconv_api_doors
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_size_t, c_ptr, c_null_ptr, c_null_char, &
                                           c_associated, c_f_pointer, c_intptr_t
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text, lower_text
    use greenconv_model_modal_set, only: modal_set
    use greenconv_conv_methods, only: check_method
    implicit none
    private

    public :: finish, from_c, to_c, put, put_if, report, handle_address, address_handle
    public :: need_pointer, need_pointers, need_count, need_method, need_capacity, start_door, modes_to_c

    interface
        !> size_t strlen(const char *s)
        pure function c_strlen(text) bind(c, name='strlen') result(length)
            import :: c_ptr, c_size_t
            implicit none
            type(c_ptr), value, intent(in) :: text
            integer(c_size_t) :: length
        end function c_strlen
    end interface

    !> Store values at a C address the caller may leave NULL (an output it does not want):
    !> nothing for NULL, else a double, an int, or an array of them laid out as Fortran stores
    !> the values (the first index fastest).
    interface put_if
        module procedure put_real_if, put_reals_if, put_table_if, put_int_if, put_ints_if
    end interface put_if

contains

    !> The status of an error (0 when none), its message copied to the caller's buffer ("" when none).
    function finish(error, errmsg, errmsg_len) result(status)
        !> The error, or unallocated for success.
        type(error_type), allocatable, intent(in) :: error
        !> Message buffer, or NULL.
        type(c_ptr), intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), intent(in) :: errmsg_len
        integer(c_int) :: status

        status = 0
        if (allocated(error)) then
            status = int(error%stat, c_int)
            call to_c(error%message, errmsg, errmsg_len)
        else
            call to_c('', errmsg, errmsg_len)
        end if
    end function finish

    !> Length of a NUL-terminated C string (0 for NULL).
    pure integer function c_length(text)
        !> A NUL-terminated C string, or NULL.
        type(c_ptr), intent(in) :: text

        c_length = 0
        if (c_associated(text)) c_length = int(c_strlen(text))
    end function c_length

    !> A NUL-terminated C string as Fortran text (empty for NULL). Its length is a specification
    !> expression, not a deferred length (see greenconv_core_text on threads).
    function from_c(text) result(fortran_text)
        !> A NUL-terminated C string, or NULL.
        type(c_ptr), intent(in) :: text
        !> The text.
        character(len=c_length(text)) :: fortran_text

        character(kind=c_char), pointer :: chars(:)
        integer :: i, n

        n = len(fortran_text)
        if (n == 0) return
        call c_f_pointer(text, chars, [n])
        do i = 1, n
            fortran_text(i:i) = chars(i)
        end do
    end function from_c

    !> Copy text into a C buffer of `length` bytes: all of it when it fits, else its first
    !> length - 1 bytes, then a NUL. Nothing for a NULL buffer or length 0. A length that does
    !> not fit a signed size (negative here) is as good as unlimited.
    subroutine to_c(text, buffer, length)
        !> The text.
        character(len=*), intent(in) :: text
        !> The C buffer, or NULL.
        type(c_ptr), intent(in) :: buffer
        !> Size of the buffer [bytes].
        integer(c_size_t), intent(in) :: length

        character(kind=c_char), pointer :: chars(:)
        integer(c_size_t) :: i, n

        if (.not. c_associated(buffer) .or. length == 0) return
        n = len(text, kind=c_size_t)
        if (length > 0) n = min(n, length - 1)
        call c_f_pointer(buffer, chars, [n + 1])
        do i = 1, n
            chars(i) = text(i:i)
        end do
        chars(n + 1) = c_null_char
    end subroutine to_c

    !> Store a value at a C `double *` (not NULL).
    subroutine put(address, value)
        !> The C address of a double.
        type(c_ptr), intent(in) :: address
        !> The value, in the unit the caller documents.
        real(dp), intent(in) :: value

        real(c_double), pointer :: target_value

        call c_f_pointer(address, target_value)
        target_value = value
    end subroutine put

    !> A double at a C `double *`, or nothing for NULL.
    subroutine put_real_if(address, value)
        !> The C address of a double, or NULL.
        type(c_ptr), intent(in) :: address
        !> The value, in the unit the caller documents.
        real(dp), intent(in) :: value

        if (c_associated(address)) call put(address, value)
    end subroutine put_real_if

    !> size(values) doubles at a C `double *`, or nothing for NULL.
    subroutine put_reals_if(address, values)
        !> The C address of the first double, or NULL.
        type(c_ptr), intent(in) :: address
        !> The values, in the unit the caller documents.
        real(dp), intent(in) :: values(:)

        real(c_double), pointer :: out(:)

        if (.not. c_associated(address)) return
        call c_f_pointer(address, out, [size(values)])
        out(:) = values
    end subroutine put_reals_if

    !> A table of doubles at a C `double *`, the first index fastest, or nothing for NULL.
    subroutine put_table_if(address, values)
        !> The C address of the first double, or NULL.
        type(c_ptr), intent(in) :: address
        !> The values, in the unit the caller documents.
        real(dp), intent(in) :: values(:, :)

        real(c_double), pointer :: out(:, :)

        if (.not. c_associated(address)) return
        call c_f_pointer(address, out, shape(values))
        out(:, :) = values
    end subroutine put_table_if

    !> An int at a C `int *`, or nothing for NULL.
    subroutine put_int_if(address, value)
        !> The C address of an int, or NULL.
        type(c_ptr), intent(in) :: address
        !> The value (a count or a label, no unit).
        integer, intent(in) :: value

        integer(c_int), pointer :: out

        if (.not. c_associated(address)) return
        call c_f_pointer(address, out)
        out = int(value, c_int)
    end subroutine put_int_if

    !> size(values) ints at a C `int *`, or nothing for NULL.
    subroutine put_ints_if(address, values)
        !> The C address of the first int, or NULL.
        type(c_ptr), intent(in) :: address
        !> The values (counts or labels, no unit).
        integer, intent(in) :: values(:)

        integer(c_int), pointer :: out(:)

        if (.not. c_associated(address)) return
        call c_f_pointer(address, out, [size(values)])
        out(:) = int(values, c_int)
    end subroutine put_ints_if

    !> Fortran 77 status and message of an error, or 0 and a blank message when there is none.
    subroutine report(error, ierr, errmsg)
        !> The error, or unallocated for success.
        type(error_type), allocatable, intent(in) :: error
        !> Status: 0, or the error's (2 bad input, 3 numerical failure).
        integer, intent(out) :: ierr
        !> The message, truncated to the caller's length; blank on success.
        character(len=*), intent(out) :: errmsg

        ierr = 0
        errmsg = ' '
        if (.not. allocated(error)) return
        ierr = error%stat
        errmsg = error%message
    end subroutine report

    !> The C address a Fortran 77 `INTEGER*8` handle stands for; C NULL for handle 0.
    function handle_address(handle) result(address)
        !> The handle.
        integer(int64), intent(in) :: handle
        type(c_ptr) :: address

        address = c_null_ptr
        if (handle /= 0_int64) address = transfer(int(handle, c_intptr_t), c_null_ptr)
    end function handle_address

    !> The Fortran 77 `INTEGER*8` handle of a C address; 0 for C NULL.
    function address_handle(address) result(handle)
        !> The address of the object behind the handle.
        type(c_ptr), intent(in) :: address
        integer(int64) :: handle

        handle = 0_int64
        if (c_associated(address)) handle = int(transfer(address, 0_c_intptr_t), int64)
    end function address_handle

    ! ---- argument checks: each keeps the first failure ----------------------------------

    !> Refuse (status 2) a NULL pointer: "<caller>: <name> is NULL: <hint>".
    subroutine need_pointer(caller, address, name, hint, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The pointer the caller passed.
        type(c_ptr), intent(in) :: address
        !> The argument's name.
        character(len=*), intent(in) :: name
        !> What to pass instead, e.g. "pass the address of a double".
        character(len=*), intent(in) :: hint
        !> Set unless already set.
        type(error_type), allocatable, intent(inout) :: error

        if (allocated(error) .or. c_associated(address)) return
        call fatal_error(error, caller//': '//name//' is NULL: '//hint)
    end subroutine need_pointer

    !> Refuse (status 2) a NULL among arrays given together: "<caller>: <names> must not be
    !> NULL[: <hint>]".
    subroutine need_pointers(caller, addresses, names, hint, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The pointers the caller passed.
        type(c_ptr), intent(in) :: addresses(:)
        !> Their names as the message lists them, e.g. "x, y and z".
        character(len=*), intent(in) :: names
        !> What to pass, e.g. "pass arrays of n_points values"; '' for none.
        character(len=*), intent(in) :: hint
        !> Set unless already set.
        type(error_type), allocatable, intent(inout) :: error

        integer :: i

        if (allocated(error)) return
        if (all([(c_associated(addresses(i)), i=1, size(addresses))])) return
        if (len(hint) > 0) then
            call fatal_error(error, caller//': '//names//' must not be NULL: '//hint)
        else
            call fatal_error(error, caller//': '//names//' must not be NULL')
        end if
    end subroutine need_pointers

    !> Refuse (status 2) a count below its least: "<caller>: <name> = <value>: give at least
    !> <least>[ <what>]".
    subroutine need_count(caller, name, value, least, what, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The count's name as the door spells it (`n_points`, `NC`).
        character(len=*), intent(in) :: name
        !> The count given.
        integer, intent(in) :: value
        !> The least count accepted.
        integer, intent(in) :: least
        !> What is counted, e.g. "point" or "samples of every g_ij"; '' for nothing.
        character(len=*), intent(in) :: what
        !> Set unless already set.
        type(error_type), allocatable, intent(inout) :: error

        if (allocated(error) .or. value >= least) return
        if (len(what) > 0) then
            call fatal_error(error, caller//': '//name//' = '//int_text(value)//': give at least '//int_text(least) &
                             //' '//what)
        else
            call fatal_error(error, caller//': '//name//' = '//int_text(value)//': give at least '//int_text(least))
        end if
    end subroutine need_count

    !> Refuse (status 2) a method the registry does not serve for multi-point contact on the
    !> door's structure (any case), with the registry's message after "<caller>: ".
    subroutine need_method(caller, method, has_g, has_modes, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The method name.
        character(len=*), intent(in) :: method
        !> Whether the structure has a sampled g (or modes to sample it from).
        logical, intent(in) :: has_g
        !> Whether the structure has modes.
        logical, intent(in) :: has_modes
        !> Set unless already set.
        type(error_type), allocatable, intent(inout) :: error

        if (allocated(error)) return
        call check_method(lower_text(method), .true., has_g, has_modes, error)
        if (allocated(error)) error%message = caller//': '//error%message
    end subroutine need_method

    !> Refuse (status 2) a negative capacity of a door's output arrays: "<caller>: capacity =
    !> <value>: expected >= 0".
    subroutine need_capacity(caller, capacity, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The capacity given (values each output array holds).
        integer, intent(in) :: capacity
        !> Set unless already set.
        type(error_type), allocatable, intent(inout) :: error

        if (allocated(error) .or. capacity >= 0) return
        call fatal_error(error, caller//': capacity = '//int_text(capacity)//': expected >= 0')
    end subroutine need_capacity

    !> Copy modes into a C door's four output arrays of `capacity` values (poles [rad/s] and
    !> residues [m/(N*s)], real and imaginary parts), or refuse (status 2) more modes than they
    !> hold: "<caller>: <n> modes found, more than capacity = <capacity>: pass arrays of at least
    !> <n> values".
    subroutine modes_to_c(caller, modes, capacity, pole_re, pole_im, residue_re, residue_im, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The modes.
        type(modal_set), intent(in) :: modes
        !> Values each output array holds.
        integer, intent(in) :: capacity
        !> C `double *` arrays (not NULL) for Re and Im of the poles and of the residues.
        type(c_ptr), intent(in) :: pole_re, pole_im, residue_re, residue_im
        !> Set unless already set.
        type(error_type), allocatable, intent(inout) :: error

        real(c_double), pointer :: out(:)
        integer :: n

        if (allocated(error)) return
        n = modes%n_modes()
        if (n > capacity) then
            call fatal_error(error, caller//': '//int_text(n)//' modes found, more than capacity = ' &
                             //int_text(capacity)//': pass arrays of at least '//int_text(n)//' values')
            return
        end if
        call c_f_pointer(pole_re, out, [n])
        out = real(modes%pole, dp)
        call c_f_pointer(pole_im, out, [n])
        out = aimag(modes%pole)
        call c_f_pointer(residue_re, out, [n])
        out = real(modes%residue, dp)
        call c_f_pointer(residue_im, out, [n])
        out = aimag(modes%residue)
    end subroutine modes_to_c

    !> The start of a C constructor: clear the caller's handle (*conv = NULL) and refuse a NULL
    !> `conv` or `method`.
    subroutine start_door(caller, conv, handle_type, method, error)
        !> Name of the front-door function, first word of a message.
        character(len=*), intent(in) :: caller
        !> The caller's `<handle_type> **`, where the new handle goes.
        type(c_ptr), intent(in) :: conv
        !> The C type of the handle, `gc_convolver` or `gc_multi_convolver`.
        character(len=*), intent(in) :: handle_type
        !> The method string.
        type(c_ptr), intent(in) :: method
        !> Set unless already set.
        type(error_type), allocatable, intent(inout) :: error

        type(c_ptr), pointer :: handle

        if (c_associated(conv)) then
            call c_f_pointer(conv, handle)
            handle = c_null_ptr
        end if
        call need_pointer(caller, conv, 'conv', 'pass the address of a '//handle_type//' * to receive the convolver', &
                          error)
        call need_pointer(caller, method, 'method', 'pass a method name such as "modal"', error)
    end subroutine start_door

end module greenconv_api_doors
