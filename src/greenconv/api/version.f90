!> The version of greenconv through the C and Fortran 77 doors: `gc_version` (include/greenconv.h)
!> and `GCVERS` (re-exported by greenconv_legacy). Both give greenconv_core_version's text,
!> "major.minor.patch" as fpm.toml states it.
module greenconv_api_version
    use, intrinsic :: iso_c_binding, only: c_int, c_ptr, c_size_t, c_associated
    use greenconv_core_error, only: stat_input
    use greenconv_core_version, only: greenconv_version
    use greenconv_capi, only: to_c
    implicit none
    private

    public :: gc_version, gcvers

contains

    !> int gc_version(char *text, size_t text_len): the version, "major.minor.patch", written to
    !> text as every message of the C API is (at most text_len - 1 bytes and a NUL). Returns
    !> GC_OK when the whole version fitted, GC_ERROR_INPUT (2) when text is NULL or too short
    !> (what fits is still written, NUL-terminated). Keeps nothing: safe from any thread.
    function gc_version(text, text_len) bind(c, name='gc_version') result(status)
        !> Buffer for the version, or NULL.
        type(c_ptr), value, intent(in) :: text
        !> Size of the buffer [bytes]; the version needs its length + 1.
        integer(c_size_t), value, intent(in) :: text_len
        integer(c_int) :: status

        character(len=:), allocatable :: version

        version = greenconv_version()
        call to_c(version, text, text_len)
        status = 0
        ! A size_t beyond the signed range reads negative here: as good as unlimited.
        if (.not. c_associated(text)) status = stat_input
        if (text_len >= 0 .and. text_len < len(version, kind=c_size_t) + 1) status = stat_input
    end function gc_version

    !> GCVERS(TEXT): the version, "major.minor.patch" as fpm.toml states it, left-justified in
    !> TEXT and blank-padded (truncated when TEXT is shorter; 16 characters are plenty).
    subroutine gcvers(text)
        !> The version text.
        character(len=*), intent(out) :: text

        text = greenconv_version()
    end subroutine gcvers

end module greenconv_api_version
