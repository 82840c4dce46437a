!> What the foreign front doors share, whatever the object behind their handles: C strings
!> and values for the C API (greenconv_capi, greenconv_capi_multi), status and message for
!> the Fortran 77 layer (greenconv_legacy, greenconv_legacy_multi), and the `INTEGER*8`
!> handle of the Fortran 77 layer as the C address it stands for. No module state.
module greenconv_api_doors
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_size_t, c_ptr, c_null_ptr, c_null_char, &
                                           c_associated, c_f_pointer, c_intptr_t
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    implicit none
    private

    public :: finish, from_c, to_c, put, report, handle_address, address_handle

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

end module greenconv_api_doors
